// The normal of the glass or mirror refraction draws at a fragment: its
// interpolated normal, through its normal map where it has one (glTF's
// normalTexture on glass with a volume and on mirrors; slot 1 of the
// material's textures, bound by renderer_draw_objects). The reference
// maps the same (ref_material.c's ref_interface_normal). Needs v_world,
// v_texcoord0/1, u_texture_set[2+] and u_texture_transform[4+].
#include "common/normal_map.glsl"
uniform sampler2D u_normal_texture;
uniform float u_normal_scale;

// n: the outward interpolated normal. Call in uniform control flow.
vec3 interface_normal(vec3 n)
{
    if (u_texture_set[1] == 0)
        return n;
    vec3 q = vec3(u_texture_set[1] == 2 ? v_texcoord1 : v_texcoord0, 1.0);
    vec2 uv = vec2(dot(u_texture_transform[2], q), dot(u_texture_transform[3], q));
    return material_mapped_normal(n, v_world, uv, texture(u_normal_texture, uv).rgb * 2.0 - 1.0, u_normal_scale);
}
