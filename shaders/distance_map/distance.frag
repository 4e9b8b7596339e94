#version 450 core
// A texel of the distance map: the diffuse surface's radiance by the one
// lighting function shade uses (common/surface_light.glsl: the lights with
// their shadow maps and the medium, ambient, emission; no caustics, which
// are the camera's images; two-sided, the side facing the centre), and its
// distance from
// the centre (Szirmay-Kalos et al. 2005). Layer 1 keeps the nearest
// surface facing the centre beyond layer 0's (src/passes/blocks/distance_map.h).
#include "common/frame.glsl"
#include "common/lighting.glsl"
#include "common/material.glsl"
#include "common/shadows.glsl"
#include "common/medium.glsl"
#include "common/surface_light.glsl"
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
    o_color = vec4(surface_light_material(v_world, n, (u_center - v_world) / max(dist, 1e-20), u_color, u_emission,
                                          vec3(0.0)), 1.0);
    o_distance = vec4(dist, 0.0, 0.0, 1.0);
}
