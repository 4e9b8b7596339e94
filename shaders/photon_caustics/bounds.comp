#version 450 core
// The box each receiver's photons landed in (shaders/photon_caustics/window.glsl).
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2D u_photons;
#include "photon_caustics/window.glsl"
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, textureSize(u_photons, 0))))
        return;
    vec4 photon = texelFetch(u_photons, p, 0);
    if (photon.w < 0.5)
        return;
    int k = int(photon.z + 0.5);
    uvec2 q = uvec2(clamp(photon.xy, vec2(0.0), vec2(1.0)) * 65535.0 + 0.5);
    atomicMin(photon_windows[4 * k], q.x);
    atomicMin(photon_windows[4 * k + 1], q.y);
    atomicMax(photon_windows[4 * k + 2], q.x);
    atomicMax(photon_windows[4 * k + 3], q.y);
}
