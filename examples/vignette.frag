#version 450 core
// Darkens the corners and tints the image; `image` and `tint` are inputs,
// `strength` a uniform from the script.
#include "common/frame.glsl"
in vec2 v_uv;
out vec4 o_color;
uniform sampler2D image;
uniform sampler2D tint;
uniform float strength;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 c = texelFetch(image, px, 0).rgb * texelFetch(tint, px, 0).rgb;
    float r = length(v_uv - 0.5) * 1.41421;
    o_color = vec4(c * (1.0 - strength * r * r), 1.0);
}
