/* Impostors (Hu & Qin §2.2.1, Fig. 12): each nearby object stands in as a
 * square rectangle of side 2 d_i at its centre O_i, perpendicular to the
 * line from the refractor's centre O_R, with a texture made by a parallel
 * projection along that line. Here the texture holds each texel's depth
 * along the line (relative to the rectangle's plane), which the iterative
 * lookup of Fig. 16 uses to correct where a ray meets the object. */
#ifndef CAUSTICA_IMPOSTORS_H
#define CAUSTICA_IMPOSTORS_H

#include <stdbool.h>

#include "core/error.h"
#include "gl/gl_texture.h"
#include "graph/pass.h"
#include "scene/scene.h"

#define IMPOSTOR_MAX 16
#define IMPOSTOR_EMPTY 1e30f /* depth of a texel where the object is not */

struct renderer;

struct impostor {
    struct object *object; /* borrowed */
    bool specular;         /* a reflector/refractor: its colour is its own reflection/refraction */
    vec3 center, axis, right, up;
    float half;            /* d_i: half the rectangle's side */
};

/* std430 mirror of `Impostor` in shaders/impostors/impostors.glsl */
struct impostor_gpu {
    float center[4]; /* xyz, w = half side */
    float axis[4];
    float right[4];
    float up[4];
};

struct impostor_set {
    int count, size;
    struct impostor items[IMPOSTOR_MAX];
    struct gl_texture depth;        /* r32f array: one layer per impostor */
    struct gl_texture color;        /* rgba16f array: the objects' radiance (lit, unshadowed) */
    struct gl_texture color_previous; /* the previous recursion level's colours */
    struct gl_texture depth_buffer; /* for rendering them */
    struct gl_framebuffer fb;
    GLuint ubo;                     /* the impostors' frames (std430 SSBO) */
    /* what the last complete build was made from (§4: a static scene reuses it) */
    bool built;
    uint64_t built_key; /* the building pass's pass_frame_key */
};

/* The building block `impostors` (issue 54: it was each reader's private
 * helper): the set around the glass, water and mirrors' centre at `size`
 * texels, with `specular` the reflectors and refractors too and
 * `recursion` levels of them reflecting each other (Fig. 1b, 24g), lit
 * through its `shadow` maps. Its output `set` is a record of
 * IMPOSTOR_SET_RECORD's type, a struct impostor_set, that refraction,
 * layered_refraction and photon_caustics read (pass_frame_record). The
 * graph adds one for a reader that names none (configured by
 * impostors_configure_block) and shares it among readers that want the
 * same set. */
struct record_type;
extern const struct record_type IMPOSTOR_SET_RECORD;

/* Sets the block's parameters for a reader: `size`, `recursion` (levels;
 * more than 0 draws the specular objects too) and the shadow maps that
 * light it, the reader's own `shadow` list (reader_shadow: its parameter's
 * index; -1: none). */
bool impostors_configure_block(struct pass *block, int size, int recursion, const struct pass *reader,
                               int reader_shadow, struct error *err);
/* Index of the impostor standing in for `object`, or -1. */
int impostors_find(const struct impostor_set *set, const struct object *object);

#endif
