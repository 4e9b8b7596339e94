/* An orthographic virtual camera along a direction D (Iwasaki et al.'s
 * virtual cameras, §4.2 and [13]): the uniforms of
 * shaders/illumination_textures/virtual_camera.glsl. Shared by
 * illumination_textures and sliced_refraction. */
#ifndef CAUSTICA_VIRTUAL_CAMERA_H
#define CAUSTICA_VIRTUAL_CAMERA_H

#include "core/vecmath.h"
#include "gl/gl_program.h"

struct virtual_camera {
    vec3 d, u, v;      /* the viewing direction and the in-plane axes */
    float center[2];   /* the square's centre in (U, V) */
    float half;        /* half its side */
    float near, far;   /* the depth range drawn, along D */
};

/* Axes U, V perpendicular to unit d. */
void virtual_camera_axes(struct virtual_camera *vc, vec3 d);
void virtual_camera_set(const struct gl_program *prog, const struct virtual_camera *vc);

#endif
