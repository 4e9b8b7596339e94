/* Iwasaki et al.'s illumination volumes and planes on the CPU (see
 * illumination_geometry.h). */
#include "passes/helpers/illumination_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/array.h"

/* One glass vertex this frame: where it is, and the light leaving for it. */
struct vertex_path {
    vec3 world, exit_position, exit_direction, transmittance;
    bool ok;
    bool facing; /* the light arrives on its front (its normal against the light) */
};

/* The light sample's direction at p (travelling away from the light). */
static vec3 light_direction(const struct frame_light *light, vec3 p)
{
    return light->kind == LIGHT_DIRECTIONAL ? light->direction
                                            : vec3_normalize_or(vec3_sub(p, light->position), vec3_make(0, -1, 0));
}

/* Vertex v of a mesh array of three floats a vertex (positions, normals). */
static vec3 vertex_vec3(const float *a, size_t v) { return vec3_make(a[v * 3], a[v * 3 + 1], a[v * 3 + 2]); }

/* A path found in the object's frame (`ok`, leaving at lp along ld) taken
 * into the world at `model`; dw, the light's direction there, stands in
 * for a direction that does not normalise. */
static void path_to_world(struct vertex_path *vp, bool ok, mat4 model, vec3 lp, vec3 ld, vec3 dw)
{
    vp->ok = ok;
    if (ok) {
        vp->exit_position = mat4_transform_point(model, lp);
        vp->exit_direction = vec3_normalize_or(mat4_transform_dir(model, ld), dw);
    }
}

bool *illum_flat_vertices(const struct mesh *m, struct error *err)
{
    size_t nv = m->vertex_count;
    bool *flat = malloc(nv > 0 ? nv : 1);
    if (!flat) {
        error_set(err, "illumination_textures: out of memory");
        return NULL;
    }
    for (size_t v = 0; v < nv; v++)
        flat[v] = true;
    for (size_t k = 0; k + 2 < m->index_count; k += 3) {
        const uint32_t *t = m->indices + k;
        vec3 p0 = vertex_vec3(m->positions, t[0]);
        vec3 g = vec3_cross(vec3_sub(vertex_vec3(m->positions, t[1]), p0), vec3_sub(vertex_vec3(m->positions, t[2]), p0));
        float len = vec3_length(g);
        if (!(len > 1e-20f))
            continue;
        for (int c = 0; c < 3; c++)
            if (vec3_dot(vertex_vec3(m->normals, t[c]), g) < 0.9999f * len)
                flat[t[c]] = false;
    }
    return flat;
}

/* The light's intensity arriving at `centre` (per unit area across it). */
static vec3 light_arriving(const struct frame_light *light, vec3 centre, vec3 dw)
{
    vec3 e = light->intensity;
    if (light->kind != LIGHT_DIRECTIONAL) {
        vec3 dd = vec3_sub(centre, light->position);
        e = vec3_scale(e, 1.0f / fmaxf(vec3_dot(dd, dd), 1e-12f));
        if (light->kind == LIGHT_SPOT) {
            float ca = vec3_dot(dw, light->direction), lo = light->cos_outer;
            float hi = fmaxf(light->cos_inner, lo + 1e-4f), x = fminf(fmaxf((ca - lo) / (hi - lo), 0.0f), 1.0f);
            e = vec3_scale(e, x * x * (3.0f - 2.0f * x));
        }
    }
    return e;
}

/* Whether the light of a triangle with these three paths is one volume:
 * every path leaves, and they leave the same way (their directions within
 * ILLUM_PART_COS of each other). Paths that part (by different faces of a
 * cube, or one totally reflected) make no volume to speak of: one spanning
 * both ways would smear the triangle's light over the gap between. */
#define ILLUM_PART_COS 0.9f
static bool paths_agree(const struct vertex_path *a, const struct vertex_path *b, const struct vertex_path *c)
{
    return a->ok && b->ok && c->ok && vec3_dot(a->exit_direction, b->exit_direction) >= ILLUM_PART_COS &&
           vec3_dot(b->exit_direction, c->exit_direction) >= ILLUM_PART_COS &&
           vec3_dot(a->exit_direction, c->exit_direction) >= ILLUM_PART_COS;
}

/* Whether three paths leave nearly parallel (within about 2.5 degrees):
 * the light between them passes as through a thin slab, and a volume
 * spanned by their exact rays is what the light does. */
