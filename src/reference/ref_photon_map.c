/* Surface photons and the multi-level grid that gathers them
 * (ref_photon_map.h). */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "reference/ref_photon_map.h"

bool ref_surface_photons_push(struct ref_surface_photons *list, const struct ref_surface_photon *photon)
{
    if (list->count == list->capacity) {
        size_t cap = list->capacity ? list->capacity * 2 : 1024;
        struct ref_surface_photon *p = realloc(list->items, cap * sizeof *p);
        if (!p)
            return false;
        list->items = p;
        list->capacity = cap;
    }
    list->items[list->count++] = *photon;
    return true;
}

void ref_surface_photons_release(struct ref_surface_photons *list)
{
    free(list->items);
    memset(list, 0, sizeof *list);
}

static size_t slot_of(const struct ref_photon_map *map, long x, long y, long z)
{
    uint64_t h = ((uint64_t)x * 73856093u) ^ ((uint64_t)y * 19349663u) ^ ((uint64_t)z * 83492791u);
    return (size_t)(h & (map->slots - 1));
}

static long cell_coordinate(double v, double cell)
{
    double c = floor(v / cell);
    /* far outside any sensible scene: clamp rather than overflow */
    return c < -1e15 ? (long)-1e15 : c > 1e15 ? (long)1e15 : (long)c;
}

void ref_photon_map_prepare(struct ref_photon_map *map, double rmax)
{
    map->top = rmax > 0.0 && isfinite(rmax) ? rmax : 1.0;
    for (int l = 0; l < REF_PHOTON_MAP_LEVELS; l++) {
        map->levels[l].built = false;
        map->levels[l].cell = ldexp(map->top, -l);
    }
}

int ref_photon_map_level_of(const struct ref_photon_map *map, double r)
{
    if (!(r > 0.0))
        return 0;
    int l = (int)floor(log2(map->top / r));
    l = l < 0 ? 0 : l >= REF_PHOTON_MAP_LEVELS ? REF_PHOTON_MAP_LEVELS - 1 : l;
    /* log2's rounding: the cell must be at least r */
    while (l > 0 && map->levels[l].cell < r)
        l--;
    return l;
}

static bool reserve(void **p, size_t *capacity, size_t n, size_t size)
{
    if (*capacity >= n && *p)
        return true;
    free(*p);
    *p = malloc(n * size);
    *capacity = *p ? n : 0;
    return *p != NULL;
}

/* Where a point lies inside its cell, as an 8x8x8 Morton code: within a
 * slot the photons are sorted by it, so that the four a gather tests
 * together lie together and are mostly all inside its disc or all
 * outside (in emission order, 54% of the lanes of a group with a photon
 * inside did work). */
#define SUBCELL_BITS 3
#define SUBCELLS (1 << (3 * SUBCELL_BITS))
static uint32_t subcell_code(double x, double y, double z, double cell)
{
    double v[3] = {x / cell, y / cell, z / cell};
    uint32_t code = 0;
    for (int a = 0; a < 3; a++) {
        double f = (v[a] - floor(v[a])) * (1 << SUBCELL_BITS);
        uint32_t q = f >= 0.0 && f < (1 << SUBCELL_BITS) ? (uint32_t)f : 0u; /* NaN: 0 */
        for (int b = 0; b < SUBCELL_BITS; b++)
            code |= ((q >> b) & 1u) << (3 * b + a);
    }
    return code;
}

/* One level's grid: the photons by slot and, within a slot, by subcell
 * (two stable counting sorts, the subcell's first: ties keep the photon
 * order), into the level's columns. */
