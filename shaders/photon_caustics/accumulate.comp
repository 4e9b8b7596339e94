#version 450 core
// Hu & Qin §3.2: each photon adds its flux to its receiver's caustic
// texture at (u, v), on the GPU (integer atomics on a fixed-point scale).
//
// With u_footprint > 0 (issue 8) a photon is not a point: its neighbours
// one texel away in the photon buffer that land on the same receiver span,
// by central differences, the parallelogram its light covers there (a ray
// differential, as layered_caustics' splat.comp); the flux is spread over
// it (n x n sample points, each by area into the texels its patch covers), so a
// diverging photon spreads, a converging one stays sharp, a uniform field
// stays uniform (no moire between the photon grid and the texel grid), and
// the flux is kept exactly. A neighbour's offset is clamped to
// u_footprint texels (a footprint torn by a silhouette or a fold smears no
// farther), or up to 4 x that where both neighbours agree that the light is
// stretched smoothly (a ball's rim light before its focus lands 40 texels
// apart: clamped to 16, black seams crossed the axes, 16 pixels at
// 256 x 256). With u_footprint = 0 each photon goes into its texel (the
// paper's).
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2D u_photons;
uniform sampler2D u_flux;
layout(r32ui) uniform uimage2DArray u_counts;
#include "common/box_taps.glsl"
#include "common/fixed_point.glsl"
#include "photon_caustics/window.glsl"

int receiver;

void deposit(vec2 at, vec2 half_size, vec3 flux) // `at` in texels (centres at +0.5)
{
    // by area into the texels the box at +- half_size overlaps, what falls
    // past the texture's edge into its edge texels: the flux stays on the
    // receiver
    ivec2 first, last;
    box_cells(at.x, half_size.x, first.x, last.x);
    box_cells(at.y, half_size.y, first.y, last.y);
    for (int y = first.y; y <= last.y; y++) {
        float wy = box_share(at.y, half_size.y, y);
        for (int x = first.x; x <= last.x; x++) {
            float w = wy * box_share(at.x, half_size.x, x);
            if (w <= 0.0)
                continue;
            ivec2 q = clamp(ivec2(x, y), ivec2(0), ivec2(u_texture - 1));
            for (int k = 0; k < 3; k++)
                imageAtomicAdd(u_counts, ivec3(q, 3 * receiver + k), fixed_point_count(flux[k] * w));
        }
    }
}

// The texel offset to neighbour q's landing point, if it landed on the same receiver.
bool neighbour(ivec2 q, vec2 from, out vec2 offset)
{
    offset = vec2(0.0);
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, textureSize(u_photons, 0))))
        return false;
    vec4 n = texelFetch(u_photons, q, 0);
    if (n.w < 0.5 || int(n.z + 0.5) != receiver)
        return false;
    offset = photon_window_uv(receiver, n.xy) * float(u_texture) - from;
    return true;
}

float footprint_limit() { return u_footprint; }
float footprint_stretch_limit() { return 4.0 * u_footprint; }
bool open_beyond(ivec2 q) { return false; }

#include "common/footprint.glsl"

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, textureSize(u_photons, 0))))
        return;
    fixed_point_seed(gl_GlobalInvocationID, u_fixed_point);
    vec4 photon = texelFetch(u_photons, p, 0);
    if (photon.w < 0.5)
        return;
    vec3 flux = texelFetch(u_flux, p, 0).rgb;
    receiver = int(photon.z + 0.5);
    vec2 at = photon_window_uv(receiver, photon.xy) * float(u_texture);
    if (u_footprint <= 0.0) {
        ivec2 t = clamp(ivec2(at), ivec2(0), ivec2(u_texture - 1));
        for (int c = 0; c < 3; c++)
            imageAtomicAdd(u_counts, ivec3(t, 3 * receiver + c), fixed_point_count(flux[c]));
        return;
    }
    vec2 bx, by;
    vec2 ex = footprint_axis(p, ivec2(1, 0), at, bx), ey = footprint_axis(p, ivec2(0, 1), at, by);
    // two sample points per texel at any size; at most 12 a side (32 a side
    // cost the ball's caustics 70% more time)
    footprint_splat(at, ex, bx, ey, by, flux, 1e30, 12, 1.0);
}
