#version 450 core
// The background: the environment (or the background colour) seen along
// each pixel's view ray.
#include "common/frame.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
void main()
{
    vec4 a = u_inv_view_proj * vec4(v_uv * 2.0 - 1.0, -1.0, 1.0);
    vec4 b = u_inv_view_proj * vec4(v_uv * 2.0 - 1.0, 1.0, 1.0);
    vec3 dir = normalize(b.xyz / b.w - a.xyz / a.w);
    o_color = vec4(environment_radiance(dir), 1.0);
}
