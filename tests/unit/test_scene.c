#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "scene/light_view.h"
#include "scene/scene.h"
#include "scene/transport.h"

static bool normals_unit(const struct mesh *m)
{
    for (size_t i = 0; i < m->vertex_count; i++) {
        const float *n = m->normals + i * 3;
        if (fabsf(sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0f) > 1e-4f)
            return false;
    }
    return true;
}

/* Every triangle's winding agrees with its vertex normals (counter-clockwise
 * seen from outside), and no index is out of range. */
static bool winding_outward(const struct mesh *m)
{
    for (size_t t = 0; t < m->index_count; t += 3) {
        for (int k = 0; k < 3; k++)
            if (m->indices[t + (size_t)k] >= m->vertex_count)
                return false;
        const float *a = m->positions + m->indices[t] * 3, *b = m->positions + m->indices[t + 1] * 3,
                    *c = m->positions + m->indices[t + 2] * 3;
        vec3 e1 = vec3_make(b[0] - a[0], b[1] - a[1], b[2] - a[2]), e2 = vec3_make(c[0] - a[0], c[1] - a[1], c[2] - a[2]);
        vec3 fn = vec3_cross(e1, e2);
        if (vec3_length(fn) < 1e-6f)
            continue; /* the sphere's poles have zero-area triangles */
        const float *n = m->normals + m->indices[t] * 3;
        if (vec3_dot(fn, vec3_make(n[0], n[1], n[2])) <= 0)
            return false;
    }
    return true;
}

/* The volume a closed mesh encloses (divergence theorem): positive when
 * its triangles face out. */
