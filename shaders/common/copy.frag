#version 450 core
// A copy of the image u_image, pixel for pixel (opaque): what shade
// draws behind its objects when given a background, and what refraction
// and water_surface start from before they draw over it.
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
uniform sampler2D u_image;
void main()
{
    o_color = vec4(texelFetch(u_image, ivec2(gl_FragCoord.xy), 0).rgb, 1.0);
}
