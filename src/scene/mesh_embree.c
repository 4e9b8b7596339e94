#include "scene/mesh_embree.h"

#include <string.h>

bool mesh_embree_create(const struct mesh *m, RTCDevice *device, RTCScene *scene, struct error *err)
{
    *device = rtcNewDevice(NULL);
    *scene = NULL;
    if (!*device)
        return error_set(err, "%s: Embree could not create a device", m->name);
    *scene = rtcNewScene(*device);
    rtcSetSceneFlags(*scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(*device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *verts = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                           m->vertex_count);
    unsigned *tris = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                             m->index_count / 3);
    if (!verts || !tris) {
        rtcReleaseGeometry(geom);
        mesh_embree_release(*device, *scene);
        return error_set(err, "%s: out of memory for its Embree scene", m->name);
    }
    memcpy(verts, m->positions, m->vertex_count * 3 * sizeof(float));
    memcpy(tris, m->indices, m->index_count * sizeof(unsigned));
    rtcCommitGeometry(geom);
    rtcAttachGeometry(*scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(*scene);
    return true;
}

void mesh_embree_release(RTCDevice device, RTCScene scene)
{
    if (scene)
        rtcReleaseScene(scene);
    if (device)
        rtcReleaseDevice(device);
}