#define ILLUM_PARALLEL_COS 0.999f
static bool paths_parallel(const struct vertex_path *a, const struct vertex_path *b, const struct vertex_path *c)
{
    return a->ok && b->ok && c->ok && vec3_dot(a->exit_direction, b->exit_direction) >= ILLUM_PARALLEL_COS &&
           vec3_dot(b->exit_direction, c->exit_direction) >= ILLUM_PARALLEL_COS &&
           vec3_dot(a->exit_direction, c->exit_direction) >= ILLUM_PARALLEL_COS;
}

/* A vertex of a curved surface the light meets within about 6 degrees of
 * grazing (cos < 0.1), or whose neighbouring table directions take
 * different paths, is also traced exactly (see illum_volumes_collect). */
#define ILLUM_GRAZING_COS 0.1f

/* eq. 1: the volume of one triangle (world corners and paths), its flux
 * L_in cos(theta) S F_t; nothing for a zero-area triangle or one facing
 * away from the light. */
static bool add_volume(const struct vertex_path *a, const struct vertex_path *b, const struct vertex_path *c,
                       const struct frame_light *light, struct illum_volume_list *out, struct error *err)
{
    vec3 pa = a->world, pb = b->world, pc = c->world;
    vec3 cr = vec3_cross(vec3_sub(pb, pa), vec3_sub(pc, pa));
    float area2 = vec3_length(cr);
    if (!(area2 > 1e-20f))
        return true; /* a zero-area triangle carries no light */
    vec3 centre = vec3_scale(vec3_add(vec3_add(pa, pb), pc), 1.0f / 3.0f);
    vec3 dw = light_direction(light, centre);
    float cos_theta = -vec3_dot(vec3_scale(cr, 1.0f / area2), dw);
    if (cos_theta <= 0.0f)
        return true; /* faces away from the light */
    vec3 e = light_arriving(light, centre, dw);
    vec3 ft = vec3_scale(vec3_add(vec3_add(a->transmittance, b->transmittance), c->transmittance), 1.0f / 3.0f);
    if (!array_grow((void **)&out->items, &out->capacity, out->count, sizeof *out->items, err))
        return error_prefix(err, "illumination_textures");
    out->items[out->count++] = (struct illum_volume){
        .o = {a->exit_position, b->exit_position, c->exit_position},
        .d = {a->exit_direction, b->exit_direction, c->exit_direction},
        .flux = vec3_scale(vec3_mul(e, ft), 0.5f * area2 * cos_theta),
        .entry = centre,
        .to_light = vec3_scale(dw, -1.0f)};
    return true;
}

/* Where the paths of one triangle part: the triangle split in four, level
 * by level, each new corner's path traced exactly, until the paths of a
 * piece agree (a volume) or ILLUM_PART_LEVELS splits leave a piece 1/16 of
 * the triangle's side across the parting line (sliver_volume). */
#define ILLUM_PART_LEVELS 4
struct part_context {
    const struct mesh *m;
    const struct transport_tracer *tracer;
    mat4 model, inverse;
    const struct frame_light *light;
    const uint32_t *tri;
    struct illum_volume_list *out;
    struct error *err;
};

/* The path at barycentric point w of the triangle. The point is taken a
 * hair inside it: light entering exactly on a box's edge meets the next
 * face at distance 0, passes it unseen and leaves by no path (the strips
 * along a cube's edges lost their light). */
static struct vertex_path path_at(const struct part_context *pc, vec3 w)
{
    w = vec3_add(vec3_scale(w, 1.0f - 1e-3f), vec3_make(1e-3f / 3.0f, 1e-3f / 3.0f, 1e-3f / 3.0f));
    vec3 p = {0, 0, 0}, n = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        float wk = k == 0 ? w.x : k == 1 ? w.y : w.z;
        p = vec3_add(p, vec3_scale(vertex_vec3(pc->m->positions, pc->tri[k]), wk));
        n = vec3_add(n, vec3_scale(vertex_vec3(pc->m->normals, pc->tri[k]), wk));
    }
    struct vertex_path vp = {.world = mat4_transform_point(pc->model, p)};
    vec3 dw = light_direction(pc->light, vp.world);
    vec3 dl = vec3_normalize_or(mat4_transform_dir(pc->inverse, dw), dw);
    vec3 lp, ld;
    bool ok = transport_trace(pc->tracer, p, n, dl, &lp, &ld, &vp.transmittance);
    path_to_world(&vp, ok, pc->model, lp, ld, dw);
    return vp;
}

