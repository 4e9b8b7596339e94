/* reference/ref_surface_gather.c: the structure test's restart, iteration
 * by iteration. Where the inner disc against the ring shows structure the
 * estimate starts again at half the radius; where only the moments do (a
 * slope: no bias for a symmetric kernel) it keeps what it has at a quarter
 * of its weight, and the estimate itself does not move. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "reference/ref_sppm_internal.h"

/* the pixel's caustic radiance as ref_sppm.c's estimate reads it */
static double estimate(const struct pixel *px, double passes)
{
    return px->tau.x / ((passes - px->passes_before - px->passes_missed) * MATH_PI * px->radius * px->radius);
}

static struct pixel pixel_with(double inner_vs_ring, double moment)
{
    struct pixel px;
    memset(&px, 0, sizeof px);
    px.radius = 1.0;
    px.radius_floor = 0.1;
    px.tau = dv(4.0, 4.0, 4.0);
    px.n = 100.0;
    px.passes_before = 2.0;
    px.passes_missed = 1.0;
    px.structure[0] = inner_vs_ring;
    px.structure[1] = moment;
    for (int k = 0; k < STRUCTURE_SUMS; k++)
        px.structure_var[k] = 1.0; /* sums of 10: 10 standard deviations */
    return px;
}

int main(void)
{
    const double passes = 9.0;
    /* no structure: nothing happens */
    struct pixel px = pixel_with(1.0, -2.0);
    CHECK(!sppm_structure_restart(&px, passes));
    CHECK(px.radius == 1.0 && px.tau.x == 4.0);

    /* the moments alone: half the radius, the estimate kept, its weight a quarter */
    px = pixel_with(0.0, 10.0);
    double before = estimate(&px, passes);
    CHECK(sppm_structure_restart(&px, passes));
    CHECK(px.radius == 0.5);
    CHECK(fabs(estimate(&px, passes) - before) < 1e-12 * before);
    CHECK(fabs((passes - px.passes_before - px.passes_missed) - 0.25 * 6.0) < 1e-12); /* 6 passes count as 1.5 */
    CHECK(fabs(px.n - 100.0 * 0.25 * 0.25) < 1e-12);
    CHECK(px.structure[1] == 0.0 && px.structure_var[1] == 0.0); /* the sums start again */

    /* the inner disc against the ring: the estimate starts again */
    px = pixel_with(10.0, 10.0);
    CHECK(sppm_structure_restart(&px, passes));
    CHECK(px.radius == 0.5);
    CHECK(px.tau.x == 0.0 && px.n == 0.0);
    CHECK(px.passes_before == passes && px.passes_missed == 0.0);

    /* at its floor a radius is not halved */
    px = pixel_with(10.0, 10.0);
    px.radius_floor = 0.6;
    CHECK(!sppm_structure_restart(&px, passes));
    CHECK(px.radius == 1.0);
    return check_finish("sppm_restart");
}
