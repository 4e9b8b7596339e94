/* Tangent frames for a normal map where a glTF file gives no TANGENT (issue
 * 50), by MikkTSpace's construction (Mikkelsen 2008, "Simulation of
 * Wrinkled Surfaces Revisited", the tangent space Blender bakes and exports
 * normal maps in): each triangle's dp/du, made perpendicular to the vertex
 * normal at each of its corners and normalized, summed per group of
 * corners weighted by the corner's angle (measured in the plane
 * perpendicular to the normal). A group is the corners at one vertex
 * (vertices of equal position, normal and coordinates counted as one)
 * whose triangles map the texture the same way round and are joined
 * through the edges they share there. A vertex of several groups (a
 * mirrored texture's seam, a fold) is split, one frame each, as MikkTSpace
 * splits it; before, its one averaged frame was wrong for every side. w is
 * the orientation: the bitangent n x t * w points up the normal map
 * (glTF's decreasing v), as both renderers read it (common/material.glsl).
 * What is not MikkTSpace's: a triangle with no area in texture space adds
 * nothing (MikkTSpace gives it its neighbours' frame), and a mesh made of
 * quads is taken as the file's triangles (MikkTSpace, given the quads,
 * splits them along its own diagonal). `tests/unit/test_tangents.c` holds
 * the frames to the ones Blender 3.4 exports. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

typedef struct { double x, y, z; } tvec;

static tvec tv_sub(tvec a, tvec b) { return (tvec){a.x - b.x, a.y - b.y, a.z - b.z}; }
static tvec tv_scale(tvec a, double s) { return (tvec){a.x * s, a.y * s, a.z * s}; }
static tvec tv_add(tvec a, tvec b) { return (tvec){a.x + b.x, a.y + b.y, a.z + b.z}; }
static double tv_dot(tvec a, tvec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static tvec tv_of(const float *p) { return (tvec){p[0], p[1], p[2]}; }

/* a unit vector along a, or zero where a has no length */
static tvec tv_normalize_or_zero(tvec a)
{
    double len = sqrt(tv_dot(a, a));
    return len > 1e-20 && isfinite(len) ? tv_scale(a, 1.0 / len) : (tvec){0, 0, 0};
}

/* a minus its part along unit n: in the plane perpendicular to n */
static tvec tv_project(tvec a, tvec n) { return tv_sub(a, tv_scale(n, tv_dot(n, a))); }

/* Vertices of equal position, normal and coordinates are one (MikkTSpace
 * welds them so): sorted by those values, each vertex names the first of
 * its equals. */
struct weld_key {
    float values[8];
    uint32_t vertex;
};

static int weld_compare(const void *a, const void *b)
{
    const struct weld_key *p = a, *q = b;
    int c = memcmp(p->values, q->values, sizeof p->values);
    if (c != 0)
        return c;
    return p->vertex < q->vertex ? -1 : p->vertex > q->vertex;
}

/* Appends copies of vertices src[0..count) to every per-vertex array of m
 * (their indices: vertex_count before, onwards). */
static bool append_vertex_copies(struct mesh *m, const uint32_t *src, size_t count)
{
    size_t n = m->vertex_count, total = n + count;
    struct {
        float **array;
        int comps;
    } arrays[] = {{&m->positions, 3}, {&m->normals, 3}, {&m->texcoords[0], 2}, {&m->texcoords[1], 2},
                  {&m->colors, 4},    {&m->tangents, 4}, {&m->joints, 4},      {&m->joint_weights, 4}};
    for (size_t a = 0; a < sizeof arrays / sizeof arrays[0]; a++) {
        float *old = *arrays[a].array;
        if (!old)
            continue;
        size_t c = (size_t)arrays[a].comps;
        float *grown = realloc(old, total * c * sizeof(float));
        if (!grown)
            return false;
        for (size_t k = 0; k < count; k++)
            memcpy(grown + (n + k) * c, grown + (size_t)src[k] * c, c * sizeof(float));
        *arrays[a].array = grown;
    }
    /* morph targets: target-major (target_count x vertex_count x 3), laid out again */
    float **targets[2] = {&m->target_positions, &m->target_normals};
    for (int a = 0; a < 2 && m->target_count > 0; a++) {
        float *old = *targets[a];
        if (!old)
            continue;
        float *laid = malloc(((size_t)m->target_count * total * 3 + 1) * sizeof(float));
        if (!laid)
            return false;
        for (int t = 0; t < m->target_count; t++) {
            memcpy(laid + (size_t)t * total * 3, old + (size_t)t * n * 3, n * 3 * sizeof(float));
            for (size_t k = 0; k < count; k++)
                memcpy(laid + ((size_t)t * total + n + k) * 3, old + ((size_t)t * n + src[k]) * 3, 3 * sizeof(float));
        }
        free(old);
        *targets[a] = laid;
    }
    free(m->thickness); /* (made on demand, from the vertices as they are) */
    m->thickness = NULL;
    m->vertex_count = total;
    return true;
}

