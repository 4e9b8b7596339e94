/* A distance impostor (Szirmay-Kalos, Aszódi, Lazányi and Premecz 2005,
 * "Approximate ray-tracing on the GPU with distance impostors"; Liktor &
 * Dachsbacher use the same for exits, §6): a cube map around the
 * refractors' centre holding, per direction, the radiance of the diffuse
 * surface seen there and its distance from the centre. A ray from any
 * point near the centre finds what it hits by a search along it against
 * the stored distances (shaders/distance_map/lookup.glsl). Unlike Hu &
 * Qin's one rectangle per object (§2.2), a floor or a wall around the
 * refractor is one more part of the same map, and what is nearer along a
 * ray wins because the search walks the ray in order.
 *
 * Two layers: the nearest surface seen from the centre, and the nearest
 * surface facing the centre beyond it. A ray that passes behind an object
 * (hidden from the centre, seen from the ray's origin: the wall beside a
 * box) finds what is behind it in the second layer; one layer leaves it
 * nothing (misses along every such ray in the identity test, docs/techniques/hu_qin.md). */
#ifndef CAUSTICA_DISTANCE_MAP_H
#define CAUSTICA_DISTANCE_MAP_H

#include <stdbool.h>
#include <stdint.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "gl/gl_texture.h"
#include "graph/pass.h"
#include "scene/scene.h"

/* The building block `distance_map` (issue 54: it was each reader's
 * private helper, built once per reader): the map around the glass,
 * water and mirrors' centre (`around = "specular"`, refraction's) or the
 * refractors' alone (`"refractors"`, beam_caustics'), of `content`
 * "radiance" (both layers, lit; refraction's lookups) or "distances"
 * (layer 0's distances alone, out to `range`; beam_caustics' exits). Its
 * output `map` is a record of DISTANCE_MAP_RECORD's type, a struct
 * distance_map, that readers take with pass_frame_record and bind. The
 * graph adds one for a reader that names none (configured by
 * distance_map_configure_block) and shares it among readers that want the
 * same one. */
struct record_type;
extern const struct record_type DISTANCE_MAP_RECORD;

enum distance_map_content { DISTANCE_MAP_RADIANCE, DISTANCE_MAP_DISTANCES };

struct distance_map {
    int size;
    enum distance_map_content content;
    vec3 center;
    float range;                    /* distances: how far the faces reach (none within: the range) */
    struct gl_texture color[2];     /* rgba16f cubes per layer: the radiance seen in each direction (linear) */
    struct gl_texture distance[2];  /* r32f cubes: its distance from the centre, 1e30 where none (nearest: a
                                       filtered distance would blend a near and a far surface into a wall
                                       that is not there) */
    struct gl_texture depth_buffer; /* for rendering its faces */
    struct gl_framebuffer fb;
    bool built;
    uint64_t built_key; /* the block's pass_frame_key (geometry, lights), the centre, size and range */
};

/* Sets the parameters of the block a reader's input asks the graph for:
 * the content, the face size, what it is centred on (OBJECT_ROLE_SPECULAR
 * or OBJECT_ROLE_REFRACTOR) and, for radiance, the shadow maps that light
 * it: the reader's own `shadow` list (reader_shadow: its parameter's
 * index; -1: none). */
bool distance_map_configure_block(struct pass *block, enum distance_map_content content, int size, unsigned around,
                                  const struct pass *reader, int reader_shadow, struct error *err);

#endif
