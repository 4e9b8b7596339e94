#version 450 core
// Issue 52: the receiver pixels in the refractors' shadow from the light,
// and of them those the caustics pass left without light. A pixel is in
// the shadow where the refractors lie between it and the light at its
// light texel and at the eight around it (a texel's margin: at the
// outline the shadow map's edge and the caustic's meet, and either may be
// a texel off), it faces the light and lies inside a spot light's cone.
#include "common/frame.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
uniform sampler2D u_receiver_depth;
uniform sampler2D u_receiver_normal;
uniform int u_has_normal; // 0: the pass has no receiver normals (its light is taken as facing them)
uniform sampler2D u_irradiance;
uniform mat4 u_light_view_proj;
#ifdef LAYER_DEPTHS
// the light's depth layers (layers/layers.glsl): layer 0's eye depth, and
// how many layers a texel holds (0: no refractor there)
uniform sampler2DArray u_layer_depth;
uniform usampler2D u_layer_info;
uniform mat4 u_light_view;
ivec2 refractor_size() { return textureSize(u_layer_info, 0); }
// The point x's depth as the refractors' are kept (q: its window position)
float point_depth(vec3 x, vec3 q) { return -(u_light_view * vec4(x, 1.0)).z; }
// Lies the refractors' nearest surface at texel s nearer the light than depth?
bool refractor_before(ivec2 s, float depth)
{
    return texelFetch(u_layer_info, s, 0).r != 0u && texelFetch(u_layer_depth, ivec3(s, 0), 0).r < depth;
}
#else
// the window depth of the nearest refractor (or mirror: its normal's w < 0)
uniform sampler2D u_refractor_depth;
uniform sampler2D u_refractor_normal;
uniform int u_has_refractor_normal;
ivec2 refractor_size() { return textureSize(u_refractor_depth, 0); }
float point_depth(vec3 x, vec3 q) { return q.z; }
bool refractor_before(ivec2 s, float depth)
{
    float z = texelFetch(u_refractor_depth, s, 0).r;
    return z < 1.0 && z < depth && (u_has_refractor_normal == 0 || texelFetch(u_refractor_normal, s, 0).w >= 0.0);
}
#endif
uniform int u_light_kind; // 0 point, 1 directional, 2 spot
uniform vec3 u_light_position;
uniform vec3 u_light_direction;
uniform float u_cos_outer; // spot: its cone; else below -1
layout(std430) buffer Coverage { uint coverage[2]; }; // pixels in the shadow, of them dark
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(u_receiver_depth, 0);
    if (any(greaterThanEqual(p, size)))
        return;
    float d = texelFetch(u_receiver_depth, p, 0).r;
    if (d >= 1.0)
        return;
    vec2 ndc = (vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 w = u_inv_view_proj * vec4(ndc, d * 2.0 - 1.0, 1.0);
    vec3 x = w.xyz / w.w;
    vec3 to_light = u_light_kind == 1 ? -u_light_direction : normalize(u_light_position - x);
    vec3 n = u_has_normal == 1 ? texelFetch(u_receiver_normal, p, 0).xyz : to_light;
    if (dot(n, n) < 0.25 || dot(n, to_light) <= 0.0 || dot(-to_light, u_light_direction) < u_cos_outer)
        return;
    vec4 l = u_light_view_proj * vec4(x, 1.0);
    if (l.w <= 0.0)
        return;
    vec3 q = l.xyz / l.w * 0.5 + 0.5;
    ivec2 tsize = refractor_size();
    ivec2 t = ivec2(floor(q.xy * vec2(tsize)));
    float depth = point_depth(x, q);
    for (int j = -1; j <= 1; j++)
        for (int i = -1; i <= 1; i++) {
            ivec2 s = t + ivec2(i, j);
            if (any(lessThan(s, ivec2(0))) || any(greaterThanEqual(s, tsize)) || !refractor_before(s, depth))
                return;
        }
    atomicAdd(coverage[0], 1u);
    vec3 e = texelFetch(u_irradiance, p, 0).rgb;
    if (max(e.r, max(e.g, e.b)) <= 0.0)
        atomicAdd(coverage[1], 1u);
}
