#version 450 core
// Pass 1 of Sandberg & Falemo §3.5: the receivers' world positions (and
// normals, facing the viewer), read back per pixel by the volumes.
#include "common/frame.glsl"
in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
void main()
{
    vec3 n = normalize(v_normal);
    if (dot(n, view_direction(v_world)) > 0.0)
        n = -n;
    o_position = vec4(v_world, 1.0);
    o_normal = vec4(n, 1.0);
}
