#version 450 core
#include "illumination_textures/virtual_camera.glsl"
in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_target; // world normal facing the light, depth along D
void main()
{
    vec3 n = normalize(v_normal);
    if (dot(n, u_vc_d) > 0.0)
        n = -n; // the side the transmitted light arrives at
    o_target = vec4(n, vc_depth(v_world));
}
