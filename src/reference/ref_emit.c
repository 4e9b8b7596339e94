/* Photon emission towards the specular triangles (ref_emit.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vecmath.h"
#include "reference/ref_emit.h"

static dvec3 vertex(const struct ref_object *o, uint32_t i)
{
    const float *p = o->positions + (size_t)i * 3;
    return dv(p[0], p[1], p[2]);
}

/* An exact sphere (ref_scene.c) is aimed at through its triangles blown up
 * about its centre until every triangle's plane lies at least a radius
 * away: the inscribed tessellation's outline falls short of the sphere's
 * (a ring of 1 - sin(2 pi / n) / (2 pi / n) of its silhouette for n
 * segments: 10% at 8, 3e-5 at 512) and the light through that ring would
 * never be aimed at; the blown-up one contains the sphere, so its facets
 * that face the light tile the sphere's whole outline as the light sees it
 * (a photon through the corners outside the sphere meets something else
 * first and is dropped: that light is counted where it lands). 1 for any
 * other object. */
static double aim_scale(const struct ref_object *o)
{
    if (!o->sphere)
        return 1.0;
    double nearest = o->sphere_radius;
    for (size_t t = 0; t < o->triangle_count; t++) {
        const uint32_t *tri = o->indices + t * 3;
        dvec3 a = vertex(o, tri[0]), b = vertex(o, tri[1]), c = vertex(o, tri[2]);
        dvec3 n2 = dv_cross(dv_sub(b, a), dv_sub(c, a));
        double len = sqrt(dv_dot(n2, n2));
        if (!(len > 1e-12 * o->sphere_radius * o->sphere_radius))
            continue; /* the poles' slivers: no plane, no measure */
        double d = fabs(dv_dot(n2, dv_sub(a, o->sphere_center))) / len;
        if (d > 1e-3 * o->sphere_radius)
            nearest = fmin(nearest, d);
    }
    return o->sphere_radius / nearest * (1.0 + 1e-9);
}

/* Vertex i of o as the photons aim at it: scaled by `scale` about an exact
 * sphere's centre (aim_scale). */
static dvec3 aim_vertex(const struct ref_object *o, uint32_t i, double scale)
{
    dvec3 p = vertex(o, i);
    return o->sphere ? dv_add(o->sphere_center, dv_scale(dv_sub(p, o->sphere_center), scale)) : p;
}

/* How much of the light's view a triangle covers, and whether it faces the
 * light: a dielectric only on its outer side (lights sit outside every
 * dielectric, so a light ray enters one through a triangle whose outward
 * normal faces it; a closed mesh's far side is never a first hit), a
 * mirror on either side (it may be an open sheet). */
static double triangle_weight(const struct ref_light *l, const struct ref_object *o, dvec3 a, dvec3 b, dvec3 c)
{
    const struct material *m = &o->material;
    dvec3 n2 = dv_cross(dv_sub(b, a), dv_sub(c, a)); /* twice the area times the unit normal */
    double area = 0.5 * sqrt(dv_dot(n2, n2));
    if (!(area > 0.0) || !isfinite(area))
        return 0.0; /* zero-area triangles have no measure to hit */
    dvec3 n = dv_scale(n2, 0.5 / area);
    double facing; /* cosine between the normal and the direction towards the light */
    double falloff = 1.0;
    if (l->kind == 1) {
        facing = -dv_dot(n, l->direction);
    } else {
        dvec3 centre = dv_scale(dv_add(dv_add(a, b), c), 1.0 / 3.0);
        dvec3 to_light = dv_sub(l->position, centre);
        double d2 = dv_dot(to_light, to_light);
        if (!(d2 > 0.0))
            return 0.0;
        facing = dv_dot(n, dv_scale(to_light, 1.0 / sqrt(d2)));
        /* A spot's cone: the centre's factor, floored so that a triangle
         * with only a corner in the cone still has a chance (any positive
         * weight keeps the estimate unbiased; this one keeps it efficient). */
        falloff = fmax(ref_light_spot(l, dv_scale(to_light, -1.0 / sqrt(d2))), 0.02) / d2;
    }
    if (!ref_is_dielectric(m) && !o->sphere) /* (a sphere is closed: its far side is never a first hit) */
        facing = fabs(facing);
    return facing > 0.0 ? area * facing * falloff : 0.0;
}

