#version 450 core
// Initial pass of Hu & Qin Fig. 4: the outward world normal of the front-
// or back-facing surface (w = Wyman's interpolated d_N), and its depth.
// The normal through the surface's normal map, where it has one
// (interface_normal.glsl), as refract.frag reads the front's. The front
// has none in an alphaMode MASK hole (a BLEND surface is kept: refract.frag
// blends it); the back is kept whole, so that a path that entered the glass
// finds its way out (Hu & Qin's exit search reads the back's depth; a hole
// there would send it to the environment).
in vec3 v_normal;
in vec3 v_world;
in float v_thickness;
in vec2 v_texcoord0;
in vec2 v_texcoord1;
uniform int u_texture_set[5];
uniform vec3 u_texture_transform[10];
#include "refraction/interface_normal.glsl"
uniform sampler2D u_base_color_texture;
#include "common/alpha.glsl" // glTF's MASK: a hole is no surface
layout(location = 0) out vec4 o_normal;
void main()
{
    vec3 n = interface_normal(normalize(v_normal));
    if (gl_FrontFacing && u_alpha_blend == 0 && material_cut_out())
        discard;
    o_normal = vec4(n, v_thickness);
}
