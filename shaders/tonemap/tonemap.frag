#version 450 core
// Linear radiance to 8-bit sRGB: exposure, an operator, then the sRGB
// transfer function. Used for PNG output and for the window alike.
in vec2 v_uv;
out vec4 o_color;
uniform sampler2D u_image;
uniform float u_exposure;
uniform int u_operator; // 0 clamp, 1 Reinhard, 2 ACES (Narkowicz's fit)

vec3 srgb_encode(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main()
{
    vec3 c = texelFetch(u_image, ivec2(gl_FragCoord.xy), 0).rgb * u_exposure;
    // Non-finite values show as magenta so they cannot hide.
    if (any(isnan(c)) || any(isinf(c)))
        c = vec3(1.0, 0.0, 1.0);
    c = max(c, vec3(0.0));
    if (u_operator == 1)
        c = c / (1.0 + c);
    else if (u_operator == 2)
        c = clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);
    o_color = vec4(srgb_encode(c), 1.0);
}
