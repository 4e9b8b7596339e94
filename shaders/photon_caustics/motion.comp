#version 450 core
// Issue 32: where the caustic moved since the last frame, from the photons
// themselves (common/light_motion.glsl says why and how).
//
// Accumulating, every frame's grid is jittered (temporal_jitter, which
// moves the light's image by +j texels): this frame's texel p sampled the
// unjittered grid at p - j_now, the last frame's at p - j_prev, so the
// last frame's landing point of the same ray is read at p + (j_prev -
// j_now), interpolated from the texel and its neighbour on that side (both
// on the same receiver, or the photon adds nothing).
#include "common/frame.glsl"
#include "common/light_motion.glsl"
#include "impostors/impostors.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2D u_photons;  // this frame's (u, v, receiver, valid)
uniform sampler2D u_previous; // the last frame's

vec3 receiver_point(int k, vec2 uv)
{
    Impostor im = impostors[k];
    vec2 s = (uv - 0.5) * 2.0 * im.center.w;
    return im.center.xyz + im.right.xyz * s.x + im.up.xyz * s.y + im.axis.xyz * impostor_depth(k, uv);
}

// the last frame's landing uv of this texel's ray on receiver k (false: no
// such photon, it landed elsewhere, or its light is stretched: STRETCHED)
bool previous_uv(ivec2 p, int k, out vec2 uv)
{
    vec4 here = texelFetch(u_previous, p, 0);
    uv = here.xy;
    if (here.w < 0.5 || int(here.z + 0.5) != k)
        return false;
    vec2 at = to_window(receiver_point(k, here.xy)).xy;
    for (int axis = 0; axis < 2; axis++) {
        float s = u_shift[axis];
        ivec2 q = p;
        q[axis] += s >= 0.0 ? 1 : -1;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(u_buffer))))
            return false;
        vec4 next = texelFetch(u_previous, q, 0);
        if (next.w < 0.5 || int(next.z + 0.5) != k)
            return false;
        if (distance(to_window(receiver_point(k, next.xy)).xy, at) > STRETCHED)
            return false;
        uv += abs(s) * (next.xy - here.xy);
    }
    return true;
}

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, ivec2(u_buffer))))
        return;
    vec4 now = texelFetch(u_photons, p, 0);
    int k = int(now.z + 0.5);
    if (now.w < 0.5 || k < 0 || k >= u_impostor_count)
        return;
    vec2 before;
    if (!previous_uv(p, k, before))
        return;
    light_motion_add(receiver_point(k, now.xy), receiver_point(k, before));
}
