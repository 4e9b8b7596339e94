#version 450 core
// Hu & Qin §3.3, caustic mapping like shadow mapping: a receiver point
// projects along its impostor's axis to (u, v); if it is the surface the
// impostor saw there (within the bias), it gets that texel's caustic
// irradiance. The receivers are the `receivers` block's (issue 54: the
// camera's diffuse objects drawn once for every caustics pass): each
// pixel's world position, w = 1 + the object's id (0: none).
#include "common/frame.glsl"
#include "impostors/impostors.glsl"
#include "photon_caustics/window.glsl"
layout(location = 0) out vec4 o_irradiance;
uniform sampler2DArray u_caustics;
uniform sampler2D u_receiver_position;
uniform int u_impostor_object[16];

// The receiver at pixel q: its position, and whether it is object `id`'s.
bool receiver_at(ivec2 q, float id, out vec3 p)
{
    p = vec3(0.0);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, textureSize(u_receiver_position, 0))))
        return false;
    vec4 r = texelFetch(u_receiver_position, q, 0);
    p = r.xyz;
    return r.w == id;
}

// The position's change to the next pixel along `axis`, as a fine screen
// derivative has it (the pixel pair of its 2 x 2 quad: forward from an even
// pixel, backward from an odd one), from the other neighbour where the
// quad's is another surface (a silhouette: the rasterizer's derivative
// continued the surface's own plane there); zero with neither.
vec3 position_step(ivec2 px, ivec2 axis, vec3 p, float id)
{
    bool even = ((axis.x == 1 ? px.x : px.y) & 1) == 0;
    vec3 q;
    if (receiver_at(even ? px + axis : px - axis, id, q))
        return even ? q - p : p - q;
    if (receiver_at(even ? px - axis : px + axis, id, q))
        return even ? p - q : q - p;
    return vec3(0.0);
}

// The caustic irradiance at receiver point p of impostor k; false where p
// is outside the caustic texture or hidden from the refractor's side.
bool caustic_at(int k, vec3 p, out vec3 irradiance)
{
    irradiance = vec3(0.0);
    vec2 uv = impostor_uv(k, p);
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))))
        return false;
    float here = dot(p - impostors[k].center.xyz, impostors[k].axis.xyz);
    if (here > impostor_depth(k, uv) + u_bias)
        return false; // hidden from the refractor's side
    vec2 wuv = photon_window_uv(k, uv);
    if (any(lessThan(wuv, vec2(0.0))) || any(greaterThan(wuv, vec2(1.0))))
        return false; // outside where the photons landed
    irradiance = texture(u_caustics, vec3(wuv, float(k))).rgb;
    return true;
}

void main()
{
    o_irradiance = vec4(0.0);
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 receiver = texelFetch(u_receiver_position, px, 0);
    if (receiver.w < 0.5)
        return; // no receiver: the sky, or glass in front of none
    int object_id = int(receiver.w + 0.5) - 1;
    vec3 v_world = receiver.xyz;
    int k = -1;
    for (int i = 0; i < u_impostor_count; i++)
        if (u_impostor_object[i] == object_id)
            k = i;
    if (k < 0)
        return;
    // The pixel's footprint on the receiver, in caustic texels: where the
    // texels are smaller than the pixel a single lookup at its centre picks
    // one texel of a caustic with sub-pixel detail (aliasing); the pixel's
    // light is the mean over its footprint (issue 8), taken as a grid of up
    // to u_pixel_samples^2 lookups across the parallelogram the screen
    // derivatives span (a texture minification filter for a texture with
    // no mip levels: the caustic is rebuilt every frame the light moves).
    vec3 dx = position_step(px, ivec2(1, 0), v_world, receiver.w);
    vec3 dy = position_step(px, ivec2(0, 1), v_world, receiver.w);
    vec2 texels = vec2(textureSize(u_caustics, 0).xy);
    vec2 wuv = photon_window_uv(k, impostor_uv(k, v_world));
    vec2 wdx = (photon_window_uv(k, impostor_uv(k, v_world + dx)) - wuv) * texels;
    vec2 wdy = (photon_window_uv(k, impostor_uv(k, v_world + dy)) - wuv) * texels;
    vec2 reach = 0.5 * (abs(wdx) + abs(wdy)) / texels;
    if (any(lessThan(wuv + reach, vec2(0.0))) || any(greaterThan(wuv - reach, vec2(1.0))))
        return; // the footprint is outside where the photons landed: no lookups
    int nx = clamp(int(ceil(length(wdx))), 1, max(u_pixel_samples, 1));
    int ny = clamp(int(ceil(length(wdy))), 1, max(u_pixel_samples, 1));
    vec3 sum = vec3(0.0);
    bool any_hit = false;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            vec2 g = pixel_grid_point(i, j, nx, ny);
            vec3 e;
            vec3 p = v_world + g.x * dx + g.y * dy;
            any_hit = caustic_at(k, p, e) || any_hit;
            sum += e;
        }
    if (any_hit)
        o_irradiance = vec4(sum / float(nx * ny), 1.0);
}
