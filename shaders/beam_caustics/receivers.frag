#version 450 core
// What the camera sees (§5.3's camera-view geometry buffer): the depth of
// every surface (beams are clipped there) and the normal of the diffuse
// ones, facing the camera (the receivers of surface caustics).
#include "common/frame.glsl"
in vec3 v_world;
in vec3 v_normal;
uniform int u_material_kind; // 0 diffuse (set by renderer_draw_objects)
layout(location = 0) out vec4 o_normal; // xyz, w = 1 on a receiver
void main()
{
    vec3 n = normalize(v_normal);
    if (dot(n, view_direction(v_world)) > 0.0)
        n = -n; // two-sided, as shade lights them
    o_normal = vec4(n, u_material_kind == 0 ? 1.0 : 0.0);
}
