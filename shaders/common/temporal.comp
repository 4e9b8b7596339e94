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
const float GAMMA = 1.5;      // the clipping box's half width in standard deviations

vec3 unproject(mat4 inverse, vec2 uv, float d)
{
    vec4 w = inverse * vec4(vec3(uv, d) * 2.0 - 1.0, 1.0);
    return w.xyz / w.w;
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
        vec2 uv = (vec2(p) + 0.5) / vec2(size);
        vec3 world = unproject(u_inv_view_proj, uv, d);
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
                vec4 history = texelFetch(u_history, hp, 0);
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
                held = min(history.a + 1.0, limit);
                result = history.rgb + (current.rgb - history.rgb) / held;
            }
        }
    }
    if (any(isnan(result)) || any(isinf(result)))
        result = current.rgb; // a history never carries a NaN forward
    imageStore(u_out, p, vec4(result, current.a));
    imageStore(u_out_history, p, vec4(result, held));
    imageStore(u_out_depth, p, vec4(d, 0.0, 0.0, 0.0));
}
