/* The lighting of surfaces on the CPU (core/shading.h); the GPU's is
 * shaders/common/lighting.glsl and surface_light.glsl, line for line. */
#include "core/shading.h"

#include <math.h>

#include "core/vecmath.h"

double shading_spot_falloff(double cos_angle, double cos_outer, double cos_inner)
{
    double lo = cos_outer, hi = fmax(cos_inner, cos_outer + 1e-4);
    double x = fmin(fmax((cos_angle - lo) / (hi - lo), 0.0), 1.0);
    return x * x * (3.0 - 2.0 * x);
}

bool shading_light_arrival(const struct shading_light *l, const double p[3], double e[3], double to_light[3],
                           double *dist)
{
    if (l->kind == SHADING_DIRECTIONAL) {
        for (int k = 0; k < 3; k++) {
            to_light[k] = -l->direction[k];
            e[k] = l->intensity[k];
        }
        *dist = INFINITY;
        return true;
    }
    double d[3], d2 = 0.0;
    for (int k = 0; k < 3; k++) {
        d[k] = l->position[k] - p[k];
        d2 += d[k] * d[k];
    }
    d2 = fmax(d2, 1e-8); /* (lighting.glsl's floor) */
    *dist = sqrt(d2);
    for (int k = 0; k < 3; k++)
        to_light[k] = d[k] / *dist;
    double falloff = 1.0;
    if (l->kind == SHADING_SPOT) {
        double c = -(to_light[0] * l->direction[0] + to_light[1] * l->direction[1] + to_light[2] * l->direction[2]);
        falloff = shading_spot_falloff(c, l->cos_outer, l->cos_inner);
    }
    for (int k = 0; k < 3; k++)
        e[k] = l->intensity[k] * falloff / d2;
    return falloff > 0.0;
}

void shading_diffuse_radiance(const double albedo[3], const double e[3], const double ambient[3],
                              const double emission[3], double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = albedo[k] / MATH_PI * e[k] + albedo[k] * ambient[k] + emission[k];
}
