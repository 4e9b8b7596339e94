/* Whether a point is inside a closed mesh: the parity of the crossings of a
 * ray from it (Möller & Trumbore's ray-triangle test, in double). Used to
 * tell a pass that the camera is inside a refractor, where a technique that
 * assumes the view ray starts outside must change how it starts. */
#include <math.h>

#include "scene/scene.h"

/* A direction no mesh edge or vertex is likely to line up with, so a ray
 * along it does not graze a shared edge and count it twice or not at all. */
static const double PROBE[3] = {0.5773502691896257, 0.5773502692096257, 0.5773502691696257};

/* Whether the ray from o along PROBE crosses triangle abc; where it does,
 * *t is the distance along the ray and *facing_along whether the
 * triangle's front side (counter-clockwise) faces the way the ray goes. */
static bool crosses_at(const double o[3], const float *a, const float *b, const float *c, double *t,
                       bool *facing_along);

static bool crosses(const double o[3], const float *a, const float *b, const float *c)
{
    double t;
    bool along;
    return crosses_at(o, a, b, c, &t, &along);
}

static bool crosses_at(const double o[3], const float *a, const float *b, const float *c, double *t,
                       bool *facing_along)
{
    double e1[3], e2[3], s[3], h[3], q[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
        s[k] = o[k] - a[k];
    }
    h[0] = PROBE[1] * e2[2] - PROBE[2] * e2[1];
    h[1] = PROBE[2] * e2[0] - PROBE[0] * e2[2];
    h[2] = PROBE[0] * e2[1] - PROBE[1] * e2[0];
    double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (fabs(det) < 1e-300)
        return false; /* parallel to the triangle, or a zero-area one */
    double inv = 1.0 / det, u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) * inv;
    if (u < 0.0 || u > 1.0)
        return false;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = (PROBE[0] * q[0] + PROBE[1] * q[1] + PROBE[2] * q[2]) * inv;
    if (v < 0.0 || u + v > 1.0)
        return false;
    *t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv;
    *facing_along = det < 0.0; /* det = -PROBE . (e1 x e2) */
    return *t > 0.0;
}

/* The crossings of the ray from p along `direction` (+1: PROBE, -1: -PROBE). */
static size_t crossings(const struct mesh *m, vec3 p, double direction)
{
    const double o[3] = {p.x, p.y, p.z};
    size_t count = 0;
    for (size_t k = 0; k + 2 < m->index_count; k += 3) {
        const float *a = m->positions + (size_t)m->indices[k] * 3, *b = m->positions + (size_t)m->indices[k + 1] * 3,
                    *c = m->positions + (size_t)m->indices[k + 2] * 3;
        if (direction > 0.0) {
            count += crosses(o, a, b, c);
        } else { /* the ray along -PROBE is the mirror image's along +PROBE */
            const double mirrored[3] = {-o[0], -o[1], -o[2]};
            const float na[3] = {-a[0], -a[1], -a[2]}, nb[3] = {-b[0], -b[1], -b[2]}, nc[3] = {-c[0], -c[1], -c[2]};
            count += crosses(mirrored, na, nb, nc);
        }
    }
    return count;
}

static bool within_bounds(const struct mesh *m, vec3 p)
{
    return !(p.x < m->bounds_min.x || p.y < m->bounds_min.y || p.z < m->bounds_min.z || p.x > m->bounds_max.x ||
             p.y > m->bounds_max.y || p.z > m->bounds_max.z);
}

bool mesh_contains_point(const struct mesh *m, vec3 p)
{
    return within_bounds(m, p) && crossings(m, p, 1.0) % 2 == 1;
}

bool mesh_encloses_point(const struct mesh *m, vec3 p)
{
    /* A closed surface is crossed an odd number of times by every ray from
     * a point inside it; an open one (a floor plane seen from below: one
     * crossing up, none down) is not, so both opposite rays must agree.
     * Inside a solid, the nearest surface along the ray is also seen from
     * its back (its front faces out, the way the ray goes); a room's walls
     * face in, towards the point, and a camera in a room is where it
     * belongs. One pass along +PROBE gives the count and the nearest face. */
    if (!within_bounds(m, p))
        return false;
    const double o[3] = {p.x, p.y, p.z};
    double nearest = INFINITY;
    bool solid = false;
    size_t count = 0;
    for (size_t k = 0; k + 2 < m->index_count; k += 3) {
        double t;
        bool along;
        if (crosses_at(o, m->positions + (size_t)m->indices[k] * 3, m->positions + (size_t)m->indices[k + 1] * 3,
                       m->positions + (size_t)m->indices[k + 2] * 3, &t, &along)) {
            count++;
            if (t < nearest) {
                nearest = t;
                solid = along;
            }
        }
    }
    return solid && count % 2 == 1 && crossings(m, p, -1.0) % 2 == 1;
}

bool object_encloses_point(const struct object *o, vec3 p)
{
    mat4 inverse;
    if (!o->mesh || !mat4_inverse(object_model_matrix(o), &inverse))
        return false;
    return mesh_encloses_point(o->mesh, mat4_transform_point(inverse, p));
}

bool object_contains_point(const struct object *o, vec3 p)
{
    mat4 inverse;
    if (!o->mesh || !mat4_inverse(object_model_matrix(o), &inverse))
        return false;
    return mesh_contains_point(o->mesh, mat4_transform_point(inverse, p));
}
