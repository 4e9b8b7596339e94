// The four cells around `at` (cell centres at +0.5) and their bilinear
// weights: how photon_caustics and layered_caustics deposit a flux.
void bilinear_taps(vec2 at, out ivec2 cells[4], out float weights[4])
{
    vec2 f = at - 0.5;
    ivec2 c = ivec2(floor(f));
    vec2 t = f - vec2(c);
    weights = float[4]((1.0 - t.x) * (1.0 - t.y), t.x * (1.0 - t.y), (1.0 - t.x) * t.y, t.x * t.y);
    cells = ivec2[4](c, c + ivec2(1, 0), c + ivec2(0, 1), c + ivec2(1, 1));
}
