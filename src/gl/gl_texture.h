/* Textures and framebuffers: each struct owns its GL name and has one
 * release path (gl_texture_destroy / gl_framebuffer_destroy). */
#ifndef CAUSTICA_GL_TEXTURE_H
#define CAUSTICA_GL_TEXTURE_H

#include <stdbool.h>

#include "core/error.h"
#include "gl/gl_api.h"

struct gl_texture {
    GLuint id;
    GLenum target;   /* GL_TEXTURE_2D, GL_TEXTURE_CUBE_MAP, GL_TEXTURE_2D_ARRAY */
    GLenum format;   /* sized internal format */
    int width, height, layers;
};

/* Parses "rgba16f", "rgba32f", "r32f", "rgba8", "depth32f" ... */
bool gl_format_parse(const char *name, GLenum *format);
const char *gl_format_name(GLenum format);
bool gl_format_is_depth(GLenum format);

bool gl_texture_create(struct gl_texture *tex, GLenum target, GLenum format, int width, int height,
                       int layers, struct error *err);
/* The same with `levels` mipmap levels (0: the full chain, filtered
 * trilinearly; fill them with glGenerateTextureMipmap). */
bool gl_texture_create_levels(struct gl_texture *tex, GLenum target, GLenum format, int width, int height,
                              int layers, int levels, struct error *err);
void gl_texture_destroy(struct gl_texture *tex);
/* `to` as a copy of 2D texture `from`'s level 0, (re)made at its size and
 * format when it is not; with its full mipmap chain, filled, where `mips`. */
bool gl_texture_copy(struct gl_texture *to, const struct gl_texture *from, bool mips, struct error *err);
/* Reads level 0 (layer `layer` of a cube map / array) as float RGBA. */
/* A 2D depth texture's window depths [0, 1], rows bottom to top. */
bool gl_texture_read_depth32f(const struct gl_texture *tex, float *out, struct error *err);
bool gl_texture_read_rgba32f(const struct gl_texture *tex, int layer, float *out, struct error *err);

struct gl_framebuffer {
    GLuint id;
};

bool gl_framebuffer_create(struct gl_framebuffer *fb, struct error *err);
void gl_framebuffer_destroy(struct gl_framebuffer *fb);
/* Attaches colour textures (layer -1 = whole level) and an optional depth
 * texture, sets the draw buffers and checks completeness. */
bool gl_framebuffer_attach(struct gl_framebuffer *fb, const struct gl_texture *const *colors,
                           const int *color_layers, int ncolors, const struct gl_texture *depth,
                           int depth_layer, struct error *err);

/* Fills level 0 of a colour texture with `rgba`. */
void gl_texture_clear(const struct gl_texture *texture, const float rgba[4]);

#endif
