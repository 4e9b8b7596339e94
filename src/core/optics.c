/* One copy of the interface optics for the CPU (core/optics.h). */
#include "core/optics.h"

#include <math.h>

double optics_fresnel(double cos_i, double eta)
{
    cos_i = fmin(fmax(cos_i, 0.0), 1.0);
    double sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0)
        return 1.0;
    double cos_t = sqrt(fmax(0.0, 1.0 - sin2_t));
    double rs = (eta * cos_i - cos_t) / fmax(eta * cos_i + cos_t, 1e-300);
    double rp = (cos_i - eta * cos_t) / fmax(cos_i + eta * cos_t, 1e-300);
    return fmin(fmax(0.5 * (rs * rs + rp * rp), 0.0), 1.0);
}

double optics_fresnel_of(double cos_i, double eta, bool ideal)
{
    if (!ideal)
        return optics_fresnel(cos_i, eta);
    cos_i = fmin(fmax(cos_i, 0.0), 1.0);
    return eta * eta * (1.0 - cos_i * cos_i) >= 1.0 ? 1.0 : 0.0;
}

bool optics_refract(const double d[3], const double n[3], double eta, double t[3])
{
    double cos_i = -(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]);
    double sin2_t = eta * eta * fmax(1.0 - cos_i * cos_i, 0.0);
    if (sin2_t >= 1.0)
        return false;
    double cos_t = sqrt(fmax(1.0 - sin2_t, 0.0));
    double v[3], len2 = 0.0;
    for (int k = 0; k < 3; k++) {
        v[k] = eta * d[k] + (eta * cos_i - cos_t) * n[k];
        len2 += v[k] * v[k];
    }
    double len = sqrt(len2);
    for (int k = 0; k < 3; k++)
        t[k] = len > 1e-300 && isfinite(len) ? v[k] / len : d[k];
    return true;
}