/* A piece still across the parting line after the last split: its light
 * goes the way of the most corners whose paths agree (the others' paths
 * replaced by one of theirs), so what enters leaves somewhere near where it
 * should rather than nowhere; a corner whose light leaves by no path at all
 * adds none (its transmittance 0). */
static bool sliver_volume(const struct vertex_path v[3], const struct frame_light *light,
                          struct illum_volume_list *out, struct error *err)
{
    int anchor = -1, best = 0;
    for (int a = 0; a < 3; a++) {
        if (!v[a].ok)
            continue;
        int agree = 1;
        for (int b = 0; b < 3; b++)
            agree += b != a && v[b].ok && vec3_dot(v[a].exit_direction, v[b].exit_direction) >= ILLUM_PART_COS;
        if (agree > best)
            best = agree, anchor = a;
    }
    if (anchor < 0)
        return true;
    struct vertex_path s[3];
    for (int b = 0; b < 3; b++) {
        s[b] = v[b];
        if (b != anchor && !(v[b].ok && vec3_dot(v[anchor].exit_direction, v[b].exit_direction) >= ILLUM_PART_COS)) {
            s[b] = v[anchor];
            s[b].world = v[b].world;
            if (!v[b].ok)
                s[b].transmittance = vec3_make(0, 0, 0);
        }
    }
    return add_volume(&s[0], &s[1], &s[2], light, out, err);
}

static bool part(const struct part_context *pc, const vec3 w[3], const struct vertex_path v[3], int level)
{
    if (paths_agree(&v[0], &v[1], &v[2]))
        return add_volume(&v[0], &v[1], &v[2], pc->light, pc->out, pc->err);
    if (!v[0].ok && !v[1].ok && !v[2].ok && level > 0)
        return true; /* no light leaves here */
    if (level >= ILLUM_PART_LEVELS)
        return sliver_volume(v, pc->light, pc->out, pc->err);
    vec3 mw[3];
    struct vertex_path mv[3];
    for (int k = 0; k < 3; k++) {
        mw[k] = vec3_scale(vec3_add(w[k], w[(k + 1) % 3]), 0.5f); /* the midpoint of edge k, k + 1 */
        mv[k] = path_at(pc, mw[k]);
    }
    const vec3 w0[3] = {w[0], mw[0], mw[2]}, w1[3] = {mw[0], w[1], mw[1]}, w2[3] = {mw[2], mw[1], w[2]},
               w3[3] = {mw[0], mw[1], mw[2]};
    const struct vertex_path v0[3] = {v[0], mv[0], mv[2]}, v1[3] = {mv[0], v[1], mv[1]}, v2[3] = {mv[2], mv[1], v[2]},
                             v3[3] = {mv[0], mv[1], mv[2]};
    return part(pc, w0, v0, level + 1) && part(pc, w1, v1, level + 1) && part(pc, w2, v2, level + 1) &&
           part(pc, w3, v3, level + 1);
}

