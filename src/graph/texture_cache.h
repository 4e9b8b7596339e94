/* The GPU copies of material textures, owned by the renderer: one GL
 * texture per (texture serial, colour space), with the texture's sampler
 * state (wrap, magnification filter, mipmaps) set on it. Colour slots use
 * GL_SRGB8_ALPHA8, so the GPU linearizes texels before filtering as the
 * reference does (texture_sample); normal maps use GL_RGBA8. Entries whose
 * texture no object of the frame's scene uses are released at the frame's
 * start. */
#ifndef CAUSTICA_TEXTURE_CACHE_H
#define CAUSTICA_TEXTURE_CACHE_H

#include <stdbool.h>
#include <stdint.h>

#include "core/error.h"
#include "gl/gl_api.h"
#include "scene/scene.h"

struct gpu_texture {
    uint64_t serial;
    bool srgb;
    GLuint id;
    bool used;
};

struct texture_cache {
    struct gpu_texture *entries;
    int count, capacity;
};

void texture_cache_init(struct texture_cache *c);
void texture_cache_release(struct texture_cache *c);
/* Marks the textures `scene`'s objects use and releases the rest. */
void texture_cache_begin_frame(struct texture_cache *c, const struct scene *scene);
/* The GL name of `t` in the given colour space (uploaded on first use). */
bool texture_cache_get(struct texture_cache *c, const struct texture *t, bool srgb, GLuint *id, struct error *err);

#endif
