#version 450 core
// Test shader: gain * (1 - image), per channel.
in vec2 v_uv;
out vec4 o_color;
uniform sampler2D image;
uniform float gain;
void main()
{
    vec3 c = texelFetch(image, ivec2(gl_FragCoord.xy), 0).rgb;
    o_color = vec4(gain * (1.0 - c), 1.0);
}
