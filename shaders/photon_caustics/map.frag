#version 450 core
#include "common/bindings.glsl"
// Hu & Qin §3.3, caustic mapping like shadow mapping: a receiver point
// projects along its impostor's axis to (u, v); if it is the surface the
// impostor saw there (within the bias), it gets that texel's caustic
// irradiance.
#include "common/frame.glsl"
#include "impostors/impostors.glsl"
#include "photon_caustics/window.glsl"
in vec3 v_world;
in vec3 v_normal;
layout(location = 0) out vec4 o_irradiance;
layout(binding = PHOTON_UNIT_CAUSTICS) uniform sampler2DArray u_caustics;
uniform int u_object_id;
uniform int u_impostor_object[16];
uniform float u_bias;
void main()
{
    int k = -1;
    for (int i = 0; i < u_impostor_count; i++)
        if (u_impostor_object[i] == u_object_id)
            k = i;
    o_irradiance = vec4(0.0);
    if (k < 0)
        return;
    vec2 uv = impostor_uv(k, v_world);
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
        return;
    float here = dot(v_world - impostors[k].center.xyz, impostors[k].axis.xyz);
    if (here > impostor_depth(k, uv) + u_bias)
        return; // hidden from the refractor's side
    vec2 wuv = photon_window_uv(k, uv);
    if (any(lessThan(wuv, vec2(0.0))) || any(greaterThan(wuv, vec2(1.0))))
        return; // outside where the photons landed
    o_irradiance = vec4(texture(u_caustics, vec3(wuv, float(k))).rgb, 1.0);
}
