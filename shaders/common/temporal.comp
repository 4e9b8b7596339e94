#version 450 core
// Temporal accumulation of a caustics pass's irradiance (src/graph/temporal.h,
// issue 32): this frame's pixel blended with its reprojected history.
// Still light and geometry: an equal-weight mean of the last u_frames
// frames (the jittered photon grids average to a denser one). Moved: the
// history clipped to this frame's 3 x 3 neighbourhood, mean +- 1.5 standard
// deviations (Salvi 2016's variance clipping, as TAA does: a caustic that
// moved far leaves no ghost), and at most the last u_moved_frames frames.
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2D u_current;       // this frame's irradiance (alpha: where it was computed)
uniform sampler2D u_depth;         // this frame's window depth of the receivers (1: none)
uniform sampler2D u_history;       // rgb: accumulated irradiance, a: frames in it
uniform sampler2D u_history_depth; // r: the window depth the history was seen at
layout(rgba32f) uniform writeonly image2D u_out;
layout(rgba32f) uniform writeonly image2D u_out_history;
layout(r32f) uniform writeonly image2D u_out_depth;
uniform mat4 u_inv_view_proj;
uniform mat4 u_prev_view_proj;
uniform mat4 u_prev_inv_view_proj;
uniform vec3 u_eye;
uniform int u_valid;
uniform int u_moved;
uniform float u_frames;

uniform float u_moved_frames; // the most frames averaged while the light or geometry moves
uniform int u_settled; // the camera, the light and the geometry all as they were the last frame
// where the pass knows how its light moved on screen (photon_caustics/
// motion.comp: x, y in 1/64 pixels and the photons that said so, summed
// per pixel), the history is taken from where the light was
uniform isampler2DArray u_motion;
uniform int u_has_motion;
const float MOTION_SCALE = 64.0;

// the mean motion of the light over the 5 x 5 pixels around p (a photon
// lands in one pixel; its light covers its footprint), false where no
// photon said
bool light_motion(ivec2 p, ivec2 size, out vec2 motion)
{
    ivec3 sum = ivec3(0);
    for (int j = -2; j <= 2; j++)
        for (int i = -2; i <= 2; i++) {
            ivec2 q = p + ivec2(i, j);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
                continue;
            sum += ivec3(texelFetch(u_motion, ivec3(q, 0), 0).r, texelFetch(u_motion, ivec3(q, 1), 0).r,
                         texelFetch(u_motion, ivec3(q, 2), 0).r);
        }
    motion = sum.z > 0 ? vec2(sum.xy) / (float(sum.z) * MOTION_SCALE) : vec2(0.0);
    return sum.z > 0;
}
const float GAMMA = 1.5;      // the clipping box's half width in standard deviations

vec3 unproject(mat4 inverse, vec2 uv, float d)
{
    vec4 w = inverse * vec4(vec3(uv, d) * 2.0 - 1.0, 1.0);
    return w.xyz / w.w;
}

// Catmull-Rom over the 4 x 4 texels around `at` (texel units, centres at
// integers): a bilinear fetch blurs the history a little every frame it is
// moved, and a sharp caustic that moves for 8 frames lost its peak (the
// resampling TAA does with a bicubic, Karis 2014); clamped at zero
// (the kernel's negative lobes)
vec4 catmull_rom_weights(float t)
{
    float t2 = t * t, t3 = t2 * t;
    return vec4(-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t,
                0.5 * t3 - 0.5 * t2);
}

vec4 history_resampled(vec2 at, ivec2 size)
{
    ivec2 base = ivec2(floor(at));
    vec2 f = at - vec2(base);
    vec4 wx = catmull_rom_weights(f.x), wy = catmull_rom_weights(f.y);
    vec4 sum = vec4(0.0);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++)
            sum += wx[i] * wy[j] * texelFetch(u_history, clamp(base + ivec2(i - 1, j - 1), ivec2(0), size - 1), 0);
    return max(sum, vec4(0.0));
}

