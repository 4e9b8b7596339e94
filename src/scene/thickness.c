/* Per-vertex thickness d_N for Wyman's refraction (SIGGRAPH 2005): the
 * distance from each vertex through the object along its inward normal,
 * precomputed once per mesh (that precomputation, and its going stale
 * when the mesh deforms, is what Hu & Qin's method removes). Traced with
 * Embree against the mesh itself. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <embree3/rtcore.h>

#include "scene/mesh_embree.h"
#include "scene/scene.h"

bool mesh_compute_thickness(struct mesh *m, struct error *err)
{
    if (m->thickness)
        return true;
    float *out = malloc(m->vertex_count * sizeof(float));
    if (!out)
        return error_set(err, "%s: out of memory for the thickness", m->name);
    RTCDevice device;
    RTCScene scene;
    if (!mesh_embree_create(m, &device, &scene, err)) {
        free(out);
        return false;
    }
    float extent = vec3_length(vec3_sub(m->bounds_max, m->bounds_min));
    for (size_t v = 0; v < m->vertex_count; v++) {
        const float *p = m->positions + v * 3, *n = m->normals + v * 3;
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        struct RTCRayHit rh;
        memset(&rh, 0, sizeof rh);
        float eps = 1e-4f * extent;
        rh.ray.org_x = p[0] - n[0] * eps;
        rh.ray.org_y = p[1] - n[1] * eps;
        rh.ray.org_z = p[2] - n[2] * eps;
        rh.ray.dir_x = -n[0];
        rh.ray.dir_y = -n[1];
        rh.ray.dir_z = -n[2];
        rh.ray.tfar = 2.0f * extent;
        rh.ray.mask = 0xffffffffu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx, &rh);
        /* an open mesh may let the ray out: fall back to no thickness */
        out[v] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? 0.0f : rh.ray.tfar + eps;
    }
    mesh_embree_release(device, scene);
    m->thickness = out;
    return true;
}
