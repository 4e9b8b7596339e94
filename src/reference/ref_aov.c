/* Debug outputs traced exactly (reference.h, enum ref_aov): from every
 * pixel centre one deterministic path that always refracts where it can,
 * through the first two interfaces only — the model of the refraction
 * pass (Hu & Qin, §2.1: a front and a back surface) — so that its `tir`
 * and `exit` outputs can be counted against an exact tracer of the same
 * model. Entering a dielectric, total internal reflection is possible only
 * for an IOR below 1; leaving it, beyond the critical angle. */
#include "reference/ref_scene.h"
#include "reference/reference.h"

/* One pixel: out[0] = TIR events (0 to 2), out[1..3] = exit direction,
 * covered = the pixel sees a refractor or a mirror first. */
static void trace_pixel(const struct ref_scene *rs, int x, int y, int w, int h, double *tir, dvec3 *exit_dir,
                        bool *covered)
{
    dvec3 origin, dir;
    ref_scene_camera_ray(rs, x + 0.5, y + 0.5, w, h, &origin, &dir);
    *tir = 0.0;
    *exit_dir = dv(0, 0, 0);
    *covered = false;
    struct ref_hit hit;
    if (!ref_scene_intersect(rs, origin, dir, INFINITY, &hit))
        return;
    const struct material *m = &rs->objects[hit.object].material;
    dvec3 n = dv_dot(dir, hit.shading_normal) < 0.0 ? hit.shading_normal : dv_scale(hit.shading_normal, -1.0);
    dvec3 ng = dv_dot(dir, hit.geometric_normal) < 0.0 ? hit.geometric_normal : dv_scale(hit.geometric_normal, -1.0);
    if (m->kind == MATERIAL_MIRROR) {
        *covered = true;
        *exit_dir = ref_reflect(dir, n);
        return;
    }
    if (!ref_is_dielectric(m))
        return;
    *covered = true;
    dvec3 t1;
    if (!ref_refract(dir, n, 1.0 / m->ior, &t1)) {
        *tir = 1.0;
        *exit_dir = ref_reflect(dir, n);
        return;
    }
    /* the back surface: the next hit of the refracted ray */
    dvec3 p1 = dv_sub(hit.position, dv_scale(ng, rs->epsilon));
    struct ref_hit back;
    if (!ref_scene_intersect(rs, p1, t1, INFINITY, &back)) {
        *exit_dir = t1; /* an open surface (a water sheet): the ray goes on */
        return;
    }
    dvec3 m2 = dv_dot(t1, back.shading_normal) < 0.0 ? back.shading_normal : dv_scale(back.shading_normal, -1.0);
    dvec3 t2;
    if (ref_refract(t1, m2, m->ior, &t2)) {
        *exit_dir = t2;
    } else {
        *tir += 1.0;
        *exit_dir = ref_reflect(t1, m2);
    }
}

bool ref_render_aov(struct renderer *r, struct scene *scene, const struct ref_options *o, struct image *out,
                    struct error *err)
{
    struct ref_scene rs;
    if (!ref_scene_build(&rs, r, scene, o->tessellated, err))
        return false;
    if (!image_create(out, o->width, o->height, err)) {
        ref_scene_release(&rs);
        return false;
    }
    for (int y = 0; y < o->height; y++)
        for (int x = 0; x < o->width; x++) {
            double tir;
            dvec3 d;
            bool covered;
            trace_pixel(&rs, x, y, o->width, o->height, &tir, &d, &covered);
            float *p = out->rgba + ((size_t)y * (size_t)o->width + (size_t)x) * 4;
            if (o->aov == REF_AOV_TIR) {
                p[0] = (float)tir;
                p[1] = p[2] = 0.0f;
            } else {
                p[0] = (float)d.x;
                p[1] = (float)d.y;
                p[2] = (float)d.z;
            }
            p[3] = covered ? 1.0f : 0.0f;
        }
    ref_scene_release(&rs);
    return true;
}
