#version 450 core
#include "common/bindings.glsl"
// Sandberg & Falemo §3.3-3.4: is the receiver point P of this pixel inside
// the volume? Cut the volume with the horizontal plane through P (the
// plane's normal is (0, 1, 0)), and test P against the cut triangle in xz.
// Inside: the irradiance I0 exp(-c d) F_P, F_P = generator area / cut area.
#include "common/frame.glsl"
#include "caustic_volumes/volume.glsl"
flat in int v_volume;
layout(location = 0) out vec4 o_irradiance;
layout(binding = VOLUMES_UNIT_POSITIONS) uniform sampler2D u_positions;
layout(binding = VOLUMES_UNIT_NORMALS) uniform sampler2D u_normals;
uniform vec3 u_attenuation;
uniform float u_cap;

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 P = texelFetch(u_positions, px, 0);
    if (P.w == 0.0)
        discard;
    CausticVolume v = volumes[v_volume];
    vec2 q[3];
    float t[3];
    for (int k = 0; k < 3; k++) {
        t[k] = (P.y - v.top[k].y) / v.dir[k].y; // dir.y < 0 for every built volume
        if (t[k] < 0.0)
            discard; // P above the surface there
        q[k] = v.top[k].xz + t[k] * v.dir[k].xz;
    }
    float area2 = cross2(q[1] - q[0], q[2] - q[0]);
    if (abs(area2) < 1e-20)
        discard;
    // barycentrics of P in the cut triangle (either orientation: a fold inverts it)
    float b1 = cross2(P.xz - q[0], q[2] - q[0]) / area2;
    float b2 = cross2(q[1] - q[0], P.xz - q[0]) / area2;
    float b0 = 1.0 - b1 - b2;
    if (b0 < 0.0 || b1 < 0.0 || b2 < 0.0)
        discard;
    float cut = 0.5 * abs(area2);
    // F_P, capped: a cut area smaller than generator / cap is not resolved by the grid
    float ratio = min(v.flux.w / max(cut, 1e-20), u_cap);
    // the refracted direction at P, and the receiver's own orientation:
    // the beam's horizontal irradiance is flux / cut; on a surface with normal n
    // it is that times (-n . R) / |R.y|
    vec3 R = normalize(b0 * v.dir[0].xyz + b1 * v.dir[1].xyz + b2 * v.dir[2].xyz);
    vec3 n = texelFetch(u_normals, px, 0).xyz;
    float facing = max(-dot(n, R), 0.0) / max(-R.y, 1e-3);
    float d = b0 * t[0] + b1 * t[1] + b2 * t[2]; // distance the light travelled in water
    vec3 e = v.flux.rgb / v.flux.w * ratio * facing * exp(-u_attenuation * d);
    o_irradiance = vec4(e, 1.0);
}
