// Material textures of diffuse surfaces (struct material's base_color,
// normal, emissive, metallic_roughness, occlusion, specular_map,
// specular_color_map, clearcoat_map, clearcoat_roughness_map and
// clearcoat_normal slots), bound by
// renderer_draw_objects. The vertex shader passes the mesh's texture
// coordinate sets as v_texcoord0/1. The reference renderer reads the same
// texels with the same filter and the same tangent frame
// (src/reference/ref_material.c).
#include "common/brdf.glsl"
#define MATERIAL_GLSL // (surface_light.glsl's material functions need this file)
uniform sampler2D u_base_color_texture;
uniform sampler2D u_normal_texture;
uniform sampler2D u_emissive_texture;
uniform sampler2D u_metallic_roughness_texture;
uniform sampler2D u_occlusion_texture;
uniform sampler2D u_specular_texture;       // KHR_materials_specular: A x the specular factor
uniform sampler2D u_specular_color_texture; // RGB (sRGB) x the specular colour
uniform sampler2D u_clearcoat_texture;           // KHR_materials_clearcoat: R x the coat's weight
uniform sampler2D u_clearcoat_roughness_texture; // G x its roughness
uniform sampler2D u_clearcoat_normal_texture;    // its own normal map
uniform int u_texture_set[10];        // per slot (base, normal, emissive, metallic-roughness, occlusion, specular,
                                      // specular colour, clearcoat, clearcoat roughness, clearcoat normal):
                                      // 0 none, 1 TEXCOORD_0, 2 TEXCOORD_1
uniform vec3 u_texture_transform[20]; // two rows per slot: uv' = (dot(row0, (uv, 1)), dot(row1, (uv, 1)))
// glTF's metallic-roughness model (struct material's pbr; the programs'
// GLTF_BRDF variant draws those materials)
uniform float u_metallic;
uniform float u_pbr_roughness;
uniform float u_pbr_ior;
uniform float u_occlusion_strength;
uniform float u_specular;      // KHR_materials_specular (1 without)
uniform vec3 u_specular_color; // (1 1 1 without)
uniform float u_clearcoat;     // KHR_materials_clearcoat (0 without)
uniform float u_clearcoat_roughness;
uniform float u_clearcoat_normal_scale;
uniform float u_normal_scale;
uniform int u_single_sided;    // glTF doubleSided false: the camera does not see its back faces (shade discards them)
// thin glass: the share of the surface that is glass (glTF's transmissionFactor) x its texture's red channel
uniform float u_transmission = 1.0;
uniform sampler2D u_transmission_texture;
uniform int u_transmission_set;           // 0: none, 1: TEXCOORD_0, 2: TEXCOORD_1
uniform vec3 u_transmission_transform[2]; // uv' = (dot(row0, (uv, 1)), dot(row1, (uv, 1)))
in vec2 v_texcoord0;
in vec2 v_texcoord1;
// u_alpha, u_alpha_cutoff, u_alpha_blend, v_color (COLOR_0), u_vertex_colors,
// material_alpha and material_cut_out:
#include "common/alpha.glsl"
// v_tangent, u_has_tangents and material_mapped_normal:
#include "common/normal_map.glsl"

// The clearcoat's normal, set by material_normal for material_brdf: its own
// normal map, else the geometry's normal
vec3 material_coat_normal = vec3(0.0, 0.0, 1.0);
// The interpolated normal before any normal map (face-forward), set by
// material_normal: the horizon the glossy lobes' reflections fade under
// (common/surface_light.glsl); 0 where material_normal was not called
vec3 material_geometry_normal = vec3(0.0);

vec2 material_uv(int slot)
{
    vec3 q = vec3(u_texture_set[slot] == 2 ? v_texcoord1 : v_texcoord0, 1.0);
    return vec2(dot(u_texture_transform[slot * 2], q), dot(u_texture_transform[slot * 2 + 1], q));
}

