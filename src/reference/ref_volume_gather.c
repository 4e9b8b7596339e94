/* The reference's volume caustics: the photons that scattered in a medium
 * after specular surfaces, in a hash grid, gathered along each pixel's
 * camera segments (ref_sppm.c runs it). */
#define _POSIX_C_SOURCE 200809L
#include "reference/ref_sppm_internal.h"

/* ---- photons ------------------------------------------------------------ */



void sppm_volume_push(struct volume_photons *v, dvec3 p, dvec3 d, dvec3 flux, int light)
{
    if (v->count == v->capacity) {
        size_t cap = v->capacity ? v->capacity * 2 : 1024;
        struct volume_photon *q = realloc(v->items, cap * sizeof *q);
        if (!q)
            return;
        v->items = q;
        v->capacity = cap;
    }
    v->items[v->count++] = (struct volume_photon){{(float)p.x, (float)p.y, (float)p.z},
                                                  {(float)d.x, (float)d.y, (float)d.z},
                                                  {(float)flux.x, (float)flux.y, (float)flux.z}, light};
}


static size_t volume_hash(const struct volume_grid *g, long x, long y, long z)
{
    uint64_t h = ((uint64_t)x * 73856093u) ^ ((uint64_t)y * 19349663u) ^ ((uint64_t)z * 83492791u);
    return (size_t)(h % g->size);
}

/* A dense grid takes at most this many cells for each photon: beyond it
 * the photons are sparse in their bounds, and the hash costs less memory
 * and less time to build (its offsets are summed cell by cell). */
#define VOLUME_DENSE_CELLS_PER_PHOTON 8

static long volume_cell_axis(double v, double origin, double cell, long n)
{
    double c = floor((v - origin) / cell);
    return c >= 0.0 ? (c < (double)n ? (long)c : n - 1) : 0; /* (NaN: cell 0, never an undefined conversion) */
}

/* The photon's cell: its index in the dense grid, or its hash slot. */
static size_t volume_cell_of(const struct volume_grid *g, const float p[3])
{
    if (g->dense)
        return (size_t)volume_cell_axis(p[0], g->origin.x, g->cell, g->nx) +
               (size_t)g->nx * ((size_t)volume_cell_axis(p[1], g->origin.y, g->cell, g->ny) +
                                (size_t)g->ny * (size_t)volume_cell_axis(p[2], g->origin.z, g->cell, g->nz));
    return volume_hash(g, (long)floor(p[0] / g->cell), (long)floor(p[1] / g->cell), (long)floor(p[2] / g->cell));
}

/* Dense where the photons' bounds hold few enough cells of the radius:
 * the gather at a point then reads the 3 cells along x of each of 9 rows
 * as one run each, where the hash read 27 slots scattered over memory (a
 * cache miss each: two thirds of the fog's volume gather). */
static void volume_grid_layout(struct volume_grid *g, const struct volume_photons *chunks, int nchunks, size_t n)
{
    g->dense = false;
    g->size = n > 0 ? n * 2 : 1;
    if (n == 0)
        return;
    dvec3 lo = dv(INFINITY, INFINITY, INFINITY), hi = dv(-INFINITY, -INFINITY, -INFINITY);
    for (int c = 0; c < nchunks; c++)
        for (size_t k = 0; k < chunks[c].count; k++) {
            const float *p = chunks[c].items[k].position;
            lo = dv(fmin(lo.x, p[0]), fmin(lo.y, p[1]), fmin(lo.z, p[2]));
            hi = dv(fmax(hi.x, p[0]), fmax(hi.y, p[1]), fmax(hi.z, p[2]));
        }
    double limit = (double)VOLUME_DENSE_CELLS_PER_PHOTON * (double)n;
    double nx = floor((hi.x - lo.x) / g->cell) + 1.0, ny = floor((hi.y - lo.y) / g->cell) + 1.0,
           nz = floor((hi.z - lo.z) / g->cell) + 1.0;
    if (!(nx * ny * nz <= limit)) /* (NaN bounds: the hash) */
        return;
    g->dense = true;
    g->origin = lo;
    g->nx = (long)nx;
    g->ny = (long)ny;
    g->nz = (long)nz;
    g->size = (size_t)(nx * ny * nz);
}

