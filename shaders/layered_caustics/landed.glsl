// The splat's fixed-point scale, from the light that landed (photons.comp
// adds each landing photon's brightest channel at u_fixed_point, the scale
// that fits all the light through the refractors below 2^30): no pixel
// gathers more than the light that landed, so that much is spread over
// 10^9 counts. Where the light's view spans much more than the camera's
// (water 100 wide seen 1 wide), all the light through the refractors left
// a pixel 1-4 counts and the dithered rounding showed as speckle.
layout(std430) buffer LandedFlux { uint landed_units; };

float landed_fixed_point()
{
    return landed_units > 0u ? u_fixed_point * (1.0e9 / float(landed_units)) : u_fixed_point;
}