vec3 material_albedo(vec3 color)
{
    if (u_vertex_colors == 1)
        color *= v_color.rgb;
    return u_texture_set[0] > 0 ? color * texture(u_base_color_texture, material_uv(0)).rgb : color;
}

// Thin glass's transmission at this texel (refraction/refract.frag reads
// solid glass's the same way)
float material_transmission()
{
    if (u_transmission_set == 0)
        return u_transmission;
    vec3 q = vec3(u_transmission_set == 2 ? v_texcoord1 : v_texcoord0, 1.0);
    return u_transmission * texture(u_transmission_texture,
                                    vec2(dot(u_transmission_transform[0], q), dot(u_transmission_transform[1], q))).r;
}

vec3 material_emission(vec3 emission)
{
    return u_texture_set[2] > 0 ? emission * texture(u_emissive_texture, material_uv(2)).rgb : emission;
}

// The glTF BRDF's parameters at this texel: base colour (factor x texture),
// metallic (B) and roughness (G) of the metallicRoughnessTexture x the
// factors (linear texels), the IOR and KHR_materials_specular's factors x
// its textures (specularTexture's A, specularColorTexture's RGB).
BrdfMaterial material_brdf(vec3 color)
{
    BrdfMaterial m;
    m.base_color = material_albedo(color);
    vec3 mr = u_texture_set[3] > 0 ? texture(u_metallic_roughness_texture, material_uv(3)).rgb : vec3(1.0);
    m.metallic = clamp(u_metallic * mr.b, 0.0, 1.0);
    m.roughness = clamp(u_pbr_roughness * mr.g, 0.0, 1.0);
    m.ior = u_pbr_ior;
    m.specular = u_texture_set[5] > 0 ? u_specular * texture(u_specular_texture, material_uv(5)).a : u_specular;
    m.specular_color = u_texture_set[6] > 0 ? u_specular_color * texture(u_specular_color_texture, material_uv(6)).rgb
                                            : u_specular_color;
    // KHR_materials_clearcoat: R and G of its textures (linear); its normal
    // was found by material_normal (derivatives: in uniform control flow)
    m.clearcoat = u_texture_set[7] > 0 ? u_clearcoat * texture(u_clearcoat_texture, material_uv(7)).r : u_clearcoat;
    m.clearcoat = clamp(m.clearcoat, 0.0, 1.0);
    m.clearcoat_roughness = clamp(u_texture_set[8] > 0
                                      ? u_clearcoat_roughness * texture(u_clearcoat_roughness_texture, material_uv(8)).g
                                      : u_clearcoat_roughness, 0.0, 1.0);
    m.clearcoat_normal = material_coat_normal;
    return m;
}

// glTF's occlusion at this texel: 1 + strength (R - 1); on the ambient sky only
float material_occlusion()
{
    return u_texture_set[4] > 0 ? 1.0 + u_occlusion_strength * (texture(u_occlusion_texture, material_uv(4)).r - 1.0)
                                : 1.0;
}

// The shading normal (the material's normal map, if it has one) for the
// face-forward normal n at world point p; in the programs' GLTF_BRDF
// variant the clearcoat's normal too (material_coat_normal). Call in
// uniform control flow.
vec3 material_normal(vec3 n, vec3 p)
{
#ifdef GLTF_BRDF
    material_geometry_normal = n;
    material_coat_normal = n;
    if (u_texture_set[9] > 0) {
        vec2 uv = material_uv(9);
        material_coat_normal = material_mapped_normal(n, p, uv, texture(u_clearcoat_normal_texture, uv).rgb * 2.0 - 1.0,
                                                      u_clearcoat_normal_scale);
    }
#endif
    if (u_texture_set[1] == 0)
        return n;
    vec2 uv = material_uv(1);
    return material_mapped_normal(n, p, uv, texture(u_normal_texture, uv).rgb * 2.0 - 1.0, u_normal_scale);
}