static void build_guide(struct ref_emitter *e)
{
    size_t k = 0;
    for (size_t m = 0; m <= e->count; m++) {
        double u = (double)m / (double)e->count;
        while (k + 1 < e->count && e->cdf[k] <= u)
            k++;
        e->guide[m] = (uint32_t)k;
    }
}

static double triangle_area(dvec3 a, dvec3 b, dvec3 c)
{
    dvec3 n2 = dv_cross(dv_sub(b, a), dv_sub(c, a));
    return 0.5 * sqrt(dv_dot(n2, n2));
}

/* Large triangles (a water surface of a few quads, a box) are split into
 * 4^level pieces for emission, so that the adaptation can tell the part
 * of a triangle that lights what the camera sees from the rest. */
#define EMIT_PIECES 2048.0 /* pieces the specular surface is split into, about */
#define EMIT_MAX_LEVEL 6

/* Cells the adaptation pools its counts over, about, on the light's whole
 * specular surface (ref_emitter_adapt): cubes of side sqrt(area /
 * EMIT_CELLS). A surface of a few large triangles keeps one piece a cell
 * (its pieces are larger than the cells); a ball of 262,144 triangles gets
 * about 12 triangles a cell, each cell a few photons a pilot round. */
#define EMIT_CELLS 16384.0

static int split_level(double area, double piece_area)
{
    int level = 0;
    while (level < EMIT_MAX_LEVEL && area > piece_area * 1.5) {
        area *= 0.25;
        level++;
    }
    return level;
}

/* Piece k (of 4^level) of triangle abc, by repeated midpoint splits. */
static void piece(dvec3 a, dvec3 b, dvec3 c, int level, size_t k, dvec3 out[3])
{
    for (int d = 0; d < level; d++) {
        dvec3 ab = dv_scale(dv_add(a, b), 0.5), bc = dv_scale(dv_add(b, c), 0.5), ca = dv_scale(dv_add(c, a), 0.5);
        switch ((k >> (2 * d)) & 3u) {
        case 0: b = ab; c = ca; break;
        case 1: a = ab; c = bc; break;
        case 2: a = ca; b = bc; break;
        default: a = ab; b = bc; c = ca; break;
        }
    }
    out[0] = a;
    out[1] = b;
    out[2] = c;
}

/* The specular surface's total area, and the pieces it splits into for
 * `piece_area` (0: no count). */
static size_t count_pieces(const struct ref_scene *rs, const double *scales, double piece_area, double *total_area)
{
    size_t n = 0;
    *total_area = 0.0;
    for (int i = 0; i < rs->object_count; i++) {
        const struct ref_object *o = &rs->objects[i];
        if (!(material_role(&o->material) & REF_SPECULAR_ROLES))
            continue;
        double scale = scales[i];
        for (size_t t = 0; t < o->triangle_count; t++) {
            const uint32_t *tri = o->indices + t * 3;
            double a = triangle_area(aim_vertex(o, tri[0], scale), aim_vertex(o, tri[1], scale),
                                     aim_vertex(o, tri[2], scale));
            a = isfinite(a) ? a : 0.0;
            *total_area += a;
            if (piece_area > 0.0)
                n += (size_t)1 << (2 * split_level(a, piece_area));
        }
    }
    return n;
}

struct cell_key {
    uint64_t key;
    uint32_t entry;
};

static int cell_key_order(const void *pa, const void *pb)
{
    const struct cell_key *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    return a->entry < b->entry ? -1 : a->entry > b->entry;
}

static dvec3 entry_centre(const struct ref_emitter *e, size_t k)
{
    const float *q = e->corners + k * 9;
    return dv(((double)q[0] + q[3] + q[6]) / 3.0, ((double)q[1] + q[4] + q[7]) / 3.0, ((double)q[2] + q[5] + q[8]) / 3.0);
}

/* Gives each entry its cell: the cube of side `side` its centre lies in,
 * on a grid of its own object's (a cell never joins two objects: one may
 * hide the other from the light). Entries come in object order. */