/* Corners at one vertex are in one group when their triangles share an
 * edge from it (the same welded vertices at both ends) and map the texture
 * the same way round: MikkTSpace's groups, found by union-find. */
struct edge_key {
    uint32_t from, to; /* welded vertices */
    int orient;
    uint32_t corner;
};

static int edge_compare(const void *a, const void *b)
{
    const struct edge_key *p = a, *q = b;
    if (p->from != q->from)
        return p->from < q->from ? -1 : 1;
    if (p->to != q->to)
        return p->to < q->to ? -1 : 1;
    if (p->orient != q->orient)
        return p->orient < q->orient ? -1 : 1;
    return p->corner < q->corner ? -1 : p->corner > q->corner;
}

static uint32_t group_find(uint32_t *parent, uint32_t c)
{
    while (parent[c] != c) {
        parent[c] = parent[parent[c]];
        c = parent[c];
    }
    return c;
}

/* What the steps share: the range's corners and what each step leaves. */
struct tangent_work {
    struct mesh *m;
    const float *uv;     /* the normal map's texture coordinates */
    uint32_t *idx;       /* the range's indices */
    size_t corners, nv;  /* its corners; the mesh's vertices before any copy */
    struct weld_key *keys;
    uint32_t *weld;      /* per vertex: the first of its equals */
    int *orient;         /* per corner: 0, 1, or -1 (not made) */
    tvec *part;          /* per corner: its weighted direction */
    tvec *sum;           /* per group (its root corner): the frame's sum */
    uint32_t *parent;    /* union-find over corners */
    struct edge_key *edges;
    size_t nedges;
    uint32_t *owner;     /* per vertex: the group that keeps it, + 1 */
    /* the copies: of vertex src[k] for group copy_group[k]; each group's
     * copies chained from first_copy[group] through next_copy[k] */
    uint32_t *first_copy, *src, *copy_group, *next_copy;
    size_t copies, capacity;
};

static bool tangent_made_here(const struct mesh *m, uint32_t v)
{
    const float *t = m->tangents + (size_t)v * 4;
    return t[0] == 0.0f && t[1] == 0.0f && t[2] == 0.0f; /* else the file's TANGENT */
}

/* 1. weld the vertices to make */
static void weld_vertices(struct tangent_work *w)
{
    size_t nkeys = 0;
    for (size_t i = 0; i < w->corners; i++) {
        uint32_t v = w->idx[i];
        if (v >= w->nv || !tangent_made_here(w->m, v))
            continue;
        struct weld_key *k = &w->keys[nkeys++];
        memcpy(k->values, w->m->positions + (size_t)v * 3, 3 * sizeof(float));
        memcpy(k->values + 3, w->m->normals + (size_t)v * 3, 3 * sizeof(float));
        memcpy(k->values + 6, w->uv + (size_t)v * 2, 2 * sizeof(float));
        k->vertex = v;
    }
    qsort(w->keys, nkeys, sizeof *w->keys, weld_compare);
    for (size_t v = 0; v < w->nv; v++)
        w->weld[v] = (uint32_t)v;
    for (size_t i = 1; i < nkeys; i++)
        if (memcmp(w->keys[i].values, w->keys[i - 1].values, sizeof w->keys[i].values) == 0)
            w->weld[w->keys[i].vertex] = w->weld[w->keys[i - 1].vertex];
}

/* 2. each corner's direction: its triangle's dp/du (MikkTSpace's eq. 18)
 * made perpendicular to the vertex normal, normalized, weighted by the
 * corner's angle in that plane; and the corner's two edges */
