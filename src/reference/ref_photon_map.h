/* The reference's surface photons of one iteration and the map that
 * gathers them for the visible points.
 *
 * Stochastic progressive photon mapping (Hachisuka & Jensen 2009) can be
 * run either way round: each photon looks for the visible points whose
 * radius holds it, or each visible point looks for the photons within its
 * radius. The sums are the same; the memory traffic is not. Photons land
 * in a random order, so the first way reads a random pixel record for
 * every deposit (at 512^2 each photon lands within the radius of some 50
 * pixels: two thirds of the photon stage were those cache misses). Here
 * photons are only stored while they are traced, then every pixel, in
 * image order, reads the few grid cells its radius covers from arrays
 * sorted by cell, so neighbouring pixels read the same cells from cache.
 *
 * The visible points' radii span a wide range (a focused caustic is
 * gathered tightly, a dim floor widely), so the map keeps grids whose
 * cells are the largest radius halved again and again, and a point reads
 * the grid whose cell is at least its radius and less than twice it: at
 * most 3 cells along each axis, about 4 times the disc's area scanned,
 * whatever the radius. A grid few points would read is not built: they
 * read the next coarser one (more photons scanned for those few, one
 * pass over all the photons saved). The grids are built in parallel.
 *
 * Each grid keeps its photons as columns (one array a quantity), slot by
 * slot and, within a slot, in the Morton order of their place in the
 * cell, and a gather tests and sums four at a time: neighbours in a
 * column are neighbours in space, so a group of four is mostly all inside
 * a disc or all outside. Each gathering thread marks the photons it took
 * in a row of its own (no atomics), folded once the gathers are done.
 */
#ifndef CAUSTICA_REF_PHOTON_MAP_H
#define CAUSTICA_REF_PHOTON_MAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "reference/ref_scene.h" /* dvec3 */

/* Where light that went through specular surfaces met a diffuse one: the
 * point, the direction it travelled, the surface's geometric normal, its
 * flux, the light it came from and its entry in the chunk's aim log (so
 * that the gather can tell the emission which photons were useful). */
struct ref_surface_photon {
    float position[3], dir[3], normal[3], flux[3];
    int light;
    uint32_t aim;
};

/* One chunk's photons, in the order they were traced. */
struct ref_surface_photons {
    struct ref_surface_photon *items;
    size_t count, capacity;
};

/* False when out of memory (the photon is lost; the estimate stays finite). */
bool ref_surface_photons_push(struct ref_surface_photons *list, const struct ref_surface_photon *photon);
void ref_surface_photons_release(struct ref_surface_photons *list);

/* Hash grids read up to 27 cells around a point, and two cells may hash
 * to one slot: a slot is read once, or its photons would count twice.
 * True the first time `slot` is offered (and then remembered in seen). */
static inline bool ref_slot_first(size_t seen[27], int *count, size_t slot)
{
    for (int i = 0; i < *count; i++)
        if (seen[i] == slot)
            return false;
    seen[(*count)++] = slot;
    return true;
}

#define REF_PHOTON_MAP_LEVELS 24

/* A level's photons as columns, slot by slot (each slot in photon order):
 * the gather reads them a few lanes at a time (ref_photon_map.c), so each
 * quantity it tests or sums lies in an array of its own. Positions are
 * relative to the map's origin. */
enum ref_photon_map_column {
    REF_COLUMN_X, REF_COLUMN_Y, REF_COLUMN_Z,    /* position */
    REF_COLUMN_DX, REF_COLUMN_DY, REF_COLUMN_DZ, /* direction of travel */
    REF_COLUMN_NX, REF_COLUMN_NY, REF_COLUMN_NZ, /* the surface's normal */
    REF_COLUMN_R, REF_COLUMN_G, REF_COLUMN_B,    /* flux */
    REF_COLUMNS
};

/* Entries past a level's last, so that a read of a whole group of lanes
 * at the end stays inside the arrays (those lanes are masked out). */
#define REF_PHOTON_MAP_PAD 8

struct ref_photon_map_level {
    bool built;
    double cell;
    uint32_t *start;  /* slots + 1 offsets into the columns */
    float *columns;   /* REF_COLUMNS columns of `stride` entries each */
    size_t stride;    /* count + REF_PHOTON_MAP_PAD */
    uint32_t *light;  /* each entry's light */
    uint32_t *photon; /* and which photon (in the map's order) it is */
    bool identity;    /* photon[k] == k: the level the map's order follows */
    uint32_t *scratch; /* the build's: each photon's slot and subcell, and their order */
};

