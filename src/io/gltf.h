/* glTF 2.0 loading: every triangle primitive of the default scene,
 * flattened into one mesh in the scene's space (node transforms applied),
 * with morph targets and the glass parameters of KHR_materials_ior,
 * _transmission and _volume. The loader is a thin C++ shim over tinygltf
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

struct gltf_material {
    bool present;
    float base_color[3];
    bool glass;                 /* transmission > 0 */
    float ior;                  /* KHR_materials_ior, 1.5 by default */
    float transmission;         /* KHR_materials_transmission */
    float attenuation_color[3]; /* KHR_materials_volume */
    float attenuation_distance; /* 0 = infinite (no absorption) */
    float emission[3];          /* emissiveFactor x KHR_materials_emissive_strength */
    struct gltf_texture base_color_texture, normal_texture, emissive_texture;
};

struct gltf_mesh {
    size_t vertex_count;
    size_t index_count;
    float *positions; /* vertex_count * 3 */
    float *normals;   /* vertex_count * 3, generated when the file has none */
    float *texcoords[2]; /* vertex_count * 2, TEXCOORD_0 and _1, or NULL when no primitive has that set */
    uint32_t *indices;
    int target_count;
    float *target_positions; /* target_count * vertex_count * 3 deltas */
    float *target_normals;   /* same layout; zero where the file has none */
    float *weights;          /* target_count default weights */
    char **target_names;     /* target_count names ("" when unnamed) */
    struct gltf_material material; /* of the first primitive that has one */
};

bool gltf_load(const char *path, struct gltf_mesh *out, struct error *err);
void gltf_mesh_free(struct gltf_mesh *mesh);

#ifdef __cplusplus
}
#endif

#endif
