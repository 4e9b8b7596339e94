/* Where the reference's photons leave the lights: only towards the
 * specular triangles that face each light, a triangle chosen with
 * probability proportional to the solid angle (point and spot lights) or
 * projected area (directional lights) it covers, a point on it uniformly.
 * Only light whose first hit is specular can make a caustic, so no other
 * direction needs a photon (POV-Ray's photon `target`, done per triangle
 * instead of per bounding sphere). The estimator stays unbiased: each
 * photon's flux is the light's radiant intensity (or irradiance) over the
 * exact density of the direction it was given, and a photon whose first
 * hit is not the triangle it was aimed at is dropped (that direction is
 * counted by the triangle it does hit first; see docs/REFERENCE.md). */
#ifndef CAUSTICA_REF_EMIT_H
#define CAUSTICA_REF_EMIT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "reference/ref_rng.h"
#include "reference/ref_scene.h"

struct ref_emitter {
    float *corners;       /* per entry: the 3 corners of the triangle, or of the piece of it, aimed at */
    double *cdf;          /* count entries, increasing, the last = 1 */
    uint32_t *guide;      /* count + 1 entries: guide[m] = the first entry whose cdf exceeds m / count (Chen & Asau's
                           * guide table: the inverse CDF in O(1) expected, still monotone) */
    double *weight;       /* per entry: its share of the light's view (the first iteration's pdf, unnormalised) */
    double *sampled, *useful; /* per entry: photons aimed at it so far, and those of them that reached a visible point */
    uint32_t *cell;       /* per entry: its usefulness cell (ref_emitter_adapt pools the counts of a cell's entries) */
    double *cell_sampled, *cell_useful; /* per cell: the sums of its entries' counts (scratch of ref_emitter_adapt) */
    size_t cells;
    int *object;          /* per entry: the object and triangle */
    unsigned *primitive;
    size_t count;
    double total;         /* sum of the unnormalised weights */
    double power;         /* estimate of the power the light sends to its targets (W, grey), for sharing photons */
};

/* Builds light l's targets. A light that sees no specular triangle gets
 * count = 0 (and power = 0): it emits no caustic photons. */
bool ref_emitter_build(struct ref_emitter *e, const struct ref_scene *rs, const struct ref_light *l, struct error *err);
void ref_emitter_release(struct ref_emitter *e);

/* Adaptive emission (Issue 15, "photons only where they matter"): after
 * each iteration, each entry's pdf becomes its share of the light's view
 * times a usefulness, judged per cell (the entries whose centres share a
 * cube of the surface about 1/EMIT_CELLS of its area: a finely tessellated
 * surface's triangles each see a photon or two, too few to judge one by):
 * for a cell that has sent a photon to a visible point, the highest useful
 * fraction any cell has (so that every photon the camera's pixels gather
 * carries the same flux, and the emission's stratification survives), and
 * for one that has not, its fraction's posterior mean 1 / (tried + 2)
 * (never 0: no direction a caustic can come from is ever given density 0).
 * Every iteration samples from a pdf fixed before it starts and divides by
 * it, so each iteration's estimate stays unbiased (adaptive importance
 * sampling). */
void ref_emitter_adapt(struct ref_emitter *e);

/* The three numbers in [0, 1) that place photon `index` of a light: the
 * Halton sequence in bases 2, 3 and 5, shifted by `shift` modulo 1
 * (Cranley-Patterson rotation). Photons spread over the light's view like
 * a jittered grid, as POV-Ray spaces its photons, instead of clumping as
 * independent random points do: the density estimate's noise falls much
 * faster, and the random shift keeps each iteration's estimate unbiased. */
void ref_emit_point(uint64_t index, const double shift[3], double u[3]);

/* One photon of `photons` emitted by l at the point u of ref_emit_point:
 * origin, unit direction, flux, and the triangle it is aimed at (its first
 * hit must be that one). False when it carries nothing (outside a spot's
 * cone, a grazing triangle). */
bool ref_emitter_sample(const struct ref_emitter *e, const struct ref_scene *rs, const struct ref_light *l,
                        long photons, const double u[3], dvec3 *origin, dvec3 *dir, dvec3 *flux, int *object,
                        unsigned *primitive, size_t *entry);

#endif