static bool assign_cells(struct ref_emitter *e, double side)
{
    struct cell_key *keys = malloc(e->count * sizeof *keys);
    if (!keys)
        return false;
    size_t cells = 0;
    for (size_t begin = 0, end; begin < e->count; begin = end) {
        dvec3 lo = dv(INFINITY, INFINITY, INFINITY), hi = dv(-INFINITY, -INFINITY, -INFINITY);
        for (end = begin; end < e->count && e->object[end] == e->object[begin]; end++) {
            dvec3 c = entry_centre(e, end);
            lo = dv(fmin(lo.x, c.x), fmin(lo.y, c.y), fmin(lo.z, c.z));
            hi = dv(fmax(hi.x, c.x), fmax(hi.y, c.y), fmax(hi.z, c.z));
        }
        /* 20 bits an axis: a long thin object gets longer cells, not more */
        double extent = fmax(fmax(hi.x - lo.x, hi.y - lo.y), hi.z - lo.z);
        double h = fmax(side, extent / 1048575.0);
        if (!(h > 0.0))
            h = 1.0; /* one point: one cell */
        for (size_t k = begin; k < end; k++) {
            dvec3 c = entry_centre(e, k);
            uint64_t ix = (uint64_t)fmin(fmax((c.x - lo.x) / h, 0.0), 1048575.0);
            uint64_t iy = (uint64_t)fmin(fmax((c.y - lo.y) / h, 0.0), 1048575.0);
            uint64_t iz = (uint64_t)fmin(fmax((c.z - lo.z) / h, 0.0), 1048575.0);
            keys[k] = (struct cell_key){(ix << 40) | (iy << 20) | iz, (uint32_t)k};
        }
        qsort(keys + begin, end - begin, sizeof *keys, cell_key_order);
        for (size_t k = begin; k < end; k++) {
            if (k == begin || keys[k].key != keys[k - 1].key)
                cells++;
            e->cell[keys[k].entry] = (uint32_t)(cells - 1);
        }
    }
    free(keys);
    e->cells = cells;
    e->cell_sampled = calloc(cells, sizeof *e->cell_sampled); /* (cells >= 1: called with entries) */
    e->cell_useful = calloc(cells, sizeof *e->cell_useful);
    return e->cell_sampled && e->cell_useful;
}

bool ref_emitter_build(struct ref_emitter *e, const struct ref_scene *rs, const struct ref_light *l, struct error *err)
{
    memset(e, 0, sizeof *e);
    double total_area;
    /* each object's aim (1, or an exact sphere's blow-up), once */
    double *scales = malloc((size_t)(rs->object_count + 1) * sizeof *scales);
    if (!scales)
        return error_set(err, "reference: out of memory for the photon targets");
    for (int i = 0; i < rs->object_count; i++)
        scales[i] = aim_scale(&rs->objects[i]);
    count_pieces(rs, scales, 0.0, &total_area);
    size_t n = count_pieces(rs, scales, total_area / EMIT_PIECES, &total_area);
    double piece_area = total_area / EMIT_PIECES;
    if (n == 0 || n > UINT32_MAX - 1) {
        free(scales);
        return n == 0 || error_set(err, "reference: too many specular triangles for the photon targets (%zu)", n);
    }
    e->corners = malloc(n * 9 * sizeof *e->corners);
    e->cdf = malloc(n * sizeof *e->cdf);
    e->guide = malloc((n + 1) * sizeof *e->guide);
    e->weight = malloc(n * sizeof *e->weight);
    e->sampled = calloc(n, sizeof *e->sampled);
    e->useful = calloc(n, sizeof *e->useful);
    e->object = malloc(n * sizeof *e->object);
    e->primitive = malloc(n * sizeof *e->primitive);
    e->cell = malloc(n * sizeof *e->cell);
    if (!e->corners || !e->guide || !e->cdf || !e->weight || !e->sampled || !e->useful || !e->object || !e->primitive ||
        !e->cell) {
        ref_emitter_release(e);
        free(scales);
        return error_set(err, "reference: out of memory for the photon targets (%zu triangles)", n);
    }
    double sum = 0.0;
    for (int i = 0; i < rs->object_count; i++) {
        const struct ref_object *o = &rs->objects[i];
        if (!(material_role(&o->material) & REF_SPECULAR_ROLES))
            continue;
        double scale = scales[i];
        for (size_t t = 0; t < o->triangle_count; t++) {
            const uint32_t *tri = o->indices + t * 3;
            dvec3 a = aim_vertex(o, tri[0], scale), b = aim_vertex(o, tri[1], scale), c = aim_vertex(o, tri[2], scale);
            double area = triangle_area(a, b, c);
            int level = split_level(isfinite(area) ? area : 0.0, piece_area);
            for (size_t k = 0; k < (size_t)1 << (2 * level); k++) {
                dvec3 p[3];
                piece(a, b, c, level, k, p);
                double w = triangle_weight(l, o, p[0], p[1], p[2]);
                if (!(w > 0.0))
                    continue;
                sum += w;
                float *q = e->corners + e->count * 9;
                for (int v = 0; v < 3; v++) {
                    q[v * 3 + 0] = (float)p[v].x;
                    q[v * 3 + 1] = (float)p[v].y;
                    q[v * 3 + 2] = (float)p[v].z;
                }
                e->weight[e->count] = w;
                e->cdf[e->count] = sum;
                e->object[e->count] = i;
                e->primitive[e->count] = (unsigned)t;
                e->count++;
            }
        }
    }
    free(scales);
    if (e->count && !assign_cells(e, sqrt(total_area / EMIT_CELLS))) {
        ref_emitter_release(e);
        return error_set(err, "reference: out of memory for the photon targets' cells (%zu pieces)", n);
    }
    e->total = sum;
    for (size_t k = 0; k < e->count; k++)
        e->cdf[k] /= sum;
    if (e->count)
        e->cdf[e->count - 1] = 1.0;
    build_guide(e);
    double grey = (l->intensity.x + l->intensity.y + l->intensity.z) / 3.0;
    e->power = e->count ? grey * sum : 0.0;
    return true;
}

