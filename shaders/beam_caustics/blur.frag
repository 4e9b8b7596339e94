#version 450 core
// The low-pass filter of the surface caustics (§7: a single area function
// per beam leaves edges between beams): a separable Gaussian over the
// receivers, weighted down across normal and depth discontinuities so
// caustics do not bleed from one surface onto another.
#include "common/frame.glsl"
uniform sampler2D u_image;
uniform sampler2D u_scene_depth;
uniform sampler2D u_scene_normal;
uniform vec2 u_direction;
uniform float u_sigma;
out vec4 o_color;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 nc = texelFetch(u_scene_normal, px, 0);
    vec3 centre = texelFetch(u_image, px, 0).rgb;
    if (nc.w < 0.5 || u_sigma <= 0.0) {
        o_color = vec4(centre, 1.0);
        return;
    }
    float dc = view_depth(texelFetch(u_scene_depth, px, 0).r);
    int radius = int(ceil(2.5 * u_sigma));
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    ivec2 size = ivec2(u_viewport.xy);
    for (int k = -radius; k <= radius; k++) {
        ivec2 q = px + ivec2(u_direction) * k;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size)))
            continue;
        vec4 nq = texelFetch(u_scene_normal, q, 0);
        if (nq.w < 0.5 || dot(nq.xyz, nc.xyz) < 0.9)
            continue;
        float dq = view_depth(texelFetch(u_scene_depth, q, 0).r);
        if (abs(dq - dc) > 0.02 * dc + 1e-4)
            continue;
        float w = exp(-0.5 * float(k * k) / (u_sigma * u_sigma));
        sum += w * texelFetch(u_image, q, 0).rgb;
        wsum += w;
    }
    o_color = vec4(wsum > 0.0 ? sum / wsum : centre, 1.0);
}
