/* The glTF 2.0 BRDF on the CPU (core/brdf.h); the GPU's is
 * shaders/common/brdf.glsl, line for line. */
#include "core/brdf.h"

#include <math.h>

#include "core/vecmath.h"

struct brdf_material brdf_material_default(double r, double g, double b, double metallic, double roughness)
{
    return (struct brdf_material){.base_color = {r, g, b},
                                  .metallic = metallic,
                                  .roughness = roughness,
                                  .ior = 1.5,
                                  .specular = 1.0,
                                  .specular_color = {1.0, 1.0, 1.0}};
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double brdf_ggx_d(double n_dot_h, double sin2, double alpha)
{
    /* Appendix B: D = alpha^2 / (pi ((NdotH)^2 (alpha^2 - 1) + 1)^2),
     * the denominator as NdotH^2 alpha^2 + sin^2 */
    double a2 = alpha * alpha;
    double k = n_dot_h * n_dot_h * a2 + fmax(sin2, 0.0);
    return n_dot_h > 0.0 ? a2 / (MATH_PI * k * k) : 0.0;
}

double brdf_smith_v(double n_dot_l, double n_dot_v, double alpha)
{
    /* Appendix B: V = 0.5 / (NdotL sqrt(NdotV^2 (1 - a^2) + a^2) + NdotV sqrt(NdotL^2 (1 - a^2) + a^2)) */
    double a2 = alpha * alpha;
    double gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    double gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    double s = gv + gl;
    return s > 0.0 ? 0.5 / s : 0.0;
}

void brdf_gltf(const double n[3], const double v[3], const double l[3], const struct brdf_material *m, double f[3])
{
    f[0] = f[1] = f[2] = 0.0;
    double n_dot_l = dot3(n, l), n_dot_v = dot3(n, v);
    if (!(n_dot_l > 0.0) || !(n_dot_v > 0.0))
        return;
    double h[3] = {v[0] + l[0], v[1] + l[1], v[2] + l[2]};
    double hl = sqrt(dot3(h, h));
    if (!(hl > 1e-12))
        return; /* v = -l: both above the surface cannot give this, but no division by 0 */
    for (int k = 0; k < 3; k++)
        h[k] /= hl;
    double n_dot_h = fmin(dot3(n, h), 1.0), v_dot_h = fmin(fabs(dot3(v, h)), 1.0);
    double alpha = fmax(m->roughness * m->roughness, BRDF_MIN_ALPHA);
    double c[3] = {n[1] * h[2] - n[2] * h[1], n[2] * h[0] - n[0] * h[2], n[0] * h[1] - n[1] * h[0]};
    double spec = brdf_ggx_d(n_dot_h, dot3(c, c), alpha) * brdf_smith_v(n_dot_l, n_dot_v, alpha);
    double w = pow(1.0 - v_dot_h, 5.0);
    double r0 = (m->ior - 1.0) / (m->ior + 1.0);
    double fd[3], fd_max = 0.0;
    for (int k = 0; k < 3; k++) {
        double f0 = fmin(r0 * r0 * m->specular_color[k], 1.0);
        fd[k] = f0 + (1.0 - f0) * w;
        fd_max = fmax(fd_max, fd[k]);
    }
    for (int k = 0; k < 3; k++) {
        double dielectric = (1.0 - m->specular * fd_max) * m->base_color[k] / MATH_PI + m->specular * fd[k] * spec;
        double metal = (m->base_color[k] + (1.0 - m->base_color[k]) * w) * spec;
        f[k] = dielectric + m->metallic * (metal - dielectric);
    }
}