static bool build_level(struct ref_photon_map *map, int l)
{
    struct ref_photon_map_level *lv = &map->levels[l];
    size_t n = map->count, stride = n + REF_PHOTON_MAP_PAD;
    if (!reserve((void **)&lv->start, &map->slots_capacity[l], map->slots + 1, sizeof *lv->start) ||
        !reserve((void **)&lv->columns, &map->columns_capacity[l], REF_COLUMNS * stride, sizeof *lv->columns) ||
        !reserve((void **)&lv->light, &map->light_capacity[l], stride, sizeof *lv->light) ||
        !reserve((void **)&lv->photon, &map->photon_capacity[l], stride, sizeof *lv->photon) ||
        !reserve((void **)&lv->scratch, &map->scratch_capacity[l], 3 * n + 1, sizeof *lv->scratch))
        return false;
    lv->stride = stride;
    uint32_t *slot = lv->scratch, *code = lv->scratch + n, *order = lv->scratch + 2 * n;
    uint32_t by_code[SUBCELLS + 1] = {0};
    memset(lv->start, 0, (map->slots + 1) * sizeof *lv->start);
    for (size_t i = 0; i < n; i++) {
        const float *p = map->photons[i].position;
        double x = p[0] - map->origin.x, y = p[1] - map->origin.y, z = p[2] - map->origin.z;
        slot[i] = (uint32_t)slot_of(map, cell_coordinate(x, lv->cell), cell_coordinate(y, lv->cell),
                                    cell_coordinate(z, lv->cell));
        code[i] = subcell_code(x, y, z, lv->cell);
        lv->start[slot[i] + 1]++;
        by_code[code[i] + 1]++;
    }
    for (size_t c = 0; c < SUBCELLS; c++)
        by_code[c + 1] += by_code[c];
    for (size_t i = 0; i < n; i++)
        order[by_code[code[i]]++] = (uint32_t)i;
    for (size_t s = 0; s < map->slots; s++)
        lv->start[s + 1] += lv->start[s];
    /* where each photon goes (start[s] is the slot's fill point while
     * filling; the shift below turns the fill points back into starts),
     * then the columns written in that order, each once and in sequence:
     * scattering the photons' fields over the columns themselves cost a
     * cache miss a column */
    for (size_t j = 0; j < n; j++) {
        uint32_t i = order[j];
        lv->photon[lv->start[slot[i]]++] = i;
    }
    float *col[REF_COLUMNS];
    for (int c = 0; c < REF_COLUMNS; c++)
        col[c] = lv->columns + (size_t)c * stride;
    for (size_t k = 0; k < n; k++) {
        const struct ref_surface_photon *ph = &map->photons[lv->photon[k]];
        col[REF_COLUMN_X][k] = (float)(ph->position[0] - map->origin.x);
        col[REF_COLUMN_Y][k] = (float)(ph->position[1] - map->origin.y);
        col[REF_COLUMN_Z][k] = (float)(ph->position[2] - map->origin.z);
        for (int c = 0; c < 3; c++) {
            col[REF_COLUMN_DX + c][k] = ph->dir[c];
            col[REF_COLUMN_NX + c][k] = ph->normal[c];
            col[REF_COLUMN_R + c][k] = ph->flux[c];
        }
        lv->light[k] = (uint32_t)ph->light;
    }
    lv->identity = true;
    for (size_t k = 0; k < n && lv->identity; k++)
        lv->identity = lv->photon[k] == (uint32_t)k;
    /* the padding: finite, and a light that exists */
    for (size_t k = n; k < stride; k++) {
        for (int c = 0; c < REF_COLUMNS; c++)
            col[c][k] = 0.0f;
        lv->light[k] = 0;
        lv->photon[k] = 0;
    }
    for (size_t s = map->slots; s > 0; s--)
        lv->start[s] = lv->start[s - 1];
    lv->start[0] = 0;
    lv->built = true;
    return true;
}

struct build_work {
    struct ref_photon_map *map;
    const bool *wanted;
    int thread, threads;
    bool ok;
};

static void *build_thread(void *arg)
{
    struct build_work *w = arg;
    w->ok = true;
    int k = 0; /* the wanted levels dealt round the threads */
    for (int l = 0; l < REF_PHOTON_MAP_LEVELS; l++)
        if (w->wanted[l] && k++ % w->threads == w->thread)
            w->ok = build_level(w->map, l) && w->ok;
    return NULL;
}

