#version 450 core
// Issue 32: where the caustic moved since the last frame, from the photons
// themselves (common/light_motion.glsl says why and how): each photon's
// landing point this frame and the same light texel's ray last frame, for
// the light through the object (layer 0) and the light reflected off its
// first interface (layer 1).
//
// Accumulating, every frame's photons start at a jittered point of their
// texel (u_jitter of photons.comp: texel p starts at p + 0.5 + j): the last
// frame's ray through this frame's start point is read at p + (j_now -
// j_prev) (u_shift, layered_caustics.c), interpolated
// from the texel and its neighbour on that side (both landed, their landing
// points at most STRETCHED pixels apart, or the photon adds nothing).
#include "common/frame.glsl"
#include "common/light_motion.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2DArray u_hits;     // this frame's landing points (xyz world, w: 1 landed)
uniform sampler2DArray u_previous; // the last frame's

bool previous_point(ivec3 p, out vec3 at)
{
    vec4 here = texelFetch(u_previous, p, 0);
    at = here.xyz;
    if (here.w < 0.5)
        return false;
    vec2 seen = to_window(here.xyz).xy;
    for (int axis = 0; axis < 2; axis++) {
        float s = u_shift[axis];
        ivec3 q = p;
        q[axis] += s >= 0.0 ? 1 : -1;
        if (any(lessThan(q.xy, ivec2(0))) || any(greaterThanEqual(q.xy, ivec2(u_buffer))))
            return false;
        vec4 next = texelFetch(u_previous, q, 0);
        if (next.w < 0.5 || distance(to_window(next.xyz).xy, seen) > STRETCHED)
            return false;
        at += abs(s) * (next.xyz - here.xyz);
    }
    return true;
}

void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p.xy, ivec2(u_buffer))))
        return;
    vec4 now = texelFetch(u_hits, p, 0);
    vec3 before;
    if (now.w < 0.5 || !previous_point(p, before))
        return;
    light_motion_add(now.xyz, before);
}