static void corner_directions(struct tangent_work *w)
{
    const struct mesh *m = w->m;
    const float *uv = w->uv;
    for (size_t f = 0; f + 2 < w->corners; f += 3) {
        uint32_t v[3] = {w->idx[f], w->idx[f + 1], w->idx[f + 2]};
        w->orient[f] = w->orient[f + 1] = w->orient[f + 2] = -1;
        if (v[0] >= w->nv || v[1] >= w->nv || v[2] >= w->nv)
            continue;
        tvec p[3];
        for (int k = 0; k < 3; k++)
            p[k] = tv_of(m->positions + (size_t)v[k] * 3);
        tvec d1 = tv_sub(p[1], p[0]), d2 = tv_sub(p[2], p[0]);
        double s1 = (double)uv[v[1] * 2] - uv[v[0] * 2], t1 = (double)uv[v[1] * 2 + 1] - uv[v[0] * 2 + 1];
        double s2 = (double)uv[v[2] * 2] - uv[v[0] * 2], t2 = (double)uv[v[2] * 2 + 1] - uv[v[0] * 2 + 1];
        double area = s1 * t2 - s2 * t1;
        if (!(fabs(area) > 1e-20) || !isfinite(area))
            continue; /* no area in texture space: no direction */
        tvec dpdu = tv_scale(tv_sub(tv_scale(d1, t2), tv_scale(d2, t1)), 1.0 / area);
        /* the triangle's orientation in texture space, as MikkTSpace decides
         * it: by the sign of its area there alone (glTF's v runs down) */
        int o = area < 0.0 ? 0 : 1;
        for (int k = 0; k < 3; k++) {
            if (!tangent_made_here(m, v[k]))
                continue;
            size_t c = f + (size_t)k;
            tvec n = tv_normalize_or_zero(tv_of(m->normals + (size_t)v[k] * 3));
            tvec e1 = tv_normalize_or_zero(tv_project(tv_sub(p[(k + 1) % 3], p[k]), n));
            tvec e2 = tv_normalize_or_zero(tv_project(tv_sub(p[(k + 2) % 3], p[k]), n));
            double angle = acos(fmin(fmax(tv_dot(e1, e2), -1.0), 1.0));
            w->orient[c] = o;
            w->part[c] = tv_scale(tv_normalize_or_zero(tv_project(dpdu, n)), angle);
            for (int e = 1; e <= 2; e++)
                w->edges[w->nedges++] = (struct edge_key){w->weld[v[k]], w->weld[v[(k + e) % 3]], o, (uint32_t)c};
        }
    }
}

/* 3. groups: corners at one welded vertex joined through shared edges, and
 * each group's sum */
static void join_groups(struct tangent_work *w)
{
    for (size_t c = 0; c < w->corners; c++)
        w->parent[c] = (uint32_t)c;
    qsort(w->edges, w->nedges, sizeof *w->edges, edge_compare);
    for (size_t i = 1; i < w->nedges; i++) {
        const struct edge_key *a = &w->edges[i], *b = &w->edges[i - 1];
        if (a->from == b->from && a->to == b->to && a->orient == b->orient) {
            uint32_t ra = group_find(w->parent, a->corner), rb = group_find(w->parent, b->corner);
            if (ra != rb)
                w->parent[ra] = rb;
        }
    }
    for (size_t c = 0; c < w->corners; c++)
        if (w->orient[c] >= 0) {
            uint32_t g = group_find(w->parent, (uint32_t)c);
            w->sum[g] = tv_add(w->sum[g], w->part[c]);
        }
}

/* The copy of vertex v made for group g, or UINT32_MAX. */
static uint32_t copy_for(const struct tangent_work *w, uint32_t g, uint32_t v)
{
    for (uint32_t k = w->first_copy[g]; k != UINT32_MAX; k = w->next_copy[k])
        if (w->src[k] == v)
            return k;
    return UINT32_MAX;
}

/* 4. a vertex used by corners of several groups keeps the first group it
 * meets and is copied for each other one (MikkTSpace's split) */