static bool build_levels(struct ref_photon_map *map, const bool wanted[REF_PHOTON_MAP_LEVELS], int threads)
{
    threads = threads < 1 ? 1 : threads > 8 ? 8 : threads;
    struct build_work work[8];
    pthread_t ids[8];
    int started = 1;
    for (int t = 0; t < threads; t++)
        work[t] = (struct build_work){map, wanted, t, threads, true};
    for (int t = 1; t < threads && pthread_create(&ids[t], NULL, build_thread, &work[t]) == 0; t++)
        started = t + 1;
    for (int t = 0; t < threads; t++)
        if (t == 0 || t >= started)
            build_thread(&work[t]);
    for (int t = 1; t < started; t++)
        pthread_join(ids[t], NULL);
    bool ok = true;
    for (int t = 0; t < threads; t++)
        ok = ok && work[t].ok;
    return ok;
}

/* Which levels to build: the coarsest any point reads, and any other that
 * at least 1/64 of the points read; each level reads the nearest built one
 * at or above it. Returns the built level most points read (-1: none). */
static int choose_levels(struct ref_photon_map *map, const size_t points_per_level[REF_PHOTON_MAP_LEVELS],
                         bool wanted[REF_PHOTON_MAP_LEVELS])
{
    size_t points = 0;
    int coarsest = -1, most = -1;
    for (int l = 0; l < REF_PHOTON_MAP_LEVELS; l++) {
        wanted[l] = false;
        points += points_per_level[l];
        if (coarsest < 0 && points_per_level[l] > 0)
            coarsest = l;
        if (points_per_level[l] > 0 && (most < 0 || points_per_level[l] > points_per_level[most]))
            most = l;
    }
    if (coarsest < 0)
        return -1;
    int read = coarsest;
    for (int l = 0; l < REF_PHOTON_MAP_LEVELS; l++) {
        wanted[l] = l == coarsest || (l > coarsest && points_per_level[l] * 64 >= points);
        if (wanted[l])
            read = l;
        map->read_level[l] = l < coarsest ? coarsest : read;
    }
    return map->read_level[most];
}

bool ref_photon_map_build(struct ref_photon_map *map, const struct ref_surface_photons *chunks, int nchunks,
                          const size_t points_per_level[REF_PHOTON_MAP_LEVELS], int threads)
{
    size_t n = 0;
    for (int c = 0; c < nchunks; c++)
        n += chunks[c].count;
    map->count = 0;
    for (int l = 0; l < REF_PHOTON_MAP_LEVELS; l++)
        map->levels[l].built = false;
    if (n > UINT32_MAX - 1)
        return false;
    if (!reserve((void **)&map->photons, &map->photons_capacity, n + 1, sizeof *map->photons) ||
        !reserve((void **)&map->original, &map->original_capacity, n + 1, sizeof *map->original) ||
        !reserve((void **)&map->rank, &map->rank_capacity, n + 1, sizeof *map->rank) ||
        !reserve((void **)&map->used, &map->used_capacity, n + 1, sizeof *map->used))
        return false;
    map->mark_threads = threads < 1 ? 1 : threads > 64 ? 64 : threads;
    size_t marks = (size_t)map->mark_threads * (n + REF_PHOTON_MAP_PAD);
    if (!reserve((void **)&map->marks, &map->marks_capacity, marks, 1))
        return false;
    memset(map->marks, 0, marks);
    dvec3 lo = dv(INFINITY, INFINITY, INFINITY);
    map->lights = 1;
    for (int c = 0; c < nchunks; c++)
        for (size_t k = 0; k < chunks[c].count; k++) {
            const struct ref_surface_photon *ph = &chunks[c].items[k];
            map->photons[map->count++] = *ph;
            if (ph->light >= 0 && (uint32_t)ph->light >= map->lights)
                map->lights = (uint32_t)ph->light + 1;
            lo = dv(fmin(lo.x, ph->position[0]), fmin(lo.y, ph->position[1]), fmin(lo.z, ph->position[2]));
        }
    memset(map->used, 0, n + 1);
    map->origin = n ? lo : dv(0, 0, 0);
    map->slots = 1;
    while (map->slots < 2 * n)
        map->slots *= 2;
    bool wanted[REF_PHOTON_MAP_LEVELS];
    int most = choose_levels(map, points_per_level, wanted);
    if (most < 0 || n == 0)
        return true;
    /* The most read level first; then the photons are put in its order
     * (the other levels, built after, index them in that order): a pixel's
     * photons then lie together in memory whichever level it reads. */
    if (!build_level(map, most))
        return false;
    uint32_t *e = map->levels[most].photon;
    for (size_t k = 0; k < n; k++)
        map->original[k] = e[k];
    for (size_t k = 0; k < n; k++) {
        map->rank[map->original[k]] = (uint32_t)k;
        e[k] = (uint32_t)k;
    }
    map->levels[most].identity = true;
    /* the permutation in place, cycle by cycle, the ranks as the marks */
    for (size_t i = 0; i < n; i++) {
        if (map->rank[i] == (uint32_t)i)
            continue;
        struct ref_surface_photon carried = map->photons[i];
        size_t at = i;
        while (map->rank[at] != (uint32_t)at) {
            size_t to = map->rank[at];
            struct ref_surface_photon next = map->photons[to];
            map->photons[to] = carried;
            carried = next;
            map->rank[at] = (uint32_t)at;
            at = to;
        }
    }
    for (size_t k = 0; k < n; k++)
        map->rank[map->original[k]] = (uint32_t)k;
    wanted[most] = false;
    return build_levels(map, wanted, threads);
}

