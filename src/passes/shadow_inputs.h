/* Shadow map inputs of a pass (shade, volume_light, refraction): the slots
 * shadow0..3 of an input list parameter `shadow` (declared from the
 * descriptor, .max = SHADOW_INPUTS_MAX), bound with the uniforms of
 * shaders/common/shadows.glsl. */
#ifndef CAUSTICA_SHADOW_INPUTS_H
#define CAUSTICA_SHADOW_INPUTS_H

#include <stdbool.h>

#include "core/error.h"
#include "gl/gl_program.h"
#include "graph/pass.h"

#define SHADOW_INPUTS_MAX 4 /* the sampler arrays u_shadow_2d[4] and u_shadow_cubes[4] */

/* What a shadow map's depth texture carries for its readers: the
 * resource's record, of SHADOW_MAP_RECORD's type (graph/pass.h), owned by
 * the shadow_map pass, NULL on a frame it made nothing. */
extern const struct record_type SHADOW_MAP_RECORD;
struct shadow_record {
    mat4 matrix;     /* the light's view-projection (2D), or its translation to the origin (cube) */
    int light_index; /* the light's first entry in the frame's GPU light list */
    int kind;        /* enum light_kind */
    float range;     /* far plane, or the cube's distance range */
    float bias;
    GLuint filter;   /* 2D maps: what thin-walled glass lets through (RGB) and its depth (A), or 0 */
};

/* Binds the shadow maps and sets the uniforms on `program`. */
void shadow_inputs_bind(struct pass *p, struct pass_frame *f, const struct gl_program *program);

#endif
