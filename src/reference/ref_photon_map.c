/* Surface photons and the multi-level grid that gathers them
 * (ref_photon_map.h). */
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

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

/* One level's grid: a counting sort of the photons by slot, stable (each
 * slot keeps the photon order). */
static bool build_level(struct ref_photon_map *map, int l)
{
    struct ref_photon_map_level *lv = &map->levels[l];
    size_t n = map->count;
    if (!reserve((void **)&lv->start, &map->slots_capacity[l], map->slots + 1, sizeof *lv->start) ||
        !reserve((void **)&lv->entries, &map->entries_capacity[l], n + 1, sizeof *lv->entries))
        return false;
    memset(lv->start, 0, (map->slots + 1) * sizeof *lv->start);
    for (size_t i = 0; i < n; i++) {
        const float *p = map->photons[i].position;
        lv->start[slot_of(map, cell_coordinate(p[0] - map->origin.x, lv->cell),
                          cell_coordinate(p[1] - map->origin.y, lv->cell),
                          cell_coordinate(p[2] - map->origin.z, lv->cell)) + 1]++;
    }
    for (size_t s = 0; s < map->slots; s++)
        lv->start[s + 1] += lv->start[s];
    for (size_t i = 0; i < n; i++) {
        const float *p = map->photons[i].position;
        double x = p[0] - map->origin.x, y = p[1] - map->origin.y, z = p[2] - map->origin.z;
        size_t s = slot_of(map, cell_coordinate(x, lv->cell), cell_coordinate(y, lv->cell), cell_coordinate(z, lv->cell));
        /* start[s] is the slot's fill point while filling; the shift below
         * turns the fill points back into starts */
        lv->entries[lv->start[s]++] = (struct ref_photon_map_entry){(float)x, (float)y, (float)z, (uint32_t)i};
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
    dvec3 lo = dv(INFINITY, INFINITY, INFINITY);
    for (int c = 0; c < nchunks; c++)
        for (size_t k = 0; k < chunks[c].count; k++) {
            const struct ref_surface_photon *ph = &chunks[c].items[k];
            map->photons[map->count++] = *ph;
            lo = dv(fmin(lo.x, ph->position[0]), fmin(lo.y, ph->position[1]), fmin(lo.z, ph->position[2]));
        }
    for (size_t i = 0; i < n; i++)
        atomic_init(&map->used[i], 0);
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
    struct ref_photon_map_entry *e = map->levels[most].entries;
    for (size_t k = 0; k < n; k++)
        map->original[k] = e[k].photon;
    for (size_t k = 0; k < n; k++) {
        map->rank[map->original[k]] = (uint32_t)k;
        e[k].photon = (uint32_t)k;
    }
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

bool ref_photon_map_was_used(const struct ref_photon_map *map, size_t i)
{
    return i < map->count && atomic_load_explicit(&map->used[map->rank[i]], memory_order_relaxed) != 0;
}

/* The photons within r of p on the lit side of a surface like the one
 * whose normal is n: their scaled flux, weighted by Epanechnikov's kernel,
 * summed into *flux, or with `rings` their grey flux (unweighted) split
 * between the inner half radius and the ring. */
#define SCAN_BLOCK 64
static long scan(const struct ref_photon_map *map, dvec3 p, dvec3 n, double r, const double *light_scale,
                 dvec3 *flux, struct ref_photon_rings *rings, long limit)
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
    float fx = (float)qx, fy = (float)qy, fz = (float)qz, r2 = (float)(r * r), inner2 = 0.25f * r2;
    float nx = (float)n.x, ny = (float)n.y, nz = (float)n.z;
    /* two directions across the surface, for the moments */
    dvec3 u = fabs(n.x) < 0.9 ? dv(0.0, n.z, -n.y) : dv(-n.z, 0.0, n.x); /* n x (1,0,0) or n x (0,1,0) */
    double ul = sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
    u = ul > 0.0 ? dv(u.x / ul, u.y / ul, u.z / ul) : dv(1, 0, 0);
    dvec3 v = dv(n.y * u.z - n.z * u.y, n.z * u.x - n.x * u.z, n.x * u.y - n.y * u.x);
    float ux = (float)u.x, uy = (float)u.y, uz = (float)u.z, vx = (float)v.x, vy = (float)v.y, vz = (float)v.z;
    double inv_r = 1.0 / r, inv_r2 = inv_r * inv_r;
    /* the structure sums in locals (through the pointer, every photon
     * stored them back) */
    struct ref_photon_rings st = {0};
    size_t seen[27];
    int nseen = 0;
    long count = 0;
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (long z = z0; z <= z1; z++)
        for (long y = y0; y <= y1; y++)
            for (long x = x0; x <= x1; x++) {
                size_t s = slot_of(map, x, y, z);
                if (!ref_slot_first(seen, &nseen, s))
                    continue;
                /* a slot in blocks: first the distance test alone, without
                 * branches (every entry written, the count moved on by the
                 * test), then the photons inside */
                for (uint32_t k0 = lv->start[s], end = lv->start[s + 1]; k0 < end; k0 += SCAN_BLOCK) {
                    uint32_t k1 = end - k0 > SCAN_BLOCK ? k0 + SCAN_BLOCK : end;
                    uint32_t inside[SCAN_BLOCK];
                    float inside_d2[SCAN_BLOCK];
                    int found = 0;
                    for (uint32_t k = k0; k < k1; k++) {
                        const struct ref_photon_map_entry *e = &lv->entries[k];
                        float dx = e->x - fx, dy = e->y - fy, dz = e->z - fz;
                        float d2 = dx * dx + dy * dy + dz * dz;
                        inside[found] = k;
                        inside_d2[found] = d2;
                        found += d2 <= r2; /* outside: the disc's, or a far cell sharing the slot */
                    }
                    for (int h = 0; h < found; h++) {
                        const struct ref_photon_map_entry *e = &lv->entries[inside[h]];
                        const struct ref_surface_photon *ph = &map->photons[e->photon];
                        /* same side of the same kind of surface, arriving from the lit side */
                        float along = nx * ph->dir[0] + ny * ph->dir[1] + nz * ph->dir[2];
                        float same = nx * ph->normal[0] + ny * ph->normal[1] + nz * ph->normal[2];
                        if (along >= 0.0f || fabsf(same) < 0.5f)
                            continue;
                        count++;
                        if (limit > 0 && count > limit)
                            return count;
                        double f = light_scale ? light_scale[ph->light] : 1.0;
                        if (rings) {
                            double g = f * (ph->flux[0] + ph->flux[1] + ph->flux[2]) * (1.0 / 3.0);
                            if (inside_d2[h] <= inner2) {
                                st.inner += g;
                                st.inner_sq += g * g;
                                for (int c = 0; c < 3; c++)
                                    st.inner_flux[c] += f * ph->flux[c];
                                st.inner_count++;
                            } else {
                                st.ring += g;
                                st.ring_sq += g * g;
                            }
                            float dx = e->x - fx, dy = e->y - fy, dz = e->z - fz;
                            double a = (dx * ux + dy * uy + dz * uz) * inv_r, b = (dx * vx + dy * vy + dz * vz) * inv_r;
                            st.moment[0] += g * a;
                            st.moment_sq[0] += g * g * a * a;
                            st.moment[1] += g * b;
                            st.moment_sq[1] += g * g * b * b;
                        }
                        if (!flux)
                            continue;
                        /* Epanechnikov's kernel, 2 (1 - d^2/r^2): its integral
                         * over the disc is the disc's area, as the flat
                         * kernel's, so the estimate's scale is unchanged.
                         * The photons lie stratified (ref_emit.c), and a
                         * stratified set's count in a disc varies only by
                         * the photons its edge cuts: a kernel that falls to
                         * 0 there does not see them (issue 53: with the
                         * photons split at interfaces, one iteration's noise
                         * at a fixed radius 1.77% -> 1.41%). */
                        double w = f * 2.0 * fmax(1.0 - inside_d2[h] * inv_r2, 0.0);
                        sx += ph->flux[0] * w;
                        sy += ph->flux[1] * w;
                        sz += ph->flux[2] * w;
                        if (!atomic_load_explicit(&map->used[e->photon], memory_order_relaxed))
                            atomic_store_explicit(&map->used[e->photon], 1, memory_order_relaxed);
                    }
                }
            }
    if (flux)
        *flux = dv(sx, sy, sz);
    if (rings)
        *rings = st;
    return count;
}

long ref_photon_map_gather(const struct ref_photon_map *map, dvec3 p, dvec3 n, double r, const double *light_scale,
                           dvec3 *flux, struct ref_photon_rings *rings)
{
    *flux = dv(0, 0, 0);
    if (rings)
        *rings = (struct ref_photon_rings){0};
    return scan(map, p, n, r, light_scale, flux, rings, 0);
}

void ref_photon_map_rings(const struct ref_photon_map *map, dvec3 p, dvec3 n, double r, struct ref_photon_rings *rings)
{
    *rings = (struct ref_photon_rings){0};
    scan(map, p, n, r, NULL, NULL, rings, 0);
}

long ref_photon_map_count(const struct ref_photon_map *map, dvec3 p, dvec3 n, double r, long limit)
{
    return scan(map, p, n, r, NULL, NULL, NULL, limit);
}

void ref_photon_map_release(struct ref_photon_map *map)
{
    free(map->photons);
    free(map->original);
    free(map->rank);
    free(map->used);
    for (int l = 0; l < REF_PHOTON_MAP_LEVELS; l++) {
        free(map->levels[l].start);
        free(map->levels[l].entries);
    }
    memset(map, 0, sizeof *map);
}
