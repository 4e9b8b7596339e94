// A photon's footprint on its receiver and its flux spread over it, shared
// by photon_caustics (accumulate.comp, in caustic-texture texels) and
// layered_caustics (splat.comp, in screen pixels). The includer defines,
// before the include:
//   bool neighbour(ivec2 q, vec2 from, out vec2 offset): the offset from
//     `from` to where photon q landed, if it landed where this one did
//     (clamped to the pass's limit: a footprint torn by a silhouette or a
//     fold smears no farther);
//   void deposit(vec2 at, vec3 flux): the flux bilinearly into the four
//     cells around `at` (centres at +0.5).

// Half the difference of the two neighbours along `step`, or the one that
// landed (a ray differential: the footprint's side along that axis).
vec2 footprint_axis(ivec2 p, ivec2 step, vec2 at)
{
    vec2 a, b;
    bool plus = neighbour(p + step, at, a), minus = neighbour(p - step, at, b);
    if (plus && minus)
        return 0.5 * (a - b);
    if (plus)
        return a;
    if (minus)
        return -b;
    return vec2(0.0);
}

// The flux over the parallelogram at +- ex / 2 +- ey / 2, as n x n sample
// points each deposited bilinearly, so a diverging photon spreads, a
// converging one stays sharp and the flux is kept exactly. Two points a
// cell along sides up to `fine_up_to` cells (one a cell beats against the
// grid where photons land 1-2 cells apart: a +-12% ripple on flat water),
// one a cell beyond, at most `max_side` a side (a wide footprint overlaps
// its neighbours' anyway).
void footprint_splat(vec2 at, vec2 ex, vec2 ey, vec3 flux, float fine_up_to, int max_side)
{
    float lx = length(ex), ly = length(ey);
    int nx = clamp(int(ceil(lx <= fine_up_to ? 2.0 * lx : lx)), 1, max_side);
    int ny = clamp(int(ceil(ly <= fine_up_to ? 2.0 * ly : ly)), 1, max_side);
    vec3 share = flux / float(nx * ny);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            deposit(at + ((float(i) + 0.5) / float(nx) - 0.5) * ex + ((float(j) + 0.5) / float(ny) - 0.5) * ey, share);
}