bool illum_volumes_collect(const struct mesh *m, const struct transport_table *table,
                           const struct transport_tracer *tracer, const bool *flat, mat4 model,
                           const struct frame_light *light, struct illum_volume_list *out, struct error *err)
{
    mat4 inverse;
    if (!mat4_inverse(model, &inverse))
        return true; /* a collapsed object lets nothing through */
    if (!flat)
        tracer = NULL; /* exact tracing is for flat faces only (illum_flat_vertices) */
    size_t nv = m->vertex_count;
    struct vertex_path *vp = malloc((nv > 0 ? nv : 1) * sizeof *vp);
    /* Per vertex of a curved surface near grazing (or whose table
     * directions take different paths), its path traced exactly (exact[v]
     * set). The table's 16 x 16 directions a vertex blend the paths of
     * directions that miss or graze the object there, and shift where the
     * outermost triangles' light lands: under an IOR-1.0 ball it fell 1% of
     * the radius inside the shadow's outline and left a black ring there
     * (issue 52, case 10: 14 pixels at 0 at 256 x 256, 60 at IOR 1.0001).
     * A triangle takes its corners' exact paths only where they leave
     * nearly parallel (paths_parallel): where they fan out (a glass ball's
     * rim at IOR 1.5) one linear volume across the fan spread the light
     * wider than the table's blend does (the ball lens 1.25 radii over its
     * floor 0.062 -> 0.073 against the closed form, measured), so there
     * the paper's table stays. */
    struct vertex_path *traced = tracer ? malloc((nv > 0 ? nv : 1) * sizeof *traced) : NULL;
    bool *exact = tracer ? calloc(nv > 0 ? nv : 1, sizeof *exact) : NULL;
    if (!vp || (tracer && (!traced || !exact))) {
        free(vp);
        free(traced);
        free(exact);
        return error_set(err, "illumination_textures: out of memory");
    }
    for (size_t v = 0; v < nv; v++) {
        vec3 p = vertex_vec3(m->positions, v), n = vertex_vec3(m->normals, v);
        vec3 pw = mat4_transform_point(model, p);
        vec3 dw = light_direction(light, pw);
        /* the light's direction in the object's frame: a rotation or
         * translation of the object needs no new table */
        vec3 dl = vec3_normalize_or(mat4_transform_dir(inverse, dw), dw);
        vec3 lp, ld;
        vp[v].world = pw;
        float cos_in = -vec3_dot(n, dl); /* the light's cosine on the vertex's front */
        vp[v].facing = cos_in > 0.0f;
        bool smooth;
        bool ok = transport_lookup_smooth(table, v, dl, &lp, &ld, &vp[v].transmittance, &smooth);
        if (!smooth && tracer && flat[v]) {
            /* on a flat face the table's directions around this one take
             * different paths: their blend is none of them, so this vertex
             * is traced exactly */
            ok = transport_trace(tracer, p, n, dl, &lp, &ld, &vp[v].transmittance);
        } else if (tracer && cos_in >= -1e-4f && (!smooth || cos_in < ILLUM_GRAZING_COS)) {
            traced[v] = vp[v];
            vec3 tp, td;
            bool tok = transport_trace(tracer, p, n, dl, &tp, &td, &traced[v].transmittance);
            path_to_world(&traced[v], tok, model, tp, td, dw);
            exact[v] = true;
        }
        path_to_world(&vp[v], ok, model, lp, ld, dw);
    }
    struct part_context pc = {m, tracer, model, inverse, light, NULL, out, err};
    for (size_t k = 0; k + 2 < m->index_count; k += 3) {
        const struct vertex_path *a = &vp[m->indices[k]], *b = &vp[m->indices[k + 1]], *c = &vp[m->indices[k + 2]];
        if (exact) {
            uint32_t ia = m->indices[k], ib = m->indices[k + 1], ic = m->indices[k + 2];
            const struct vertex_path *ta = exact[ia] ? &traced[ia] : a, *tb = exact[ib] ? &traced[ib] : b,
                                     *tc = exact[ic] ? &traced[ic] : c;
            if ((ta != a || tb != b || tc != c) && paths_parallel(ta, tb, tc))
                a = ta, b = tb, c = tc;
        }
        bool ok;
        if (paths_agree(a, b, c)) {
            ok = add_volume(a, b, c, light, out, err);
        } else if (tracer && a->facing && b->facing && c->facing && flat[m->indices[k]] &&
                   flat[m->indices[k + 1]] && flat[m->indices[k + 2]]) {
            /* A triangle of a flat face whose paths part, the light arriving
             * on its front: traced exactly where they part (the cube's light
             * leaving by two faces lands on both sides of the line between
             * them, not nowhere). On a curved surface, where paths part at
             * every grazing entry and total internal reflection, it makes no
             * volume, as the paper's table alone would: there its pieces,
             * sub-texel points at grazing angles, made blotches (the turning
             * ball 0.173 -> 0.196 on its first frame, the terminator's pieces
             * 0.205). */
            vec3 cr = vec3_cross(vec3_sub(b->world, a->world), vec3_sub(c->world, a->world));
            vec3 centre = vec3_scale(vec3_add(vec3_add(a->world, b->world), c->world), 1.0f / 3.0f);
            if (vec3_dot(cr, light_direction(light, centre)) >= 0.0f)
                continue;
            pc.tri = m->indices + k;
            const vec3 w[3] = {vec3_make(1, 0, 0), vec3_make(0, 1, 0), vec3_make(0, 0, 1)};
            struct vertex_path v[3];
            for (int q = 0; q < 3; q++)
                v[q] = path_at(&pc, w[q]);
            ok = part(&pc, w, v, 0);
        } else {
            continue; /* the table alone: no volume where the paths part */
        }
        if (!ok) {
            free(vp);
            free(traced);
            free(exact);
            return false;
        }
    }
    free(vp);
    free(traced);
    free(exact);
    return true;
}

