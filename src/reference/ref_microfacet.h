/* Rough dielectric interfaces in the reference: the GGX microfacet
 * distribution of Walter et al. 2007 ("Microfacet Models for Refraction
 * through Rough Surfaces", EGSR), with glTF's roughness (alpha =
 * roughness^2). ref_sppm.c's specular_step samples a microfacet normal
 * from D(m) |m.n| and weights the path by their eq. 41. */
#ifndef CAUSTICA_REF_MICROFACET_H
#define CAUSTICA_REF_MICROFACET_H

#include "reference/ref_scene.h"

/* A microfacet normal about the unit normal n, drawn from D(m) |m.n|
 * (Walter et al. eqs. 35-36: tan^2 theta_m = alpha^2 u1 / (1 - u1), phi =
 * 2 pi u2). */
dvec3 ref_ggx_sample_normal(dvec3 n, double alpha, double u1, double u2);
/* Smith's shadowing-masking of direction v (pointing away from the
 * surface) for microfacet m about n (eq. 34, with its chi+ of
 * (v.m)/(v.n)): 0 when v sees the back of m. */
double ref_ggx_g1(dvec3 v, dvec3 m, dvec3 n, double alpha);

#endif