bool ref_photon_map_build_levels(struct ref_photon_map *map, const size_t points_per_level[REF_PHOTON_MAP_LEVELS],
                                 int threads)
{
    bool wanted[REF_PHOTON_MAP_LEVELS];
    for (int l = 0; l < REF_PHOTON_MAP_LEVELS; l++)
        map->levels[l].built = false;
    if (choose_levels(map, points_per_level, wanted) < 0 || map->count == 0)
        return true;
    return build_levels(map, wanted, threads);
}

void ref_photon_map_collect_marks(struct ref_photon_map *map)
{
    size_t n = map->count, stride = n + REF_PHOTON_MAP_PAD;
    for (int t = 0; t < map->mark_threads; t++)
        for (size_t i = 0; i < n; i++)
            map->used[i] |= map->marks[(size_t)t * stride + i];
}

bool ref_photon_map_was_used(const struct ref_photon_map *map, size_t i)
{
    return i < map->count && map->used[map->rank[i]] != 0;
}

/* The gather tests and sums LANES photons at a time, from the level's
 * columns, with the compilers' vector types (GCC and Clang; lowered to
 * scalar code where a target has no vector unit). Scalar, it spent about
 * 120 instructions on each photon it took and tested almost 4 for each it
 * took (the cells are up to twice the radius); rearranging the scalar
 * loop (tiles, prefetching, float sums, a smaller record) never moved it
 * (docs/REFERENCE.md's levers). A slot is read in two passes: the
 * distance test over every group of four, then the normal test and the
 * sums over the groups with a photon inside, every lane of such a group
 * running them, masked (scan). */
#define LANES 4
typedef float lanes_f __attribute__((vector_size(LANES * sizeof(float))));
typedef int32_t lanes_i __attribute__((vector_size(LANES * sizeof(int32_t))));

static inline lanes_f lanes_load(const float *p)
{
    lanes_f v;
    memcpy(&v, p, sizeof v);
    return v;
}

static inline lanes_f lanes_splat(float x)
{
    return (lanes_f){0} + x;
}

/* v where the mask is set, else 0 */
static inline lanes_f lanes_select(lanes_i mask, lanes_f v)
{
    return (lanes_f)(mask & (lanes_i)v);
}

static inline lanes_f lanes_abs(lanes_f v)
{
    return (lanes_f)((lanes_i)v & 0x7fffffff);
}

