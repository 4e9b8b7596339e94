/* Ray differentials as neighbouring rays (ref_footprint.h). */
#include "reference/ref_footprint.h"

void ref_footprint_camera(const struct ref_scene *rs, double px, double py, int width, int height,
                          struct ref_footprint *f)
{
    /* one pixel on, as the rasterizer's derivatives difference neighbours */
    ref_scene_camera_ray(rs, px + 1.0, py, width, height, &f->origin[0], &f->dir[0]);
    ref_scene_camera_ray(rs, px, py + 1.0, width, height, &f->origin[1], &f->dir[1]);
    f->valid = true;
}

static void triangle(const struct ref_object *o, unsigned primitive, dvec3 p[3], const float *n[3])
{
    const uint32_t *tri = o->indices + (size_t)primitive * 3;
    for (int k = 0; k < 3; k++) {
        const float *q = o->positions + tri[k] * 3;
        p[k] = dv(q[0], q[1], q[2]);
        n[k] = o->normals + tri[k] * 3;
    }
}

void ref_footprint_hit(const struct ref_scene *rs, struct ref_footprint *f, struct ref_hit *h)
{
    h->footprint = false;
    if (!f->valid)
        return;
    if (rs->objects[h->object].sphere) {
        f->valid = false; /* an exact sphere has no triangle to carry the footprint across: level 0 beyond it */
        return;
    }
    dvec3 p[3];
    const float *n[3];
    triangle(&rs->objects[h->object], h->primitive, p, n);
    dvec3 e1 = dv_sub(p[1], p[0]), e2 = dv_sub(p[2], p[0]);
    double d00 = dv_dot(e1, e1), d01 = dv_dot(e1, e2), d11 = dv_dot(e2, e2);
    double det = d00 * d11 - d01 * d01;
    dvec3 ng = h->geometric_normal;
    for (int k = 0; k < 2; k++) {
        /* the neighbour on the path's triangle's plane (Igehy's transfer) */
        double along = dv_dot(f->dir[k], ng);
        double t = dv_dot(dv_sub(p[0], f->origin[k]), ng) / along;
        if (!(fabs(along) > 1e-9) || !(t > 0.0) || !isfinite(t) || !(det > 1e-30 * d00 * d11)) {
            f->valid = false; /* a neighbour parallel to the plane, behind it, or a triangle of no area */
            return;
        }
        f->point[k] = dv_add(f->origin[k], dv_scale(f->dir[k], t));
        dvec3 r = dv_sub(f->point[k], p[0]);
        double d20 = dv_dot(r, e1), d21 = dv_dot(r, e2);
        f->bary[k][0] = (d11 * d20 - d01 * d21) / det;
        f->bary[k][1] = (d00 * d21 - d01 * d20) / det;
        h->dbary[2 * k] = f->bary[k][0] - h->bary_u;
        h->dbary[2 * k + 1] = f->bary[k][1] - h->bary_v;
    }
    h->footprint = true;
}

void ref_footprint_bounce(const struct ref_scene *rs, struct ref_footprint *f, const struct ref_hit *h, dvec3 in,
                          dvec3 out)
{
    if (!f->valid || !h->footprint)
        return;
    const struct ref_object *o = &rs->objects[h->object];
    const struct material *m = &o->material;
    if (m->roughness > 0.0f) {
        f->valid = false;
        return;
    }
    dvec3 p[3];
    const float *n[3];
    triangle(o, h->primitive, p, n);
    dvec3 ng = h->geometric_normal;
    bool entering = dv_dot(in, ng) < 0.0;
    bool reflected = (dv_dot(out, ng) < 0.0) != entering;
    for (int k = 0; k < 2; k++) {
        f->origin[k] = f->point[k];
        double u = f->bary[k][0], v = f->bary[k][1], w = 1.0 - u - v;
        dvec3 nk = dv(w * n[0][0] + u * n[1][0] + v * n[2][0], w * n[0][1] + u * n[1][1] + v * n[2][1],
                      w * n[0][2] + u * n[1][2] + v * n[2][2]);
        nk = dv_normalize_or(nk, ng);
        if (dv_dot(nk, ng) <= 0.0)
            nk = ng; /* as ref_scene_intersect: a flipped interpolation trusts the triangle */
        if (!entering)
            nk = dv_scale(nk, -1.0); /* facing the neighbour, as specular_step faces the path's */
        if (reflected) {
            f->dir[k] = ref_reflect(f->dir[k], nk);
        } else if (ref_is_dielectric(m)) {
            double eta = entering ? 1.0 / m->ior : m->ior;
            if (!ref_refract(f->dir[k], nk, eta, &f->dir[k])) {
                f->valid = false; /* the neighbour totally reflected where the path did not */
                return;
            }
        } /* else through a thin pane, undeviated */
    }
}
