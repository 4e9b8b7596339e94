#version 450 core
// What thin-walled glass lets through towards a 2D shadow map's light
// (shadow_map.c blends these over the map: the colours multiplied, the
// least depth kept): (1 - F) x tint x transmission of each pane, F at the
// light's angle of incidence, as the reference's shadow rays see a pane
// (ref_scene_transmittance). A receiver behind the nearest pane takes the
// product of them all (common/shadows.glsl); one between two panes takes
// it too (an approximation: stacked panes are rare).
#include "common/frame.glsl"
#include "common/lighting.glsl"
#include "common/fresnel.glsl"
#include "common/material.glsl"
#include "common/roles.glsl"
in vec3 v_world;
in vec3 v_normal;
out vec4 o_filter;
uniform int u_light_index; // the light's entry in the frame's list
uniform float u_ior;
uniform float u_ideal;
uniform vec3 u_tint;
void main()
{
    vec3 to_light;
    float dist;
    light_arrival(u_light_index, v_world, to_light, dist);
    if (!role_is(ROLE_THIN)) { // a blended surface (alphaMode BLEND: diffuse, glass or a mirror)
        // a blended surface covers alpha of the light's way: 1 - alpha passes
        o_filter = vec4(vec3(1.0 - material_alpha()), gl_FragCoord.z);
        return;
    }
    vec3 n = normalize(v_normal);
    if (dot(n, to_light) < 0.0)
        n = -n;
    n = material_normal(n, v_world);
    if (material_cut_out() && u_alpha_blend == 0)
        discard; // a hole in the pane
    float f = fresnel_of(clamp(dot(to_light, n), 0.0, 1.0), 1.0 / u_ior, u_ideal);
    float transmission = material_transmission();
    float a = u_alpha_blend == 1 ? material_alpha() : 1.0; // BLEND: the pane covers alpha
    vec3 passed = a * transmission * (1.0 - f) * material_albedo(u_tint) + vec3(1.0 - a);
    o_filter = vec4(passed, gl_FragCoord.z);
}
