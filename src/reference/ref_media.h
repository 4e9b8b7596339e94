/* Participating media for the reference: transmittance (exact for a
 * homogeneous medium, ratio tracking otherwise), free-flight sampling by
 * weighted delta tracking (spectral tracking, Kutz et al. 2017) for RGB
 * coefficients, and the Henyey-Greenstein phase function. */
#ifndef CAUSTICA_REF_MEDIA_H
#define CAUSTICA_REF_MEDIA_H

#include <stdbool.h>

#include "reference/ref_rng.h"
#include "reference/ref_scene.h"

struct ref_medium {
    bool present, homogeneous;
    const struct medium *m; /* borrowed */
    dvec3 sigma_s, sigma_a, sigma_t; /* at density 1 */
    double g;
    dvec3 lo, hi;
    double majorant; /* >= every channel of sigma_t x density anywhere */
};

void ref_medium_init(struct ref_medium *rm, const struct medium *m);
/* The part [t0, t1] of the ray (o, d, [0, tmax]) inside the medium's box. */
bool ref_medium_clip(const struct ref_medium *rm, dvec3 o, dvec3 d, double tmax, double *t0, double *t1);
double ref_medium_density(const struct ref_medium *rm, dvec3 p);
/* Transmittance along the ray over [0, tmax] (an unbiased estimate for a
 * heterogeneous medium, exact for a homogeneous one). */
dvec3 ref_medium_transmittance(const struct ref_medium *rm, dvec3 o, dvec3 d, double tmax, struct ref_rng *rng);

enum ref_medium_event { REF_MEDIUM_PASS, REF_MEDIUM_SCATTER, REF_MEDIUM_ABSORB };
/* Tracks a particle along the ray over [0, tmax]: returns where it
 * scatters (t) or that it passed or was absorbed; `weight` is multiplied
 * by the tracking weights (1 for a grey medium). */
enum ref_medium_event ref_medium_track(const struct ref_medium *rm, dvec3 o, dvec3 d, double tmax,
                                       struct ref_rng *rng, double *t, dvec3 *weight);
/* Henyey-Greenstein: cos_theta between the light's travel direction and
 * the scattered direction. Integrates to 1 over the sphere. */
double ref_phase_hg(double g, double cos_theta);

#endif
