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

/* The receivers (visible diffuse objects, at most IMPOSTOR_MAX) around
 * `refractor_center`, each rendered at size x size; with `include_specular`
 * the reflectors and refractors too, their colour the environment they
 * reflect and refract (the recursion's level 0). They are lit as shade
 * lights (common/surface_light.glsl), through the shadow maps `owner` has
 * as inputs (none: unshadowed) and the frame's medium. */
bool impostors_build(struct impostor_set *set, struct pass *owner, struct pass_frame *f, vec3 refractor_center,
                     int size, bool include_specular, uint64_t key, struct error *err);
/* One level of recursive reflection/refraction (Hu & Qin §2.2, Fig. 1b,
 * 24g): the specular objects' impostors are drawn again, reflecting and
 * refracting the impostors of the previous level. */
bool impostors_recurse(struct impostor_set *set, struct renderer *r, const struct scene *scene, struct error *err);
void impostors_release(struct impostor_set *set);
/* The key a pass builds its impostors under: its pass_frame_key with the
 * geometry and the lights (Hu & Qin §4's reuse in a static scene). */
uint64_t impostors_key(const struct pass *p, const struct pass_frame *f);
/* Whether the last build stands for `key` (and no geometry animates). */
bool impostors_current(const struct impostor_set *set, const struct pass_frame *f, uint64_t key);
/* Index of the impostor standing in for `object`, or -1. */
int impostors_find(const struct impostor_set *set, const struct object *object);

#endif
