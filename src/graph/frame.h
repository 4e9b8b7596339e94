/* The frame snapshot: everything a frame's passes and the reference read
 * about the scene, worked out once per frame by renderer_begin_frame:
 * the lights expanded as the shaders see them (a linear light into its
 * point samples, with a slot map back to the scene's lights), the camera's
 * matrices, each object's world and normal matrices and where its vertices
 * come from, and whether any geometry animates. Passes read it through
 * pass_frame.snapshot, the renderer uploads the uniform block from it, and
 * the reference builds its scene from it, so all three agree by
 * construction. */
#ifndef CAUSTICA_FRAME_H
#define CAUSTICA_FRAME_H

#include <stdbool.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "scene/scene.h"

struct frame_light {
    enum light_kind kind;   /* point, directional or spot: a linear light's samples are points */
    vec3 position;
    vec3 direction;         /* normalised */
    vec3 intensity;         /* a linear light's share per sample */
    float cos_outer, cos_inner; /* spot cone */
    int scene_light;        /* index in scene->lights */
};

enum frame_vertices {
    FRAME_VERTICES_MESH,     /* the mesh's own buffers */
    FRAME_VERTICES_MORPHED,  /* morph targets blended this frame */
    FRAME_VERTICES_DEFORMED, /* a deformer (after morphs) */
    FRAME_VERTICES_WATER,    /* a simulated water surface */
};

struct frame_object {
    const struct object *object;
    mat4 model, normal_matrix; /* normal_matrix: inverse transpose of model */
    enum frame_vertices vertices;
};

struct frame {
    int width, height;
    int index;   /* frame number */
    double time; /* seconds */
    vec3 eye;
    mat4 view, proj, view_proj, inv_view_proj;
    struct frame_light lights[SCENE_MAX_GPU_LIGHTS];
    int light_count;
    /* Per scene light: its first entry in `lights` and how many. */
    int light_first[SCENE_MAX_GPU_LIGHTS];
    int light_entries[SCENE_MAX_GPU_LIGHTS];
    struct frame_object *objects; /* in scene->objects order */
    int object_count, object_capacity;
    bool geometry_animated; /* a visible object morphs, deforms or is simulated */
    bool casters_animated;  /* ... and casts shadows */
};

void frame_init(struct frame *f);
bool frame_build(struct frame *f, const struct scene *scene, int width, int height, int index, double time,
                 struct error *err);
void frame_release(struct frame *f);
/* The snapshot of `object`, or NULL when it is not in the frame's scene. */
const struct frame_object *frame_object_of(const struct frame *f, const struct object *object);

#endif
