/* GGX microfacets for rough glass (ref_microfacet.h). */
#include "reference/ref_microfacet.h"

#include <math.h>

dvec3 ref_ggx_sample_normal(dvec3 n, double alpha, double u1, double u2)
{
    /* a frame about n (Duff et al. 2017's branchless basis) */
    double sign = n.z >= 0.0 ? 1.0 : -1.0;
    double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    dvec3 t = dv(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    dvec3 s = dv(b, sign + n.y * n.y * a, -n.y);
    u1 = fmin(u1, 1.0 - 1e-12);
    double tan2 = alpha * alpha * u1 / (1.0 - u1);
    double cos_t = 1.0 / sqrt(1.0 + tan2), sin_t = sqrt(fmax(0.0, 1.0 - cos_t * cos_t));
    double phi = 2.0 * MATH_PI * u2;
    dvec3 m = dv_add(dv_add(dv_scale(t, sin_t * cos(phi)), dv_scale(s, sin_t * sin(phi))), dv_scale(n, cos_t));
    return dv_normalize_or(m, n);
}

double ref_ggx_g1(dvec3 v, dvec3 m, dvec3 n, double alpha)
{
    double vn = dv_dot(v, n), vm = dv_dot(v, m);
    if (vm * vn <= 0.0)
        return 0.0;
    double cos2 = fmin(vn * vn, 1.0);
    double tan2 = (1.0 - cos2) / fmax(cos2, 1e-300);
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
}
