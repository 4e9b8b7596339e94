/* The geometry of Iwasaki et al.'s illumination textures, GL-free (unit
 * tested in tests/unit/test_illumination.c): the illumination volumes a
 * glass object's transport table gives for one light sample (§4.1, eq. 1),
 * their flux-weighted direction, the virtual planes and the square where
 * the flux crosses them (§4.2), and each volume's intersection triangle
 * with a plane, its vertices carrying eq. 3's intensity (the cosine at the
 * receiver is the shader's). illumination_textures.c draws what this
 * computes. */
#ifndef CAUSTICA_ILLUMINATION_GEOMETRY_H
#define CAUSTICA_ILLUMINATION_GEOMETRY_H

#include <stdbool.h>
#include <stddef.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "graph/frame.h"
#include "scene/transport.h"

#define ILLUM_MAX_PLANES 16
#define ILLUM_VERTEX_FLOATS 15 /* position, intensity, direction, its volume's entry and the way to the light */

/* One illumination volume: the three outgoing rays of a surface triangle
 * and the flux through it. */
struct illum_volume {
    vec3 o[3], d[3];
    vec3 flux;
    vec3 entry, to_light; /* where the light meets the glass (the triangle's centre), and the way back to the light:
                             the panes it crossed on its way there (illumination.vert's pane_filter) */
};

struct illum_volume_list {
    struct illum_volume *items;
    int count, capacity;
};

/* §4.1: the volumes of one glass object (the mesh its table samples, at
 * `model`) lit by one light sample, appended to `out`: per vertex the
 * light's direction in the object's frame looked up in the table, per
 * triangle facing the light the flux L cos(theta) S F_t (eq. 1). A
 * zero-area triangle makes no volume. On a flat face (`flat`, from
 * illum_flat_vertices) `tracer` (the table's own paths at any point)
 * traces exactly a vertex whose neighbouring table directions take
 * different paths, and splits a triangle whose vertices' paths part (leave
 * by different faces, or not at all) where they part; elsewhere, or
 * without a tracer or `flat` (NULL), such a triangle makes no volume. On a
 * curved surface a vertex within about 6 degrees of grazing (or whose table
 * directions part) is traced too, and a triangle takes its corners' exact
 * paths where they leave nearly parallel (the rim of an IOR-1.0 ball). */
bool illum_volumes_collect(const struct mesh *m, const struct transport_table *table,
                           const struct transport_tracer *tracer, const bool *flat, mat4 model,
                           const struct frame_light *light, struct illum_volume_list *out, struct error *err);

/* Per vertex of m, whether it lies on a flat face (its normal is every one
 * of its triangles'); the caller frees it, NULL (err set) when out of
 * memory. Where the table's directions take different paths on a flat face
 * they leave by different faces, and their blend is a ray from nowhere (a
 * tilted cube's caustic smeared over its shadow: 0.72 in the optics
 * matrix). On a curved surface the paths turn with the direction and the
 * blend is the paper's approximation, kept: traced exactly there, the glass
 * bunny's spray of light came out sharper and further from the reference
 * (0.405 -> 0.462 in the room). A property of the mesh: made once with its
 * tracer, not per light sample. */
bool *illum_flat_vertices(const struct mesh *m, struct error *err);

/* The volumes' flux-weighted mean direction (straight down when there is
 * no flux). */
vec3 illum_mean_direction(const struct illum_volume_list *vols);

/* `planes` depths along d evenly from lo to hi (one plane: the middle). */
void illum_planes_spread(float lo, float hi, int planes, float *depth);

/* The square (centre cu, cv and half side in the axes u, v) where 99% of
 * the flux crosses the planes, no larger than `limit`; false when no
 * volume crosses any plane ahead of it. */
bool illum_flux_square(const struct illum_volume_list *vols, vec3 d, vec3 u, vec3 v, const float *depth, int planes,
                       float limit, float *cu, float *cv, float *half);

/* The intersection triangles of every volume with every plane, in a square
 * of size x size texels (centre cu, cv, half side `half` on axes u, v):
 * plane pl's triangles are triangles[first[pl] .. first[pl] + count[pl])
 * (vertices, ILLUM_VERTEX_FLOATS floats each: position, intensity = flux /
 * (S0 cos), direction), and a triangle the texel centres miss (a focus,
 * S0 -> 0) is three points a third of its flux each, one texel apiece, in
 * points[point_first[pl] ..]. The caller frees both arrays. */
struct illum_intersections {
    float *triangles, *points;
    size_t first[ILLUM_MAX_PLANES], count[ILLUM_MAX_PLANES];
    size_t point_first[ILLUM_MAX_PLANES], point_count[ILLUM_MAX_PLANES];
    size_t triangle_vertices, point_vertices;
};
bool illum_intersect(const struct illum_volume_list *vols, vec3 d, vec3 u, vec3 v, const float *depth, int planes,
                     float cu, float cv, float half, int size, struct illum_intersections *out, struct error *err);
void illum_intersections_release(struct illum_intersections *x);

/* Whether the rasterizer would draw any fragment of the triangle with
 * texture-space (texel unit) corners a, b, c: a texel centre inside it. */
bool illum_covers_a_texel_centre(const float a[2], const float b[2], const float c[2]);

#endif
