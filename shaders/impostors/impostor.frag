#version 450 core
// The impostor's texel (Hu & Qin Fig. 12): the object's depth along the
// axis from the rectangle's plane (for Fig. 16's correction), and its
// radiance seen from the refractor's side, by the one lighting function
// shade uses (common/surface_light.glsl: the lights through the building
// pass's shadow maps and the medium, the ambient; no caustics).
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
uniform vec3 u_impostor_center;
uniform vec3 u_impostor_axis;
uniform vec3 u_color;
uniform vec3 u_emission; // a diffuse surface's own radiance
uniform float u_ior;
uniform float u_ideal;
layout(location = 0) out vec4 o_depth;
layout(location = 1) out vec4 o_color;
void main()
{
    o_depth = vec4(dot(v_world - u_impostor_center, u_impostor_axis), 0.0, 0.0, 1.0);
    vec3 n = normalize(v_normal);
    if (dot(n, u_impostor_axis) > 0.0)
        n = -n; // the side the refractor sees
    vec3 mapped = material_normal(n, v_world);
    if (material_cut_out()) // (after the derivatives)
        discard;
    if (role_is(ROLE_RECEIVER))
        n = mapped;
    if (!role_is(ROLE_RECEIVER)) {
        // a reflector/refractor seen along the axis: level 0 of the recursion
        // reflects and refracts (one interface) the environment only
        vec3 v = u_impostor_axis;
        float f = role_is(ROLE_MIRROR) ? 1.0 : fresnel_of(-dot(v, n), 1.0 / u_ior, u_ideal);
        vec3 t = refract_or_reflect(v, n, 1.0 / u_ior);
        vec3 tint = role_is(ROLE_MIRROR) ? u_color : vec3(1.0);
        o_color = vec4(tint * (f * environment_radiance(reflect(v, n)) + (1.0 - f) * environment_radiance(t)), 1.0);
        return;
    }
    o_color = vec4(surface_light_material(v_world, n, -u_impostor_axis, u_color, u_emission, vec3(0.0)), 1.0);
}
