/* Photon emission towards the specular triangles (ref_emit.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/vecmath.h"
#include "reference/ref_emit.h"

static bool is_dielectric(const struct material *m) { return m->kind == MATERIAL_GLASS || m->kind == MATERIAL_WATER; }

static dvec3 vertex(const struct ref_object *o, uint32_t i)
{
    const float *p = o->positions + (size_t)i * 3;
    return dv(p[0], p[1], p[2]);
}

/* How much of the light's view a triangle covers, and whether it faces the
 * light: a dielectric only on its outer side (lights sit outside every
 * dielectric, so a light ray enters one through a triangle whose outward
 * normal faces it; a closed mesh's far side is never a first hit), a
 * mirror on either side (it may be an open sheet). */
static double triangle_weight(const struct ref_light *l, const struct ref_object *o, const uint32_t *tri)
{
    dvec3 a = vertex(o, tri[0]), b = vertex(o, tri[1]), c = vertex(o, tri[2]);
    dvec3 n2 = dv_cross(dv_sub(b, a), dv_sub(c, a)); /* twice the area times the unit normal */
    double area = 0.5 * sqrt(dv_dot(n2, n2));
    if (!(area > 0.0) || !isfinite(area))
        return 0.0; /* zero-area triangles have no measure to hit */
    dvec3 n = dv_scale(n2, 0.5 / area);
    double facing; /* cosine between the normal and the direction towards the light */
    double falloff = 1.0;
    if (l->kind == 1) {
        facing = -dv_dot(n, l->direction);
    } else {
        dvec3 centre = dv_scale(dv_add(dv_add(a, b), c), 1.0 / 3.0);
        dvec3 to_light = dv_sub(l->position, centre);
        double d2 = dv_dot(to_light, to_light);
        if (!(d2 > 0.0))
            return 0.0;
        facing = dv_dot(n, dv_scale(to_light, 1.0 / sqrt(d2)));
        /* A spot's cone: the centre's factor, floored so that a triangle
         * with only a corner in the cone still has a chance (any positive
         * weight keeps the estimate unbiased; this one keeps it efficient). */
        falloff = fmax(ref_light_spot(l, dv_scale(to_light, -1.0 / sqrt(d2))), 0.02) / d2;
    }
    if (!is_dielectric(&o->material))
        facing = fabs(facing);
    return facing > 0.0 ? area * facing * falloff : 0.0;
}

bool ref_emitter_build(struct ref_emitter *e, const struct ref_scene *rs, const struct ref_light *l, struct error *err)
{
    memset(e, 0, sizeof *e);
    size_t n = 0;
    for (int i = 0; i < rs->object_count; i++)
        if (material_is_specular(&rs->objects[i].material))
            n += rs->objects[i].triangle_count;
    if (n == 0)
        return true;
    e->cdf = malloc(n * sizeof *e->cdf);
    e->object = malloc(n * sizeof *e->object);
    e->primitive = malloc(n * sizeof *e->primitive);
    if (!e->cdf || !e->object || !e->primitive) {
        ref_emitter_release(e);
        return error_set(err, "reference: out of memory for the photon targets (%zu triangles)", n);
    }
    double sum = 0.0;
    for (int i = 0; i < rs->object_count; i++) {
        const struct ref_object *o = &rs->objects[i];
        if (!material_is_specular(&o->material))
            continue;
        for (size_t t = 0; t < o->triangle_count; t++) {
            double w = triangle_weight(l, o, o->indices + t * 3);
            if (!(w > 0.0))
                continue;
            sum += w;
            e->cdf[e->count] = sum;
            e->object[e->count] = i;
            e->primitive[e->count] = (unsigned)t;
            e->count++;
        }
    }
    e->total = sum;
    for (size_t k = 0; k < e->count; k++)
        e->cdf[k] /= sum;
    if (e->count)
        e->cdf[e->count - 1] = 1.0;
    double grey = (l->intensity.x + l->intensity.y + l->intensity.z) / 3.0;
    e->power = e->count ? grey * sum : 0.0;
    return true;
}

void ref_emitter_release(struct ref_emitter *e)
{
    free(e->cdf);
    free(e->object);
    free(e->primitive);
    memset(e, 0, sizeof *e);
}

bool ref_emitter_sample(const struct ref_emitter *e, const struct ref_scene *rs, const struct ref_light *l,
                        long photons, struct ref_rng *rng, dvec3 *origin, dvec3 *dir, dvec3 *flux, int *object,
                        unsigned *primitive)
{
    if (e->count == 0 || photons <= 0)
        return false;
    double u = ref_rng_uniform(rng);
    size_t lo = 0, hi = e->count - 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (e->cdf[mid] > u)
            hi = mid;
        else
            lo = mid + 1;
    }
    double p_tri = e->cdf[lo] - (lo ? e->cdf[lo - 1] : 0.0);
    const struct ref_object *o = &rs->objects[e->object[lo]];
    const uint32_t *tri = o->indices + (size_t)e->primitive[lo] * 3;
    dvec3 a = vertex(o, tri[0]), b = vertex(o, tri[1]), c = vertex(o, tri[2]);
    /* a uniform point on the triangle */
    double s = sqrt(ref_rng_uniform(rng)), t = ref_rng_uniform(rng);
    dvec3 x = dv_add(dv_scale(a, 1.0 - s), dv_add(dv_scale(b, s * (1.0 - t)), dv_scale(c, s * t)));
    dvec3 n2 = dv_cross(dv_sub(b, a), dv_sub(c, a));
    double area = 0.5 * sqrt(dv_dot(n2, n2));
    if (!(p_tri > 0.0) || !(area > 0.0))
        return false;
    dvec3 n = dv_scale(n2, 0.5 / area);
    *object = e->object[lo];
    *primitive = e->primitive[lo];
    if (l->kind == 1) {
        /* Directional: the photon crosses a plane far upstream at the point
         * whose ray meets x; its density there is p_tri / (area |cos|). */
        double c_abs = fabs(dv_dot(n, l->direction));
        if (!(c_abs > 1e-12))
            return false;
        dvec3 ext = dv_sub(rs->bounds_hi, rs->bounds_lo);
        double back = sqrt(dv_dot(ext, ext)) + 1.0;
        *dir = l->direction;
        *origin = dv_sub(x, dv_scale(l->direction, back));
        *flux = dv_scale(l->intensity, area * c_abs / (p_tri * (double)photons));
        return true;
    }
    /* Point and spot: the direction's density over the sphere is
     * p_tri / area * d^2 / |cos| (area measure to solid angle). */
    dvec3 to = dv_sub(x, l->position);
    double d2 = dv_dot(to, to);
    if (!(d2 > 0.0))
        return false;
    double d = sqrt(d2);
    *dir = dv_scale(to, 1.0 / d);
    double c_abs = fabs(dv_dot(n, *dir));
    double spot = ref_light_spot(l, *dir);
    if (!(c_abs > 1e-12) || spot <= 0.0)
        return false;
    *origin = l->position;
    *flux = dv_scale(l->intensity, spot * area * c_abs / (d2 * p_tri * (double)photons));
    return true;
}
