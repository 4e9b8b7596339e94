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
    // the mean over the pixel where its directions span several texels (a
    // fine environment in a small image), as the refraction pass takes it
    // through an IOR-1.0 object
    o_color = vec4(environment_radiance_grad(dir, dFdx(dir), dFdy(dir)), 1.0);
}