void sppm_volume_grid_build(struct volume_grid *g, const struct volume_photons *chunks, int nchunks, double radius)
{
    size_t n = 0;
    for (int c = 0; c < nchunks; c++)
        n += chunks[c].count;
    g->radius = radius;
    g->cell = radius;
    volume_grid_layout(g, chunks, nchunks, n);
    g->start = calloc(g->size + 1, sizeof *g->start);
    g->items = malloc((n + 1) * sizeof *g->items);
    if (!g->start || !g->items) {
        g->size = 0;
        return;
    }
    for (int c = 0; c < nchunks; c++)
        for (size_t k = 0; k < chunks[c].count; k++)
            g->start[volume_cell_of(g, chunks[c].items[k].position) + 1]++;
    for (size_t s = 0; s < g->size; s++)
        g->start[s + 1] += g->start[s];
    size_t *fill = malloc((g->size + 1) * sizeof *fill);
    if (!fill) {
        g->size = 0;
        return;
    }
    memcpy(fill, g->start, (g->size + 1) * sizeof *fill);
    for (int c = 0; c < nchunks; c++)
        for (size_t k = 0; k < chunks[c].count; k++)
            g->items[fill[volume_cell_of(g, chunks[c].items[k].position)]++] = chunks[c].items[k];
    free(fill);
}

void sppm_volume_grid_release(struct volume_grid *g)
{
    free(g->start);
    free(g->items);
    memset(g, 0, sizeof *g);
}

/* The photons of items [from, to) within the radius of x, each flux times
 * the phase function towards -view, added to sum. */
static dvec3 volume_photons_add(const struct volume_grid *g, size_t from, size_t to, double phase_g, dvec3 x,
                                dvec3 view, double r2, dvec3 sum)
{
    for (size_t k = from; k < to; k++) {
        const struct volume_photon *p = &g->items[k];
        dvec3 d = dv(p->position[0] - x.x, p->position[1] - x.y, p->position[2] - x.z);
        if (dv_dot(d, d) > r2)
            continue;
        /* (cells beside the sphere, and hash collisions: the distance test rejects them) */
        double ph = ref_phase_hg(phase_g, -(p->dir[0] * view.x + p->dir[1] * view.y + p->dir[2] * view.z));
        sum = dv_add(sum, dv_scale(dv(p->flux[0], p->flux[1], p->flux[2]), ph));
    }
    return sum;
}

/* In-scattered radiance of the volume photons at x towards -view: the
 * volume radiance estimate sum(flux * phase) / (4/3 pi r^3) (Jensen &
 * Christensen 1998). */
dvec3 sppm_volume_estimate(const struct volume_grid *g, double phase_g, dvec3 x, dvec3 view)
{
    dvec3 sum = dv(0, 0, 0);
    if (g->size == 0)
        return sum;
    double r2 = g->radius * g->radius;
    if (g->dense) {
        double fx = floor((x.x - g->origin.x) / g->cell), fy = floor((x.y - g->origin.y) / g->cell),
               fz = floor((x.z - g->origin.z) / g->cell);
        /* a point more than a cell outside the photons' bounds has none within r */
        if (!(fx >= -1.0 && fx <= (double)g->nx && fy >= -1.0 && fy <= (double)g->ny && fz >= -1.0 &&
              fz <= (double)g->nz))
            return sum;
        long cx = (long)fx, cy = (long)fy, cz = (long)fz;
        long x0 = cx - 1 < 0 ? 0 : cx - 1, x1 = cx + 1 >= g->nx ? g->nx - 1 : cx + 1;
        for (long z = cz - 1; z <= cz + 1; z++)
            for (long y = cy - 1; y <= cy + 1; y++) {
                if (z < 0 || z >= g->nz || y < 0 || y >= g->ny || x0 > x1)
                    continue;
                size_t row = (size_t)g->nx * ((size_t)y + (size_t)g->ny * (size_t)z);
                sum = volume_photons_add(g, g->start[row + (size_t)x0], g->start[row + (size_t)x1 + 1], phase_g, x,
                                         view, r2, sum);
            }
    } else {
        long cx = (long)floor(x.x / g->cell), cy = (long)floor(x.y / g->cell), cz = (long)floor(x.z / g->cell);
        /* two of the 27 cells may hash to one slot: each slot is read once,
         * or its photons would count twice */
        size_t seen[27];
        int nseen = 0;
        for (long z = cz - 1; z <= cz + 1; z++)
            for (long y = cy - 1; y <= cy + 1; y++)
                for (long xx = cx - 1; xx <= cx + 1; xx++) {
                    size_t h = volume_hash(g, xx, y, z);
                    if (ref_slot_first(seen, &nseen, h))
                        sum = volume_photons_add(g, g->start[h], g->start[h + 1], phase_g, x, view, r2, sum);
                }
    }
    return dv_scale(sum, 1.0 / (4.0 / 3.0 * MATH_PI * g->radius * g->radius * g->radius));
}