/* bit i set where lane i's mask is */
static inline unsigned lanes_bits(lanes_i mask)
{
#if defined(__SSE2__) && LANES == 4
    return (unsigned)_mm_movemask_ps((__m128)mask);
#else
    unsigned bits = 0;
    for (int i = 0; i < LANES; i++)
        bits |= (unsigned)(mask[i] != 0) << i;
    return bits;
#endif
}

/* how many bits a group's mask has set */
_Static_assert(LANES == 4, "lanes_popcount and lanes_mark are written for four lanes");
static const unsigned char lanes_popcount[1 << LANES] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

/* marks the set lanes' bytes (at most one thread writes them) */
static inline void lanes_mark(unsigned char *marks, unsigned bits)
{
    /* one 4-byte OR: byte i is 1 where bit i is set, on either byte order */
    static const unsigned char spread[16][4] = {
        {0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {1, 1, 0, 0}, {0, 0, 1, 0}, {1, 0, 1, 0}, {0, 1, 1, 0}, {1, 1, 1, 0},
        {0, 0, 0, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, {1, 1, 0, 1}, {0, 0, 1, 1}, {1, 0, 1, 1}, {0, 1, 1, 1}, {1, 1, 1, 1}};
    uint32_t word, add;
    memcpy(&word, marks, 4);
    memcpy(&add, spread[bits], 4);
    word |= add;
    memcpy(marks, &word, 4);
}

/* the lanes summed in doubles, in a fixed order (the same sum on every
 * run: the reference is deterministic for a seed) */
static inline double lanes_sum(lanes_f v)
{
    double s = 0.0;
    for (int i = 0; i < LANES; i++)
        s += (double)v[i];
    return s;
}

/* The sums a gather keeps in lanes; they go into doubles every
 * FLUSH_GROUPS groups that took photons (a float sum of a few dozen
 * photons loses nothing an estimate could see; of thousands it might). */
#define FLUSH_GROUPS 64

/* groups a slot is read in at a time (ref_photon_map_gather) */
#define SCAN_BATCH 64
struct lanes_sums {
    lanes_f flux[3], inner, inner_sq, ring, ring_sq, moment[2], moment_sq[2], inner_flux[3];
    lanes_i inner_count;
};

static inline __attribute__((always_inline)) void lanes_flush(struct lanes_sums *acc, double flux[3],
                                                              struct ref_photon_rings *st, bool want_flux,
                                                              bool want_rings)
{
    if (want_flux)
        for (int c = 0; c < 3; c++)
            flux[c] += lanes_sum(acc->flux[c]);
    if (!want_rings)
        return;
    for (int c = 0; c < 3; c++)
        st->inner_flux[c] += lanes_sum(acc->inner_flux[c]);
    st->inner += lanes_sum(acc->inner);
    st->inner_sq += lanes_sum(acc->inner_sq);
    st->ring += lanes_sum(acc->ring);
    st->ring_sq += lanes_sum(acc->ring_sq);
    for (int c = 0; c < 2; c++) {
        st->moment[c] += lanes_sum(acc->moment[c]);
        st->moment_sq[c] += lanes_sum(acc->moment_sq[c]);
    }
    for (int i = 0; i < LANES; i++)
        st->inner_count -= acc->inner_count[i]; /* the masks are -1 */
}

/* On x86-64 the gather is built twice, for AVX2 and for the baseline,
 * and the loader picks the one the machine runs: the same four lanes, in
 * VEX's three-operand forms (0.92x the whole reference at 2.5 R). Not FMA:
 * a fused multiply-add would round the distances differently; without it
 * both builds give the same image, bit for bit. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) || defined(__x86_64__) && defined(__clang__) && __clang_major__ >= 14
#define GATHER_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define GATHER_CLONES
#endif

/* The photons within r of p on the lit side of a surface like the one
 * whose normal is n: their scaled flux, weighted by Epanechnikov's kernel,
 * summed into *flux (want_flux), and their grey flux (unweighted) split
 * between the inner half radius and the ring into *rings (want_rings).
 * Inlined into each caller, so that the sums it does not want fold away. */
static inline __attribute__((always_inline)) long
scan(const struct ref_photon_map *map, int thread, dvec3 p, dvec3 n, double r, const double *light_scale, dvec3 *flux,
     struct ref_photon_rings *rings, long limit, bool want_flux, bool want_rings)
{
    if (map->count == 0 || !(r > 0.0))
        return 0;
    const struct ref_photon_map_level *lv = &map->levels[map->read_level[ref_photon_map_level_of(map, r)]];
    if (!lv->built)
        return 0;
    double qx = p.x - map->origin.x, qy = p.y - map->origin.y, qz = p.z - map->origin.z;
    long x0 = cell_coordinate(qx - r, lv->cell), x1 = cell_coordinate(qx + r, lv->cell);
    long y0 = cell_coordinate(qy - r, lv->cell), y1 = cell_coordinate(qy + r, lv->cell);
    long z0 = cell_coordinate(qz - r, lv->cell), z1 = cell_coordinate(qz + r, lv->cell);
    /* the cell is at least r, so the box spans at most 3 cells an axis
     * (a radius past the last level's cell: clamp, and lose the far part
     * rather than loop over a huge box) */
    x1 = x1 > x0 + 2 ? x0 + 2 : x1;
    y1 = y1 > y0 + 2 ? y0 + 2 : y1;
    z1 = z1 > z0 + 2 ? z0 + 2 : z1;
    float r2 = (float)(r * r), inner2 = 0.25f * r2;
    lanes_f fx = lanes_splat((float)qx), fy = lanes_splat((float)qy), fz = lanes_splat((float)qz);
    float nx = (float)n.x, ny = (float)n.y, nz = (float)n.z;
    /* two directions across the surface, for the moments */
    dvec3 u = fabs(n.x) < 0.9 ? dv(0.0, n.z, -n.y) : dv(-n.z, 0.0, n.x); /* n x (1,0,0) or n x (0,1,0) */
    double ul = sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
    u = ul > 0.0 ? dv(u.x / ul, u.y / ul, u.z / ul) : dv(1, 0, 0);
    dvec3 v = dv(n.y * u.z - n.z * u.y, n.z * u.x - n.x * u.z, n.x * u.y - n.y * u.x);
    float inv_r = (float)(1.0 / r), inv_r2 = (float)(1.0 / (r * r));
    float ux = (float)u.x * inv_r, uy = (float)u.y * inv_r, uz = (float)u.z * inv_r;
    float vx = (float)v.x * inv_r, vy = (float)v.y * inv_r, vz = (float)v.z * inv_r;
    /* one light (or none scaled): its scale for every lane */
    bool per_lane_scale = light_scale && map->lights > 1;
    lanes_f scale = lanes_splat(light_scale ? (float)light_scale[0] : 1.0f);
    size_t stride = lv->stride;
    unsigned char *marks = want_flux && thread >= 0 && thread < map->mark_threads
                               ? map->marks + (size_t)thread * (map->count + REF_PHOTON_MAP_PAD)
                               : NULL;
    const float *X = lv->columns + REF_COLUMN_X * stride, *Y = lv->columns + REF_COLUMN_Y * stride,
                *Z = lv->columns + REF_COLUMN_Z * stride;
    const float *DX = lv->columns + REF_COLUMN_DX * stride, *DY = lv->columns + REF_COLUMN_DY * stride,
                *DZ = lv->columns + REF_COLUMN_DZ * stride;
    const float *NX = lv->columns + REF_COLUMN_NX * stride, *NY = lv->columns + REF_COLUMN_NY * stride,
                *NZ = lv->columns + REF_COLUMN_NZ * stride;
    const float *R = lv->columns + REF_COLUMN_R * stride, *G = lv->columns + REF_COLUMN_G * stride,
                *B = lv->columns + REF_COLUMN_B * stride;
    lanes_i lane;
    for (int i = 0; i < LANES; i++)
        lane[i] = i;
    struct lanes_sums acc = {0};
    struct ref_photon_rings st = {0};
    double sum[3] = {0.0, 0.0, 0.0};
    int pending = 0;
    size_t seen[27];
    int nseen = 0;
    long count = 0;
    for (long z = z0; z <= z1; z++)
        for (long y = y0; y <= y1; y++)
            for (long x = x0; x <= x1; x++) {
                size_t s = slot_of(map, x, y, z);
                uint32_t begin = lv->start[s], end = lv->start[s + 1];
                if (begin == end || !ref_slot_first(seen, &nseen, s))
                    continue;
                /* In batches, two passes: the distance test over every
                 * group, noting the groups with a photon inside (without
                 * a branch: a third of the groups have one, beyond the
                 * focus, too many and too scattered to predict),
                 * then the rest of the test and the sums over those. */
                for (uint32_t b0 = begin; b0 < end; b0 += LANES * SCAN_BATCH) {
                    uint32_t b1 = end - b0 > LANES * SCAN_BATCH ? b0 + LANES * SCAN_BATCH : end;
                    uint32_t hit[SCAN_BATCH];
                    int hits = 0;
                    for (uint32_t k = b0; k < b1; k += LANES) {
                        lanes_f dx = lanes_load(X + k) - fx, dy = lanes_load(Y + k) - fy, dz = lanes_load(Z + k) - fz;
                        /* the lanes past the slot's end read the next
                         * slot's entries (or the padding): masked out;
                         * outside r: the disc's, or a far cell sharing
                         * the slot */
                        lanes_i in = (lane < (int32_t)(end - k)) & (dx * dx + dy * dy + dz * dz <= r2);
                        hit[hits] = k;
                        hits += lanes_bits(in) != 0;
                    }
                    for (int h = 0; h < hits; h++) {
                        uint32_t k = hit[h];
                        /* (the distances again: cheaper than keeping them for every group) */
                        lanes_f dx = lanes_load(X + k) - fx, dy = lanes_load(Y + k) - fy, dz = lanes_load(Z + k) - fz;
                        lanes_f d2 = dx * dx + dy * dy + dz * dz;
                        lanes_i in = (lane < (int32_t)(end - k)) & (d2 <= r2);
                        /* same side of the same kind of surface, arriving from the lit side */
                        lanes_f along = nx * lanes_load(DX + k) + ny * lanes_load(DY + k) + nz * lanes_load(DZ + k);
                        lanes_f same = nx * lanes_load(NX + k) + ny * lanes_load(NY + k) + nz * lanes_load(NZ + k);
                        in &= (along < 0.0f) & (lanes_abs(same) >= 0.5f);
                        unsigned bits = lanes_bits(in);
                        if (!bits) /* none on the lit side: not counted */
                            continue;
                        count += lanes_popcount[bits];
                        if (limit > 0 && count > limit)
                            return limit + 1;
                        if (!want_flux && !want_rings)
                            continue;
                        lanes_f f = scale;
                        if (per_lane_scale)
                            for (int i = 0; i < LANES; i++)
                                f[i] = (float)light_scale[lv->light[k + (uint32_t)i]];
                        lanes_f fr = lanes_select(in, f * lanes_load(R + k)), fg = lanes_select(in, f * lanes_load(G + k)),
                                fb = lanes_select(in, f * lanes_load(B + k));
                        if (want_rings) {
                            lanes_i inner = in & (d2 <= inner2);
                            lanes_f g = (fr + fg + fb) * (1.0f / 3.0f);
                            lanes_f gi = lanes_select(inner, g), go = g - gi;
                            acc.inner += gi;
                            acc.inner_sq += gi * gi;
                            acc.ring += go;
                            acc.ring_sq += go * go;
                            acc.inner_flux[0] += lanes_select(inner, fr);
                            acc.inner_flux[1] += lanes_select(inner, fg);
                            acc.inner_flux[2] += lanes_select(inner, fb);
                            acc.inner_count += inner;
                            lanes_f ga = g * (dx * ux + dy * uy + dz * uz), gb = g * (dx * vx + dy * vy + dz * vz);
                            acc.moment[0] += ga;
                            acc.moment_sq[0] += ga * ga;
                            acc.moment[1] += gb;
                            acc.moment_sq[1] += gb * gb;
                        }
                        if (want_flux) {
                            /* Epanechnikov's kernel, 2 (1 - d^2/r^2): its
                             * integral over the disc is the disc's area, as the
                             * flat kernel's, so the estimate's scale is
                             * unchanged. The photons lie stratified
                             * (ref_emit.c), and a stratified set's count in a
                             * disc varies only by the photons its edge cuts: a
                             * kernel that falls to 0 there does not see them
                             * (issue 53: with the photons split at interfaces,
                             * one iteration's noise at a fixed radius 1.77% ->
                             * 1.41%). */
                            lanes_f w = 2.0f * (1.0f - d2 * inv_r2);
                            w = lanes_select(w > 0.0f, w); /* the masked lanes' flux is 0 already */
                            acc.flux[0] += fr * w;
                            acc.flux[1] += fg * w;
                            acc.flux[2] += fb * w;
                            /* the thread's own marks: no branch, no atomic */
                            if (marks && lv->identity)
                                lanes_mark(marks + k, bits);
                            else if (marks)
                                for (int i = 0; i < LANES; i++)
                                    marks[lv->photon[k + (uint32_t)i]] |= (unsigned char)((bits >> i) & 1u);
                        }
                        if (++pending == FLUSH_GROUPS) {
                            lanes_flush(&acc, sum, &st, want_flux, want_rings);
                            acc = (struct lanes_sums){0};
                            pending = 0;
                        }
                    }
                }
            }
    lanes_flush(&acc, sum, &st, want_flux, want_rings);
    if (want_flux)
        *flux = dv(sum[0], sum[1], sum[2]);
    if (want_rings)
        *rings = st;
    return count;
}

/* (the clones on a function of this file, which calls it: Clang 14
 * makes the loader's choice only for a clone its own file uses) */
static GATHER_CLONES long gather(const struct ref_photon_map *map, int thread, dvec3 p, dvec3 n, double r,
                                 const double *light_scale, dvec3 *flux, struct ref_photon_rings *rings)
{
    *flux = dv(0, 0, 0);
    if (!rings)
        return scan(map, thread, p, n, r, light_scale, flux, NULL, 0, true, false);
    *rings = (struct ref_photon_rings){0};
    return scan(map, thread, p, n, r, light_scale, flux, rings, 0, true, true);
}

long ref_photon_map_gather(const struct ref_photon_map *map, int thread, dvec3 p, dvec3 n, double r,
                           const double *light_scale, dvec3 *flux, struct ref_photon_rings *rings)
{
    return gather(map, thread, p, n, r, light_scale, flux, rings);
}

void ref_photon_map_rings(const struct ref_photon_map *map, dvec3 p, dvec3 n, double r, struct ref_photon_rings *rings)
{
    *rings = (struct ref_photon_rings){0};
    scan(map, -1, p, n, r, NULL, NULL, rings, 0, false, true);
}

long ref_photon_map_count(const struct ref_photon_map *map, dvec3 p, dvec3 n, double r, long limit)
{
    return scan(map, -1, p, n, r, NULL, NULL, NULL, limit, false, false);
}

void ref_photon_map_release(struct ref_photon_map *map)
{
    free(map->photons);
    free(map->original);
    free(map->rank);
    free(map->used);
    free(map->marks);
    for (int l = 0; l < REF_PHOTON_MAP_LEVELS; l++) {
        free(map->levels[l].start);
        free(map->levels[l].columns);
        free(map->levels[l].light);
        free(map->levels[l].photon);
        free(map->levels[l].scratch);
    }
    memset(map, 0, sizeof *map);
}