void ref_emitter_adapt(struct ref_emitter *e)
{
    /* A cell (below) no photon of which has reached a visible point is
     * weighted by its useful fraction's posterior mean under a uniform
     * prior, 1 / (sampled + 2): optimistic where few photons were tried (an
     * untried cell counts as half useful), so a cell is starved only once
     * many of its photons were seen to miss. A photon's flux is inverse to
     * its piece's density, so a cell whose estimate tracks its true
     * fraction r contributes variance ~ r / estimate, bounded, instead of
     * the unbounded fireflies of a piece judged useless on too few
     * photons. */
    if (e->count == 0)
        return;
    /* A cell that has sent a photon to a visible point is live: every live
     * cell gets the pdf of the most useful one (the highest posterior
     * mean), so that photons from the pieces the camera sees all carry the
     * same flux. Graded by each piece's own rate, a view cut by piece
     * boundaries got photons whose flux differed 36-fold (flat water seen
     * close up): the emission's stratification was lost in the mix, and
     * the per-pixel noise with 200 photons a gather stayed at Poisson's
     * level. A cell never seen useful keeps its posterior mean.
     * Judged per cell, not per entry: the ball of 262,144 triangles had
     * about one photon a triangle a pilot round, so that a triangle the
     * camera needs was often dead or untried by chance (its one photon
     * reflected, or none yet) and weighted a third or a half of its live
     * neighbours: after the pilot the live entries held 23% of the pdf, and
     * the photons of one gather carried fluxes 2 or 3 times apart, which
     * undid the emission's stratification. */
    memset(e->cell_sampled, 0, e->cells * sizeof *e->cell_sampled);
    memset(e->cell_useful, 0, e->cells * sizeof *e->cell_useful);
    for (size_t k = 0; k < e->count; k++) {
        e->cell_sampled[e->cell[k]] += e->sampled[k];
        e->cell_useful[e->cell[k]] += e->useful[k];
    }
    double live = 0.0;
    for (size_t c = 0; c < e->cells; c++)
        if (e->cell_useful[c] > 0.0)
            live = fmax(live, (e->cell_useful[c] + 1.0) / (e->cell_sampled[c] + 2.0));
    double sum = 0.0;
    for (size_t k = 0; k < e->count; k++) {
        uint32_t c = e->cell[k];
        sum += e->weight[k] * (e->cell_useful[c] > 0.0 ? live : 1.0 / (e->cell_sampled[c] + 2.0));
        e->cdf[k] = sum;
    }
    for (size_t k = 0; k < e->count; k++)
        e->cdf[k] /= sum;
    e->cdf[e->count - 1] = 1.0;
    build_guide(e);
}

