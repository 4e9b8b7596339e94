// Fixed-point sums of light by integer atomics (GL 4.5 has no float
// atomic add): value * fixed_point_units counts. Rounding to nearest is biased
// where a photon spreads over many texels and leaves each a few counts: it
// lost the dim spread light (the halo around a ball's caustic faded as the
// photon buffer grew, issue 8). Rounding up with the probability of the
// fraction keeps the expected sum exact. The random numbers are a PCG
// step (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT
// 2020); fixed_point_seed starts a stream per invocation.
uint fixed_point_state;
float fixed_point_units; // counts per unit of flux (the includer's scale: photon_caustics' u_fixed_point, or
                         // layered_caustics' from the light that landed)

// Starts the invocation's stream, counting `units` per unit of flux.
void fixed_point_seed(uvec3 id, float units)
{
    fixed_point_state = id.x * 9781u + id.y * 6271u * 65536u + id.z * 3571u + 1u;
    fixed_point_units = units;
}

float fixed_point_random()
{
    fixed_point_state = fixed_point_state * 747796405u + 2891336453u;
    uint w = ((fixed_point_state >> ((fixed_point_state >> 28u) + 4u)) ^ fixed_point_state) * 277803737u;
    return float((w >> 22u) ^ w) * (1.0 / 4294967296.0);
}

uint fixed_point_count(float value)
{
    return uint(clamp(value * fixed_point_units, 0.0, 4.0e9) + fixed_point_random());
}
