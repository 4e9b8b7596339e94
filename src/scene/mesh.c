/* Meshes: procedural shapes and what every mesh shares (glTF files:
 * mesh_gltf.c, parts: mesh_parts.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

static uint64_t mesh_next_serial(void)
{
    static uint64_t next = 1;
    return next++;
}

/* Texture coordinates for a procedural mesh (texcoord set 0); false, and
 * the mesh destroyed, when out of memory. */
static bool add_texcoords(struct mesh *m, struct error *err)
{
    m->texcoords[0] = malloc(m->vertex_count * 2 * sizeof(float));
    if (!m->texcoords[0]) {
        error_set(err, "%s: out of memory", m->name);
        mesh_destroy(m);
        return false;
    }
    return true;
}

struct mesh *mesh_create_from_arrays(const char *name, float *positions, float *normals, size_t vertex_count,
                                     uint32_t *indices, size_t index_count, struct error *err)
{
    struct mesh *m = calloc(1, sizeof *m);
    if (m) {
        m->references = 1;
        m->serial = mesh_next_serial();
    }
    if (!m || !positions || !normals || !indices) {
        free(m);
        free(positions);
        free(normals);
        free(indices);
        error_set(err, "%s: out of memory", name);
        return NULL;
    }
    snprintf(m->name, sizeof m->name, "%s", name);
    material_init(&m->material, MATERIAL_DIFFUSE);
    m->positions = positions;
    m->normals = normals;
    m->indices = indices;
    m->vertex_count = vertex_count;
    m->index_count = index_count;
    mesh_compute_bounds(m);
    return m;
}

void mesh_compute_bounds(struct mesh *m)
{
    vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < m->vertex_count; i++) {
        vec3 p = {m->positions[i * 3], m->positions[i * 3 + 1], m->positions[i * 3 + 2]};
        lo = vec3_min(lo, p);
        hi = vec3_max(hi, p);
    }
    if (m->vertex_count == 0)
        lo = hi = vec3_make(0, 0, 0);
    m->bounds_min = lo;
    m->bounds_max = hi;
    float extent = 0.0f;
    size_t n = (size_t)m->target_count * m->vertex_count;
    for (size_t i = 0; i < n; i++) {
        const float *d = m->target_positions + i * 3;
        float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (len > extent)
            extent = len;
    }
    m->morph_extent = extent;
}

static size_t count_of(int n) { return n > 0 ? (size_t)n : 0; }

void mesh_sphere_counts(int segments, size_t *vertices, size_t *indices)
{
    size_t rings = segments / 2 < 2 ? 2 : count_of(segments / 2), around = count_of(segments);
    *vertices = (rings + 1) * (around + 1);
    *indices = rings * around * 6;
}

void mesh_grid_counts(int cells_x, int cells_z, size_t *vertices, size_t *indices)
{
    *vertices = (count_of(cells_x) + 1) * (count_of(cells_z) + 1);
    *indices = count_of(cells_x) * count_of(cells_z) * 6;
}

void mesh_torus_counts(int segments, int sides, size_t *vertices, size_t *indices)
{
    *vertices = (count_of(segments) + 1) * (count_of(sides) + 1);
    *indices = count_of(segments) * count_of(sides) * 6;
}

struct mesh *mesh_create_sphere(float radius, int segments, struct error *err)
{
    if (!(radius > 0.0f) || !isfinite(radius) || segments < 3 || segments > 2048) {
        error_set(err, "sphere: radius must be > 0 and segments in 3..2048 (got %g, %d)", (double)radius, segments);
        return NULL;
    }
    int rings = segments / 2 < 2 ? 2 : segments / 2;
    size_t nv, ni;
    mesh_sphere_counts(segments, &nv, &ni);
    float *p = malloc(nv * 3 * sizeof(float)), *n = malloc(nv * 3 * sizeof(float));
    uint32_t *idx = malloc(ni * sizeof(uint32_t));
    size_t v = 0, k = 0;
    for (int r = 0; r <= rings && p && n; r++) {
        float theta = (float)MATH_PI * (float)r / (float)rings;
        for (int s = 0; s <= segments; s++, v++) {
            float phi = 2.0f * (float)MATH_PI * (float)s / (float)segments;
            float x = sinf(theta) * cosf(phi), y = cosf(theta), z = -sinf(theta) * sinf(phi);
            n[v * 3] = x;
            n[v * 3 + 1] = y;
            n[v * 3 + 2] = z;
            p[v * 3] = radius * x;
            p[v * 3 + 1] = radius * y;
            p[v * 3 + 2] = radius * z;
        }
    }
    for (int r = 0; r < rings && idx; r++)
        for (int s = 0; s < segments; s++) {
            uint32_t a = (uint32_t)(r * (segments + 1) + s), b = a + (uint32_t)segments + 1;
            /* counter-clockwise seen from outside */
            idx[k++] = a; idx[k++] = b; idx[k++] = a + 1;
            idx[k++] = a + 1; idx[k++] = b; idx[k++] = b + 1;
        }
    struct mesh *m = mesh_create_from_arrays("sphere", p, n, nv, idx, ni, err);
    if (!m || !add_texcoords(m, err))
        return NULL;
    m->sphere_radius = radius;
    /* u around the axis (from +x towards -z, as phi runs), v from the top pole down */
    for (int r = 0, vi = 0; r <= rings; r++)
        for (int s = 0; s <= segments; s++, vi++) {
            m->texcoords[0][vi * 2] = (float)s / (float)segments;
            m->texcoords[0][vi * 2 + 1] = (float)r / (float)rings;
        }
    return m;
}