static double radical_inverse(uint64_t index, unsigned base)
{
    double inv = 1.0 / base, f = inv, r = 0.0;
    while (index > 0) {
        r += (double)(index % base) * f;
        index /= base;
        f *= inv;
    }
    return r;
}

void ref_emit_point(uint64_t index, const double shift[3], double u[3])
{
    static const unsigned bases[3] = {2, 3, 5};
    for (int k = 0; k < 3; k++) {
        double v = radical_inverse(index, bases[k]) + shift[k];
        v -= floor(v);
        u[k] = v < 1.0 ? v : 0.0;
    }
}

void ref_emitter_release(struct ref_emitter *e)
{
    free(e->corners);
    free(e->guide);
    free(e->cdf);
    free(e->weight);
    free(e->sampled);
    free(e->useful);
    free(e->object);
    free(e->primitive);
    free(e->cell);
    free(e->cell_sampled);
    free(e->cell_useful);
    memset(e, 0, sizeof *e);
}

bool ref_emitter_sample(const struct ref_emitter *e, const struct ref_scene *rs, const struct ref_light *l,
                        long photons, const double point[3], dvec3 *origin, dvec3 *dir, dvec3 *flux, int *object,
                        unsigned *primitive, size_t *entry)
{
    if (e->count == 0 || photons <= 0)
        return false;
    /* The first coordinate picks the piece by the inverse CDF (monotone, so
     * a well-spread first coordinate gives each piece its share of photons
     * to within one), the other two the point on it. */
    double u = point[0];
    size_t m = (size_t)(u * (double)e->count);
    size_t lo = e->guide[m < e->count ? m : e->count - 1];
    while (lo + 1 < e->count && e->cdf[lo] <= u)
        lo++;
    double p_tri = e->cdf[lo] - (lo ? e->cdf[lo - 1] : 0.0);
    const float *q = e->corners + lo * 9;
    dvec3 a = dv(q[0], q[1], q[2]), b = dv(q[3], q[4], q[5]), c = dv(q[6], q[7], q[8]);
    /* a uniform point on the triangle */
    double s = sqrt(point[1]), t = point[2];
    dvec3 x = dv_add(dv_scale(a, 1.0 - s), dv_add(dv_scale(b, s * (1.0 - t)), dv_scale(c, s * t)));
    dvec3 n2 = dv_cross(dv_sub(b, a), dv_sub(c, a));
    double area = 0.5 * sqrt(dv_dot(n2, n2));
    if (!(p_tri > 0.0) || !(area > 0.0))
        return false;
    dvec3 n = dv_scale(n2, 0.5 / area);
    *entry = lo;
    *object = e->object[lo];
    *primitive = e->primitive[lo];
    if (l->kind == 1) {
        /* Directional: the photon crosses a plane far upstream at the point
         * whose ray meets x; its density there is p_tri / (area |cos|). */
        double c_abs = fabs(dv_dot(n, l->direction));
        if (!(c_abs > 1e-12))
            return false;
        dvec3 ext = dv_sub(rs->bounds_hi, rs->bounds_lo);
        double back = sqrt(dv_dot(ext, ext)) + 1.0;
        *dir = l->direction;
        *origin = dv_sub(x, dv_scale(l->direction, back));
        *flux = dv_scale(l->intensity, area * c_abs / (p_tri * (double)photons));
        return true;
    }
    /* Point and spot: the direction's density over the sphere is
     * p_tri / area * d^2 / |cos| (area measure to solid angle). */
    dvec3 to = dv_sub(x, l->position);
    double d2 = dv_dot(to, to);
    if (!(d2 > 0.0))
        return false;
    double d = sqrt(d2);
    *dir = dv_scale(to, 1.0 / d);
    double c_abs = fabs(dv_dot(n, *dir));
    double spot = ref_light_spot(l, *dir);
    if (!(c_abs > 1e-12) || spot <= 0.0)
        return false;
    *origin = l->position;
    *flux = dv_scale(l->intensity, spot * area * c_abs / (d2 * p_tri * (double)photons));
    return true;
}
