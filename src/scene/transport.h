/* The light transport table of a transparent mesh (Iwasaki et al., §3,
 * after their [12]): for each vertex and each incident light direction of
 * a grid on the sphere (in the mesh's own frame), where the light that
 * enters at the vertex leaves the object, in which direction, and with
 * what transmittance (Fresnel at both interfaces, absorption inside).
 * Traced once per mesh, IOR and resolution with Embree against the mesh
 * itself; looking it up at render time makes any translation and rotation
 * of the object and any light direction free of tracing. Rigid meshes
 * only: a deformed or morphed object uses its base shape's table. */
#ifndef CAUSTICA_TRANSPORT_H
#define CAUSTICA_TRANSPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "scene/scene.h"

enum transport_internal {
    TRANSPORT_INTERNAL_NONE,  /* the paper's: only paths refracted in and out; a total internal reflection ends the path */
    TRANSPORT_INTERNAL_FIRST, /* also follow the first total internal reflection */
};

#define TRANSPORT_FLOATS 9 /* exit position xyz, exit direction xyz (0 = no path), transmittance rgb */

struct transport_table {
    uint64_t mesh_serial;
    float ior;
    bool ideal;
    vec3 absorption;
    int resolution;                  /* directions: resolution^2 cells of an octahedral map */
    enum transport_internal internal;
    size_t vertex_count;
    float *entries;                  /* owned: vertex_count * resolution^2 * TRANSPORT_FLOATS */
    double build_seconds;
    size_t bytes;
    bool from_cache;                 /* read from the disk cache rather than traced */
};

/* The tables' disk cache: $CAUSTICA_CACHE, else $XDG_CACHE_HOME/caustica,
 * else $HOME/.cache/caustica (its `transport` folder), one file per mesh,
 * material and settings, named by a hash of all of them. A table that
 * cannot be written there is simply not cached. */
#define TRANSPORT_MAX_BYTES ((size_t)512 << 20)

/* The largest table resolution up to `wanted` whose table for `vertex_count`
 * vertices fits TRANSPORT_MAX_BYTES; 0 when not even 2 x 2 directions fit. A
 * 512-segment sphere (131,841 vertices) gets 10 x 10 instead of 16 x 16. */
int transport_fit_resolution(size_t vertex_count, int wanted);
/* The table of mesh m (object number `object` of its scene) at `wanted`
 * directions per side, or the most that fit, built unless `t` already
 * holds it; where fewer fit, `report` says so. False (err set) when the
 * mesh is too fine for any table or the build fails. */
bool transport_table_ensure(struct transport_table *t, const struct mesh *m, const struct material *mat, int wanted,
                            enum transport_internal internal, int object, char *report, size_t reportlen,
                            struct error *err);
bool transport_table_build(struct transport_table *t, const struct mesh *m, const struct material *mat,
                           int resolution, enum transport_internal internal, struct error *err);
void transport_table_release(struct transport_table *t);
/* Whether a table was built for this mesh and material at these settings. */
bool transport_table_matches(const struct transport_table *t, const struct mesh *m, const struct material *mat,
                             int resolution, enum transport_internal internal);
/* The unit direction at octahedral cell (i, j), and the continuous cell
 * coordinates of a unit direction. */
vec3 transport_direction(int resolution, double i, double j);
void transport_cell(int resolution, vec3 d, double *i, double *j);
/* The outgoing ray for light arriving along `dir` (object frame) at
 * `vertex`, interpolated bilinearly over the valid neighbouring directions
 * (a direction exactly on a sample reads that sample); false where no
 * neighbour has a path. */
bool transport_lookup(const struct transport_table *t, size_t vertex, vec3 dir, vec3 *position, vec3 *direction,
                      vec3 *transmittance);
/* The same, and whether the directions it interpolates agree: all have a
 * path, leaving within TRANSPORT_SMOOTH_COS of each other. Where they do
 * not (the light leaves by another face, or is totally reflected, a cell
 * away) the interpolated ray is a blend of different paths, no path at all. */
#define TRANSPORT_SMOOTH_COS 0.9f
bool transport_lookup_smooth(const struct transport_table *t, size_t vertex, vec3 dir, vec3 *position,
                             vec3 *direction, vec3 *transmittance, bool *smooth);

/* The same paths traced exactly at any point of the mesh, for the light of
 * one triangle whose vertices' paths part (they leave by different faces,
 * or some are totally reflected): the table cannot say where between its
 * vertices they part. Holds an Embree scene of the mesh (its base shape);
 * the mesh must outlive it. */
struct transport_tracer;
bool transport_tracer_create(struct transport_tracer **out, const struct mesh *m, const struct material *mat,
                             enum transport_internal internal, struct error *err);
void transport_tracer_destroy(struct transport_tracer *t);
/* The outgoing ray for light arriving along `dir` at point p of (shading)
 * normal n, all in the mesh's frame; false where no light leaves. */
bool transport_trace(const struct transport_tracer *t, vec3 p, vec3 n, vec3 dir, vec3 *position, vec3 *direction,
                     vec3 *transmittance);

#endif
