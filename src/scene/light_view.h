/* A light's view of a bounding sphere: the one fit behind the depth layers
 * (Chaudhari / Liktor & Dachsbacher's light-space layers), the photon
 * buffer (Hu & Qin §3.1) and the directional shadow map. Each caller keeps
 * its own margins, as data: how far back an orthographic eye sits, where
 * its near and far planes fall, how much a perspective view widens the
 * sphere's angle, and what to do with a light inside the sphere. */
#ifndef CAUSTICA_LIGHT_VIEW_H
#define CAUSTICA_LIGHT_VIEW_H

#include <stdbool.h>

#include "core/vecmath.h"

struct light_view_margins {
    float radius_scale;   /* the sphere's radius is widened by this first */
    float eye_radii;      /* orthographic: the eye this many radii back from the centre, against the light */
    float ortho_near_radii, ortho_far_radii; /* orthographic: the planes, in radii from the eye */
    float fov_scale;      /* perspective: the sphere's angle widened by this (at most 170 degrees) */
    float near_scale;     /* perspective: near = (distance - radius) * near_scale */
    float far_radii;      /* perspective: far = distance + far_radii * radius */
    float inside_half_angle; /* a light inside the sphere: this half angle (radians); 0: refused */
    bool up_z_when_vertical; /* a view within 8 degrees of vertical takes +z as up (else the look-at's own rule) */
};

struct light_view {
    mat4 view, proj;
    bool ortho;
    float half_extent; /* orthographic: the half width; perspective: tan(half fov) */
    float half_width, half_height; /* orthographic: the projection's half sides (both half_extent unless narrowed) */
    float distance;    /* perspective: from the light to the centre */
};

/* Fits the view of the sphere (center, radius) from a directional light
 * (`ortho`, along `direction`) or one at `position`. False when the light
 * is inside the sphere and the margins refuse that. Never NaN: a zero
 * radius or direction falls back to a small sphere and straight down. */
bool light_view_fit(bool ortho, vec3 position, vec3 direction, vec3 center, float radius,
                    const struct light_view_margins *m, struct light_view *out);

#endif
