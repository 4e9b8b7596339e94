/* reference/ref_photon_map.c: the gather from the pixels' side against a
 * brute-force sum over every photon, on photons spread over a floor, a
 * wall and a dense cluster (radii across many levels, slots that several
 * cells share), and the structure sums against their definitions. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "reference/ref_photon_map.h"

static double uniform(unsigned *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) * (1.0 / 16777216.0);
}

struct brute {
    double flux[3], inner, ring, moment[2];
    long count, inner_count;
    long on_inner_edge; /* photons the float split between disc and ring may put either side */
};

/* every photon, as the map's gather defines them */
/* must[i]: photon i (in chunk order) is clearly taken; may[i]: taken or
 * on the float edge (either may be NULL) */
static struct brute brute_gather(const struct ref_surface_photons *chunks, int nchunks, dvec3 p, dvec3 n, double r,
                                 const double *scale, bool *must, bool *may)
{
    size_t index = 0;
    struct brute b = {{0, 0, 0}, 0, 0, {0, 0}, 0, 0, 0};
    dvec3 u = fabs(n.x) < 0.9 ? dv(0.0, n.z, -n.y) : dv(-n.z, 0.0, n.x);
    double ul = sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
    u = dv(u.x / ul, u.y / ul, u.z / ul);
    dvec3 v = dv(n.y * u.z - n.z * u.y, n.z * u.x - n.x * u.z, n.x * u.y - n.y * u.x);
    for (int c = 0; c < nchunks; c++)
        for (size_t k = 0; k < chunks[c].count; k++, index++) {
            const struct ref_surface_photon *ph = &chunks[c].items[k];
            double dx = ph->position[0] - p.x, dy = ph->position[1] - p.y, dz = ph->position[2] - p.z;
            double d2 = dx * dx + dy * dy + dz * dz;
            double along = n.x * ph->dir[0] + n.y * ph->dir[1] + n.z * ph->dir[2];
            double same = n.x * ph->normal[0] + n.y * ph->normal[1] + n.z * ph->normal[2];
            if (along >= 0.0 || fabs(same) < 0.5)
                continue;
            /* the map tests in floats: stay clear of the edge */
            if (fabs(d2 - r * r) < 1e-5 * r * r) {
                if (may)
                    may[index] = true;
                continue;
            }
            if (d2 > r * r)
                continue;
            if (must)
                must[index] = may[index] = true;
            /* counted and weighed like any other; only the rings' split
             * cannot be told for it */
            b.on_inner_edge += fabs(d2 - 0.25 * r * r) < 1e-5 * r * r;
            double f = scale[ph->light];
            b.count++;
            /* Epanechnikov's kernel, normalised to the disc's area */
            for (int q = 0; q < 3; q++)
                b.flux[q] += f * 2.0 * (1.0 - d2 / (r * r)) * ph->flux[q];
            double g = f * (ph->flux[0] + ph->flux[1] + ph->flux[2]) / 3.0;
            if (d2 <= 0.25 * r * r) {
                b.inner += g;
                b.inner_count++;
            } else {
                b.ring += g;
            }
            b.moment[0] += g * (dx * u.x + dy * u.y + dz * u.z) / r;
            b.moment[1] += g * (dx * v.x + dy * v.y + dz * v.z) / r;
        }
    return b;
}