vec3 illum_mean_direction(const struct illum_volume_list *vols)
{
    vec3 sum = {0, 0, 0};
    for (int i = 0; i < vols->count; i++) {
        const struct illum_volume *v = &vols->items[i];
        float w = v->flux.x + v->flux.y + v->flux.z;
        sum = vec3_add(sum, vec3_scale(vec3_add(vec3_add(v->d[0], v->d[1]), v->d[2]), w));
    }
    return vec3_normalize_or(sum, vec3_make(0, -1, 0));
}

void illum_planes_spread(float lo, float hi, int planes, float *depth)
{
    for (int i = 0; i < planes; i++)
        depth[i] = planes == 1 ? 0.5f * (lo + hi) : lo + (hi - lo) * (float)i / (float)(planes - 1);
}

struct weighted { float x, w; };

static int compare_weighted(const void *a, const void *b)
{
    float x = ((const struct weighted *)a)->x, y = ((const struct weighted *)b)->x;
    return (x > y) - (x < y);
}

/* The values below which fractions lo and hi of the weight lie. */
static void weighted_range(struct weighted *v, size_t n, float lo, float hi, float *a, float *b)
{
    qsort(v, n, sizeof *v, compare_weighted);
    double total = 0.0, run = 0.0;
    for (size_t i = 0; i < n; i++)
        total += v[i].w;
    *a = v[0].x, *b = v[n - 1].x;
    bool found_a = false;
    for (size_t i = 0; i < n; i++) {
        run += v[i].w;
        if (!found_a && run >= lo * total) {
            *a = v[i].x;
            found_a = true;
        }
        if (run >= hi * total) {
            *b = v[i].x;
            break;
        }
    }
}

/* Where ray o + t dir meets the plane dot(x, d) = depth ahead of o; false
 * for a ray parallel to the plane or the plane behind it. */
static bool plane_hit(vec3 o, vec3 dir, vec3 d, float depth, float *cos_d, vec3 *q)
{
    float cd = vec3_dot(dir, d);
    float t = cd > 1e-4f ? (depth - vec3_dot(o, d)) / cd : -1.0f;
    *cos_d = cd;
    if (!(t >= 0.0f) || !isfinite(t))
        return false;
    *q = vec3_add(o, vec3_scale(dir, t));
    return true;
}

static float clampf(float x, float lo, float hi) { return x < lo ? lo : x > hi ? hi : x; }

/* Where 99% of the volumes' flux crosses the planes (u from range[0] to
 * range[1], v from range[2] to range[3]) and its median; false when none
 * crosses. */
static bool crossing_range(const struct illum_volume_list *vols, vec3 d, vec3 u, vec3 v, const float *depth,
                           int planes, float range[4], float mid[2])
{
    size_t cap = (size_t)vols->count * (size_t)planes;
    struct weighted *wu = malloc((cap > 0 ? cap : 1) * sizeof *wu);
    struct weighted *wv = malloc((cap > 0 ? cap : 1) * sizeof *wv);
    size_t nw = 0;
    for (int i = 0; wu && wv && i < vols->count; i++)
        for (int pl = 0; pl < planes; pl++) {
            const struct illum_volume *vol = &vols->items[i];
            vec3 o = vec3_scale(vec3_add(vec3_add(vol->o[0], vol->o[1]), vol->o[2]), 1.0f / 3.0f);
            vec3 dd = vec3_normalize_or(vec3_add(vec3_add(vol->d[0], vol->d[1]), vol->d[2]), d);
            float cd;
            vec3 q;
            if (!plane_hit(o, dd, d, depth[pl], &cd, &q))
                continue;
            float w = vol->flux.x + vol->flux.y + vol->flux.z;
            wu[nw] = (struct weighted){vec3_dot(q, u), w};
            wv[nw] = (struct weighted){vec3_dot(q, v), w};
            nw++;
        }
    float unused;
    if (nw > 0) {
        weighted_range(wu, nw, 0.005f, 0.995f, &range[0], &range[1]);
        weighted_range(wv, nw, 0.005f, 0.995f, &range[2], &range[3]);
        weighted_range(wu, nw, 0.5f, 1.0f, &mid[0], &unused);
        weighted_range(wv, nw, 0.5f, 1.0f, &mid[1], &unused);
    }
    free(wu);
    free(wv);
    return nw > 0 && range[0] <= range[1] && range[2] <= range[3];
}

