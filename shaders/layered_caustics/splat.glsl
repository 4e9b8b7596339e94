// Splatting a photon's flux into the screen-space flux image with a cone
// kernel of radius `radius` pixels, normalised over the pixels it covers so
// that no energy is made or lost (pixels that are not receivers lose their
// share, as a texture's border would).
layout(binding = LAYERED_UNIT_RECEIVER_NORMAL) uniform sampler2D u_receiver_normal;
layout(r32ui, binding = LAYERED_IMAGE_FLUX) uniform uimage2DArray u_flux;
uniform float u_fixed_point;

float splat_weight(vec2 offset, float radius) { return max(1.0 - length(offset) / (radius + 0.5), 0.0); }

void splat(vec2 at, vec3 flux, float radius)
{
    ivec2 c = ivec2(floor(at));
    int reach = int(ceil(radius + 0.5));
    float total = 0.0;
    for (int j = -reach; j <= reach; j++)
        for (int i = -reach; i <= reach; i++)
            total += splat_weight(vec2(c + ivec2(i, j)) + 0.5 - at, radius);
    if (total <= 0.0)
        return;
    for (int j = -reach; j <= reach; j++)
        for (int i = -reach; i <= reach; i++) {
            ivec2 q = c + ivec2(i, j);
            float w = splat_weight(vec2(q) + 0.5 - at, radius) / total;
            if (w <= 0.0 || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(u_viewport.xy))))
                continue;
            if (texelFetch(u_receiver_normal, q, 0).w < 0.5)
                continue;
            for (int k = 0; k < 3; k++)
                imageAtomicAdd(u_flux, ivec3(q, k), uint(clamp(flux[k] * w * u_fixed_point, 0.0, 4.0e9) + 0.5));
        }
}
