// What a ray leaving the refractors sees, found in the camera's image of
// the scene without them (a `shade { specular = false }` colour and depth):
// march the ray in steps, bisect the first step that passes behind the
// depth buffer, and accept it where the ray is within a step of the
// surface there (else it passed behind an occluder and marches on). Rays
// that leave the image, turn towards the camera past the near plane or hit
// nothing see the environment. Requires common/frame.glsl.
#include "common/scene_bounds.glsl"
uniform sampler2D u_scene_depth;
uniform float u_scene_extent; // the longest a ray is marched (the scene's bounding diameter)
uniform int u_scene_steps;
// > 0: a hit on a surface the camera sees more obliquely than this (its
// depth changing by more than u_scene_grazing pixel widths per pixel) is
// not taken when the ray looks at it from elsewhere: a few pixels of it
// stand for all the ray sees there, and their neighbours' colours leak in
// (a box's side seen through a lens came out as its lit front; the
// refraction pass has its distance map to ask instead; issue 8). 0: every
// hit is taken.
uniform float u_scene_grazing = 0.0;
// > 0 (photons, which start far outside the camera's view over a large
// pool and land near and past its edges): a guard band of this many pixels
// around the image, where the receivers are taken to go on as they are at
// the nearest edge pixel (their depth clamped to the edge), so a photon
// that lands just past the edge still spreads its footprint's share into
// the image (without it the last column got none of it: black, or a
// quarter too dark); and a sample past the band does not end the march
// (the ray may come into the image later), the step from an on-image
// sample to it searched for a crossing still on the image. 0: the ray
// leaves at the image's edge (what the refraction passes then look up in
// the environment).
uniform float u_scene_guard = 0.0;

// The part [t0, t1] of the ray o + t d inside the camera's frustum widened
// by the guard band (each clip-space plane is linear in t); false where it
// misses. Marching only there keeps photons that pass far from the view
// from marching at all.
bool scene_frustum_segment(vec3 o, vec3 d, inout float t0, inout float t1)
{
    vec4 a = u_view_proj * vec4(o, 1.0), b = u_view_proj * vec4(d, 0.0);
    vec2 g = 1.0 + 2.0 * u_scene_guard / u_viewport.xy; // the widened image's half-extent in NDC
    // w g.x - x >= 0, w g.x + x >= 0, the same for y, and w + z >= 0 (the near plane)
    float A[5] = float[5](a.w * g.x - a.x, a.w * g.x + a.x, a.w * g.y - a.y, a.w * g.y + a.y, a.w + a.z);
    float B[5] = float[5](b.w * g.x - b.x, b.w * g.x + b.x, b.w * g.y - b.y, b.w * g.y + b.y, b.w + b.z);
    for (int k = 0; k < 5; k++) {
        if (abs(B[k]) < 1e-12) {
            if (A[k] < 0.0)
                return false;
        } else if (B[k] > 0.0) {
            t0 = max(t0, -A[k] / B[k]);
        } else {
            t1 = min(t1, -A[k] / B[k]);
        }
    }
    return t0 <= t1;
}

// Eye depth of world point p, and its pixel (false: outside the image, and
// its guard band, or behind the camera).
bool scene_project(vec3 p, out ivec2 px, out float depth)
{
    vec4 c = u_view_proj * vec4(p, 1.0);
    if (c.w <= 1e-6)
        return false;
    vec2 at = (c.xy / c.w * 0.5 + 0.5) * u_viewport.xy;
    if (any(lessThan(at, vec2(-u_scene_guard))) || any(greaterThanEqual(at, u_viewport.xy + u_scene_guard)))
        return false;
    px = clamp(ivec2(floor(at)), ivec2(0), ivec2(u_viewport.xy) - 1);
    depth = -(u_view * vec4(p, 1.0)).z;
    return depth > 0.0;
}

// How far point p is behind the scene's surface at its pixel (> 0:
// behind); false off the image or where the scene is empty there.
bool scene_behind(vec3 p, out float behind, out ivec2 px)
{
    float depth;
    if (!scene_project(p, px, depth))
        return false;
    float d = texelFetch(u_scene_depth, px, 0).r;
    if (d >= 1.0) {
        behind = -1e30; // background: never behind it
        return true;
    }
    behind = depth - view_depth(d);
    return true;
}

