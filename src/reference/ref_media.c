#include "reference/ref_media.h"

#include <math.h>

#include "core/vecmath.h"

static dvec3 d3(vec3 v) { return dv(v.x, v.y, v.z); }

void ref_medium_init(struct ref_medium *rm, const struct medium *m)
{
    rm->present = m != NULL && m->max_density > 0.0f;
    if (!rm->present)
        return;
    rm->m = m;
    rm->homogeneous = m->grid == NULL;
    rm->sigma_s = d3(m->sigma_s);
    rm->sigma_a = d3(m->sigma_a);
    rm->sigma_t = dv_add(rm->sigma_s, rm->sigma_a);
    rm->g = m->g;
    rm->lo = d3(m->box_min);
    rm->hi = d3(m->box_max);
    double smax = fmax(rm->sigma_t.x, fmax(rm->sigma_t.y, rm->sigma_t.z));
    rm->majorant = smax * (double)m->max_density;
    rm->present = rm->majorant > 0.0;
}

bool ref_medium_clip(const struct ref_medium *rm, dvec3 o, dvec3 d, double tmax, double *t0, double *t1)
{
    if (!rm->present)
        return false;
    double lo = 0.0, hi = tmax;
    const double oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z}, bl[3] = {rm->lo.x, rm->lo.y, rm->lo.z},
                 bh[3] = {rm->hi.x, rm->hi.y, rm->hi.z};
    for (int a = 0; a < 3; a++) {
        if (fabs(dd[a]) < 1e-300) {
            if (oo[a] < bl[a] || oo[a] > bh[a])
                return false;
            continue;
        }
        double ta = (bl[a] - oo[a]) / dd[a], tb = (bh[a] - oo[a]) / dd[a];
        if (ta > tb) {
            double x = ta;
            ta = tb;
            tb = x;
        }
        lo = fmax(lo, ta);
        hi = fmin(hi, tb);
    }
    *t0 = lo;
    *t1 = hi;
    return hi > lo;
}

double ref_medium_density(const struct ref_medium *rm, dvec3 p)
{
    return medium_density(rm->m, vec3_make((float)p.x, (float)p.y, (float)p.z));
}

dvec3 ref_medium_transmittance(const struct ref_medium *rm, dvec3 o, dvec3 d, double tmax, struct ref_rng *rng)
{
    double t0, t1;
    if (!ref_medium_clip(rm, o, d, tmax, &t0, &t1))
        return dv(1, 1, 1);
    if (rm->homogeneous) {
        double len = (t1 - t0) * rm->m->density;
        return dv(exp(-rm->sigma_t.x * len), exp(-rm->sigma_t.y * len), exp(-rm->sigma_t.z * len));
    }
    /* Ratio tracking (Novak et al. 2014): the product over tentative
     * collisions of 1 - sigma_t(x) / majorant, per channel. */
    dvec3 tr = dv(1, 1, 1);
    double t = t0;
    for (int step = 0; step < 100000; step++) {
        t -= log(1.0 - ref_rng_uniform(rng)) / rm->majorant;
        if (t >= t1)
            break;
        double rho = ref_medium_density(rm, dv_add(o, dv_scale(d, t)));
        tr = dv_mul(tr, dv(1.0 - rm->sigma_t.x * rho / rm->majorant, 1.0 - rm->sigma_t.y * rho / rm->majorant,
                           1.0 - rm->sigma_t.z * rho / rm->majorant));
        if (fmax(tr.x, fmax(tr.y, tr.z)) < 1e-12)
            return dv(0, 0, 0);
    }
    return tr;
}

static double avg3(dvec3 v) { return (v.x + v.y + v.z) / 3.0; }

enum ref_medium_event ref_medium_track(const struct ref_medium *rm, dvec3 o, dvec3 d, double tmax,
                                       struct ref_rng *rng, double *t_out, dvec3 *weight)
{
    double t0, t1;
    if (!ref_medium_clip(rm, o, d, tmax, &t0, &t1))
        return REF_MEDIUM_PASS;
    double t = t0;
    for (int step = 0; step < 100000; step++) {
        t -= log(1.0 - ref_rng_uniform(rng)) / rm->majorant;
        if (t >= t1)
            return REF_MEDIUM_PASS;
        double rho = ref_medium_density(rm, dv_add(o, dv_scale(d, t)));
        dvec3 ss = dv_scale(rm->sigma_s, rho), sa = dv_scale(rm->sigma_a, rho);
        dvec3 sn = dv(rm->majorant - ss.x - sa.x, rm->majorant - ss.y - sa.y, rm->majorant - ss.z - sa.z);
        /* Event probabilities from the channel averages (they sum to one);
         * the per-channel weights keep the estimate unbiased. */
        double ps = avg3(ss) / rm->majorant, pa = avg3(sa) / rm->majorant;
        double u = ref_rng_uniform(rng);
        if (u < ps) {
            *weight = dv_mul(*weight, dv_scale(ss, 1.0 / (rm->majorant * ps)));
            *t_out = t;
            return REF_MEDIUM_SCATTER;
        }
        if (u < ps + pa)
            return REF_MEDIUM_ABSORB;
        double pn = 1.0 - ps - pa;
        if (pn <= 1e-12)
            return REF_MEDIUM_ABSORB;
        *weight = dv_mul(*weight, dv_scale(sn, 1.0 / (rm->majorant * pn)));
    }
    return REF_MEDIUM_ABSORB;
}

double ref_phase_hg(double g, double cos_theta)
{
    double denom = 1.0 + g * g - 2.0 * g * cos_theta;
    return (1.0 - g * g) / (4.0 * MATH_PI * denom * sqrt(fmax(denom, 1e-300)));
}
