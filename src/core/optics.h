/* The optics of a dielectric interface in double precision, one copy for
 * the CPU code (the light transport tables, the reference): Fresnel's
 * reflectance and its ideal-interface form, and Snell's refraction. The
 * shaders' equivalents are shaders/common/fresnel.glsl (fresnel_dielectric,
 * fresnel_of) and GLSL's refract. */
#ifndef CAUSTICA_OPTICS_H
#define CAUSTICA_OPTICS_H

#include <stdbool.h>

/* Exact unpolarised Fresnel reflectance, eta = n_incident / n_transmitted:
 * 1 under total internal reflection, 0 for matched indices, in [0, 1]
 * for any cos_i (clamped to [0, 1]) and never a NaN. */
double optics_fresnel(double cos_i, double eta);
/* The reflectance of a material's interface: Fresnel's, or for an ideal
 * one (fresnel = false) 0, and 1 where refraction is impossible. */
double optics_fresnel_of(double cos_i, double eta, bool ideal);
/* Snell refraction of unit d about unit n facing against d (eta = n_from /
 * n_to) into unit t; false under total internal reflection (t untouched).
 * Never a NaN: grazing and degenerate input fall back to d. */
bool optics_refract(const double d[3], const double n[3], double eta, double t[3]);

#endif
