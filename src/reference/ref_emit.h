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

#include "core/error.h"
#include "reference/ref_rng.h"
#include "reference/ref_scene.h"

struct ref_emitter {
    double *cdf;          /* count entries, increasing, the last = 1 */
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

/* One photon of `photons` emitted by l: origin, unit direction, flux, and
 * the triangle it is aimed at (its first hit must be that one). False when
 * it carries nothing (outside a spot's cone, a grazing triangle). */
bool ref_emitter_sample(const struct ref_emitter *e, const struct ref_scene *rs, const struct ref_light *l,
                        long photons, struct ref_rng *rng, dvec3 *origin, dvec3 *dir, dvec3 *flux, int *object,
                        unsigned *primitive);

#endif
