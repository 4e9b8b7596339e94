/* An Embree scene of one mesh in its own frame (its base shape), for the
 * precomputations that trace a mesh against itself: Wyman's thickness
 * (thickness.c) and the light transport table (transport.c). */
#ifndef CAUSTICA_MESH_EMBREE_H
#define CAUSTICA_MESH_EMBREE_H

#include <stdbool.h>

#include <embree3/rtcore.h>

#include "core/error.h"
#include "scene/scene.h"

/* A device and a committed scene holding the mesh (robust traversal);
 * release both with mesh_embree_release. */
bool mesh_embree_create(const struct mesh *m, RTCDevice *device, RTCScene *scene, struct error *err);
void mesh_embree_release(RTCDevice device, RTCScene scene);

#endif
