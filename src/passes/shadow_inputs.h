/* Shadow map inputs of a pass (shade, volume_light): declared as slots
 * shadow0..3 from a list parameter, bound with the uniforms of
 * shaders/common/shadows.glsl. */
#ifndef CAUSTICA_SHADOW_INPUTS_H
#define CAUSTICA_SHADOW_INPUTS_H

#include <stdbool.h>

#include "core/error.h"
#include "gl/gl_program.h"
#include "graph/pass.h"

#define SHADOW_INPUTS_MAX 4 /* sampler units SHADE_UNIT_SHADOW_2D.. and SHADE_UNIT_SHADOW_CUBE.. */

/* Declares one input slot per name in the list parameter `param`. */
bool shadow_inputs_declare(struct pass *p, int param, struct error *err);
/* Binds the shadow maps and sets the uniforms on `program`. */
void shadow_inputs_bind(struct pass *p, struct pass_frame *f, const struct gl_program *program);

#endif