bool illum_flux_square(const struct illum_volume_list *vols, vec3 d, vec3 u, vec3 v, const float *depth, int planes,
                       float limit, float *cu, float *cv, float *half)
{
    float range[4], mid[2];
    if (!crossing_range(vols, d, u, v, depth, planes, range, mid))
        return false;
    float want = 0.5f * fmaxf(range[1] - range[0], range[3] - range[2]) * 1.05f;
    *half = clampf(want, 1e-4f, fmaxf(limit, 1e-4f));
    *cu = 0.5f * (range[0] + range[1]);
    *cv = 0.5f * (range[2] + range[3]);
    if (want > *half) {
        /* Wider than the targets: light leaving nearly along the planes (a
         * cube's side faces after a total internal reflection, 10-25% of
         * the flux at IOR 2.42) crosses them far away, to one side. The
         * square keeps the flux's median inside, not the middle of its
         * range, which left the caustic out (a black floor). */
        *cu = clampf(*cu, mid[0] - 0.5f * *half, mid[0] + 0.5f * *half);
        *cv = clampf(*cv, mid[1] - 0.5f * *half, mid[1] + 0.5f * *half);
    }
    return true;
}

bool illum_covers_a_texel_centre(const float a[2], const float b[2], const float c[2])
{
    float x0 = fminf(a[0], fminf(b[0], c[0])), x1 = fmaxf(a[0], fmaxf(b[0], c[0]));
    float y0 = fminf(a[1], fminf(b[1], c[1])), y1 = fmaxf(a[1], fmaxf(b[1], c[1]));
    float area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (area == 0.0f)
        return false;
    for (float y = floorf(y0 - 0.5f) + 0.5f; y <= y1; y += 1.0f)
        for (float x = floorf(x0 - 0.5f) + 0.5f; x <= x1; x += 1.0f) {
            float e0 = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
            float e1 = (c[0] - b[0]) * (y - b[1]) - (c[1] - b[1]) * (x - b[0]);
            float e2 = (a[0] - c[0]) * (y - c[1]) - (a[1] - c[1]) * (x - c[0]);
            if (area > 0.0f ? (e0 >= 0 && e1 >= 0 && e2 >= 0) : (e0 <= 0 && e1 <= 0 && e2 <= 0))
                return true;
        }
    return false;
}

static void put_vertex(float *o, vec3 p, vec3 intensity, vec3 dir, const struct illum_volume *vol)
{
    o[0] = p.x, o[1] = p.y, o[2] = p.z;
    o[3] = intensity.x, o[4] = intensity.y, o[5] = intensity.z;
    o[6] = dir.x, o[7] = dir.y, o[8] = dir.z;
    o[9] = vol->entry.x, o[10] = vol->entry.y, o[11] = vol->entry.z;
    o[12] = vol->to_light.x, o[13] = vol->to_light.y, o[14] = vol->to_light.z;
}

