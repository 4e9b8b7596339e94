// A photon's footprint on its receiver and its flux spread over it, shared
// by photon_caustics (accumulate.comp, in caustic-texture texels) and
// layered_caustics (splat.comp, in screen pixels). The includer defines,
// before the include:
//   bool neighbour(ivec2 q, vec2 from, out vec2 offset): the offset from
//     `from` to where photon q landed, if it landed where this one did;
//   float footprint_limit(): the longest offset a neighbour may stand for
//     when nothing says the light is smoothly stretched there (one
//     neighbour only, or two that disagree: a footprint torn by a
//     silhouette or a fold smears no farther);
//   float footprint_stretch_limit(): the longest when both neighbours
//     agree (light spread thin and evenly: the rim of a ball lens before
//     its focus, where photons land farther apart than footprint_limit);
//   bool open_beyond(ivec2 q): texel q of the light's view has no photon
//     to bound this one's cell on that side: its ray missed every
//     refractor (the object's silhouette lies between q and this photon),
//     or its photon landed nowhere the includer keeps (flew past the view:
//     a ball's rim rays leave sideways); false where that is unknown;
//   void deposit(vec2 at, vec2 half_size, vec3 flux): the flux of the
//     patch at +- half_size, by area into the cells it overlaps (common/box_taps.glsl).

vec2 footprint_clamped(vec2 offset, float limit)
{
    float len = length(offset);
    return len > limit ? offset * (limit / len) : offset;
}

// The side of a photon whose neighbour at p - step is open_beyond, from its
// neighbour `a` at p + step (the side runs towards it): the half towards it
// ends at their midpoint, and the open half reaches as far as the parabola
// through this photon and the next two inwards, at p + step and
// p + 2 step, says its cell's edge lands (between as far as the inner half
// and three times that, at most `widest`). A ball lens' rim before its
// focus spreads faster and faster towards the silhouette, so the outer
// half of the last photon's cell lands farther out than the inner half:
// a cell stretched as far outwards as inwards left black notches between
// the photon columns' last footprints at the lit disc's edge (8 pixels at
// 256 x 256). The bend is that of the footprint through the two ends.
vec2 footprint_open_side(ivec2 p, ivec2 step, vec2 at, vec2 a, float widest, out vec2 bend)
{
    vec2 inner = 0.5 * footprint_clamped(a, widest), outer = -inner;
    vec2 a2;
    if (neighbour(p + 2 * step, at, a2)) {
        // f(t) = t s + t^2 k through f(1) = a, f(2) = a2; the open edge f(-1/2)
        vec2 k = 0.5 * (a2 - 2.0 * a), s = a - k;
        vec2 edge = -0.5 * s + 0.25 * k;
        float len = length(edge), least = length(inner), most = min(3.0 * least, 0.5 * widest);
        // a fold between them (the edge turned back past this photon) keeps the symmetric cell
        if (dot(edge, inner) < 0.0 && len > 0.0)
            outer = edge * (clamp(len, least, most) / len);
    }
    // g(s) = s e + s^2 bend with g(1/2) = inner, g(-1/2) = outer
    bend = 2.0 * (inner + outer);
    return inner - outer;
}

// The footprint's side along `step` and its bend: the parabola
// at + t side + t^2 bend through the midpoints between this photon's
// landing point and its neighbours', t = -1/2, 0, 1/2 (a second-order ray
// differential that ends where the neighbours' footprints begin, so that
// neighbours tile: the parabola through the neighbours themselves at
// t = +-1, evaluated at +-1/2, ended short of or past the midpoints where
// the landing map is more than quadratic, and a ball's rim light before
// its focus showed black and bright chevrons along the photon columns,
// 8 black pixels at 128 x 128 and 256 at 256 x 256). Where the light folds
// (a caustic line between the neighbours: both land on the same side) the
// side goes to zero and the bend keeps the footprint's extent, its flux
// piled at the fold as the rays are; a photon with one neighbour has a
// straight side, one with none a point. Each neighbour's offset is clamped to footprint_limit(), or to
// up to three times the shorter one (at most footprint_stretch_limit())
// when both landed: a smooth stretch lands them about equally far, a tear
// does not. A photon whose other neighbour is open_beyond (a silhouette,
// or a photon that flew past the view) has its one neighbour's offset
// allowed up to the stretch limit and its open half drawn by
// footprint_open_side (the light of a ball lens' rim, spread thin before
// the focus, came out as black bands between the rim photons' clamped
// footprints, and as black spokes where the next photons out flew past
// the image).
vec2 footprint_axis(ivec2 p, ivec2 step, vec2 at, out vec2 bend)
{
    vec2 a, b;
    bend = vec2(0.0);
    bool plus = neighbour(p + step, at, a), minus = neighbour(p - step, at, b);
    float limit = footprint_limit(), widest = max(limit, footprint_stretch_limit());
    if (plus && minus) {
        float stretch = clamp(3.0 * min(length(a), length(b)), limit, widest);
        a = footprint_clamped(a, stretch);
        b = footprint_clamped(b, stretch);
        bend = a + b;
        return 0.5 * (a - b);
    }
    if (plus)
        return open_beyond(p - step) ? footprint_open_side(p, step, at, a, widest, bend)
                                     : footprint_clamped(a, limit);
    if (minus)
        return -(open_beyond(p + step) ? footprint_open_side(p, -step, at, b, widest, bend)
                                       : footprint_clamped(b, limit));
    return vec2(0.0);
}

// The flux over the footprint at + s ex + s^2 bx + t ey + t^2 by for s, t
// in [-cell/2, cell/2]: the photon's own cell of the light's grid (cell 1),
// or the part of it around the photon (cell < 1: a pass that jitters its
// photons over a cell x cell finer pattern, frame after frame, and
// accumulates them, so that the frames' footprints tile the finer grid),
// as n x n sample points, each deposited as the box around its own patch
// of the footprint (the patch's bounding box), so that the
// patches of neighbouring photons tile the receiver and a uniform light
// deposits uniformly whatever the photons' spacing; a diverging photon
// spreads, a converging one stays sharp and the flux is kept exactly. Two
// points a pixel along sides up to `fine_up_to` cells (one a cell beats
// against the grid where photons land 1-2 cells apart: a +-12% ripple on
// flat water), one a cell beyond, at most `max_side` a side (a wide
// footprint overlaps its neighbours' anyway).
void footprint_splat(vec2 at, vec2 ex, vec2 bx, vec2 ey, vec2 by, vec3 flux, float fine_up_to, int max_side, float cell)
{
    // the longest chord of the side's parabola over the cell
    float lx = cell * (length(ex) + 0.25 * cell * length(bx)), ly = cell * (length(ey) + 0.25 * cell * length(by));
    int nx = clamp(int(ceil(lx <= fine_up_to ? 2.0 * lx : lx)), 1, max_side);
    int ny = clamp(int(ceil(ly <= fine_up_to ? 2.0 * ly : ly)), 1, max_side);
    vec3 share = flux / float(nx * ny);
    // each point's patch: a 1/nx x 1/ny piece of the cell, its bounding box
    vec2 half_size = 0.5 * (abs(ex) * (cell / float(nx)) + abs(ey) * (cell / float(ny)));
    for (int j = 0; j < ny; j++) {
        float t = cell * ((float(j) + 0.5) / float(ny) - 0.5);
        for (int i = 0; i < nx; i++) {
            float s = cell * ((float(i) + 0.5) / float(nx) - 0.5);
            deposit(at + s * ex + s * s * bx + t * ey + t * t * by, half_size, share);
        }
    }
}
