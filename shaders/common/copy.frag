#version 450 core
// A copy of the image at UNIT_IMAGE, pixel for pixel (opaque): what shade
// draws behind its objects when given a background, and what refraction
// and water_surface start from before they draw over it.
#include "common/bindings.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
layout(binding = UNIT_IMAGE) uniform sampler2D u_image;
void main()
{
    o_color = vec4(texelFetch(u_image, ivec2(gl_FragCoord.xy), 0).rgb, 1.0);
}
