#version 450 core
#include "common/bindings.glsl"
// Hu & Qin §3.2: each photon adds its flux to its receiver's caustic
// texture at (u, v), on the GPU (integer atomics on a fixed-point scale).
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = PHOTON_UNIT_PHOTONS) uniform sampler2D u_photons;
layout(binding = PHOTON_UNIT_FLUX) uniform sampler2D u_flux;
layout(r32ui, binding = PHOTON_IMAGE_COUNTS) uniform uimage2DArray u_counts;
uniform float u_fixed_point;
uniform int u_texture;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, textureSize(u_photons, 0))))
        return;
    vec4 photon = texelFetch(u_photons, p, 0);
    if (photon.w < 0.5)
        return;
    vec3 flux = texelFetch(u_flux, p, 0).rgb;
    ivec2 t = clamp(ivec2(photon.xy * float(u_texture)), ivec2(0), ivec2(u_texture - 1));
    int k = int(photon.z + 0.5);
    for (int c = 0; c < 3; c++)
        imageAtomicAdd(u_counts, ivec3(t, 3 * k + c), uint(clamp(flux[c] * u_fixed_point, 0.0, 4.0e9) + 0.5));
}
