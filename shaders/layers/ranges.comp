#version 450 core
// §3.7: the depth range of every layer over the image (exact atomic
// min/max of positive float bits, which order as the floats do) and the
// largest layer count, to bound the search along a ray.
#include "layers/layers.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2DArray u_depth;
uniform usampler2D u_info;
layout(std430) buffer Ranges { uint ranges[]; };
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, textureSize(u_info, 0))))
        return;
    int count = int(texelFetch(u_info, p, 0).r);
    if (count == 0)
        return;
    atomicMax(ranges[2 * 32], uint(count));
    for (int k = 0; k < count; k++) {
        float d = max(texelFetch(u_depth, ivec3(p, k), 0).r, 0.0);
        atomicMin(ranges[2 * k], floatBitsToUint(d));
        atomicMax(ranges[2 * k + 1], floatBitsToUint(d));
    }
}
