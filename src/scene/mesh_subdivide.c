/* Midpoint subdivision of a mesh's triangles, for the per-vertex light
 * transport table of Iwasaki et al. (scene/transport.c): the table samples
 * the light's path at the vertices and illumination_textures builds one
 * illumination volume per triangle from its three vertices' paths (§4.1,
 * Fig. 3), which assumes the path varies smoothly across a triangle. A
 * cube's face is two triangles whose corners' light leaves through
 * different faces: the volumes came out torn and no caustic was drawn at
 * all. Splitting every triangle into four, level after level, until the
 * longest edge is short against the object, keeps each volume's three
 * paths close (the surface stays exactly where it was: the new vertices lie
 * on the old triangles). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

float mesh_longest_edge(const struct mesh *m)
{
    float longest = 0.0f;
    for (size_t k = 0; k + 2 < m->index_count; k += 3)
        for (int e = 0; e < 3; e++) {
            const float *a = m->positions + (size_t)m->indices[k + (size_t)e] * 3;
            const float *b = m->positions + (size_t)m->indices[k + (size_t)(e + 1) % 3] * 3;
            float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
            longest = fmaxf(longest, sqrtf(dx * dx + dy * dy + dz * dz));
        }
    return longest;
}

int mesh_subdivision_levels(const struct mesh *m, float max_edge, size_t max_triangles)
{
    size_t triangles = m->index_count / 3;
    float longest = mesh_longest_edge(m);
    int levels = 0;
    while (longest > max_edge && triangles * 4 <= max_triangles && levels < 16) {
        longest *= 0.5f;
        triangles *= 4;
        levels++;
    }
    return levels;
}

/* One level: each edge's midpoint made once (an open-addressing table keyed
 * by the edge's two vertices), so neighbouring triangles share it. */
static struct mesh *subdivide_once(const struct mesh *m, struct error *err)
{
    size_t nt = m->index_count / 3, edges_max = nt * 3, slots = 16;
    while (slots < edges_max * 2)
        slots <<= 1;
    size_t nv_max = m->vertex_count + edges_max;
    float *pos = malloc(nv_max * 3 * sizeof *pos), *nrm = malloc(nv_max * 3 * sizeof *nrm);
    uint32_t *idx = malloc(nt * 12 * sizeof *idx);
    uint64_t *keys = malloc(slots * sizeof *keys);
    uint32_t *values = malloc(slots * sizeof *values);
    if (!pos || !nrm || !idx || !keys || !values || nv_max > UINT32_MAX) {
        free(pos);
        free(nrm);
        free(idx);
        free(keys);
        free(values);
        error_set(err, "%s: out of memory subdividing %zu triangles", m->name, nt);
        return NULL;
    }
    memset(keys, 0xff, slots * sizeof *keys);
    memcpy(pos, m->positions, m->vertex_count * 3 * sizeof *pos);
    memcpy(nrm, m->normals, m->vertex_count * 3 * sizeof *nrm);
    size_t nv = m->vertex_count;
    for (size_t t = 0; t < nt; t++) {
        uint32_t v[3] = {m->indices[t * 3], m->indices[t * 3 + 1], m->indices[t * 3 + 2]}, mid[3];
        for (int e = 0; e < 3; e++) {
            uint32_t a = v[e], b = v[(e + 1) % 3], lo = a < b ? a : b, hi = a < b ? b : a;
            uint64_t key = (uint64_t)lo << 32 | hi;
            size_t h = (size_t)((key * 0x9E3779B97F4A7C15ull) >> 20) & (slots - 1);
            while (keys[h] != UINT64_MAX && keys[h] != key)
                h = (h + 1) & (slots - 1);
            if (keys[h] == key) {
                mid[e] = values[h];
                continue;
            }
            keys[h] = key;
            values[h] = mid[e] = (uint32_t)nv;
            float n[3], len = 0.0f;
            for (int c = 0; c < 3; c++) {
                pos[nv * 3 + (size_t)c] = 0.5f * (pos[(size_t)a * 3 + (size_t)c] + pos[(size_t)b * 3 + (size_t)c]);
                n[c] = nrm[(size_t)a * 3 + (size_t)c] + nrm[(size_t)b * 3 + (size_t)c];
                len += n[c] * n[c];
            }
            len = sqrtf(len);
            for (int c = 0; c < 3; c++) /* opposite normals (a crease folded flat): keep the first's */
                nrm[nv * 3 + (size_t)c] = len > 1e-12f ? n[c] / len : nrm[(size_t)a * 3 + (size_t)c];
            nv++;
        }
        const uint32_t tris[4][3] = {{v[0], mid[0], mid[2]}, {mid[0], v[1], mid[1]}, {mid[2], mid[1], v[2]},
                                     {mid[0], mid[1], mid[2]}};
        memcpy(idx + t * 12, tris, sizeof tris);
    }
    free(keys);
    free(values);
    return mesh_create_from_arrays(m->name, pos, nrm, nv, idx, nt * 12, err);
}

struct mesh *mesh_create_subdivided(const struct mesh *m, int levels, struct error *err)
{
    struct mesh *out = NULL;
    const struct mesh *from = m;
    for (int l = 0; l < levels; l++) {
        struct mesh *next = subdivide_once(from, err);
        if (out)
            mesh_destroy(out);
        if (!next)
            return NULL;
        out = next;
        from = out;
    }
    return out;
}

const struct mesh *mesh_table_mesh(struct mesh_table_fine *c, const struct mesh *m, float edge_fraction,
                                   size_t max_triangles, struct error *err)
{
    float diagonal = vec3_length(vec3_sub(m->bounds_max, m->bounds_min));
    int levels = mesh_subdivision_levels(m, edge_fraction * diagonal, max_triangles);
    if (levels == 0)
        return m;
    if (!c->fine || c->of != m->serial || c->levels != levels) {
        mesh_table_fine_release(c);
        c->fine = mesh_create_subdivided(m, levels, err);
        if (!c->fine)
            return NULL;
        c->of = m->serial;
        c->levels = levels;
    }
    return c->fine;
}

void mesh_table_fine_release(struct mesh_table_fine *c)
{
    if (c->fine)
        mesh_destroy(c->fine);
    *c = (struct mesh_table_fine){0};
}
