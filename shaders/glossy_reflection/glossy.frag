#version 450 core
// A glTF BRDF surface drawn again over the input image (glossy_reflection.c):
// its base lobe's mirror direction marched through the input's depth; where
// it meets a surface on screen, the lobe's albedo x (that surface as the
// input shows it, blurred over the lobe's width - the environment shade
// lit the lobe by) is added. The Lambert variant draws nothing.
#include "common/frame.glsl"
#include "common/lighting.glsl"
#include "common/fresnel.glsl"
#include "common/material.glsl"
#include "common/shadows.glsl"
#include "common/medium.glsl"
#include "common/surface_light.glsl"
#include "layers/scene_trace.glsl"

in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_color;
uniform vec3 u_color;
uniform sampler2D u_scene_mips; // the input colour with mipmaps

// What a lobe of albedo `albedo` and roughness `roughness` about mirror
// direction r adds: albedo x (the surface its march meets, blurred over the
// lobe's width, 2 alpha - the environment shade put there), faded under
// the geometry's horizon (normal ng); 0 where the march meets nothing
vec3 glossy_seen(vec3 albedo, vec3 r, float roughness, vec3 ng)
{
    float horizon = surface_horizon(r, ng);
    ivec2 px;
    float t;
    // (from a hair above the surface, along its geometric normal: the march
    // must not meet the surface it leaves)
    vec3 o = v_world + ng * (1e-4 * u_scene_extent);
    if (!(horizon > 0.0) || !(max(albedo.r, max(albedo.g, albedo.b)) > 1e-4) || !scene_trace_at(o, r, px, t))
        return vec3(0.0);
    // the lobe's width over the distance to what it meets, in pixels there:
    // the mip level of that radius (as refraction's seen_rough)
    float alpha = roughness * roughness;
    vec3 hit = o + r * t;
    float z = u_proj[3][3] == 0.0 ? max(-(u_view * vec4(hit, 1.0)).z, 1e-6) : 1.0;
    float pixel = 2.0 * z / (u_proj[1][1] * u_viewport.y);
    float radius = t * tan(min(2.0 * alpha, 1.2)) / max(pixel, 1e-9);
    vec2 uv = (vec2(px) + 0.5) * u_viewport.zw;
    vec3 seen = textureLod(u_scene_mips, uv, log2(max(radius, 1.0))).rgb;
    return albedo * (seen - environment_glossy(r, roughness)) * horizon;
}

void main()
{
#ifndef GLTF_BRDF
    discard; // (a Lambert surface has no glossy lobe)
#else
    vec3 n = normalize(v_normal);
    vec3 view = view_direction(v_world);
    if (dot(n, view) > 0.0)
        n = -n;
    vec3 mapped = material_normal(n, v_world); // (derivatives: before any branch)
    if (material_cut_out() || (u_single_sided == 1 && !gl_FrontFacing) || u_alpha_blend == 1)
        discard;
    BrdfMaterial m = material_brdf(u_color);
    vec3 v = -view;
    // the base lobe's share of the specular albedo, and a coat's, each
    // marched about its own mirror direction
    vec3 base;
    float coat;
    brdf_specular_albedos(mapped, v, m, base, coat);
    vec3 added = glossy_seen(base, reflect(view, mapped), m.roughness, n);
    if (coat > 1e-4)
        added += glossy_seen(vec3(coat), reflect(view, m.clearcoat_normal), m.clearcoat_roughness, n);
    o_color = vec4(added * material_occlusion(), 0.0);
#endif
}
