#version 450 core
// Each photon over its own footprint (common/footprint.glsl, a
// second-order ray differential): its neighbours one texel away in the
// light's view give the curved parallelogram its light covers on the
// receiver, spread as the camera sees it (n x n sample points, each
// by area into the pixels its patch covers), so a diverging photon spreads, a
// converging one stays sharp, and the flux is kept exactly. A side is
// clamped to 2 x u_max_radius pixels (light that diverges fast, a
// reflection off a faceted surface, or a footprint torn by a silhouette
// spreads that far and no farther) unless both neighbours agree that the
// light is stretched smoothly, or the photon sits on the refractor's
// silhouette or beside one that flew past the image: then up to
// u_stretch_limit. A photon with no neighbour on an
// axis is a point along it.
#include "common/frame.glsl"
uniform sampler2D u_receiver_normal;
layout(r32ui) uniform uimage2DArray u_flux;
#include "common/box_taps.glsl"
#include "common/fixed_point.glsl"
#include "layered_caustics/landed.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f) uniform readonly image2DArray u_hits;
layout(rgba32f) uniform readonly image2DArray u_photons;
// (u_buffer_size, u_max_radius, u_stretch_limit: landed.glsl's block)

vec2 to_pixels(vec3 p)
{
    vec4 c = u_view_proj * vec4(p, 1.0);
    return (c.xy / max(c.w, 1e-20) * 0.5 + 0.5) * u_viewport.xy;
}

int branch; // 0: through the object, 1: reflected off its first interface (gl_GlobalInvocationID.z)

bool in_buffer(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, u_buffer_size)); }

// The screen offset to neighbour q's landing point, if it landed near.
bool neighbour(ivec2 q, vec2 from, out vec2 offset)
{
    offset = vec2(0.0);
    if (!in_buffer(q))
        return false;
    vec4 h = imageLoad(u_hits, ivec3(q, branch));
    if (h.w < 0.5)
        return false;
    offset = to_pixels(h.xyz) - from;
    return true;
}

float footprint_limit() { return 2.0 * u_max_radius; }
float footprint_stretch_limit() { return u_stretch_limit; }

// photons.comp marks a texel whose ray missed the refractors w = -1, one
// whose photon landed nowhere on screen or in the guard band w = 0: either
// way nothing bounds this photon's cell on that side (a ball's rim photons
// before its focus land far outside the image: their inner neighbours'
// footprints, clamped, left black spokes at the image's edges)
bool open_beyond(ivec2 q)
{
    return !in_buffer(q) || imageLoad(u_hits, ivec3(q, branch)).w < 0.5;
}

void deposit(vec2 at, vec2 half_size, vec3 flux)
{
    // by area into the pixels the box at +- half_size overlaps
    ivec2 first, last;
    box_cells(at.x, half_size.x, first.x, last.x);
    box_cells(at.y, half_size.y, first.y, last.y);
    first = max(first, ivec2(0));
    last = min(last, ivec2(u_viewport.xy) - 1);
    for (int y = first.y; y <= last.y; y++) {
        float wy = box_share(at.y, half_size.y, y);
        for (int x = first.x; x <= last.x; x++) {
            float w = wy * box_share(at.x, half_size.x, x);
            ivec2 q = ivec2(x, y);
            if (w <= 0.0 || texelFetch(u_receiver_normal, q, 0).w < 0.5)
                continue;
            for (int k = 0; k < 3; k++)
                imageAtomicAdd(u_flux, ivec3(q, k), fixed_point_count(flux[k] * w));
        }
    }
}

#include "common/footprint.glsl"

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    branch = int(gl_GlobalInvocationID.z);
    fixed_point_seed(gl_GlobalInvocationID, landed_fixed_point());
    if (any(greaterThanEqual(p, u_buffer_size)))
        return;
    vec4 h = imageLoad(u_hits, ivec3(p, branch));
    if (h.w < 0.5)
        return;
    vec3 flux = imageLoad(u_photons, ivec3(p, branch)).rgb;
    vec2 at = to_pixels(h.xyz);
    vec2 bx, by;
    vec2 ex = footprint_axis(p, ivec2(1, 0), at, bx), ey = footprint_axis(p, ivec2(0, 1), at, by);
    // two points a pixel on footprints up to 3 pixels across, one beyond
    // (their neighbours' overlap smooths the ripple; the ball's splat cost
    // 3.5x with two everywhere), at most 32 a side
    footprint_splat(at, ex, bx, ey, by, flux, 3.0, 32, 1.0);
}
