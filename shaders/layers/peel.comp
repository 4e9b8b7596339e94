#version 450 core
// §3.4.2: the set bits of a pixel, in order of depth, become its layers.
// A layer's depth is its slice's centre (the voxel estimate; the attribute
// pass replaces it with the fragment's exact depth unless told not to),
// except the first and last, which are the pixel's exact bounds. Surfaces
// past the `u_layers`-th are dropped (counted in info.g).
#include "layers/layers.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2D u_bounds;
uniform usampler2DArray u_bits;
layout(r32f) uniform writeonly image2DArray u_depth;
layout(rg32ui) uniform writeonly uimage2D u_info;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, textureSize(u_bounds, 0))))
        return;
    vec2 b = texelFetch(u_bounds, p, 0).rg;
    float zmin = -b.g, zmax = b.r;
    if (zmax < -1e29) { // no fragment here
        imageStore(u_info, p, uvec4(0u));
        return;
    }
    int total = 0, kept = 0;
    int last_slice = -1;
    for (int w = 0; w < u_voxels / 128; w++) {
        uvec4 word = texelFetch(u_bits, ivec3(p, w), 0);
        for (int c = 0; c < 4; c++) {
            uint bits = word[c];
            while (bits != 0u) {
                int bit = findLSB(bits);
                bits &= bits - 1u;
                int slice = w * 128 + c * 32 + bit;
                if (kept < u_layers) {
                    float d = zmin + (float(slice) + 0.5) / float(u_voxels) * (zmax - zmin);
                    imageStore(u_depth, ivec3(p, kept), vec4(kept == 0 ? zmin : d));
                    kept++;
                    last_slice = slice;
                }
                total++;
            }
        }
    }
    // the deepest kept layer is the pixel's Zmax when nothing was dropped
    if (kept > 1 && total == kept)
        imageStore(u_depth, ivec3(p, kept - 1), vec4(zmax));
    imageStore(u_info, p, uvec4(uint(kept), uint(total - kept), 0u, 0u));
}
