#version 450 core
#include "common/bindings.glsl"
// The background: the environment seen along each pixel's view ray, or a
// given image (FROM_TEXTURE).
#include "common/frame.glsl"
in vec2 v_uv;
layout(location = 0) out vec4 o_color;
#ifdef FROM_TEXTURE
layout(binding = UNIT_IMAGE) uniform sampler2D u_image;
#endif
void main()
{
#ifdef FROM_TEXTURE
    o_color = vec4(texelFetch(u_image, ivec2(gl_FragCoord.xy), 0).rgb, 1.0);
#else
    vec4 a = u_inv_view_proj * vec4(v_uv * 2.0 - 1.0, -1.0, 1.0);
    vec4 b = u_inv_view_proj * vec4(v_uv * 2.0 - 1.0, 1.0, 1.0);
    vec3 dir = normalize(b.xyz / b.w - a.xyz / a.w);
    o_color = vec4(environment_radiance(dir), 1.0);
#endif
}
