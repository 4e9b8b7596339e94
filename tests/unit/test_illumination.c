/* The illumination textures' geometry without GL (passes/helpers/illumination_geometry.c):
 * the volumes a glass cube's transport table gives under a sun (their flux
 * is the light through the top face, less Fresnel at two interfaces), the
 * planes, the flux square, the intersection triangles (a parallel beam
 * keeps its irradiance; a focus on the plane becomes points carrying the
 * same flux) and the texel-centre test. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "passes/helpers/illumination_geometry.h"

static struct illum_volume beam(float x, float z, float side, float spread, vec3 flux)
{
    /* a triangle at height 1 whose rays go down, converging by `spread` */
    struct illum_volume v;
    vec3 c = vec3_make(x, 1.0f, z);
    v.o[0] = vec3_add(c, vec3_make(0, 0, 0));
    v.o[1] = vec3_add(c, vec3_make(side, 0, 0));
    v.o[2] = vec3_add(c, vec3_make(0, 0, side));
    vec3 centre = vec3_add(c, vec3_make(side / 3.0f, -1.0f, side / 3.0f));
    for (int k = 0; k < 3; k++) {
        vec3 to = vec3_sub(centre, v.o[k]);
        vec3 down = vec3_make(0, -1, 0);
        v.d[k] = vec3_normalize_or(vec3_add(vec3_scale(down, 1.0f - spread), vec3_scale(to, spread)), down);
    }
    v.flux = flux;
    return v;
}

