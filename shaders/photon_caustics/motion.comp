#version 450 core
// Issue 32: where the caustic moved since the last frame, from the photons
// themselves (a caustic has no motion vectors of its own: the receiver
// under it stands still while its light slides across it). A photon is
// the light of one texel of the light's view; the same texel last frame
// carried the same part of the beam, so its two landing points, seen by
// this frame's camera, are how far that light moved on screen. Each
// photon adds that offset to the pixel it lands in (fixed point), and
// common/temporal.comp takes the history from where the light was.
//
// Accumulating, every frame's grid is jittered (temporal_jitter, which
// moves the light's image by +j texels): this frame's texel p sampled the
// unjittered grid at p - j_now, the last frame's at p - j_prev, so the
// last frame's landing point of the same ray is read at p + (j_prev -
// j_now), interpolated from the texel and its neighbour on that side (both
// on the same receiver, or the photon adds nothing).
#include "common/frame.glsl"
#include "impostors/impostors.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2D u_photons;  // this frame's (u, v, receiver, valid)
uniform sampler2D u_previous; // the last frame's
uniform sampler2D u_depth;    // this frame's window depth of the receivers (1: none)
uniform vec2 u_shift;         // j_prev - j_now, photon texels (photon_caustics.c)
uniform int u_buffer;
layout(r32i) uniform iimage2DArray u_motion; // layers: x, y (1/MOTION_SCALE pixels), photons
const float MOTION_SCALE = 64.0;
const float MOTION_LIMIT = 128.0; // pixels: a jump farther is no motion to follow
const float STRETCHED = 1.5;      // pixels between neighbouring photons' landing points (previous_uv)

vec3 to_window(vec3 p)
{
    vec4 c = u_view_proj * vec4(p, 1.0);
    return vec3((c.xy / max(c.w, 1e-20) * 0.5 + 0.5) * u_viewport.xy, c.z / max(c.w, 1e-20) * 0.5 + 0.5);
}

vec3 to_world(vec2 pixel, float depth)
{
    vec4 w = u_inv_view_proj * vec4(vec3(pixel * u_viewport.zw, depth) * 2.0 - 1.0, 1.0);
    return w.xyz / w.w;
}

// the last frame's landing uv of this texel's ray on receiver k (false: no
// such photon, it landed elsewhere, or its light is stretched: see main)
bool previous_uv(ivec2 p, int k, out vec2 uv)
{
    vec4 here = texelFetch(u_previous, p, 0);
    uv = here.xy;
    if (here.w < 0.5 || int(here.z + 0.5) != k)
        return false;
    vec2 at = to_window(impostor_point(k, here.xy)).xy;
    for (int axis = 0; axis < 2; axis++) {
        float s = u_shift[axis];
        ivec2 q = p;
        q[axis] += s >= 0.0 ? 1 : -1;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(u_buffer))))
            return false;
        vec4 next = texelFetch(u_previous, q, 0);
        if (next.w < 0.5 || int(next.z + 0.5) != k)
            return false;
        // A photon whose neighbour landed more than STRETCHED pixels away
        // says nothing: there the landing point turns fast with the ray
        // (a ball's rim), the linear step across the jitter misses it by
        // pixels (measured on the turning ball: a false inward motion of
        // 2.6 pixels a frame 15-30 pixels out, which drew the history from
        // the dark outside and dimmed the caustic 20% in 15 frames), and
        // the light there is spread thin and smooth, so it needs no motion.
        if (distance(to_window(impostor_point(k, next.xy)).xy, at) > STRETCHED)
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
    vec3 here = impostor_point(k, now.xy);
    vec3 w = to_window(here);
    ivec2 pixel = ivec2(floor(w.xy));
    if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, ivec2(u_viewport.xy))))
        return;
    // the photon must land on the surface this pixel shows (not behind it)
    float d = texelFetch(u_depth, pixel, 0).r;
    if (d >= 1.0)
        return;
    vec3 seen = to_world(vec2(pixel) + 0.5, d);
    if (distance(seen, here) > 0.01 * distance(here, u_camera_pos.xyz) + 2.0 * distance(seen, to_world(vec2(pixel) + 1.5, d)))
        return;
    vec2 moved = w.xy - to_window(impostor_point(k, before)).xy;
    if (any(isnan(moved)) || any(greaterThan(abs(moved), vec2(MOTION_LIMIT))))
        return;
    imageAtomicAdd(u_motion, ivec3(pixel, 0), int(round(moved.x * MOTION_SCALE)));
    imageAtomicAdd(u_motion, ivec3(pixel, 1), int(round(moved.y * MOTION_SCALE)));
    imageAtomicAdd(u_motion, ivec3(pixel, 2), 1);
}
