#version 450 core
// §3.3, second pass (after Eisemann & Decoret 2006): the fragment's slice
// bit, ORed into the words by the logic op (GL_OR on RGBA32UI targets).
#include "layers/layers.glsl"
uniform sampler2D u_bounds;
in vec3 v_normal;
in float v_depth;
layout(location = 0) out uvec4 o_word0;
layout(location = 1) out uvec4 o_word1;
layout(location = 2) out uvec4 o_word2;
layout(location = 3) out uvec4 o_word3;
layout(location = 4) out uvec4 o_word4;
layout(location = 5) out uvec4 o_word5;
layout(location = 6) out uvec4 o_word6;
layout(location = 7) out uvec4 o_word7;
void main()
{
    vec2 b = texelFetch(u_bounds, ivec2(gl_FragCoord.xy), 0).rg;
    int slice = layer_slice(v_depth, -b.g, b.r);
    uvec4 bit = uvec4(0u);
    bit[(slice & 127) >> 5] = 1u << uint(slice & 31);
    int word = slice >> 7;
    o_word0 = word == 0 ? bit : uvec4(0u);
    o_word1 = word == 1 ? bit : uvec4(0u);
    o_word2 = word == 2 ? bit : uvec4(0u);
    o_word3 = word == 3 ? bit : uvec4(0u);
    o_word4 = word == 4 ? bit : uvec4(0u);
    o_word5 = word == 5 ? bit : uvec4(0u);
    o_word6 = word == 6 ? bit : uvec4(0u);
    o_word7 = word == 7 ? bit : uvec4(0u);
}
