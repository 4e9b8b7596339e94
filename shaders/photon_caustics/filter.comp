#version 450 core
// Hu & Qin §3.2: c(u, v) = s * sum p(u + i, v + j) sqrt(1 + 2k^2 - (i^2 + j^2)),
// |i|, |j| <= k. We divide by the sum of the weights, so that s = 1 keeps
// the photons' energy, and by the texel's area: the result is irradiance.
#include "impostors/impostors.glsl"
#include "photon_caustics/window.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(r32ui) readonly uniform uimage2DArray u_counts;
layout(rgba32f) writeonly uniform image2DArray u_caustics;
void main()
{
    ivec3 g = ivec3(gl_GlobalInvocationID);
    if (g.x >= u_texture || g.y >= u_texture || g.z >= u_impostor_count)
        return;
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int j = -u_k; j <= u_k; j++)
        for (int i = -u_k; i <= u_k; i++) {
            float w = sqrt(max(1.0 + 2.0 * float(u_k * u_k) - float(i * i + j * j), 0.0));
            wsum += w;
            ivec2 q = g.xy + ivec2(i, j);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(u_texture))))
                continue;
            for (int c = 0; c < 3; c++)
                sum[c] += w * float(imageLoad(u_counts, ivec3(q, 3 * g.z + c)).r);
        }
    vec3 flux = sum / max(wsum, 1e-6) / u_fixed_point * u_s;
    vec4 w = photon_window(g.z);
    vec2 texel = 2.0 * impostors[g.z].center.w * (w.zw - w.xy) / float(u_texture);
    imageStore(u_caustics, g, vec4(flux / (texel.x * texel.y), 1.0));
}