// The ray's first hit: its pixel and its ray parameter (the point is
// o + dir * t_hit, on the surface within the bisection's precision).
bool scene_trace_at(vec3 o, vec3 dir, out ivec2 hit_px, out float t_hit)
{
    int steps = max(u_scene_steps, 1);
    float step = u_scene_extent / float(steps), lo = 0.0;
    // Only the steps inside the diffuse objects' box: a hit lies on one of
    // them (the steps keep their places, so what is found is what the
    // whole march finds).
    float t_enter, t_exit;
    if (!scene_bounds_segment(o, dir, t_enter, t_exit))
        return false;
    if (u_scene_guard > 0.0) {
        // photons: march only where the ray is in view (with its guard band), a step's margin either side
        float f0 = t_enter, f1 = t_exit;
        if (!scene_frustum_segment(o, dir, f0, f1))
            return false;
        t_enter = max(t_enter, f0 - step);
        t_exit = min(t_exit, f1 + step);
    }
    int first = max(int(floor(t_enter / step)), 1);
    lo = step * float(first - 1);
    float lo_behind;
    ivec2 lo_px;
    bool lo_on_image = u_scene_guard > 0.0 && scene_behind(o + dir * lo, lo_behind, lo_px);
    for (int j = first; j <= steps; j++) {
        float t = step * float(j), behind;
        if (t - step > t_exit)
            return false;
        ivec2 px;
        if (!scene_behind(o + dir * t, behind, px)) {
            if (u_scene_guard <= 0.0)
                return false;
            // the last point of the step still on the image: behind the
            // surface there, the ray crossed it inside the image
            bool found = false;
            if (lo_on_image) {
                float a = lo, b = t, bs;
                ivec2 ps;
                for (int i = 0; i < 12; i++) {
                    float m = 0.5 * (a + b);
                    if (scene_behind(o + dir * m, bs, ps))
                        a = m;
                    else
                        b = m;
                }
                if (a > lo && scene_behind(o + dir * a, bs, ps) && bs > 0.0) {
                    t = a;
                    behind = bs;
                    px = ps;
                    found = true;
                }
            }
            if (!found) {
                lo = t;
                lo_on_image = false;
                continue;
            }
        }
        lo_on_image = true;
        if (behind > 0.0) {
            float a = lo, b = t;
            for (int i = 0; i < 8; i++) {
                float m = 0.5 * (a + b);
                float bm;
                ivec2 pm;
                if (scene_behind(o + dir * m, bm, pm) && bm > 0.0)
                    b = m;
                else
                    a = m;
            }
            float bb;
            scene_behind(o + dir * b, bb, px);
            // A hit when the bisected point is on the surface: within the
            // depth the surface itself changes across a pixel there (a
            // floor seen at a grazing angle), plus a twentieth of a step.
            // A ray passing behind an occluder's edge stays deep behind
            // it (two steps' leeway once accepted those: the wall beside
            // a box seen through a lens came out as the box).
            // Per axis the smaller of the two one-sided differences: on a
            // surface seen at a grazing angle both are large, at an
            // occluder's edge only the one across the edge is (taking it
            // accepted a ray point on a box's hidden side as the lit front
            // face next to it: issue 8's IOR-1.5 sphere in the room).
            float here = texelFetch(u_scene_depth, px, 0).r, slope = 0.0;
            for (int axis = 0; axis < 2; axis++) {
                float smooth_side = 1e30;
                for (int side = -1; side <= 1; side += 2) {
                    ivec2 q = clamp(px + (axis == 0 ? ivec2(side, 0) : ivec2(0, side)), ivec2(0), ivec2(u_viewport.xy) - 1);
                    float dq = texelFetch(u_scene_depth, q, 0).r;
                    if (dq < 1.0 && here < 1.0)
                        smooth_side = min(smooth_side, abs(view_depth(dq) - view_depth(here)));
                }
                if (smooth_side < 1e30)
                    slope = max(slope, smooth_side);
            }
            if (bb < 2.0 * slope + 0.05 * step + 1e-3 * t) {
                if (u_scene_grazing > 0.0) {
                    float seen = view_depth(here);
                    float pixel = camera_is_ortho() ? 2.0 / (u_proj[1][1] * u_viewport.y)
                                                    : 2.0 * seen / (u_proj[1][1] * u_viewport.y);
                    // ... unless the ray looks at it as the camera does
                    // (within 5 degrees; an IOR-1.0 object: then the image
                    // is exactly right)
                    vec3 camera_dir = view_direction(o + dir * b);
                    if (slope > u_scene_grazing * pixel && dot(normalize(dir), camera_dir) < 0.9962)
                        return false;
                }
                hit_px = px;
                t_hit = b;
                return true;
            }
        }
        lo = t;
    }
    return false;
}

bool scene_trace(vec3 o, vec3 dir, out ivec2 hit_px)
{
    float t;
    return scene_trace_at(o, dir, hit_px, t);
}