int main(void)
{
    struct error err;
    /* texel centres */
    const float a[2] = {0.0f, 0.0f}, b[2] = {2.0f, 0.0f}, c[2] = {0.0f, 2.0f};
    CHECK(illum_covers_a_texel_centre(a, b, c));
    const float s0[2] = {0.6f, 0.6f}, s1[2] = {0.9f, 0.6f}, s2[2] = {0.6f, 0.9f};
    CHECK(!illum_covers_a_texel_centre(s0, s1, s2)); /* between centres */
    CHECK(!illum_covers_a_texel_centre(a, a, c));   /* zero area */

    /* planes */
    float depth[ILLUM_MAX_PLANES];
    illum_planes_spread(-2.0f, 2.0f, 1, depth);
    CHECK_NEAR(depth[0], 0.0, 1e-6);
    illum_planes_spread(-2.0f, 2.0f, 3, depth);
    CHECK_NEAR(depth[0], -2.0, 1e-6);
    CHECK_NEAR(depth[1], 0.0, 1e-6);
    CHECK_NEAR(depth[2], 2.0, 1e-6);

    /* a parallel beam (flux 2 through a triangle of area 0.5) and a beam
     * focused on the plane y = 0 (flux 1) */
    struct illum_volume items[2] = {beam(0.0f, 0.0f, 1.0f, 0.0f, vec3_make(2, 2, 2)),
                                    beam(-0.5f, -0.5f, 0.3f, 1.0f, vec3_make(1, 1, 1))};
    struct illum_volume_list vols = {items, 2, 2};
    vec3 d = illum_mean_direction(&vols);
    CHECK_NEAR(d.y, -1.0, 1e-3);
    vec3 u = vec3_make(1, 0, 0), v = vec3_make(0, 0, 1);
    float plane[1] = {vec3_dot(vec3_make(0, 0, 0), d)}; /* y = 0 */
    float cu, cv, half;
    CHECK(illum_flux_square(&vols, d, u, v, plane, 1, 10.0f, &cu, &cv, &half));
    CHECK(half > 0.3f && half < 1.5f);
    float above[1] = {-5.0f}; /* y = 5: behind every origin */
    CHECK(!illum_flux_square(&vols, d, u, v, above, 1, 10.0f, &cu, &cv, &half));
    CHECK(illum_flux_square(&vols, d, u, v, plane, 1, 10.0f, &cu, &cv, &half));
    struct illum_intersections x;
    CHECK(illum_intersect(&vols, d, u, v, plane, 1, cu, cv, half, 64, &x, &err));
    CHECK(x.count[0] == 3);       /* the parallel beam: one triangle */
    CHECK(x.point_count[0] == 3); /* the focus: three points */
    /* the triangle keeps the beam's irradiance: flux / area (cos 1) */
    CHECK_NEAR(x.triangles[3], 2.0 / 0.5, 1e-3);
    CHECK_NEAR(x.triangles[1], 0.0, 1e-5);
    /* the points carry the focused flux: 3 x intensity x texel area = 1 */
    float texel = 2.0f * half / 64.0f;
    double carried = 0.0;
    for (size_t k = 0; k < x.point_count[0]; k++)
        carried += x.points[(x.point_first[0] + k) * ILLUM_VERTEX_FLOATS + 3] * texel * texel;
    CHECK_NEAR(carried, 1.0, 1e-3);
    for (size_t k = 0; k < x.triangle_vertices * ILLUM_VERTEX_FLOATS; k++)
        CHECK(isfinite(x.triangles[k]));
    illum_intersections_release(&x);

    /* a glass cube under a sun: every volume comes from the top face and
     * carries L S (1 - F)^2 between them, F = 0.04 at normal incidence */
    struct mesh *box = mesh_create_box(vec3_make(1, 1, 1), &err);
    CHECK(box != NULL);
    struct material glass;
    material_init(&glass, MATERIAL_GLASS);
    glass.ior = 1.5f;
    struct transport_table table;
    memset(&table, 0, sizeof table);
    CHECK(transport_table_build(&table, box, &glass, 8, TRANSPORT_INTERNAL_NONE, &err));
    struct frame_light sun = {.kind = LIGHT_DIRECTIONAL, .direction = {0, -1, 0}, .intensity = {1, 1, 1}};
    struct illum_volume_list cube = {0};
    CHECK(illum_volumes_collect(box, &table, NULL, NULL, mat4_identity(), &sun, &cube, &err));
    CHECK(cube.count == 2);
    double total = 0.0;
    for (int i = 0; i < cube.count; i++) {
        total += cube.items[i].flux.x;
        for (int k = 0; k < 3; k++) {
            CHECK_NEAR(cube.items[i].o[k].y, -0.5, 1e-3); /* out through the bottom */
            CHECK_NEAR(cube.items[i].d[k].y, -1.0, 0.02); /* straight on, to the 8 x 8 table's interpolation */
        }
    }
    CHECK_NEAR(total, 0.96 * 0.96, 2e-3);
    /* the exact tracer gives the table's own paths where the table has a
     * sample: the vertices at directions on the table's grid */
    struct transport_tracer *tracer = NULL;
    CHECK(transport_tracer_create(&tracer, box, &glass, TRANSPORT_INTERNAL_NONE, &err));
    for (size_t vi = 0; vi < box->vertex_count; vi++)
        for (int c = 0; c < 64; c += 7) {
            vec3 dir = transport_direction(8, c % 8, c / 8);
            vec3 tp, td, tt, lp, ld, lt;
            vec3 p = vec3_make(box->positions[vi * 3], box->positions[vi * 3 + 1], box->positions[vi * 3 + 2]);
            vec3 n = vec3_make(box->normals[vi * 3], box->normals[vi * 3 + 1], box->normals[vi * 3 + 2]);
            bool traced = transport_trace(tracer, p, n, dir, &tp, &td, &tt);
            bool looked = transport_lookup(&table, vi, dir, &lp, &ld, &lt);
            CHECK(traced == looked);
            if (traced && looked) {
                CHECK_NEAR(vec3_length(vec3_sub(tp, lp)), 0.0, 1e-4);
                CHECK_NEAR(vec3_dot(td, ld), 1.0, 1e-4);
                CHECK_NEAR(tt.x, lt.x, 1e-4);
            }
        }
    /* A sun at a slant on an ideal cube of IOR 1.01, its faces cut in 4 x 4
     * (as the pass subdivides a coarse mesh for its table): the light
     * entering the top and two sides all leaves (no total internal
     * reflection at this IOR and slant), by the bottom or a side. The
     * triangles across a parting line (two faces' light in each) make no
     * volume from the table alone; with the tracer they are split where the
     * paths part, and the flux that enters is all there but the slivers
     * along the parting lines (1/16 of a triangle across after four
     * splits). */
    struct mesh *fine_box = mesh_create_subdivided(box, 2, &err);
    CHECK(fine_box != NULL);
    struct material ideal;
    material_init(&ideal, MATERIAL_GLASS);
    ideal.ior = 1.01f;
    ideal.ideal = true;
    struct transport_table slant_table;
    memset(&slant_table, 0, sizeof slant_table);
    CHECK(transport_table_build(&slant_table, fine_box, &ideal, 16, TRANSPORT_INTERNAL_NONE, &err));
    struct transport_tracer *slant_tracer = NULL;
    CHECK(transport_tracer_create(&slant_tracer, fine_box, &ideal, TRANSPORT_INTERNAL_NONE, &err));
    vec3 slant = vec3_normalize_or(vec3_make(0.35f, -1.0f, 0.2f), vec3_make(0, -1, 0));
    struct frame_light slant_sun = {.kind = LIGHT_DIRECTIONAL, .direction = slant, .intensity = {1, 1, 1}};
    struct illum_volume_list alone = {0}, traced = {0};
    bool *flat_faces = illum_flat_vertices(fine_box, &err);
    CHECK(flat_faces != NULL);
    CHECK(illum_volumes_collect(fine_box, &slant_table, NULL, NULL, mat4_identity(), &slant_sun, &alone, &err));
    CHECK(illum_volumes_collect(fine_box, &slant_table, slant_tracer, flat_faces, mat4_identity(), &slant_sun, &traced,
                                &err));
    free(flat_faces);
    double entering = fabs(slant.x) + fabs(slant.y) + fabs(slant.z), alone_flux = 0.0, traced_flux = 0.0;
    for (int i = 0; i < alone.count; i++)
        alone_flux += alone.items[i].flux.x;
    for (int i = 0; i < traced.count; i++) {
        traced_flux += traced.items[i].flux.x;
        for (int k = 0; k < 3; k++)
            CHECK(isfinite(traced.items[i].o[k].x) && isfinite(traced.items[i].d[k].x));
    }
    printf("slanted cube: %.4f of the entering flux with the table alone, %.4f traced where paths part\n",
           alone_flux / entering, traced_flux / entering);
    CHECK(alone_flux < 0.95 * entering);
    CHECK(traced_flux > 0.98 * entering && traced_flux <= entering * 1.0001);
    free(alone.items);
    free(traced.items);
    transport_tracer_destroy(slant_tracer);
    transport_tracer_destroy(tracer);
    transport_table_release(&slant_table);
    material_release(&ideal);
    mesh_destroy(fine_box);

    /* a degenerate model matrix lets nothing through, without NaN */
    struct illum_volume_list none = {0};
    mat4 flat = mat4_identity();
    flat.m[5] = 0.0f;
    CHECK(illum_volumes_collect(box, &table, NULL, NULL, flat, &sun, &none, &err));
    CHECK(none.count == 0);
    free(cube.items);
    free(none.items);
    transport_table_release(&table);
    material_release(&glass);
    mesh_destroy(box);
    return check_finish("test_illumination");
}