struct ref_photon_map {
    dvec3 origin;
    double top;   /* level L's cell is top / 2^L */
    size_t count, slots;
    /* the photons in the order of the most read level's cells (so that
     * the records a pixel reads lie together), and where each came from
     * in chunk order, and back */
    struct ref_surface_photon *photons;
    uint32_t *original, *rank;
    /* per gathering thread and photon (in the map's order): the thread
     * took it; each thread writes its own row, without atomics or
     * branches, and ref_photon_map_collect_marks folds the rows into used */
    unsigned char *marks;
    int mark_threads;
    unsigned char *used; /* per photon (in the map's order): a visible point gathered it */
    struct ref_photon_map_level levels[REF_PHOTON_MAP_LEVELS];
    int read_level[REF_PHOTON_MAP_LEVELS];     /* the built level a radius of each level reads */
    /* the arrays' sizes, kept from one build to the next */
    size_t photons_capacity, original_capacity, rank_capacity, used_capacity, marks_capacity;
    size_t slots_capacity[REF_PHOTON_MAP_LEVELS], columns_capacity[REF_PHOTON_MAP_LEVELS];
    size_t light_capacity[REF_PHOTON_MAP_LEVELS], photon_capacity[REF_PHOTON_MAP_LEVELS];
    size_t scratch_capacity[REF_PHOTON_MAP_LEVELS];
    uint32_t lights; /* 1 + the largest light index among the photons */
};

/* Sets the levels for radii up to rmax (> 0). */
void ref_photon_map_prepare(struct ref_photon_map *map, double rmax);

/* The level whose cell suits a radius r (at least r, less than 2r where
 * the levels reach that far down). */
int ref_photon_map_level_of(const struct ref_photon_map *map, double r);

/* Builds the map over the chunks' photons (in chunk order, so that sums do
 * not depend on the thread count), on up to `threads` threads (and for
 * gathers on threads 0 .. threads - 1, at most 64): the levels
 * that at least 1/64 of the points read (points_per_level, by
 * ref_photon_map_level_of), and the coarsest one that any point reads.
 * False when out of memory. */
bool ref_photon_map_build(struct ref_photon_map *map, const struct ref_surface_photons *chunks, int nchunks,
                          const size_t points_per_level[REF_PHOTON_MAP_LEVELS], int threads);

/* The photons a gather at p with radius r would take, in two parts: the
 * inner disc (radius r / 2) and the ring around it, each as the sum of
 * their grey flux and of its square (the variance of a sum of photons is
 * about the sum of their squares); and the first moments of their flux
 * along two directions across the surface, sum g (d.u) / r, with the sums
 * of their squares (both 0 on average where the light is even). The
 * structure test's sums. */
struct ref_photon_rings {
    double inner, inner_sq, ring, ring_sq;
    double moment[2], moment_sq[2];
    double inner_flux[3]; /* the inner disc's (scaled) flux, and how many photons */
    long inner_count;
};
void ref_photon_map_rings(const struct ref_photon_map *map, dvec3 p, dvec3 n, double r, struct ref_photon_rings *rings);

/* The photons within r of p that arrived on the side of the surface whose
 * normal is n (travelling against it) on a surface of the same kind
 * (normals within 60 degrees either way): their flux, each scaled by
 * light_scale[light] (NULL: 1) and by Epanechnikov's kernel 2 (1 - d^2/r^2)
 * (whose integral over the disc is its area: *flux / (pi r^2) estimates the
 * flux density), summed into *flux, and with `rings` (may be NULL) their
 * grey flux, unweighted, split as ref_photon_map_rings does; returns how
 * many. Marks them taken in `thread`'s row (one of the threads the build
 * was given; each gathering thread its own): ref_photon_map_collect_marks
 * then tells ref_photon_map_was_used. */
long ref_photon_map_gather(const struct ref_photon_map *map, int thread, dvec3 p, dvec3 n, double r,
                           const double *light_scale, dvec3 *flux, struct ref_photon_rings *rings);

/* How many photons a gather at p with radius r would take, counted up to
 * limit + 1 (limit 0: all). */
long ref_photon_map_count(const struct ref_photon_map *map, dvec3 p, dvec3 n, double r, long limit);

/* Builds the levels again over the photons the map holds, for other radii
 * (as ref_photon_map_build chooses them). False when out of memory. */
bool ref_photon_map_build_levels(struct ref_photon_map *map, const size_t points_per_level[REF_PHOTON_MAP_LEVELS],
                                 int threads);

/* After the gathers, before ref_photon_map_was_used: folds the threads'
 * marks. */
void ref_photon_map_collect_marks(struct ref_photon_map *map);

/* Whether the gathers took photon i (i counts the chunks' photons in
 * chunk order, as the build read them). */
bool ref_photon_map_was_used(const struct ref_photon_map *map, size_t i);

void ref_photon_map_release(struct ref_photon_map *map);

#endif
