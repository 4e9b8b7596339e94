#version 450 core
// The diffuse surfaces the camera sees (the caustics' receivers): world
// normal facing the camera, and depth (the depth buffer) for the photons'
// screen-space search.
#include "common/frame.glsl"
in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_normal; // xyz, w = 1 on a receiver
void main()
{
    vec3 n = normalize(v_normal);
    if (dot(n, view_direction(v_world)) > 0.0)
        n = -n; // two-sided, as shade lights them
    o_normal = vec4(n, 1.0);
}