int main(void)
{
    enum { CHUNKS = 5 };
    struct ref_surface_photons chunks[CHUNKS] = {{0}};
    unsigned seed = 12345u;
    /* a floor (y = 0, photons from above), a wall (x = 2, photons from -x),
     * a dense cluster on the floor, and photons arriving from below the
     * floor (the wrong side: never gathered by a point facing up) */
    for (int i = 0; i < 20000; i++) {
        struct ref_surface_photon ph = {{0}};
        int kind = i % 4;
        if (kind == 0 || kind == 3) {
            double s = kind == 3 ? 0.01 : 1.0;
            ph = (struct ref_surface_photon){{(float)(s * (uniform(&seed) * 2 - 1)), 0.0f, (float)(s * (uniform(&seed) * 2 - 1))},
                                             {0.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {1.0f, 0.5f, 0.25f}, i % 2, 0};
        } else if (kind == 1) {
            ph = (struct ref_surface_photon){{2.0f, (float)uniform(&seed), (float)(uniform(&seed) * 2 - 1)},
                                             {1.0f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f}, 0, 0};
        } else {
            ph = (struct ref_surface_photon){{(float)(uniform(&seed) * 2 - 1), 0.0f, (float)(uniform(&seed) * 2 - 1)},
                                             {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {9.0f, 9.0f, 9.0f}, 1, 0};
        }
        ph.aim = (uint32_t)i;
        CHECK(ref_surface_photons_push(&chunks[i % CHUNKS], &ph));
    }
    const double scale[2] = {1.0, 0.5};
    /* query points and radii spanning 1e-3 .. 0.5 (many levels) */
    enum { QUERIES = 400 };
    dvec3 points[QUERIES], normals[QUERIES];
    double radii[QUERIES];
    for (int q = 0; q < QUERIES; q++) {
        bool wall = q % 5 == 4;
        points[q] = wall ? dv(2.0, uniform(&seed), uniform(&seed) * 2 - 1)
                         : dv((uniform(&seed) * 2 - 1) * (q % 3 == 0 ? 0.01 : 1.0), 0.0,
                              (uniform(&seed) * 2 - 1) * (q % 3 == 0 ? 0.01 : 1.0));
        normals[q] = wall ? dv(-1, 0, 0) : dv(0, 1, 0);
        radii[q] = 0.001 * pow(500.0, uniform(&seed));
    }
    struct ref_photon_map map = {0};
    double rmax = 0.0;
    for (int q = 0; q < QUERIES; q++)
        rmax = fmax(rmax, radii[q]);
    ref_photon_map_prepare(&map, rmax);
    size_t per_level[REF_PHOTON_MAP_LEVELS] = {0};
    for (int q = 0; q < QUERIES; q++)
        per_level[ref_photon_map_level_of(&map, radii[q])]++;
    CHECK(ref_photon_map_build(&map, chunks, CHUNKS, per_level, 2));
    CHECK(map.count == 20000);
    bool all_equal = true, rings_equal = true, counts_equal = true;
    long gathered = 0, rings_compared = 0;
    static bool must[20000], may[20000];
    for (int q = 0; q < QUERIES; q++) {
        struct brute b = brute_gather(chunks, CHUNKS, points[q], normals[q], radii[q], scale, must, may);
        dvec3 flux;
        struct ref_photon_rings rings;
        long m = ref_photon_map_gather(&map, q % 2, points[q], normals[q], radii[q], scale, &flux, &rings);
        /* photons on the float edge may go either way: allow one */
        /* (the kernel's weight from the map's float distances: a
         * photon's within 1e-3 of the brute force's at the smallest radii) */
        if (labs(m - b.count) > 1 || fabs(flux.x - b.flux[0]) > 9.0 * (double)labs(m - b.count) + 1e-3 * (1 + b.flux[0]))
            all_equal = false;
        rings_compared += m == b.count && b.on_inner_edge == 0;
        if (m == b.count && b.on_inner_edge == 0 && (fabs(rings.inner - b.inner) > 1e-6 * (1 + b.inner) ||
                             fabs(rings.ring - b.ring) > 1e-6 * (1 + b.ring) || rings.inner_count != b.inner_count ||
                             fabs(rings.moment[0] - b.moment[0]) > 1e-4 * (1 + fabs(b.inner + b.ring)) ||
                             fabs(rings.moment[1] - b.moment[1]) > 1e-4 * (1 + fabs(b.inner + b.ring))))
            rings_equal = false;
        long limited = ref_photon_map_count(&map, points[q], normals[q], radii[q], 10);
        if (limited != (m > 10 ? 11 : m))
            counts_equal = false;
        gathered += m;
    }
    CHECK(all_equal);
    CHECK(rings_equal);
    CHECK(rings_compared > QUERIES / 2); /* the rings were compared on most queries */
    CHECK(counts_equal);
    CHECK(gathered > 1000); /* the queries found photons */
    /* photons from below the floor and on the wall facing away are never
     * used by floor points; the gathers marked the ones they took */
    ref_photon_map_collect_marks(&map);
    long used = 0, used_wrong_side = 0, missed = 0, extra = 0;
    size_t i = 0;
    for (int c = 0; c < CHUNKS; c++)
        for (size_t k = 0; k < chunks[c].count; k++, i++) {
            bool u = ref_photon_map_was_used(&map, i);
            used += u;
            if (u && chunks[c].items[k].dir[1] > 0.5f)
                used_wrong_side++;
            /* the gathers alternated between two threads' marks: the
             * photons either took are the brute force's */
            missed += must[i] && !u;
            extra += u && !may[i];
        }
    CHECK(used > 1000);
    CHECK(used_wrong_side == 0);
    CHECK(missed == 0);
    CHECK(extra == 0);
    /* rebuilt for other radii, the gathers still agree */
    ref_photon_map_prepare(&map, 0.05);
    size_t one_level[REF_PHOTON_MAP_LEVELS] = {0};
    one_level[ref_photon_map_level_of(&map, 0.05)] = 1;
    CHECK(ref_photon_map_build_levels(&map, one_level, 1));
    struct brute b = brute_gather(chunks, CHUNKS, dv(0.1, 0, 0.2), dv(0, 1, 0), 0.05, scale, NULL, NULL);
    dvec3 flux;
    long m = ref_photon_map_gather(&map, 0, dv(0.1, 0, 0.2), dv(0, 1, 0), 0.05, scale, &flux, NULL);
    CHECK(labs(m - b.count) <= 1);
    /* the kernel: one photon at half the radius weighs 2 (1 - 1/4) = 1.5,
     * one at the centre 2, and their sum over a disc of even photons is
     * the flat count's (checked against the brute force above) */
    struct ref_surface_photons single[1] = {{0}};
    struct ref_surface_photon one = {{0.05f, 0.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 0, 0};
    CHECK(ref_surface_photons_push(&single[0], &one));
    ref_photon_map_prepare(&map, 0.1);
    size_t single_level[REF_PHOTON_MAP_LEVELS] = {0};
    single_level[ref_photon_map_level_of(&map, 0.1)] = 1;
    CHECK(ref_photon_map_build(&map, single, 1, single_level, 1));
    CHECK(ref_photon_map_gather(&map, 0, dv(0, 0, 0), dv(0, 1, 0), 0.1, NULL, &flux, NULL) == 1);
    CHECK(fabs(flux.x - 1.5) < 1e-5);
    CHECK(ref_photon_map_gather(&map, 0, dv(0.05, 0, 0), dv(0, 1, 0), 0.1, NULL, &flux, NULL) == 1);
    CHECK(fabs(flux.y - 2.0) < 1e-5);
    /* one light's photons only: its scale for every lane */
    const double half[1] = {0.5};
    CHECK(ref_photon_map_gather(&map, 0, dv(0.05, 0, 0), dv(0, 1, 0), 0.1, half, &flux, NULL) == 1);
    CHECK(fabs(flux.y - 1.0) < 1e-5);
    ref_surface_photons_release(&single[0]);
    /* an empty map gathers nothing; a zero radius nothing */
    struct ref_surface_photons empty[1] = {{0}};
    CHECK(ref_photon_map_build(&map, empty, 1, per_level, 2));
    CHECK(ref_photon_map_gather(&map, 0, dv(0, 0, 0), dv(0, 1, 0), 0.1, NULL, &flux, NULL) == 0);
    CHECK(flux.x == 0.0);
    ref_photon_map_release(&map);
    for (int c = 0; c < CHUNKS; c++)
        ref_surface_photons_release(&chunks[c]);
    return check_finish("photon_map");
}
