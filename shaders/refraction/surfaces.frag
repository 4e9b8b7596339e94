#version 450 core
// Initial pass of Hu & Qin Fig. 4: the outward world normal of the front-
// or back-facing surface (w = Wyman's interpolated d_N), and its depth.
// The normal through the surface's normal map, where it has one
// (interface_normal.glsl), as refract.frag reads the front's.
in vec3 v_normal;
in vec3 v_world;
in float v_thickness;
in vec2 v_texcoord0;
in vec2 v_texcoord1;
uniform int u_texture_set[5];
uniform vec3 u_texture_transform[10];
#include "refraction/interface_normal.glsl"
layout(location = 0) out vec4 o_normal;
void main()
{
    o_normal = vec4(interface_normal(normalize(v_normal)), v_thickness);
}
