// Where the caustic texture of receiver k lies on its impostor (issue 8):
// the box its photons landed in (bounds.comp: their impostor (u, v) in
// 1/65535 steps), grown by an eighth each way for the footprints' and the
// filter's reach, at least a 64th of the impostor's side and within it.
// The texture's texels go where the caustic is instead of over the whole
// receiver: a floor 10 units wide under a ball's caustic 0.2 wide.
layout(std430) buffer PhotonWindows { uint photon_windows[]; };
uniform int u_fit = 1;

vec4 photon_window(int k)
{
    if (u_fit == 0)
        return vec4(0.0, 0.0, 1.0, 1.0);
    vec2 lo = vec2(photon_windows[4 * k], photon_windows[4 * k + 1]) / 65535.0;
    vec2 hi = vec2(photon_windows[4 * k + 2], photon_windows[4 * k + 3]) / 65535.0;
    if (any(greaterThan(lo, hi)))
        return vec4(0.0, 0.0, 1.0, 1.0); // no photon landed: the whole impostor
    vec2 size = max(hi - lo, vec2(1.0 / 64.0));
    vec2 centre = 0.5 * (lo + hi);
    size *= 1.25;
    lo = clamp(centre - 0.5 * size, vec2(0.0), vec2(1.0));
    hi = clamp(centre + 0.5 * size, vec2(0.0), vec2(1.0));
    return vec4(lo, hi);
}

// impostor (u, v) -> the caustic texture's (u, v)
vec2 photon_window_uv(int k, vec2 uv)
{
    vec4 w = photon_window(k);
    return (uv - w.xy) / max(w.zw - w.xy, vec2(1e-6));
}