static double mesh_volume(const struct mesh *m)
{
    double v = 0.0;
    for (size_t t = 0; t < m->index_count; t += 3) {
        const float *a = m->positions + m->indices[t] * 3, *b = m->positions + m->indices[t + 1] * 3,
                    *c = m->positions + m->indices[t + 2] * 3;
        v += ((double)a[0] * (b[1] * c[2] - b[2] * c[1]) - (double)a[1] * (b[0] * c[2] - b[2] * c[0]) +
              (double)a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
    }
    return v;
}

static bool texcoords_in_unit_square(const struct mesh *m)
{
    for (size_t i = 0; m->texcoords[0] && i < m->vertex_count * 2; i++)
        if (!(m->texcoords[0][i] >= 0.0f && m->texcoords[0][i] <= 1.0f))
            return false;
    return m->texcoords[0] != NULL;
}

/* The clip-space w-divided position of p: inside [-1, 1]^3 when in view. */
static vec3 project(const struct light_view *lv, vec3 p)
{
    mat4 vp = mat4_mul(lv->proj, lv->view);
    const float *m = vp.m;
    float c[4];
    for (int r = 0; r < 4; r++)
        c[r] = m[r] * p.x + m[4 + r] * p.y + m[8 + r] * p.z + m[12 + r];
    return vec3_make(c[0] / c[3], c[1] / c[3], c[2] / c[3]);
}

/* Every point of the sphere's surface (a sample of directions) in view. */
static bool sphere_in_view(const struct light_view *lv, vec3 c, float r)
{
    for (int i = 0; i < 64; i++) {
        float z = -1.0f + (2.0f * (float)i + 1.0f) / 64.0f, phi = 2.399963f * (float)i, s = sqrtf(1.0f - z * z);
        vec3 q = project(lv, vec3_add(c, vec3_scale(vec3_make(s * cosf(phi), s * sinf(phi), z), r)));
        if (!(fabsf(q.x) <= 1.0f && fabsf(q.y) <= 1.0f && fabsf(q.z) <= 1.0f))
            return false;
    }
    return true;
}

static bool view_finite(const struct light_view *lv)
{
    for (int k = 0; k < 16; k++)
        if (!isfinite(lv->view.m[k]) || !isfinite(lv->proj.m[k]))
            return false;
    return isfinite(lv->half_extent);
}

int main(void)
{
    struct error err;
    struct mesh *s = mesh_create_sphere(0.5f, 16, &err);
    CHECK(s && normals_unit(s) && winding_outward(s));
    CHECK_NEAR(s->bounds_max.y, 0.5, 1e-6);
    CHECK_NEAR(s->bounds_min.x, -0.5, 1e-3);
    struct mesh *g = mesh_create_grid(2.0f, 4, &err);
    CHECK(g && g->vertex_count == 25 && g->index_count == 96 && winding_outward(g));
    struct mesh *b = mesh_create_box(vec3_make(1, 2, 3), &err);
    CHECK(b && b->vertex_count == 24 && normals_unit(b) && winding_outward(b));
    CHECK_NEAR(b->bounds_max.z, 1.5, 1e-6);
    struct mesh *tor = mesh_create_torus(1.0f, 0.25f, 32, 16, &err);
    CHECK(tor && normals_unit(tor) && winding_outward(tor));
    CHECK_NEAR(tor->bounds_max.x, 1.25, 1e-5);
    CHECK(mesh_create_torus(0.2f, 0.3f, 32, 16, &err) == NULL);
    mesh_destroy(tor);
    CHECK(mesh_create_sphere(-1.0f, 16, &err) == NULL);
    CHECK_CONTAINS(err.message, "radius");
    CHECK(mesh_create_grid(1.0f, 0, &err) == NULL);
    CHECK(mesh_create_box(vec3_make(0, 1, 1), &err) == NULL);

    /* Objects: bounds follow the transform and grow with a morph. */
    struct object *o = object_create(b);
    o->position = vec3_make(10, 0, 0);
    vec3 lo, hi;
    object_world_bounds(o, &lo, &hi);
    CHECK_NEAR(lo.x, 9.5, 1e-5);
    CHECK_NEAR(hi.x, 10.5, 1e-5);
    CHECK(!object_is_animated_geometry(o));
    o->deform.kind = DEFORM_WAVE;
    o->deform.amplitude = 0.25f;
    CHECK(object_is_animated_geometry(o));
    object_world_bounds(o, &lo, &hi);
    CHECK_NEAR(hi.y, 1.25, 1e-5);

    /* Roles: the one predicate; an invisible object has none. */
    CHECK(object_role(o) == OBJECT_ROLE_RECEIVER);
    static const enum material_kind kinds[4] = {MATERIAL_DIFFUSE, MATERIAL_GLASS, MATERIAL_WATER, MATERIAL_MIRROR};
    static const unsigned roles[4] = {OBJECT_ROLE_RECEIVER, OBJECT_ROLE_GLASS, OBJECT_ROLE_WATER, OBJECT_ROLE_MIRROR};
    static const char *const names[4] = {"receiver", "glass", "water", "mirror"};
    for (int k = 0; k < 4; k++) {
        o->material.kind = kinds[k];
        CHECK(object_role(o) == roles[k]);
        CHECK(strcmp(object_role_name(object_role(o)), names[k]) == 0);
        CHECK(object_is(o, OBJECT_ROLE_SPECULAR) == (k > 0));
        CHECK(object_is(o, OBJECT_ROLE_REFRACTOR) == (k == 1 || k == 2));
        o->visible = false;
        CHECK(object_role(o) == 0 && !object_is(o, roles[k]));
        CHECK(material_role(&o->material) == roles[k]);
        o->visible = true;
    }
    o->material.kind = MATERIAL_DIFFUSE;

    /* The light's view of a sphere: in view whole, orthographic and
     * perspective, straight down too; a light inside refused or widened as
     * the margins say; degenerate input stays finite. */
    {
        const struct light_view_margins m = {.radius_scale = 1.02f, .eye_radii = 3.0f, .ortho_near_radii = 0.5f,
                                             .ortho_far_radii = 6.0f, .fov_scale = 1.02f, .near_scale = 0.9f,
                                             .far_radii = 1.1f, .up_z_when_vertical = true};
        struct light_view lv;
        vec3 c = vec3_make(1, 2, -3);
        CHECK(light_view_fit(true, vec3_make(0, 0, 0), vec3_make(0.3f, -1, 0.2f), c, 2.0f, &m, &lv));
        CHECK(lv.ortho && sphere_in_view(&lv, c, 2.0f) && view_finite(&lv));
        CHECK(light_view_fit(true, vec3_make(0, 0, 0), vec3_make(0, -1, 0), c, 2.0f, &m, &lv));
        CHECK(sphere_in_view(&lv, c, 2.0f) && view_finite(&lv));
        CHECK(light_view_fit(false, vec3_make(4, 9, 0), vec3_make(0, -1, 0), c, 2.0f, &m, &lv));
        CHECK(!lv.ortho && sphere_in_view(&lv, c, 2.0f) && view_finite(&lv));
        CHECK(light_view_fit(false, vec3_make(1, 12, -3), vec3_make(0, -1, 0), c, 2.0f, &m, &lv)); /* above */
        CHECK(sphere_in_view(&lv, c, 2.0f) && view_finite(&lv));
        CHECK(!light_view_fit(false, vec3_make(1, 2.5f, -3), vec3_make(0, -1, 0), c, 2.0f, &m, &lv)); /* inside */
        struct light_view_margins wide = m;
        wide.inside_half_angle = 1.2f;
        CHECK(light_view_fit(false, vec3_make(1, 2.5f, -3), vec3_make(0, -1, 0), c, 2.0f, &wide, &lv));
        CHECK(view_finite(&lv));
        CHECK(light_view_fit(true, c, vec3_make(0, 0, 0), c, 0.0f, &m, &lv) && view_finite(&lv));
        CHECK(light_view_fit(false, vec3_make(0, 5, 0), vec3_make(0, 0, 0), vec3_make(0, 0, 0), 0.0f, &m, &lv));
        CHECK(view_finite(&lv));
    }

    /* The scene: adding twice is once; versions change when objects do. */
    struct scene sc;
    scene_init(&sc);
    CHECK(scene_object_add(&sc, o, &err));
    CHECK(scene_object_add(&sc, o, &err));
    CHECK(sc.object_count == 1);
    uint64_t v = scene_geometry_version(&sc);
    o->version++;
    CHECK(scene_geometry_version(&sc) != v);
    CHECK(scene_bounds(&sc, &lo, &hi));
    scene_object_remove(&sc, o);
    CHECK(sc.object_count == 0);
    CHECK(!scene_bounds(&sc, &lo, &hi));
    scene_release(&sc);

    /* Midpoint subdivision (for the transport tables): a box of side 1,
     * two levels: 16 times the triangles, the edges a quarter as long, each
     * face's midpoints shared (a face of 2 triangles has 25 vertices after
     * two levels, 4 + 21 new), every vertex still on the box, the normals
     * unit and the winding kept. */
    struct mesh *box = mesh_create_box(vec3_make(1, 1, 1), &err);
    CHECK(box != NULL);
    CHECK_NEAR(mesh_longest_edge(box), sqrt(2.0), 1e-5);
    CHECK(mesh_subdivision_levels(box, 0.5f, 1 << 20) == 2);
    CHECK(mesh_subdivision_levels(box, 0.5f, 12 * 4) == 1); /* the triangle cap holds */
    CHECK(mesh_subdivision_levels(box, 2.0f, 1 << 20) == 0);
    struct mesh *fine = mesh_create_subdivided(box, 2, &err);
    CHECK(fine != NULL);
    if (fine) {
        CHECK(fine->index_count == box->index_count * 16);
        CHECK(fine->vertex_count == 6 * 25);
        CHECK_NEAR(mesh_longest_edge(fine), sqrt(2.0) / 4, 1e-5);
        CHECK(normals_unit(fine));
        CHECK(winding_outward(fine));
        bool on_box = true;
        for (size_t i = 0; i < fine->vertex_count * 3; i += 3) {
            float m = fmaxf(fmaxf(fabsf(fine->positions[i]), fabsf(fine->positions[i + 1])), fabsf(fine->positions[i + 2]));
            on_box = on_box && fabsf(m - 0.5f) < 1e-6f;
        }
        CHECK(on_box);
        mesh_destroy(fine);
    }
    /* a zero-area triangle and opposite normals on an edge: finite */
    float *zp = malloc(9 * sizeof *zp), *zn = malloc(9 * sizeof *zn);
    uint32_t *zi = malloc(3 * sizeof *zi);
    if (zp && zn && zi) {
        const float p9[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0}, n9[9] = {0, 1, 0, 0, -1, 0, 0, 1, 0};
        memcpy(zp, p9, sizeof p9);
        memcpy(zn, n9, sizeof n9);
        zi[0] = 0, zi[1] = 1, zi[2] = 2;
    }
    struct mesh *flat = mesh_create_from_arrays("zero-area", zp, zn, 3, zi, 3, &err);
    CHECK(flat != NULL);
    if (flat) {
        struct mesh *f2 = mesh_create_subdivided(flat, 3, &err);
        CHECK(f2 != NULL);
        bool finite = true;
        for (size_t i = 0; f2 && i < f2->vertex_count * 3; i++)
            finite = finite && isfinite(f2->positions[i]) && isfinite(f2->normals[i]);
        CHECK(finite);
        CHECK(f2 && normals_unit(f2));
        if (f2)
            mesh_destroy(f2);
        mesh_destroy(flat);
    }
    /* Surfaces of revolution: closed, facing out, the volume of the
     * polygon turned (a 256-gon's area is 0.99990 of the circle's). */
    {
        struct mesh *cyl = mesh_create_cylinder(0.5f, 2.0f, 256, &err);
        CHECK(cyl && normals_unit(cyl) && winding_outward(cyl) && texcoords_in_unit_square(cyl));
        if (cyl) {
            double polygon = 0.5 * 256 * sin(2 * MATH_PI / 256);
            CHECK_NEAR(mesh_volume(cyl), polygon * 0.25 * 2.0, 1e-4);
            CHECK_NEAR(cyl->bounds_min.y, -1.0, 1e-6);
            CHECK_NEAR(cyl->bounds_max.y, 1.0, 1e-6);
            CHECK(mesh_contains_point(cyl, vec3_make(0.45f, 0.9f, 0.0f)));
            CHECK(!mesh_contains_point(cyl, vec3_make(0.55f, 0.0f, 0.0f)));
            /* the rim is a crease: a side vertex's normal is horizontal */
            bool side = false;
            for (size_t i = 0; i < cyl->vertex_count; i++)
                side |= fabsf(cyl->positions[i * 3 + 1] - 1.0f) < 1e-6f && fabsf(cyl->normals[i * 3 + 1]) < 1e-6f;
            CHECK(side);
            mesh_destroy(cyl);
        }
        struct mesh *cone = mesh_create_cone(1.0f, 3.0f, 256, &err);
        CHECK(cone && normals_unit(cone) && winding_outward(cone));
        if (cone) {
            double polygon = 0.5 * 256 * sin(2 * MATH_PI / 256);
            CHECK_NEAR(mesh_volume(cone), polygon * 3.0 / 3.0, 1e-4);
            mesh_destroy(cone);
        }
        /* a profile given top to bottom faces out all the same; a repeated
         * point is dropped, not a zero-area ring */
        const float down[10] = {0, 1, 1, 1, 1, 1, 1, -1, 0, -1};
        struct mesh *lathe = mesh_create_lathe("lathe", down, 5, 32, &err);
        CHECK(lathe && winding_outward(lathe) && mesh_volume(lathe) > 0.0);
        mesh_destroy(lathe);
        /* an open profile (a bowl) has no inside, but its winding holds */
        const float bowl[8] = {0, -0.5f, 0.4f, -0.45f, 0.6f, 0.0f, 0.7f, 0.5f};
        struct mesh *open = mesh_create_lathe("bowl", bowl, 4, 48, &err);
        CHECK(open && normals_unit(open) && winding_outward(open));
        mesh_destroy(open);
        const float axis_only[4] = {0, 0, 0, 1}, nan_point[4] = {1, 0, NAN, 1}, negative[4] = {-1, 0, 1, 1};
        CHECK(mesh_create_lathe("lathe", axis_only, 2, 16, &err) == NULL);
        CHECK(mesh_create_lathe("lathe", nan_point, 2, 16, &err) == NULL && strstr(err.message, "point 2"));
        CHECK(mesh_create_lathe("lathe", negative, 2, 16, &err) == NULL);
        CHECK(mesh_create_lathe("lathe", down, 5, 2, &err) == NULL);
        CHECK(mesh_create_cylinder(0.0f, 1.0f, 16, &err) == NULL);
        CHECK(mesh_create_cone(1.0f, INFINITY, 16, &err) == NULL);
    }

    /* A transport table that fits: fewer directions for a fine mesh, none
     * for one too fine for any. */
    CHECK(transport_fit_resolution(1000, 16) == 16);
    CHECK(transport_fit_resolution(131841, 16) == 10);
    CHECK(transport_fit_resolution((size_t)1 << 40, 16) == 0);

    /* Inside a closed mesh: the parity of a ray's crossings. */
    CHECK(mesh_contains_point(box, vec3_make(0, 0, 0)));
    CHECK(mesh_contains_point(box, vec3_make(0.49f, -0.3f, 0.2f)));
    CHECK(!mesh_contains_point(box, vec3_make(0.51f, 0, 0)));
    CHECK(!mesh_contains_point(box, vec3_make(0, 2, 0)));
    struct mesh *ball = mesh_create_sphere(0.55f, 96, &err);
    CHECK(ball != NULL);
    if (ball) {
        CHECK(mesh_contains_point(ball, vec3_make(0.1f, 0.05f, 0.05f)));
        CHECK(mesh_contains_point(ball, vec3_make(0, 0.54f, 0)));
        CHECK(!mesh_contains_point(ball, vec3_make(0.4f, 0.4f, 0.4f)));
        mesh_destroy(ball);
    }
    mesh_destroy(box);

    object_destroy(o);
    mesh_destroy(s);
    mesh_destroy(g);
    mesh_destroy(b);
    return check_finish("test_scene");
}
