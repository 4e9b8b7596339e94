/* A mesh's part: some of its triangles as a mesh of their own, for a file
 * whose primitives use several materials (each part one material). Parts
 * keep the whole's coordinates, so the group's transform, morph weights
 * and deformer apply to every part alike. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

/* The part's copy of a per-vertex attribute of `comps` floats (NULL where
 * the whole has none, or out of memory: *ok false) */
static float *part_attribute(const float *whole_values, size_t whole_count, const uint32_t *remap, size_t nv,
                             int comps, bool *ok)
{
    if (!*ok || !whole_values)
        return NULL;
    float *values = malloc((nv ? nv : 1) * (size_t)comps * sizeof(float));
    *ok = values != NULL;
    for (size_t v = 0; values && v < whole_count; v++)
        if (remap[v])
            memcpy(values + (remap[v] - 1) * (size_t)comps, whole_values + v * (size_t)comps,
                   (size_t)comps * sizeof(float));
    return values;
}

struct mesh *mesh_create_part(const struct mesh *whole, const char *name, const size_t *first_index,
                              const size_t *index_count, int count, struct error *err)
{
    size_t n_idx = 0;
    for (int r = 0; r < count; r++)
        n_idx += index_count[r];
    /* old vertex -> new vertex + 1 (0: not used yet) */
    uint32_t *remap = calloc(whole->vertex_count ? whole->vertex_count : 1, sizeof *remap);
    uint32_t *indices = malloc((n_idx ? n_idx : 1) * sizeof *indices);
    if (!remap || !indices) {
        free(remap);
        free(indices);
        error_set(err, "%s: out of memory", name);
        return NULL;
    }
    size_t nv = 0, k = 0;
    for (int r = 0; r < count; r++)
        for (size_t i = first_index[r]; i < first_index[r] + index_count[r]; i++) {
            uint32_t v = whole->indices[i];
            if (!remap[v])
                remap[v] = (uint32_t)++nv;
            indices[k++] = remap[v] - 1;
        }
    float *positions = malloc((nv ? nv : 1) * 3 * sizeof(float));
    float *normals = malloc((nv ? nv : 1) * 3 * sizeof(float));
    if (positions && normals) {
        for (size_t v = 0; v < whole->vertex_count; v++)
            if (remap[v]) {
                memcpy(positions + (remap[v] - 1) * 3, whole->positions + v * 3, 3 * sizeof(float));
                memcpy(normals + (remap[v] - 1) * 3, whole->normals + v * 3, 3 * sizeof(float));
            }
    }
    struct mesh *m = mesh_create_from_arrays(name, positions, normals, nv, indices, n_idx, err); /* frees them on failure */
    if (!m) {
        free(remap);
        return NULL;
    }
    bool ok = true;
    for (int set = 0; set < 2; set++)
        m->texcoords[set] = part_attribute(whole->texcoords[set], whole->vertex_count, remap, nv, 2, &ok);
    m->colors = part_attribute(whole->colors, whole->vertex_count, remap, nv, 4, &ok);
    m->tangents = part_attribute(whole->tangents, whole->vertex_count, remap, nv, 4, &ok);
    m->joints = part_attribute(whole->joints, whole->vertex_count, remap, nv, 4, &ok);
    m->joint_weights = part_attribute(whole->joint_weights, whole->vertex_count, remap, nv, 4, &ok);
    m->joint_count = whole->joint_count;
    if (ok && whole->target_count > 0) {
        size_t per = nv * 3, whole_per = whole->vertex_count * 3;
        m->target_positions = malloc(((size_t)whole->target_count * per + 1) * sizeof(float));
        m->target_normals = malloc(((size_t)whole->target_count * per + 1) * sizeof(float));
        ok = m->target_positions && m->target_normals;
        for (int t = 0; ok && t < whole->target_count; t++)
            for (size_t v = 0; v < whole->vertex_count; v++)
                if (remap[v]) {
                    size_t to = (size_t)t * per + (remap[v] - 1) * 3, from = (size_t)t * whole_per + v * 3;
                    memcpy(m->target_positions + to, whole->target_positions + from, 3 * sizeof(float));
                    memcpy(m->target_normals + to, whole->target_normals + from, 3 * sizeof(float));
                }
        if (ok) {
            m->target_count = whole->target_count;
            memcpy(m->default_weights, whole->default_weights, sizeof m->default_weights);
        }
    }
    free(remap);
    if (!ok) {
        error_set(err, "%s: out of memory", name);
        mesh_destroy(m);
        return NULL;
    }
    mesh_compute_bounds(m);
    return m;
}
