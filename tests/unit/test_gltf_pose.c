/* scene/gltf_pose.c against values worked out by hand: each sampler
 * between and outside its keys (a cubic spline with different in- and
 * out-tangents, which the Khronos files do not have), the spherical
 * interpolation of rotations, a node tree's composition, and the
 * decomposition of a world matrix with a mirror in it. */
#include "check.h"
#include "scene/gltf_pose.h"

int main(void)
{
    /* CUBICSPLINE, two keys 2 s apart (td = 2), per key in, value, out:
     * at u = 1/2 the Hermite weights are h00 = h01 = 1/2, h10 = 1/8,
     * h11 = -1/8: 0.5 * 0 + 0.125 * 2 * 4 + 0.5 * 1 - 0.125 * 2 * (-2) = 2 */
    float cubic_times[] = {1, 3};
    float cubic_values[] = {9, 0, 4, /* key 0: in (unused), value, out */ -2, 1, 7 /* key 1: in, value, out */};
    struct gltf_channel cubic = {.node = 0, .path = GLTF_PATH_TRANSLATION, .interpolation = GLTF_CUBICSPLINE,
                                 .components = 1, .key_count = 2, .times = cubic_times, .values = cubic_values};
    float v[4];
    gltf_channel_sample(&cubic, 2.0, v);
    CHECK_NEAR(v[0], 2.0, 1e-6);
    gltf_channel_sample(&cubic, 0.0, v); /* before the first key: its value */
    CHECK_NEAR(v[0], 0.0, 0);
    gltf_channel_sample(&cubic, 10.0, v); /* after the last: its value */
    CHECK_NEAR(v[0], 1.0, 0);
    gltf_channel_sample(&cubic, 3.0, v);
    CHECK_NEAR(v[0], 1.0, 1e-6);

    /* STEP holds the earlier key up to the next; LINEAR a quarter of the way */
    float times[] = {0, 1, 2};
    float values[] = {0, 10, 30};
    struct gltf_channel step = {.path = GLTF_PATH_SCALE, .interpolation = GLTF_STEP, .components = 1,
                                .key_count = 3, .times = times, .values = values};
    gltf_channel_sample(&step, 0.999, v);
    CHECK_NEAR(v[0], 0.0, 0);
    gltf_channel_sample(&step, 1.0, v);
    CHECK_NEAR(v[0], 10.0, 0);
    struct gltf_channel linear = step;
    linear.interpolation = GLTF_LINEAR;
    gltf_channel_sample(&linear, 1.25, v);
    CHECK_NEAR(v[0], 15.0, 1e-5);

    /* rotations: half-way from identity to 90 degrees about z is 45
     * degrees about z; from q to -q (the same rotation) stays put */
    float s = 0.70710678f;
    float rot_values[] = {0, 0, 0, 1, 0, 0, s, s};
    struct gltf_channel rot = {.path = GLTF_PATH_ROTATION, .interpolation = GLTF_LINEAR, .components = 4,
                               .key_count = 2, .times = times, .values = rot_values};
    gltf_channel_sample(&rot, 0.5, v);
    CHECK_NEAR(v[2], 0.38268343, 1e-6);
    CHECK_NEAR(v[3], 0.92387953, 1e-6);
    float flip_values[] = {0, 0, s, s, 0, 0, -s, -s};
    rot.values = flip_values;
    gltf_channel_sample(&rot, 0.5, v);
    CHECK_NEAR(v[2] * v[3], 0.5, 1e-6); /* q or -q, never a zero quaternion */

    /* a tree: a root at x = 1 turned 90 degrees about y, its child at
     * z = 2 scaled by 3, animated to x = 5 at t >= 1 */
    struct gltf_node nodes[2] = {
        {.parent = -1, .mesh = -1, .camera = -1, .light = -1, .translation = {1, 0, 0},
         .rotation = {0, s, 0, s}, .scale = {1, 1, 1}},
        {.parent = 0, .mesh = 0, .camera = -1, .light = -1, .translation = {0, 0, 2}, .rotation = {0, 0, 0, 1},
         .scale = {3, 3, 3}},
    };
    float key_times[] = {0, 1};
    float key_values[] = {0, 0, 2, 5, 0, 0};
    struct gltf_channel move = {.node = 1, .path = GLTF_PATH_TRANSLATION, .interpolation = GLTF_LINEAR,
                                .components = 3, .key_count = 2, .times = key_times, .values = key_values};
    struct gltf_animation anim = {.name = "move", .channel_count = 1, .channels = &move, .start = 0, .end = 1};
    struct gltf_scene scene = {.node_count = 2, .nodes = nodes, .animation_count = 1, .animations = &anim};
    struct gltf_pose pose;
    struct error err;
    CHECK(gltf_pose_init(&pose, &scene, &err));
    /* rest: the child's origin at (1,0,0) + R_y(90)(0,0,2) = (3,0,0) */
    vec3 o = mat4_transform_point(pose.world[1], vec3_make(0, 0, 0));
    CHECK_NEAR(o.x, 3, 1e-5);
    CHECK_NEAR(o.z, 0, 1e-5);
    /* its x axis, scaled by 3 and turned: (0, 0, -3) */
    vec3 ax = mat4_transform_dir(pose.world[1], vec3_make(1, 0, 0));
    CHECK_NEAR(ax.z, -3, 1e-5);
    gltf_pose_at(&pose, &scene, 0, 2.0); /* held at (5, 0, 0): (1,0,0) + R_y(90)(5,0,0) = (1,0,-5) */
    o = mat4_transform_point(pose.world[1], vec3_make(0, 0, 0));
    CHECK_NEAR(o.x, 1, 1e-5);
    CHECK_NEAR(o.z, -5, 1e-5);
    CHECK(pose.driven[1] && !pose.driven[0]);

    /* decomposition: a mirror goes to the x scale, the rest is rotation */
    mat4 m = mat4_trs(vec3_make(1, 2, 3), quat_axis_angle(vec3_make(0, 0, 1), 0.5f), vec3_make(-2, 3, 4));
    vec3 p, sc;
    quat q;
    gltf_pose_decompose(m, &p, &q, &sc);
    mat4 back = mat4_trs(p, q, sc);
    for (int i = 0; i < 16; i++)
        CHECK_NEAR(back.m[i], m.m[i], 1e-5);
    CHECK_NEAR(sc.x, -2, 1e-5);
    gltf_pose_free(&pose);
    return check_finish("test_gltf_pose");
}
