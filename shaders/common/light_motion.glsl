// Issue 32: where a caustic moved on screen since the last frame, from its
// light samples themselves (a caustic has no motion vectors of its own: the
// receiver under it stands still while its light slides across it). A
// photon is the light of one texel of the light's view; the same texel last
// frame carried the same part of the beam, so its two landing points, seen
// by this frame's camera, are how far that light moved on screen. Each
// photon adds that offset to the pixel it lands in (fixed point), and
// common/temporal.comp takes the history from where the light was.
// Included by photon_caustics/motion.comp and layered_caustics/motion.comp
// (after common/frame.glsl), which find the two landing points.
layout(r32i) uniform iimage2DArray u_motion; // layers: x, y (1/MOTION_SCALE pixels), photons
uniform sampler2D u_depth;    // this frame's window depth of the receivers (1: none)
uniform vec2 u_shift;         // j_prev - j_now, light texels: where the last frame's grid had this texel's ray
uniform int u_buffer;         // the light's view, texels per side
const float MOTION_SCALE = 64.0;
const float MOTION_LIMIT = 128.0; // pixels: a jump farther is no motion to follow
// Pixels between neighbouring photons' landing points beyond which a photon
// says nothing: there the landing point turns fast with the ray (a ball's
// rim), the linear step across the jitter misses it by pixels (measured on
// the turning ball: a false inward motion of 2.6 pixels a frame 15-30
// pixels out, which drew the history from the dark outside and dimmed the
// caustic 20% in 15 frames), and the light there is spread thin and smooth,
// so it needs no motion.
const float STRETCHED = 1.5;

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

// Adds the motion of the light that lands at world point `here` this frame
// and landed at `before` the last frame to the pixel it lands in, where that
// pixel shows the surface it lands on (not one in front of it).
void light_motion_add(vec3 here, vec3 before)
{
    vec3 w = to_window(here);
    ivec2 pixel = ivec2(floor(w.xy));
    if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, ivec2(u_viewport.xy))))
        return;
    float d = texelFetch(u_depth, pixel, 0).r;
    if (d >= 1.0)
        return;
    vec3 seen = to_world(vec2(pixel) + 0.5, d);
    if (distance(seen, here) > 0.01 * distance(here, u_camera_pos.xyz) + 2.0 * distance(seen, to_world(vec2(pixel) + 1.5, d)))
        return;
    vec2 moved = w.xy - to_window(before).xy;
    if (any(isnan(moved)) || any(greaterThan(abs(moved), vec2(MOTION_LIMIT))))
        return;
    imageAtomicAdd(u_motion, ivec3(pixel, 0), int(round(moved.x * MOTION_SCALE)));
    imageAtomicAdd(u_motion, ivec3(pixel, 1), int(round(moved.y * MOTION_SCALE)));
    imageAtomicAdd(u_motion, ivec3(pixel, 2), 1);
}
