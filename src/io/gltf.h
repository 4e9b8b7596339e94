/* glTF 2.0 loading: every triangle primitive of the default scene,
 * flattened into one mesh in the scene's space (node transforms applied),
 * with morph targets, and each primitive's index range with the material
 * it names (pbrMetallicRoughness, alphaMode, KHR_materials_ior,
 * _transmission, _volume and _emissive_strength; what else a material asks
 * for is listed in its `unread`). The loader is a thin C++ shim over tinygltf
 * (gltf_shim.cpp, the project's only C++). */
#ifndef CAUSTICA_GLTF_H
#define CAUSTICA_GLTF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A texture a material reads: the image file's bytes (PNG or JPEG, decoded
 * by the caller), its sampler and the texture info's transform. */
struct gltf_texture {
    uint8_t *bytes; /* owned; NULL when the material has no such texture */
    size_t size;
    char name[96];  /* "image 2 'name'" for messages */
    int texcoord;   /* TEXCOORD_n */
    float transform[6]; /* KHR_texture_transform as a 3x2 matrix (see struct texture_ref) */
    float scale;    /* normalTexture.scale */
    int wrap_s, wrap_t; /* 0 repeat, 1 clamp, 2 mirrored repeat */
    bool nearest;   /* magFilter NEAREST */
    bool mipmaps;   /* minFilter one of the *_MIPMAP_* (or unset) */
};

enum gltf_alpha_mode { GLTF_ALPHA_OPAQUE, GLTF_ALPHA_MASK, GLTF_ALPHA_BLEND };

struct gltf_material {
    char name[64];              /* the material's name, or "material N" */
    float base_color[3];
    float alpha;                /* baseColorFactor's fourth component */
    float metallic, roughness;  /* pbrMetallicRoughness factors (1 and 1 when absent, as glTF says) */
    enum gltf_alpha_mode alpha_mode;
    float alpha_cutoff;         /* MASK: 0.5 by default */
    bool double_sided;          /* doubleSided (false by default: back faces are culled) */
    bool glass;                 /* transmission > 0 */
    float ior;                  /* KHR_materials_ior, 1.5 by default */
    float transmission;         /* KHR_materials_transmission */
    float attenuation_color[3]; /* KHR_materials_volume */
    float attenuation_distance; /* 0 = infinite (no absorption) */
    bool volume;                /* KHR_materials_volume present (else glTF calls the material thin-walled) */
    float thickness;            /* its thicknessFactor */
    float emission[3];          /* emissiveFactor x KHR_materials_emissive_strength */
    struct gltf_texture base_color_texture, normal_texture, emissive_texture;
    struct gltf_texture metallic_roughness_texture; /* G: roughness, B: metallic */
    struct gltf_texture occlusion_texture;          /* R: ambient occlusion, scaled by occlusion_strength */
    float occlusion_strength;                       /* occlusionTexture.strength, [0, 1] */
    float specular;                                 /* KHR_materials_specular specularFactor, [0, 1]; 1 without */
    float specular_color[3];                        /* its specularColorFactor, [0, 1e3]; 1 without */
    struct gltf_texture transmission_texture;       /* R: KHR_materials_transmission's factor per texel */
    struct gltf_texture specular_texture;           /* A: KHR_materials_specular's specularFactor per texel */
    struct gltf_texture specular_color_texture;     /* RGB (sRGB): its specularColorFactor per texel */
    struct gltf_texture thickness_texture;          /* G: KHR_materials_volume's thicknessFactor per texel */
    float clearcoat, clearcoat_roughness;           /* KHR_materials_clearcoat's factors, [0, 1]; 0 without */
    struct gltf_texture clearcoat_texture;          /* R: x clearcoat */
    struct gltf_texture clearcoat_roughness_texture; /* G: x clearcoat_roughness */
    struct gltf_texture clearcoat_normal_texture;   /* the coat's own normal map (its scale); none: the geometry's */
    /* What the material asks for that the loader does not read at all
     * ("metallicRoughnessTexture, KHR_materials_clearcoat"), for `info`. */
    char unread[1024];
    int unread_more; /* what did not fit in `unread` (a file may name any number of extensions) */
};

/* A run of triangles (indices [first_index, first_index + index_count))
 * that share one material: an index into gltf_mesh.materials, or -1 for a
 * primitive without one. */
struct gltf_range {
    size_t first_index, index_count;
    int material;
};

struct gltf_mesh {
    size_t vertex_count;
    size_t index_count;
    float *positions; /* vertex_count * 3 */
    float *normals;   /* vertex_count * 3, generated when the file has none */
    float *texcoords[2]; /* vertex_count * 2, TEXCOORD_0 and _1, or NULL when no primitive has that set */
    float *colors;       /* vertex_count * 4, COLOR_0 as linear RGBA (white where a primitive has none), or NULL */
    float *tangents;     /* vertex_count * 4: TANGENT (world xyz, w), or made per vertex where a normal map
                          * needs them; (0 0 0 1) where a primitive has none; NULL: no primitive has any */
    uint32_t *indices;
    int target_count;
    float *target_positions; /* target_count * vertex_count * 3 deltas */
    float *target_normals;   /* same layout; zero where the file has none */
    float *weights;          /* target_count default weights */
    char **target_names;     /* target_count names ("" when unnamed) */
    int material_count;
    struct gltf_material *materials; /* the materials the primitives name, in first-use order */
    size_t range_count;
    struct gltf_range *ranges;       /* in index order, covering every index */
};

bool gltf_load(const char *path, struct gltf_mesh *out, struct error *err);
void gltf_mesh_free(struct gltf_mesh *mesh);

#ifdef __cplusplus
}
#endif

#endif
