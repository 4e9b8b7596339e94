#version 450 core
// The box each receiver's photons landed in (shaders/photon_caustics/window.glsl),
// and apart, the box and the count of those the camera may see: a photon
// that lands outside the view (with a margin of a quarter of it each way,
// for the footprints that reach back into it) lights nothing on screen.
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2D u_photons;
#include "common/frame.glsl"
#include "impostors/impostors.glsl"
#include "photon_caustics/window.glsl"

bool may_be_seen(vec3 p)
{
    vec4 c = u_view_proj * vec4(p, 1.0);
    return c.w > 0.0 && all(lessThanEqual(abs(c.xy), vec2(1.5 * abs(c.w))));
}
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
    int at = PHOTON_WINDOW_STRIDE * k;
    atomicMin(photon_windows[at + 5], q.x);
    atomicMin(photon_windows[at + 6], q.y);
    atomicMax(photon_windows[at + 7], q.x);
    atomicMax(photon_windows[at + 8], q.y);
    if (!may_be_seen(impostor_point(k, photon.xy)))
        return;
    atomicMin(photon_windows[at], q.x);
    atomicMin(photon_windows[at + 1], q.y);
    atomicMax(photon_windows[at + 2], q.x);
    atomicMax(photon_windows[at + 3], q.y);
    atomicAdd(photon_windows[at + 4], 1u);
}
