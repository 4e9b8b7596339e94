/* A glTF scene's node transforms at one moment (issue 51): an animation's
 * channels sampled over the rest pose (STEP, LINEAR with a spherical
 * interpolation for rotations, CUBICSPLINE: the glTF 2.0 specification,
 * Appendix C) and composed down the node tree. GL-free; unit tested in
 * tests/unit/test_gltf_pose.c against values worked out by hand. */
#ifndef CAUSTICA_GLTF_POSE_H
#define CAUSTICA_GLTF_POSE_H

#include <stdbool.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "io/gltf.h"

struct gltf_pose {
    int node_count;
    vec3 *translation;
    quat *rotation;
    vec3 *scale;
    bool *driven; /* an animation moves the node: its TRS is used, not the file's matrix */
    float (*weights)[GLTF_MAX_WEIGHTS];
    mat4 *world;  /* after gltf_pose_compose */
    bool *composed; /* scratch: whose world this composition has made */
};

bool gltf_pose_init(struct gltf_pose *pose, const struct gltf_scene *scene, struct error *err);
void gltf_pose_free(struct gltf_pose *pose);

/* The rest pose, then animation `animation` (< 0: none) at t seconds of
 * the file's clock: before its first key a channel holds the first key's
 * value, after its last the last's. Then the world matrices. */
void gltf_pose_at(struct gltf_pose *pose, const struct gltf_scene *scene, int animation, double t);

/* Skin `skin`'s joint matrices at the pose: each joint's world matrix times
 * its inverse bind matrix (glTF 2.0 §3.7.3.2), joint_count x 16 floats
 * into out, column-major. The skinned mesh's own node is not applied (the
 * specification has its transform ignored). */
void gltf_pose_joint_matrices(const struct gltf_pose *pose, const struct gltf_scene *scene, int skin, float *out);

/* One channel's value at t (out: `components` floats; a rotation comes out
 * normalised). */
void gltf_channel_sample(const struct gltf_channel *channel, double t, float *out);

/* A world matrix as position, rotation and scale (the rotation of its
 * normalised columns; a shear is lost, a mirror goes to the x scale). */
void gltf_pose_decompose(mat4 m, vec3 *position, quat *rotation, vec3 *scale);

#endif
