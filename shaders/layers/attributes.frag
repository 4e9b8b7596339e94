#version 450 core
// The layer a fragment belongs to is the number of set bits below its
// slice (§3.4's order); it writes the interpolated mesh normal and its
// refractor's slot there, and its exact depth (u_exact_depth). Fragments
// that share a slice (surfaces closer than one voxel) share a layer: the
// last one written wins.
#include "layers/layers.glsl"
uniform sampler2D u_bounds;
uniform usampler2DArray u_bits;
layout(r32f) uniform writeonly image2DArray u_depth;
layout(rgba32f) uniform writeonly image2DArray u_normal;
uniform int u_slot;
in vec3 v_normal;
in float v_depth;
void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 b = texelFetch(u_bounds, p, 0).rg;
    int slice = layer_slice(v_depth, -b.g, b.r);
    int below = 0;
    for (int w = 0; w <= (slice >> 7); w++) {
        uvec4 word = texelFetch(u_bits, ivec3(p, w), 0);
        for (int c = 0; c < 4; c++) {
            int first = w * 128 + c * 32;
            if (first + 32 <= slice)
                below += bitCount(word[c]);
            else if (first < slice)
                below += bitCount(word[c] & ((1u << uint(slice - first)) - 1u));
        }
    }
    if (below >= u_layers)
        return;
    vec3 n = v_normal;
    float len = length(n);
    n = len > 1e-20 ? n / len : vec3(0.0, 0.0, 1.0);
    imageStore(u_normal, ivec3(p, below), vec4(n, float(u_slot) + 1.0));
    if (u_exact_depth == 1)
        imageStore(u_depth, ivec3(p, below), vec4(v_depth));
}
