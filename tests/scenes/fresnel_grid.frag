#version 450 core
// Test shader: shaders/common/fresnel.glsl tabulated, cos_i = x / (width - 1)
// along a row, one IOR ratio (eta = n_incident / n_transmitted) per row;
// R: fresnel_dielectric, G: fresnel_of with an ideal interface.
#include "common/fresnel.glsl"
out vec4 o_color;
// (tests/lua/values_test.lua lists the same eight)
const float etas[8] = float[8](1.0 / 1.5, 1.5, 1.0 / 2.42, 2.42, 1.0, 0.1, 10.0, 1.0001);
void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    float cos_i = float(p.x) / 63.0;
    float eta = etas[clamp(p.y, 0, 7)];
    o_color = vec4(fresnel_dielectric(cos_i, eta), fresnel_of(cos_i, eta, 1.0), 0.0, 1.0);
}
