#version 450 core
// Thin-walled glass (material.thin; glTF's glass without KHR_materials_volume),
// blended by shade over what lies behind it: one surface, seen from both
// sides, that reflects F of the environment and lets (1 - F) x tint through
// undeviated, glTF's single-interface thin-walled BTDF (KHR_materials_
// transmission: the specular transmission lobe about the same normal, so no
// bending). Dual-source blending (shade.c): the colour is what the surface
// adds, the second output what it multiplies the image behind it by.
// The reference (ref_sppm.c's specular_step) follows the same rule.
// Which panes (u_panes, src/passes/helpers/thin_glass_over.c): 0 all; 1 all but those
// in front of a visible glass, water or mirror surface that a view technique
// draws later over shade's image (shade); 2 those alone, over that surface
// (the view technique). u_surface_depth: that surface's window depth.
#include "common/frame.glsl"
#include "common/lighting.glsl"
#include "common/fresnel.glsl"
#include "common/material.glsl"
#include "common/shadows.glsl"
#include "common/medium.glsl"
#include "common/surface_light.glsl"

in vec3 v_world;
in vec3 v_normal;
layout(location = 0, index = 0) out vec4 o_color;
layout(location = 0, index = 1) out vec4 o_filter;

uniform vec3 u_color;
uniform float u_ior;
uniform float u_ideal;
uniform vec3 u_tint;
uniform int u_panes;
uniform sampler2D u_surface_depth;
#ifdef VIEW_FROM_CENTER
// drawn into a distance map (src/passes/blocks/distance_map.c): seen from its centre
uniform vec3 u_center;
vec3 pane_view(vec3 p) { return normalize(p - u_center); }
#else
vec3 pane_view(vec3 p) { return view_direction(p); }
#endif

void main()
{
    if (u_panes != 0) {
        float surface = texelFetch(u_surface_depth, ivec2(gl_FragCoord.xy), 0).r;
        bool over = surface < 1.0 && gl_FragCoord.z < surface;
        if (over != (u_panes == 2))
            discard;
    }
    vec3 n = normalize(v_normal);
    vec3 view = pane_view(v_world);
    if (dot(n, view) > 0.0)
        n = -n; // seen from either side
    n = material_normal(n, v_world);
    if ((material_cut_out() && u_alpha_blend == 0) || (u_single_sided == 1 && !gl_FrontFacing))
        discard; // a crack cut out of a pane (alphaMode MASK) is a hole; a single-sided pane's back is not seen
    float cos_i = clamp(dot(-view, n), 0.0, 1.0);
    float f = fresnel_of(cos_i, 1.0 / u_ior, u_ideal);
    vec3 tint = material_albedo(u_tint); // base colour x baseColorTexture x COLOR_0
    float transmission = material_transmission();
    // transmission t < 1: the rest of the surface is diffuse of the base
    // colour, lit as any diffuse surface (the reference picks one per path)
    vec3 added = transmission * f * environment_radiance(reflect(view, n));
    if (transmission < 1.0)
        added += (1.0 - transmission) * surface_light_diffuse(v_world, n, material_albedo(u_color), vec3(0.0), vec3(0.0));
    vec3 passed = transmission * (1.0 - f) * tint;
    // alphaMode BLEND: the pane covers alpha of the pixel
    float a = u_alpha_blend == 1 ? material_alpha() : 1.0;
    o_color = vec4(a * added, 1.0);
    o_filter = vec4(a * passed + vec3(1.0 - a), 1.0);
}