void main()
{
    ivec2 size = textureSize(u_current, 0);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, size)))
        return;
    vec4 current = texelFetch(u_current, p, 0);
    float d = texelFetch(u_depth, p, 0).r;
    vec3 result = current.rgb;
    float held = 1.0;
    if (u_valid != 0 && d < 1.0) {
        vec2 from = vec2(p) + 0.5;
        float dfrom = d;
        vec2 motion;
        bool tracked = false;
        if (u_moved != 0 && u_has_motion != 0 && light_motion(p, size, motion)) {
            // the light here was at from - motion on this frame's screen:
            // the surface point there is where the history saw it
            ivec2 q = ivec2(floor(from - motion));
            float dq = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)) ? texelFetch(u_depth, q, 0).r : 1.0;
            if (dq < 1.0) {
                from -= motion;
                dfrom = dq;
                tracked = true;
            }
        }
        vec3 world = unproject(u_inv_view_proj, from / vec2(size), dfrom);
        vec4 c = u_prev_view_proj * vec4(world, 1.0);
        vec3 q = c.xyz / c.w * 0.5 + 0.5;
        bool inside = c.w > 0.0 && all(greaterThanEqual(q.xy, vec2(0.0))) && all(lessThanEqual(q.xy, vec2(1.0)));
        if (inside) {
            // the texel the point fell in the last frame (no bilinear blend: a
            // still camera must not blur the history frame after frame)
            ivec2 hp = clamp(ivec2(q.xy * vec2(size)), ivec2(0), size - 1);
            float hd = texelFetch(u_history_depth, hp, 0).r;
            vec3 seen = unproject(u_prev_inv_view_proj, (vec2(hp) + 0.5) / vec2(size), hd);
            // the same surface: within 1% of the distance from the eye (a
            // pixel's footprint at a grazing angle, not a disocclusion)
            bool same = hd < 1.0 && distance(seen, world) <= 0.01 * distance(world, u_eye) + 1e-5;
            if (same) {
                // following the light, interpolated: a caustic that moves
                // less than a pixel a frame would otherwise never leave its texel
                vec4 history = tracked ? history_resampled(q.xy * vec2(size) - 0.5, size) : texelFetch(u_history, hp, 0);
                float limit = u_frames;
                if (u_moved != 0) {
                    vec3 m1 = vec3(0.0), m2 = vec3(0.0);
                    for (int j = -1; j <= 1; j++)
                        for (int i = -1; i <= 1; i++) {
                            vec3 v = texelFetch(u_current, clamp(p + ivec2(i, j), ivec2(0), size - 1), 0).rgb;
                            m1 += v;
                            m2 += v * v;
                        }
                    m1 /= 9.0;
                    vec3 sigma = sqrt(max(m2 / 9.0 - m1 * m1, vec3(0.0)));
                    history.rgb = clamp(history.rgb, m1 - GAMMA * sigma, m1 + GAMMA * sigma);
                    limit = min(limit, u_moved_frames);
                }
                if (u_settled != 0 && history.a >= u_frames) {
                    // Nothing moved and the history holds u_frames frames
                    // already: it is the mean over the jitter's offsets, each
                    // once (u_frames a multiple of 16, temporal_jitter), and
                    // kept as it is. Blending on (a running mean over the last
                    // u_frames) would weigh the newest offsets up to 2.6 times
                    // the oldest: a pass whose photons cover only their part
                    // of the finer grid (layered_caustics' `cell`) would show
                    // that grid crawl, frame after frame.
                    held = history.a;
                    result = history.rgb;
                } else {
                    held = min(history.a + 1.0, limit);
                    result = history.rgb + (current.rgb - history.rgb) / held;
                }
            }
        }
    }
    if (any(isnan(result)) || any(isinf(result)))
        result = current.rgb; // a history never carries a NaN forward
    imageStore(u_out, p, vec4(result, current.a));
    imageStore(u_out_history, p, vec4(result, held));
    imageStore(u_out_depth, p, vec4(d, 0.0, 0.0, 0.0));
}