static bool plan_copies(struct tangent_work *w)
{
    memset(w->owner, 0, (w->nv + 1) * sizeof *w->owner);
    for (size_t c = 0; c < w->corners; c++)
        w->first_copy[c] = UINT32_MAX;
    for (size_t c = 0; c < w->corners; c++) {
        if (w->orient[c] < 0)
            continue;
        uint32_t v = w->idx[c], g = group_find(w->parent, (uint32_t)c);
        if (!w->owner[v]) {
            w->owner[v] = g + 1;
            continue;
        }
        if (w->owner[v] == g + 1 || copy_for(w, g, v) != UINT32_MAX)
            continue;
        if (w->copies == w->capacity) {
            w->capacity = w->capacity ? 2 * w->capacity : 64;
            uint32_t *a = realloc(w->src, w->capacity * sizeof *a);
            w->src = a ? a : w->src;
            uint32_t *b = a ? realloc(w->copy_group, w->capacity * sizeof *b) : NULL;
            w->copy_group = b ? b : w->copy_group;
            uint32_t *n = b ? realloc(w->next_copy, w->capacity * sizeof *n) : NULL;
            w->next_copy = n ? n : w->next_copy;
            if (!n)
                return false;
        }
        w->src[w->copies] = v;
        w->copy_group[w->copies] = g;
        w->next_copy[w->copies] = w->first_copy[g];
        w->first_copy[g] = (uint32_t)w->copies++;
    }
    return true;
}

/* 5. each corner's vertex (or its group's copy) takes its group's frame */
static void write_tangents(struct tangent_work *w)
{
    for (size_t c = 0; c < w->corners; c++) {
        if (w->orient[c] < 0)
            continue;
        uint32_t v = w->idx[c], g = group_find(w->parent, (uint32_t)c), to = v;
        if (w->owner[v] != g + 1)
            to = (uint32_t)w->nv + copy_for(w, g, v);
        w->idx[c] = to;
        tvec t = tv_normalize_or_zero(w->sum[g]);
        float *out = w->m->tangents + (size_t)to * 4;
        out[0] = (float)t.x;
        out[1] = (float)t.y;
        out[2] = (float)t.z;
        out[3] = w->orient[c] == 0 ? 1.0f : -1.0f;
    }
}

bool mesh_make_tangents(struct mesh *m, size_t first_index, size_t index_count, int set, struct error *err)
{
    if (set < 0 || set > 1 || !m->texcoords[set] || index_count < 3)
        return true;
    if (!m->tangents) {
        m->tangents = calloc(m->vertex_count * 4 + 1, sizeof(float));
        if (!m->tangents)
            return error_set(err, "%s: out of memory for tangents", m->name);
        for (size_t v = 0; v < m->vertex_count; v++)
            m->tangents[v * 4 + 3] = 1.0f;
    }
    size_t corners = index_count - index_count % 3, nv = m->vertex_count;
    struct tangent_work w = {.m = m, .uv = m->texcoords[set], .idx = m->indices + first_index, .corners = corners,
                             .nv = nv};
    w.keys = malloc((corners + 1) * sizeof *w.keys);
    w.weld = malloc((nv + 1) * sizeof *w.weld);
    w.orient = malloc((corners + 1) * sizeof *w.orient);
    w.part = calloc(corners + 1, sizeof *w.part);
    w.sum = calloc(corners + 1, sizeof *w.sum);
    w.parent = malloc((corners + 1) * sizeof *w.parent);
    w.edges = malloc((2 * corners + 1) * sizeof *w.edges);
    w.owner = malloc((nv + 1) * sizeof *w.owner);
    w.first_copy = malloc((corners + 1) * sizeof *w.first_copy);
    bool ok = w.keys && w.weld && w.orient && w.part && w.sum && w.parent && w.edges && w.owner && w.first_copy;
    if (ok) {
        weld_vertices(&w);
        corner_directions(&w);
        join_groups(&w);
        ok = plan_copies(&w) && (w.copies == 0 || append_vertex_copies(m, w.src, w.copies));
    }
    if (ok) {
        write_tangents(&w);
    }
    free(w.keys);
    free(w.weld);
    free(w.orient);
    free(w.part);
    free(w.sum);
    free(w.parent);
    free(w.edges);
    free(w.owner);
    free(w.first_copy);
    free(w.copy_group);
    free(w.next_copy);
    free(w.src);
    if (!ok)
        return error_set(err, "%s: out of memory making its tangents", m->name);
    return true;
}
