// The splat's fixed-point scale, from the light that landed (photons.comp
// adds each landing photon's brightest channel at u_fixed_point, the scale
// that fits all the light through the refractors below 2^30): no pixel
// gathers more than the light that landed, so that much is spread over
// 10^9 counts. Where the light's view spans much more than the camera's
// (water 100 wide seen 1 wide), all the light through the refractors left
// a pixel 1-4 counts and the dithered rounding showed as speckle.
layout(std430) buffer LandedFlux { uint landed_units; };

// The pass's values for one frame, every stage's (issue 54): one block,
// uploaded in one call, mirrored by struct layered_caustics_params in
// src/passes/techniques/layered_caustics.c (gl_param_block).
layout(std140) uniform LayeredCausticsParams {
    vec2 u_jitter;         // where in its texel the photon starts (texels, within +-0.5; issue 32)
    ivec2 u_buffer_size;   // the light's view, in texels
    int u_light;           // the light's entry in the frame's list
    int u_light_ortho;     // a directional light: parallel photons
    float u_texel_area;    // directional: the area a texel spans across the beam
    float u_texel_tan;     // point/spot: a texel's side on the plane at distance 1
    float u_fixed_point;   // counts per unit of flux that fit all the light below 2^30
    float u_pixel_tan;     // a pixel's side on the plane at distance 1 (perspective camera)
    float u_pixel_size;    // a pixel's side (orthographic camera)
    float u_max_radius;    // a footprint's largest radius, pixels
    float u_stretch_limit; // the longest a footprint's side may stretch, pixels (layered_caustics.c)
};

float landed_fixed_point()
{
    return landed_units > 0u ? u_fixed_point * (1.0e9 / float(landed_units)) : u_fixed_point;
}
