/* Whether a point is inside a closed mesh: the parity of the crossings of a
 * ray from it (Möller & Trumbore's ray-triangle test, in double). Used to
 * tell a pass that the camera is inside a refractor, where a technique that
 * assumes the view ray starts outside must change how it starts. */
#include <math.h>

#include "scene/scene.h"

/* A direction no mesh edge or vertex is likely to line up with, so a ray
 * along it does not graze a shared edge and count it twice or not at all. */
static const double PROBE[3] = {0.5773502691896257, 0.5773502692096257, 0.5773502691696257};

static bool crosses(const double o[3], const float *a, const float *b, const float *c)
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
    return (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) * inv > 0.0;
}

bool mesh_contains_point(const struct mesh *m, vec3 p)
{
    if (p.x < m->bounds_min.x || p.y < m->bounds_min.y || p.z < m->bounds_min.z || p.x > m->bounds_max.x ||
        p.y > m->bounds_max.y || p.z > m->bounds_max.z)
        return false;
    const double o[3] = {p.x, p.y, p.z};
    size_t count = 0;
    for (size_t k = 0; k + 2 < m->index_count; k += 3)
        count += crosses(o, m->positions + (size_t)m->indices[k] * 3, m->positions + (size_t)m->indices[k + 1] * 3,
                         m->positions + (size_t)m->indices[k + 2] * 3);
    return count % 2 == 1;
}

bool object_contains_point(const struct object *o, vec3 p)
{
    mat4 inverse;
    if (!o->mesh || !mat4_inverse(object_model_matrix(o), &inverse))
        return false;
    return mesh_contains_point(o->mesh, mat4_transform_point(inverse, p));
}
