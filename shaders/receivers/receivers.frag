#version 450 core
// The receivers as the camera sees them (the `receivers` building block,
// issue 26): every diffuse surface's world normal, turned to face the
// camera (two-sided, as shade lights them), w = 1 on a receiver; the
// depth buffer holds their depth; location 1, when the block has a
// position target, their world position, w = 1 + the object's id (which
// receiver: photon_caustics' caustic mapping picks its impostor by it;
// 0 where there is none). Liktor & Dachsbacher
// §5.3's camera-view G-buffer, Sandberg & Falemo §3.5's pass 1, and the
// receivers of Chaudhari's eye-space photon search are this one image.
#include "common/frame.glsl"
in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_normal;
layout(location = 1) out vec4 o_position;
uniform int u_object_id;
void main()
{
    vec3 n = normalize(v_normal);
    if (dot(n, view_direction(v_world)) > 0.0)
        n = -n;
    o_normal = vec4(n, 1.0);
    o_position = vec4(v_world, 1.0 + float(u_object_id));
}
