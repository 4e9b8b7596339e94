#version 450 core
// Sandberg & Falemo §3.3-3.4: is the receiver point P of this pixel inside
// the volume? Cut the volume with the horizontal plane through P (the
// plane's normal is (0, 1, 0)), and test P against the cut triangle in xz.
// Inside: the irradiance I0 exp(-c d) F_P, F_P = generator area / cut area.
#include "common/frame.glsl"
#include "caustic_volumes/volume.glsl"
flat in int v_volume;
layout(location = 0) out vec4 o_irradiance;
uniform sampler2D u_positions;
uniform sampler2D u_normals;

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

// The edge function of p against the edge a -> b, computed from its
// endpoints in one canonical order, so that two triangles sharing the edge
// get bit-identical values (of opposite sign) for the same p.
float edge_function(vec2 a, vec2 b, vec2 p)
{
    bool swap = a.x > b.x || (a.x == b.x && a.y > b.y);
    vec2 lo = swap ? b : a, hi = swap ? a : b;
    float e = cross2(hi - lo, p - lo);
    return swap ? -e : e;
}

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
    // barycentrics of P in the cut triangle (either orientation: a fold
    // inverts it), with a half-open fill rule: a point exactly on an edge
    // belongs to the triangle for which that edge, wound counter-clockwise,
    // is a top or left edge, so neighbouring volumes never both count it
    // (a row of exactly 2x) nor both miss it (a row of 0)
    float orientation = area2 > 0.0 ? 1.0 : -1.0;
    float bary[3];
    for (int k = 0; k < 3; k++) {
        vec2 a = q[(k + 1) % 3], b = q[(k + 2) % 3];
        float e = edge_function(a, b, P.xz) * orientation;
        if (e < 0.0)
            discard;
        if (e == 0.0) {
            vec2 d = (b - a) * orientation;
            if (!(d.y < 0.0 || (d.y == 0.0 && d.x > 0.0)))
                discard;
        }
        bary[k] = e / abs(area2);
    }
    float b0 = bary[0], b1 = bary[1], b2 = bary[2];
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
