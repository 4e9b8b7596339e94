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

struct renderer;

struct distance_map {
    int size;
    vec3 center;
    struct gl_texture color[2];     /* rgba16f cubes per layer: the radiance seen in each direction (linear) */
    struct gl_texture distance[2];  /* r32f cubes: its distance from the centre, 1e30 where none (nearest: a
                                       filtered distance would blend a near and a far surface into a wall
                                       that is not there) */
    struct gl_texture depth_buffer; /* for rendering its faces */
    struct gl_framebuffer fb;
    bool built;
    uint64_t built_key; /* the building pass's pass_frame_key (geometry, lights), the centre and size */
};

/* Renders the map around `center` (size x size per face): the visible
 * diffuse objects lit as `shade` lights them (Lambert, ambient, emission),
 * shadowed by the shadow maps of `shadow_pass`'s inputs when it has any
 * (shadow_inputs). A static scene keeps the last map (pass_frame_key of
 * `shadow_pass` with the geometry and lights, and the same centre and size;
 * only the receivers' animation counts: a deforming glass dragon does not
 * make it stale). */
bool distance_map_update(struct distance_map *m, struct renderer *r, struct pass *shadow_pass, struct pass_frame *f,
                         vec3 center, int size, struct error *err);
/* The distances alone (layer 0, no colour) around `center` out to `range`:
 * the receivers' distance impostor beam_caustics traces its exits against
 * (Szirmay-Kalos et al. 2005; Liktor & Dachsbacher §4.3). No surface within
 * the range reads as the range; the faces are filtered (linear), as the
 * beams' march expects. Reused as the full map is (the key with the range). */
bool distance_map_update_distances(struct distance_map *m, struct renderer *r, struct pass *owner,
                                   struct pass_frame *f, vec3 center, int size, float range, struct error *err);
void distance_map_release(struct distance_map *m);

#endif
