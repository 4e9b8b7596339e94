/* The lighting of surfaces in double precision, the C twin of
 * shaders/common/lighting.glsl and shaders/common/surface_light.glsl
 * (issue 50: one lighting function): the light a point receives from a
 * point, spot or directional light, and the radiance a diffuse surface
 * sends back. The reference lights its surfaces with these
 * (src/reference/ref_sppm.c); tests/unit/test_shading.c holds them and
 * the GLSL to each other on a grid. */
#ifndef CAUSTICA_SHADING_H
#define CAUSTICA_SHADING_H

#include <stdbool.h>

enum shading_light_kind { SHADING_POINT = 0, SHADING_DIRECTIONAL = 1, SHADING_SPOT = 2 }; /* the frame's kinds */

struct shading_light {
    int kind;            /* enum shading_light_kind */
    double position[3];  /* point and spot */
    double direction[3]; /* unit: the way the light travels (directional), the spot's axis */
    double intensity[3]; /* W/sr (point, spot), W/m^2 (directional) */
    double cos_outer, cos_inner; /* spot cone */
};

/* A spot's falloff for a direction at cos_angle from its axis: 0 outside
 * the outer cone, 1 inside the inner one, a smoothstep between (GLSL's
 * smoothstep(cos_outer, max(cos_inner, cos_outer + 1e-4), c)). */
double shading_spot_falloff(double cos_angle, double cos_outer, double cos_inner);

/* Irradiance at p from light l on a surface facing it (no cosine): e, the
 * unit direction towards the light `to_light` and its distance `dist`
 * (INFINITY for a directional light). False (e zero) where the light sends
 * nothing towards p (outside a spot's cone). Never a NaN: p at the light
 * is taken as 1e-8 away, as the GLSL does. */
bool shading_light_arrival(const struct shading_light *l, const double p[3], double e[3], double to_light[3],
                           double *dist);

/* Lambert's radiance for irradiance e (lights and caustics), the ambient
 * sky and the surface's own emission: albedo / pi * e + albedo * ambient +
 * emission (GLSL: surface_diffuse_radiance). */
void shading_diffuse_radiance(const double albedo[3], const double e[3], const double ambient[3],
                              const double emission[3], double out[3]);

#endif
