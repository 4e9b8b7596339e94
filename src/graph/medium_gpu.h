/* The scene's participating medium on the GPU: its coefficients as
 * uniforms and its density grid as a 3D texture at MEDIUM_UNIT_DENSITY,
 * read by shaders/common/medium.glsl (shade attenuates direct light with
 * it, volume_light and beam_caustics scatter in it). */
#ifndef CAUSTICA_MEDIUM_GPU_H
#define CAUSTICA_MEDIUM_GPU_H

#include <stdbool.h>

#include "core/error.h"
#include "gl/gl_program.h"
#include "scene/scene.h"

struct renderer;

/* Uploads the density grid when the medium changed and sets the uniforms
 * of common/medium.glsl on `program` (u_medium = 0 without a medium or
 * with one that neither scatters nor absorbs). */
bool medium_gpu_bind(struct renderer *r, const struct scene *scene, const struct gl_program *program,
                     struct error *err);
/* Does the scene have a medium that scatters or absorbs? */
bool medium_gpu_present(const struct scene *scene);

#endif