#define ILLUM_SLIVER_SPLIT 3
bool illum_intersect(const struct illum_volume_list *vols, vec3 d, vec3 u, vec3 v, const float *depth, int planes,
                     float cu, float cv, float half, int size, struct illum_intersections *out, struct error *err)
{
    memset(out, 0, sizeof *out);
    float texel = 2.0f * half / (float)size, texel_area = texel * texel;
    size_t nverts = (size_t)vols->count * (size_t)planes * 3;
    out->triangles = malloc((nverts > 0 ? nverts : 1) * ILLUM_VERTEX_FLOATS * sizeof(float));
    int point_capacity = 0;
    if (!out->triangles) {
        illum_intersections_release(out);
        return error_set(err, "illumination_textures: out of memory for %zu vertices", nverts);
    }
    size_t n = 0, np = 0;
    for (int pl = 0; pl < planes; pl++) {
        out->first[pl] = n;
        out->point_first[pl] = np;
        for (int i = 0; i < vols->count; i++) {
            const struct illum_volume *vol = &vols->items[i];
            vec3 q[3];
            float cd[3];
            bool valid = true;
            for (int k = 0; k < 3 && valid; k++)
                valid = plane_hit(vol->o[k], vol->d[k], d, depth[pl], &cd[k], &q[k]);
            if (!valid)
                continue; /* a ray parallel to the plane, or the plane behind where it leaves */
            float s0 = 0.5f * vec3_length(vec3_cross(vec3_sub(q[1], q[0]), vec3_sub(q[2], q[0])));
            bool tiny = !(s0 >= texel_area);
            if (!tiny && s0 < 16.0f * texel_area) {
                /* a triangle a few texels across that no texel centre falls
                 * in would be lost by the rasterizer: a point instead */
                float t2[3][2];
                for (int k = 0; k < 3; k++) {
                    t2[k][0] = ((vec3_dot(q[k], u) - cu) / (2.0f * half) + 0.5f) * (float)size;
                    t2[k][1] = ((vec3_dot(q[k], v) - cv) / (2.0f * half) + 0.5f) * (float)size;
                }
                tiny = !illum_covers_a_texel_centre(t2[0], t2[1], t2[2]);
            }
            if (tiny) {
                /* S_0 -> 0 (a focus on the plane), or a triangle the texels
                 * miss: points inside it, one texel apiece, each an equal
                 * share of its flux. Up to a texel long: three, at
                 * barycentric (2/3, 1/6, 1/6) and its turns. Longer (a
                 * sliver): the triangle cut into m x m equal ones, m its
                 * longest side in texels (at most ILLUM_SLIVER_SPLIT), a
                 * point at each one's centroid (their mean is the whole
                 * one's: nothing shifts; a row of points along the longest
                 * side alone came out 3x worse on a ball at IOR 10). Three
                 * points alone left holes and spikes where slivers fan out
                 * of a pole (a UV sphere's top seen along its axis). */
                vec3 dd = vec3_normalize_or(vec3_add(vec3_add(vol->d[0], vol->d[1]), vol->d[2]), d);
                float longest = fmaxf(fmaxf(vec3_length(vec3_sub(q[1], q[0])), vec3_length(vec3_sub(q[2], q[1]))),
                                      vec3_length(vec3_sub(q[0], q[2])));
                int m = (int)fminf(fmaxf(ceilf(longest / texel), 1.0f), (float)ILLUM_SLIVER_SPLIT);
                int count = m == 1 ? 3 : m * m;
                vec3 in = vec3_scale(vol->flux, 1.0f / ((float)count * texel_area * fmaxf(vec3_dot(dd, d), 1e-4f)));
                for (int k = 0; k < count; k++) {
                    if (!array_grow((void **)&out->points, &point_capacity, (int)np, ILLUM_VERTEX_FLOATS * sizeof(float),
                                    err)) {
                        illum_intersections_release(out);
                        return error_prefix(err, "illumination_textures");
                    }
                    float w[3];
                    if (m == 1) {
                        w[k] = 2.0f / 3.0f, w[(k + 1) % 3] = w[(k + 2) % 3] = 1.0f / 6.0f;
                    } else {
                        /* the k-th small triangle: m (m + 1) / 2 pointing as the
                         * whole, then (m - 1) m / 2 turned over, row by row */
                        int up = m * (m + 1) / 2, j = k < up ? k : k - up, row = 0, rows = k < up ? m : m - 1;
                        while (j >= rows - row) {
                            j -= rows - row;
                            row++;
                        }
                        float shift = k < up ? 1.0f / 3.0f : 2.0f / 3.0f;
                        w[0] = ((float)row + shift) / (float)m;
                        w[1] = ((float)j + shift) / (float)m;
                        w[2] = 1.0f - w[0] - w[1];
                    }
                    vec3 c = vec3_add(vec3_add(vec3_scale(q[0], w[0]), vec3_scale(q[1], w[1])), vec3_scale(q[2], w[2]));
                    put_vertex(out->points + np * ILLUM_VERTEX_FLOATS, c, in, dd, vol);
                    np++;
                }
                continue;
            }
            for (int k = 0; k < 3; k++)
                put_vertex(out->triangles + (n + (size_t)k) * ILLUM_VERTEX_FLOATS, q[k],
                           vec3_scale(vol->flux, 1.0f / (s0 * fmaxf(cd[k], 1e-4f))), vol->d[k], vol);
            n += 3;
        }
        out->count[pl] = n - out->first[pl];
        out->point_count[pl] = np - out->point_first[pl];
    }
    out->triangle_vertices = n;
    out->point_vertices = np;
    return true;
}

void illum_intersections_release(struct illum_intersections *x)
{
    free(x->triangles);
    free(x->points);
    x->triangles = x->points = NULL;
}