/* The volume caustic seen along a pixel's medium segments. */
static void gather_volume(struct job *j, int x, int y)
{
    size_t i = (size_t)y * (size_t)j->o->width + (size_t)x;
    struct pixel *px = &j->pixels[i];
    px->volume_samples += j->pass_fraction;
    const struct pixel_segments *kept = j->segments ? &j->segments[i] : NULL;
    if (!kept || kept->count == 0)
        return;
    struct ref_rng rng = ref_rng_seed(j->o->seed, 1000003u * (uint64_t)j->iteration + 3u,
                                      (uint64_t)y * (uint64_t)j->o->width + (uint64_t)x);
    const struct ref_medium *rm = j->medium;
    for (int k = 0; k < kept->count; k++) {
        int samples = j->volume_samples > 0 ? j->volume_samples : VOLUME_SAMPLES;
        double t0 = kept->segments[k].t0, t1 = kept->segments[k].t1, step = (t1 - t0) / samples;
        dvec3 o = kept->segments[k].origin, d = kept->segments[k].dir;
        dvec3 sum = dv(0, 0, 0);
        for (int s = 0; s < samples; s++) {
            double t = t0 + step * (s + ref_rng_uniform(&rng));
            dvec3 p = dv_add(o, dv_scale(d, t));
            dvec3 l = sppm_volume_estimate(j->volume_grid, rm->g, p, d);
            if (l.x + l.y + l.z <= 0.0)
                continue;
            sum = dv_add(sum, dv_mul(ref_medium_transmittance(rm, o, d, t, &rng), l));
        }
        px->volume = dv_add(px->volume, dv_mul(kept->segments[k].beta, dv_scale(sum, step)));
    }
}

/* The rows a volume gather does: all, or (the first gather under a time
 * budget) every VOLUME_PROBE_STRIDE-th row first at VOLUME_PROBE_SAMPLES
 * points a ray, timed (1/128 of the whole gather's cost), then the rest. */

void *sppm_volume_thread(void *arg)
{
    struct job *j = arg;
    for (int y = j->thread; y < j->o->height; y += j->threads) {
        bool probe_row = y % VOLUME_PROBE_STRIDE == 0;
        if ((j->volume_rows == VOLUME_ROWS_PROBE && !probe_row) || (j->volume_rows == VOLUME_ROWS_REST && probe_row))
            continue;
        if (j->iteration > 0 && sppm_budget_spent(j->budget))
            return NULL;
        if (j->volume_rows == VOLUME_ROWS_REST && sppm_budget_spent(j->budget)) {
            /* the last resort of a first gather the probe misjudged: the
             * row keeps no medium light, and the warning counts it */
            atomic_fetch_add(&j->volume_rows_left, 1);
            continue;
        }
        for (int x = 0; x < j->o->width; x++)
            gather_volume(j, x, y);
    }
    return NULL;
}
