/* Iwasaki et al.'s illumination volumes and planes on the CPU (see
 * illumination_geometry.h). */
#include "passes/illumination_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/array.h"

/* One glass vertex this frame: where it is, and the light leaving for it. */
struct vertex_path {
    vec3 world, exit_position, exit_direction, transmittance;
    bool ok;
};

/* The light sample's direction at p (travelling away from the light). */
static vec3 light_direction(const struct frame_light *light, vec3 p)
{
    return light->kind == LIGHT_DIRECTIONAL ? light->direction
                                            : vec3_normalize_or(vec3_sub(p, light->position), vec3_make(0, -1, 0));
}

bool illum_volumes_collect(const struct mesh *m, const struct transport_table *table, mat4 model,
                           const struct frame_light *light, struct illum_volume_list *out, struct error *err)
{
    mat4 inverse;
    if (!mat4_inverse(model, &inverse))
        return true; /* a collapsed object lets nothing through */
    size_t nv = m->vertex_count;
    struct vertex_path *vp = malloc((nv > 0 ? nv : 1) * sizeof *vp);
    if (!vp)
        return error_set(err, "illumination_textures: out of memory");
    for (size_t v = 0; v < nv; v++) {
        vec3 pw = mat4_transform_point(model, vec3_make(m->positions[v * 3], m->positions[v * 3 + 1],
                                                        m->positions[v * 3 + 2]));
        vec3 dw = light_direction(light, pw);
        /* the light's direction in the object's frame: a rotation or
         * translation of the object needs no new table */
        vec3 dl = vec3_normalize_or(mat4_transform_dir(inverse, dw), dw);
        vec3 lp, ld;
        vp[v].world = pw;
        vp[v].ok = transport_lookup(table, v, dl, &lp, &ld, &vp[v].transmittance);
        if (vp[v].ok) {
            vp[v].exit_position = mat4_transform_point(model, lp);
            vp[v].exit_direction = vec3_normalize_or(mat4_transform_dir(model, ld), dw);
        }
    }
    for (size_t k = 0; k + 2 < m->index_count; k += 3) {
        const struct vertex_path *a = &vp[m->indices[k]], *b = &vp[m->indices[k + 1]], *c = &vp[m->indices[k + 2]];
        if (!a->ok || !b->ok || !c->ok)
            continue;
        vec3 pa = a->world, pb = b->world, pc = c->world;
        vec3 cr = vec3_cross(vec3_sub(pb, pa), vec3_sub(pc, pa));
        float area2 = vec3_length(cr);
        if (!(area2 > 1e-20f))
            continue; /* a zero-area triangle carries no light */
        vec3 centre = vec3_scale(vec3_add(vec3_add(pa, pb), pc), 1.0f / 3.0f);
        vec3 dw = light_direction(light, centre);
        float cos_theta = -vec3_dot(vec3_scale(cr, 1.0f / area2), dw);
        if (cos_theta <= 0.0f)
            continue; /* faces away from the light */
        /* eq. 1: L_in cos(theta) S, the flux through the triangle, times F_t */
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
        vec3 ft = vec3_scale(vec3_add(vec3_add(a->transmittance, b->transmittance), c->transmittance), 1.0f / 3.0f);
        if (!array_grow((void **)&out->items, &out->capacity, out->count, sizeof *out->items, err)) {
            free(vp);
            return error_prefix(err, "illumination_textures");
        }
        out->items[out->count++] = (struct illum_volume){
            .o = {a->exit_position, b->exit_position, c->exit_position},
            .d = {a->exit_direction, b->exit_direction, c->exit_direction},
            .flux = vec3_scale(vec3_mul(e, ft), 0.5f * area2 * cos_theta)};
    }
    free(vp);
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

bool illum_flux_square(const struct illum_volume_list *vols, vec3 d, vec3 u, vec3 v, const float *depth, int planes,
                       float limit, float *cu, float *cv, float *half)
{
    float umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
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
    if (nw > 0) {
        weighted_range(wu, nw, 0.005f, 0.995f, &umin, &umax);
        weighted_range(wv, nw, 0.005f, 0.995f, &vmin, &vmax);
    }
    free(wu);
    free(wv);
    if (!(umin <= umax) || !(vmin <= vmax))
        return false;
    *half = clampf(0.5f * fmaxf(umax - umin, vmax - vmin) * 1.05f, 1e-4f, fmaxf(limit, 1e-4f));
    *cu = 0.5f * (umin + umax);
    *cv = 0.5f * (vmin + vmax);
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

static void put_vertex(float *o, vec3 p, vec3 intensity, vec3 dir)
{
    o[0] = p.x, o[1] = p.y, o[2] = p.z;
    o[3] = intensity.x, o[4] = intensity.y, o[5] = intensity.z;
    o[6] = dir.x, o[7] = dir.y, o[8] = dir.z;
}

bool illum_intersect(const struct illum_volume_list *vols, vec3 d, vec3 u, vec3 v, const float *depth, int planes,
                     float cu, float cv, float half, int size, struct illum_intersections *out, struct error *err)
{
    memset(out, 0, sizeof *out);
    float texel = 2.0f * half / (float)size, texel_area = texel * texel;
    size_t nverts = (size_t)vols->count * (size_t)planes * 3;
    out->triangles = malloc((nverts > 0 ? nverts : 1) * ILLUM_VERTEX_FLOATS * sizeof(float));
    out->points = malloc((nverts > 0 ? nverts : 1) * ILLUM_VERTEX_FLOATS * sizeof(float));
    if (!out->triangles || !out->points) {
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
                 * miss: three points inside it, at barycentric (2/3, 1/6,
                 * 1/6) and its turns, a third of its flux each, one texel
                 * apiece (a sliver spanning several texels spreads along) */
                vec3 dd = vec3_normalize_or(vec3_add(vec3_add(vol->d[0], vol->d[1]), vol->d[2]), d);
                vec3 in = vec3_scale(vol->flux, 1.0f / (3.0f * texel_area * fmaxf(vec3_dot(dd, d), 1e-4f)));
                for (int k = 0; k < 3; k++) {
                    vec3 c = vec3_add(vec3_scale(q[k], 2.0f / 3.0f),
                                      vec3_scale(vec3_add(q[(k + 1) % 3], q[(k + 2) % 3]), 1.0f / 6.0f));
                    put_vertex(out->points + np * ILLUM_VERTEX_FLOATS, c, in, dd);
                    np++;
                }
                continue;
            }
            for (int k = 0; k < 3; k++)
                put_vertex(out->triangles + (n + (size_t)k) * ILLUM_VERTEX_FLOATS, q[k],
                           vec3_scale(vol->flux, 1.0f / (s0 * fmaxf(cd[k], 1e-4f))), vol->d[k]);
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
