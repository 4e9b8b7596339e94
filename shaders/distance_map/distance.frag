#version 450 core
// A texel of the distance map: the diffuse surface's radiance as `shade`
// computes it (Lambert from the lights with their shadow maps, ambient,
// emission; two-sided, the side facing the centre), and its distance from
// the centre (Szirmay-Kalos et al. 2005). Layer 1 keeps the nearest
// surface facing the centre beyond layer 0's (src/passes/distance_map.h).
#include "common/frame.glsl"
#include "common/lighting.glsl"
#include "common/material.glsl"
#include "common/shadows.glsl"
uniform samplerCube u_first; // layer 0's distances
uniform int u_layer;
in vec3 v_world;
in vec3 v_normal;
uniform vec3 u_center;
uniform vec3 u_color;
uniform vec3 u_emission;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_distance;
void main()
{
    vec3 n = normalize(v_normal);
    float dist = length(v_world - u_center);
    if (u_layer == 1) {
        // peel: beyond layer 0 (by a relative margin: its texel holds the
        // distance at its centre), and facing the centre (a closed object's
        // far side is not what a ray passing behind it sees)
        if (dist <= texture(u_first, v_world - u_center).r * 1.01 + 1e-4 || dot(n, v_world - u_center) > 0.0)
            discard;
    }
    if (dot(n, v_world - u_center) > 0.0)
        n = -n; // the side the centre sees
    n = material_normal(n, v_world);
    if (material_cut_out()) // (after the derivatives)
        discard;
    vec3 e = vec3(0.0);
    for (int i = 0; i < u_counts.x; i++) {
        vec3 to_light;
        float dist;
        vec3 irr = light_irradiance(i, v_world, n, to_light, dist);
        if (max(irr.r, max(irr.g, irr.b)) > 0.0)
            e += irr * visibility(i, v_world, n, to_light);
    }
    vec3 albedo = material_albedo(u_color);
    o_color = vec4(albedo / PI * e + albedo * u_ambient.rgb + material_emission(u_emission), 1.0);
    o_distance = vec4(dist, 0.0, 0.0, 1.0);
}