struct mesh *mesh_create_grid(float size, int resolution, struct error *err)
{
    if (!(size > 0.0f) || !isfinite(size) || resolution < 1 || resolution > 4096) {
        error_set(err, "grid: size must be > 0 and resolution in 1..4096 (got %g, %d)", (double)size, resolution);
        return NULL;
    }
    return mesh_create_grid_xz(size, size, resolution, resolution, err);
}

struct mesh *mesh_create_grid_xz(float size_x, float size_z, int cells_x, int cells_z, struct error *err)
{
    if (!(size_x > 0.0f) || !(size_z > 0.0f) || !isfinite(size_x) || !isfinite(size_z) || cells_x < 1 ||
        cells_z < 1 || cells_x > 4096 || cells_z > 4096) {
        error_set(err, "grid: sizes must be > 0 and cells in 1..4096 (got %g x %g, %d x %d)", (double)size_x,
                  (double)size_z, cells_x, cells_z);
        return NULL;
    }
    size_t side_x = (size_t)cells_x + 1, side_z = (size_t)cells_z + 1;
    size_t nv, ni;
    mesh_grid_counts(cells_x, cells_z, &nv, &ni);
    float *p = malloc(nv * 3 * sizeof(float)), *n = malloc(nv * 3 * sizeof(float));
    uint32_t *idx = malloc(ni * sizeof(uint32_t));
    for (size_t j = 0; j < side_z && p && n; j++)
        for (size_t i = 0; i < side_x; i++) {
            size_t v = j * side_x + i;
            p[v * 3] = size_x * ((float)i / (float)cells_x - 0.5f);
            p[v * 3 + 1] = 0.0f;
            p[v * 3 + 2] = size_z * ((float)j / (float)cells_z - 0.5f);
            n[v * 3] = 0.0f;
            n[v * 3 + 1] = 1.0f;
            n[v * 3 + 2] = 0.0f;
        }
    size_t k = 0;
    for (size_t j = 0; j < (size_t)cells_z && idx; j++)
        for (size_t i = 0; i < (size_t)cells_x; i++) {
            uint32_t a = (uint32_t)(j * side_x + i), b = a + (uint32_t)side_x;
            /* +Y faces up: counter-clockwise seen from above */
            idx[k++] = a; idx[k++] = b; idx[k++] = a + 1;
            idx[k++] = a + 1; idx[k++] = b; idx[k++] = b + 1;
        }
    struct mesh *m = mesh_create_from_arrays("grid", p, n, nv, idx, ni, err);
    if (!m || !add_texcoords(m, err))
        return NULL;
    /* u along +x, v along +z: [0,1]^2 over the whole grid, so a texture
     * seen from above reads as its image with the top row at -z */
    for (size_t j = 0; j < side_z; j++)
        for (size_t i = 0; i < side_x; i++) {
            m->texcoords[0][(j * side_x + i) * 2] = (float)i / (float)cells_x;
            m->texcoords[0][(j * side_x + i) * 2 + 1] = (float)j / (float)cells_z;
        }
    return m;
}

struct mesh *mesh_create_torus(float radius, float tube, int segments, int sides, struct error *err)
{
    if (!(radius > 0.0f) || !(tube > 0.0f) || !isfinite(radius) || tube >= radius || segments < 3 || sides < 3 ||
        segments > 4096 || sides > 4096) {
        error_set(err, "torus: radius > tube > 0 and segments, sides in 3..4096 expected");
        return NULL;
    }
    size_t nv, ni;
    mesh_torus_counts(segments, sides, &nv, &ni);
    float *p = malloc(nv * 3 * sizeof(float)), *n = malloc(nv * 3 * sizeof(float));
    uint32_t *idx = malloc(ni * sizeof(uint32_t));
    size_t v = 0, k = 0;
    for (int i = 0; i <= segments && p && n; i++) {
        float u = 2.0f * (float)MATH_PI * (float)i / (float)segments;
        for (int j = 0; j <= sides; j++, v++) {
            float w = 2.0f * (float)MATH_PI * (float)j / (float)sides;
            /* ring in the xz plane, tube around it */
            vec3 nn = {cosf(w) * cosf(u), sinf(w), cosf(w) * sinf(u)};
            n[v * 3] = nn.x;
            n[v * 3 + 1] = nn.y;
            n[v * 3 + 2] = nn.z;
            p[v * 3] = (radius + tube * cosf(w)) * cosf(u);
            p[v * 3 + 1] = tube * sinf(w);
            p[v * 3 + 2] = (radius + tube * cosf(w)) * sinf(u);
        }
    }
    for (int i = 0; i < segments && idx; i++)
        for (int j = 0; j < sides; j++) {
            uint32_t a = (uint32_t)(i * (sides + 1) + j), b = a + (uint32_t)sides + 1;
            idx[k++] = a; idx[k++] = a + 1; idx[k++] = b;
            idx[k++] = b; idx[k++] = a + 1; idx[k++] = b + 1;
        }
    struct mesh *m = mesh_create_from_arrays("torus", p, n, nv, idx, ni, err);
    if (!m || !add_texcoords(m, err))
        return NULL;
    for (int i = 0, vi = 0; i <= segments; i++)
        for (int j = 0; j <= sides; j++, vi++) {
            m->texcoords[0][vi * 2] = (float)i / (float)segments;
            m->texcoords[0][vi * 2 + 1] = (float)j / (float)sides;
        }
    return m;
}

