#version 450 core
// The impostor's texel (Hu & Qin Fig. 12): the object's depth along the
// axis from the rectangle's plane (for Fig. 16's correction), and its
// radiance seen from the refractor's side: Lambert from the lights (no
// shadows) plus the ambient, as `shade` lights diffuse surfaces.
#include "common/frame.glsl"
#include "common/lighting.glsl"
in vec3 v_world;
in vec3 v_normal;
uniform vec3 u_impostor_center;
uniform vec3 u_impostor_axis;
uniform vec3 u_color;
layout(location = 0) out vec4 o_depth;
layout(location = 1) out vec4 o_color;
void main()
{
    o_depth = vec4(dot(v_world - u_impostor_center, u_impostor_axis), 0.0, 0.0, 1.0);
    vec3 n = normalize(v_normal);
    if (dot(n, u_impostor_axis) > 0.0)
        n = -n; // the side the refractor sees
    vec3 e = vec3(0.0);
    for (int i = 0; i < u_counts.x; i++) {
        vec3 to_light;
        float dist;
        e += light_irradiance(i, v_world, n, to_light, dist);
    }
    o_color = vec4(u_color / PI * e + u_color * u_ambient.rgb, 1.0);
}
