#version 450 core
// §4.2: cos(gamma) per pixel, between the target's normal (the normal map
// of the virtual camera) and the light arriving (interpolated over the
// intersection triangle); accumulated additively into the plane's
// illumination texture.
uniform sampler2D u_target;
in vec3 v_intensity;
in vec3 v_direction;
layout(location = 0) out vec4 o_irradiance;
void main()
{
    vec4 t = texelFetch(u_target, ivec2(gl_FragCoord.xy), 0);
    float cos_gamma = t.w < 1e29 ? max(dot(t.xyz, -normalize(v_direction)), 0.0) : 1.0;
    o_irradiance = vec4(v_intensity * cos_gamma, 1.0);
}
