#version 450 core
#include "common/frame.glsl"
#include "common/lighting.glsl"
#include "common/fresnel.glsl"
#include "common/material.glsl"
#include "common/shadows.glsl"
#include "common/medium.glsl"
#include "common/surface_light.glsl"
#include "common/roles.glsl"

in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_normal;   // world normal, w = object id + 1
layout(location = 2) out vec4 o_position; // world position, w = 1 on geometry

uniform vec3 u_color;
uniform vec3 u_emission; // a diffuse surface's own radiance (seen; it lights nothing)
uniform float u_ior;
uniform float u_ideal;
uniform vec3 u_absorption;
uniform vec3 u_tint; // glTF's transmission tint (struct material)
uniform float u_thickness; // glTF's thicknessFactor (world units): the path inside glass seen through one interface
uniform sampler2D u_thickness_texture;  // x its green channel (KHR_materials_volume's thicknessTexture)
uniform int u_thickness_set;            // 0: none, 1: TEXCOORD_0, 2: TEXCOORD_1
uniform vec3 u_thickness_transform[2];  // uv' = (dot(row0, (uv, 1)), dot(row1, (uv, 1)))
uniform int u_object_id;
uniform int u_blending; // 1: the second draw, of alphaMode BLEND surfaces over the rest (shade.c)

uniform sampler2D u_caustics[4];
uniform int u_has_caustics; // how many caustic irradiance images to add

void main()
{
    vec3 n = normalize(v_normal);
    vec3 view = view_direction(v_world);
    if (dot(n, view) > 0.0 && role_is(ROLE_RECEIVER))
        n = -n; // two-sided diffuse surfaces
    vec3 mapped = material_normal(n, v_world); // (derivatives: before any branch)
    if ((u_blending == 0 && material_cut_out()) || (u_single_sided == 1 && !gl_FrontFacing))
        discard; // a cut-out, or the back of a single-sided surface (glTF's doubleSided false)
    vec3 radiance;
    if (role_is(ROLE_RECEIVER)) {
        n = mapped;
        vec3 caustic = vec3(0.0);
        for (int k = 0; k < u_has_caustics; k++)
            caustic += texelFetch(u_caustics[k], ivec2(gl_FragCoord.xy), 0).rgb;
        radiance = surface_light_material(v_world, n, -view, u_color, u_emission, caustic);
    } else if (role_is(ROLE_MIRROR)) {
        radiance = u_color * environment_radiance(reflect(view, n));
    } else {
        // One interface only: the refraction passes trace the second. What
        // the light crosses inside is the material's thicknessFactor (glTF's
        // KHR_materials_volume: the thickness a rasterizer that sees one
        // surface stands in for the volume with), absorbed by Beer-Lambert.
        bool entering = dot(n, view) < 0.0;
        vec3 nn = entering ? n : -n;
        float eta = entering ? 1.0 / u_ior : u_ior;
        float f = fresnel_of(dot(-view, nn), eta, u_ideal);
        vec3 t = refract_or_reflect(view, nn, eta);
        float thickness = u_thickness;
        if (u_thickness_set > 0) {
            vec3 q = vec3(u_thickness_set == 2 ? v_texcoord1 : v_texcoord0, 1.0);
            thickness *= texture(u_thickness_texture, vec2(dot(u_thickness_transform[0], q),
                                                          dot(u_thickness_transform[1], q))).g;
        }
        vec3 inside = material_albedo(u_tint) * exp(-u_absorption * thickness); // x baseColorTexture
        radiance = f * environment_radiance(reflect(view, nn)) + (1.0 - f) * inside * environment_radiance(t);
    }
    o_color = vec4(radiance, u_blending == 1 ? material_alpha() : 1.0); // (blended by alpha in the second draw)
    o_normal = vec4(n, float(u_object_id + 1));
    o_position = vec4(v_world, 1.0);
}