struct mesh *mesh_create_plane(float size, int subdivisions, struct error *err)
{
    struct mesh *m = mesh_create_grid(size, subdivisions, err);
    if (m)
        snprintf(m->name, sizeof m->name, "plane");
    return m;
}

struct mesh *mesh_create_box(vec3 size, struct error *err)
{
    if (!(size.x > 0 && size.y > 0 && size.z > 0) || !math_finite3(size)) {
        error_set(err, "box: every side must be finite and > 0");
        return NULL;
    }
    static const float normals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    float *p = malloc(24 * 3 * sizeof(float)), *n = malloc(24 * 3 * sizeof(float));
    uint32_t *idx = malloc(36 * sizeof(uint32_t));
    if (p && n && idx)
        for (int f = 0; f < 6; f++) {
            vec3 nn = {normals[f][0], normals[f][1], normals[f][2]};
            /* two axes spanning the face, ordered so that u x v = n */
            vec3 u = fabsf(nn.y) > 0.5f ? vec3_make(1, 0, 0) : vec3_make(0, 1, 0);
            vec3 v = vec3_cross(nn, u);
            u = vec3_cross(v, nn);
            static const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (int c = 0; c < 4; c++) {
                vec3 q = vec3_add(nn, vec3_add(vec3_scale(u, corners[c][0]), vec3_scale(v, corners[c][1])));
                int vi = f * 4 + c;
                p[vi * 3] = q.x * size.x * 0.5f;
                p[vi * 3 + 1] = q.y * size.y * 0.5f;
                p[vi * 3 + 2] = q.z * size.z * 0.5f;
                n[vi * 3] = nn.x;
                n[vi * 3 + 1] = nn.y;
                n[vi * 3 + 2] = nn.z;
            }
            uint32_t b = (uint32_t)f * 4;
            uint32_t *t = idx + f * 6;
            t[0] = b; t[1] = b + 1; t[2] = b + 2; t[3] = b; t[4] = b + 2; t[5] = b + 3;
        }
    struct mesh *m = mesh_create_from_arrays("box", p, n, 24, idx, 36, err);
    if (!m || !add_texcoords(m, err))
        return NULL;
    /* Each face holds the whole [0,1]^2. */
    static const float face_uv[4][2] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    for (int vi = 0; vi < 24; vi++) {
        m->texcoords[0][vi * 2] = face_uv[vi % 4][0];
        m->texcoords[0][vi * 2 + 1] = face_uv[vi % 4][1];
    }
    return m;
}

size_t mesh_texture_bytes(const struct mesh *m)
{
    if (!m)
        return 0;
    /* a part's textures are its material's own; the mesh's material holds
     * its first part's again (a reference, not a copy) */
    size_t bytes = 0;
    for (int p = 0; p < m->part_count; p++)
        bytes += mesh_texture_bytes(m->parts[p]);
    if (m->has_material && m->part_count == 0)
        bytes += texture_bytes(m->material.base_color.texture) + texture_bytes(m->material.normal.texture) +
                 texture_bytes(m->material.emissive.texture) + texture_bytes(m->material.transmission_map.texture);
    return bytes;
}

void mesh_retain(struct mesh *m)
{
    if (m)
        m->references++;
}

void mesh_destroy(struct mesh *m)
{
    if (!m || --m->references > 0)
        return;
    free(m->positions);
    free(m->normals);
    free(m->indices);
    free(m->target_positions);
    free(m->target_normals);
    free(m->thickness);
    free(m->texcoords[0]);
    free(m->texcoords[1]);
    free(m->colors);
    free(m->tangents);
    free(m->joints);
    free(m->joint_weights);
    material_release(&m->material);
    for (int p = 0; p < m->part_count; p++)
        mesh_destroy(m->parts[p]);
    free(m->parts);
    free(m);
}
