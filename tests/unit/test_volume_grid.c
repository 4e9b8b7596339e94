/* reference/ref_volume_gather.c: the volume photons' grid. Where their
 * bounds hold few enough cells it is dense (a gather reads 9 runs of 3
 * cells), else a hash; either way a gather must take exactly the photons
 * within the radius, as a brute-force sum does, at points inside the
 * bounds, on their edges and outside them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "reference/ref_rng.h"
#include "reference/ref_sppm_internal.h"

static dvec3 brute_force(const struct volume_photons *v, double radius, double g, dvec3 x, dvec3 view)
{
    dvec3 sum = dv(0, 0, 0);
    for (size_t k = 0; k < v->count; k++) {
        const struct volume_photon *p = &v->items[k];
        dvec3 d = dv(p->position[0] - x.x, p->position[1] - x.y, p->position[2] - x.z);
        if (dv_dot(d, d) > radius * radius)
            continue;
        double ph = ref_phase_hg(g, -(p->dir[0] * view.x + p->dir[1] * view.y + p->dir[2] * view.z));
        sum = dv_add(sum, dv_scale(dv(p->flux[0], p->flux[1], p->flux[2]), ph));
    }
    return dv_scale(sum, 1.0 / (4.0 / 3.0 * MATH_PI * radius * radius * radius));
}

/* Gathers at random points in and around the box [0, 1]^3 (and the far
 * photon's place, if any) against the brute force; returns how many of
 * them found photons. */
static int compare(const struct volume_photons *v, const struct volume_grid *grid, double radius)
{
    struct ref_rng rng = ref_rng_seed(5, 1, 0);
    int found = 0;
    for (int i = 0; i < 400; i++) {
        dvec3 x = dv(1.2 * ref_rng_uniform(&rng) - 0.1, 1.2 * ref_rng_uniform(&rng) - 0.1,
                     1.2 * ref_rng_uniform(&rng) - 0.1);
        if (i % 10 == 0) /* on a face of the bounds, where the dense grid clamps */
            x.x = i % 20 == 0 ? 0.0 : 1.0;
        dvec3 view = dv(0.0, -1.0, 0.0);
        dvec3 want = brute_force(v, radius, 0.3, x, view), got = sppm_volume_estimate(grid, 0.3, x, view);
        CHECK_NEAR(got.x, want.x, 1e-9 * (1.0 + fabs(want.x)));
        CHECK_NEAR(got.z, want.z, 1e-9 * (1.0 + fabs(want.z)));
        found += want.x > 0.0;
    }
    return found;
}

int main(void)
{
    struct volume_photons chunks[2];
    memset(chunks, 0, sizeof chunks);
    struct ref_rng rng = ref_rng_seed(3, 2, 0);
    for (int k = 0; k < 4000; k++) {
        dvec3 p = dv(ref_rng_uniform(&rng), ref_rng_uniform(&rng), ref_rng_uniform(&rng));
        if (k % 97 == 0) /* some exactly on the bounds' faces */
            p.y = k % 2 ? 0.0 : 1.0;
        dvec3 d = dv(ref_rng_uniform(&rng) - 0.5, -1.0, ref_rng_uniform(&rng) - 0.5);
        double l = sqrt(dv_dot(d, d));
        sppm_volume_push(&chunks[k % 2], p, dv_scale(d, 1.0 / l), dv(1.0 + k % 3, 2.0, 0.5), 0);
    }
    struct volume_photons all = {0};
    for (int c = 0; c < 2; c++)
        for (size_t k = 0; k < chunks[c].count; k++) {
            const struct volume_photon *p = &chunks[c].items[k];
            sppm_volume_push(&all, dv(p->position[0], p->position[1], p->position[2]),
                             dv(p->dir[0], p->dir[1], p->dir[2]), dv(p->flux[0], p->flux[1], p->flux[2]), 0);
        }

    /* compact photons: the dense grid */
    const double radius = 0.07;
    struct volume_grid grid;
    sppm_volume_grid_build(&grid, chunks, 2, radius);
    CHECK(grid.dense);
    CHECK(grid.size > 0);
    CHECK(compare(&all, &grid, radius) > 100);
    sppm_volume_grid_release(&grid);

    /* one photon far away makes the bounds too large for a dense grid: the hash */
    dvec3 far = dv(1e4, 0.5, 0.5);
    sppm_volume_push(&chunks[1], far, dv(0, -1, 0), dv(1, 1, 1), 0);
    sppm_volume_push(&all, far, dv(0, -1, 0), dv(1, 1, 1), 0);
    sppm_volume_grid_build(&grid, chunks, 2, radius);
    CHECK(!grid.dense);
    CHECK(compare(&all, &grid, radius) > 100);
    dvec3 at_far = sppm_volume_estimate(&grid, 0.3, far, dv(0, -1, 0));
    CHECK(at_far.x > 0.0);
    sppm_volume_grid_release(&grid);

    /* no photons at all */
    struct volume_photons none[1];
    memset(none, 0, sizeof none);
    sppm_volume_grid_build(&grid, none, 1, radius);
    dvec3 zero = sppm_volume_estimate(&grid, 0.3, dv(0.5, 0.5, 0.5), dv(0, -1, 0));
    CHECK(zero.x == 0.0 && zero.y == 0.0 && zero.z == 0.0);
    sppm_volume_grid_release(&grid);

    for (int c = 0; c < 2; c++)
        free(chunks[c].items);
    free(all.items);
    return check_finish("volume_grid");
}
