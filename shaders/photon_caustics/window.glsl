// Where the caustic texture of receiver k lies on its impostor (issue 8):
// the box its photons landed in (bounds.comp: their impostor (u, v) in
// 1/65535 steps), grown by an eighth each way for the footprints' and the
// filter's reach, at least a 64th of the impostor's side and within it.
// The texture's texels go where the caustic is instead of over the whole
// receiver: a floor 10 units wide under a ball's caustic 0.2 wide.
//
// Within that box, the texels go where the camera may see the photons land
// (bounds.comp counts those apart): a ball lens' rim rays leave sideways
// and land far out on the floor, and had widened the box fivefold and
// blurred the focus under it over the coarser texels (the matrix's ball
// 1.25 radii above the floor: error 0.28). That box is grown again until it
// holds at most two texels per photon counted, since texels much finer
// than the photons' spacing only add noise (the matrix's water, a 6-unit
// pool seen 1 unit wide: cut to the view, 0.1 photons a texel raised the
// error of its folds 0.27 -> 0.32; one photon a texel blurred the ball's
// focus, 0.095 -> 0.120; half of one kept both: 0.27 and 0.095), but never
// past the box of all the photons.
const int PHOTON_WINDOW_STRIDE = 9; // the seen ones' lo, hi and count; all of them's lo, hi
layout(std430) buffer PhotonWindows { uint photon_windows[]; };
// The caustic textures' values for one frame, every stage's from the
// photon buffer on (issue 54: one block, uploaded in one call, mirrored by
// struct photon_params in src/passes/techniques/photon_caustics.c). The
// light side's (trace.frag: the light's matrices from the fit) stay its own.
layout(std140) uniform PhotonParams {
    int u_fit;            // 1: each receiver's texture covers the box its photons landed in
    int u_texture;        // the caustic texture's side in texels
    float u_footprint;    // accumulate: a photon's spread at most, texels (0: a point)
    int u_k;              // filter: radius (§3.2)
    float u_s;            // filter: scale
    float u_fixed_point;  // counts per unit of flux (all the light below 2^31)
    float u_bias;         // map: the caustic mapping test's depth tolerance
    int u_pixel_samples;  // map: lookups per pixel along each axis where the footprint spans more texels
};
const float PHOTONS_PER_TEXEL = 0.5;

// a box of photons' (u, v) in 1/65535 steps, grown by an eighth each way
// for the footprints' and the filter's reach, at least a 64th of the
// impostor's side; false: no photon
bool photon_box(int at, out vec2 lo, out vec2 hi)
{
    lo = vec2(photon_windows[at], photon_windows[at + 1]) / 65535.0;
    hi = vec2(photon_windows[at + 2], photon_windows[at + 3]) / 65535.0;
    if (any(greaterThan(lo, hi)))
        return false;
    vec2 size = 1.25 * max(hi - lo, vec2(1.0 / 64.0)), centre = 0.5 * (lo + hi);
    size = min(size, vec2(1.0)); // kept whole inside the impostor: a box cut at its edge would be finer
    lo = clamp(centre - 0.5 * size, vec2(0.0), vec2(1.0) - size);
    hi = lo + size;
    return true;
}

vec4 photon_window(int k)
{
    int at = PHOTON_WINDOW_STRIDE * k;
    vec2 all_lo, all_hi, lo, hi;
    if (u_fit == 0 || !photon_box(at + 5, all_lo, all_hi))
        return vec4(0.0, 0.0, 1.0, 1.0); // no photon landed: the whole impostor
    if (!photon_box(at, lo, hi))
        return vec4(all_lo, all_hi); // none where the camera may see: it samples nothing
    vec2 size = hi - lo, centre = 0.5 * (lo + hi);
    float wanted = PHOTONS_PER_TEXEL * float(u_texture) * float(u_texture);
    float photons = max(float(photon_windows[at + 4]), 1.0);
    if (wanted > photons)
        size *= sqrt(wanted / photons);
    size = min(size, all_hi - all_lo);
    lo = clamp(centre - 0.5 * size, all_lo, all_hi - size);
    return vec4(lo, lo + size);
}

// impostor (u, v) -> the caustic texture's (u, v)
vec2 photon_window_uv(int k, vec2 uv)
{
    vec4 w = photon_window(k);
    return (uv - w.xy) / max(w.zw - w.xy, vec2(1e-6));
}
