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
    float *joints;        /* vertex_count * 4: JOINTS_0 (indices into the node's skin's joints), or NULL;
                           * read by gltf_file_mesh only */
    float *joint_weights; /* vertex_count * 4: WEIGHTS_0, normalised to sum 1 (0 0 0 0: unskinned) */
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

/* ---- a file as a scene (issue 51) ---------------------------------------
 * The file parsed once (gltf_file_open), then read as its parts: each glTF
 * mesh in its own frame (gltf_file_mesh), and one scene's node tree,
 * cameras, KHR_lights_punctual lights and animations (gltf_file_scene).
 * scene/gltf_pose.c turns a scene and a time into node transforms. */
struct gltf_file;
bool gltf_file_open(const char *path, struct gltf_file **out, struct error *err);
void gltf_file_close(struct gltf_file *file);
/* How many meshes the file holds. */
int gltf_file_mesh_count(const struct gltf_file *file);
/* glTF mesh `index`'s triangle primitives, untransformed (the node that
 * names it places it). */
bool gltf_file_mesh(const struct gltf_file *file, int index, struct gltf_mesh *out, struct error *err);

#define GLTF_NAME 64
#define GLTF_MAX_WEIGHTS 8 /* morph weights a node carries (SCENE_MAX_MORPH_TARGETS) */
#define GLTF_MAX_JOINTS 256 /* joints a skin may have (SCENE_MAX_JOINTS) */

struct gltf_node {
    char name[GLTF_NAME];    /* the file's name, or "node N" */
    int parent;              /* -1: a root */
    int mesh, camera, light; /* indices into the file's meshes and the scene's cameras, lights; -1: none */
    int skin;                /* index into the scene's skins; -1: none */
    bool in_scene;           /* under one of the chosen scene's roots */
    float translation[3], rotation[4], scale[3]; /* the rest pose (rotation x y z w); identity with a matrix */
    bool has_matrix;         /* the file gives `matrix`: it is used as is, unless an animation drives the node */
    float matrix[16];        /* column-major */
    int weight_count;        /* the morph targets of its mesh (0: none) */
    float weights[GLTF_MAX_WEIGHTS]; /* node.weights, else the mesh's, else 0 */
};

struct gltf_camera {
    char name[GLTF_NAME];
    bool orthographic;
    float yfov, aspect;      /* perspective: vertical field of view (radians); aspect 0 when the file gives none */
    float xmag, ymag;        /* orthographic: half the width and height */
    float znear, zfar;       /* zfar 0: infinite (perspective) */
};

enum gltf_light_kind { GLTF_LIGHT_DIRECTIONAL, GLTF_LIGHT_POINT, GLTF_LIGHT_SPOT };
struct gltf_light {
    char name[GLTF_NAME];
    enum gltf_light_kind kind;
    float color[3], intensity; /* candela (point, spot) or lux (directional) */
    float range;               /* 0: infinite */
    float inner_cone, outer_cone; /* spot: radians from the axis */
};

enum gltf_path { GLTF_PATH_TRANSLATION, GLTF_PATH_ROTATION, GLTF_PATH_SCALE, GLTF_PATH_WEIGHTS };
enum gltf_interpolation { GLTF_STEP, GLTF_LINEAR, GLTF_CUBICSPLINE };
struct gltf_channel {
    int node;
    enum gltf_path path;
    enum gltf_interpolation interpolation;
    int components;   /* 3, 4, or the node's weight count */
    size_t key_count;
    float *times;     /* key_count, non-decreasing, finite */
    float *values;    /* key_count x components; CUBICSPLINE: x 3 (in-tangent, value, out-tangent) */
};
struct gltf_animation {
    char name[GLTF_NAME]; /* or "animation N" */
    int channel_count;
    struct gltf_channel *channels;
    float start, end;     /* the first and last key of all its channels */
};

/* A skin (glTF 2.0 §3.7.3): its joints, nodes of the file, each with the
 * inverse of its bind matrix (identity when the file gives none). */
struct gltf_skin {
    char name[GLTF_NAME];
    int joint_count;
    int *joints;          /* node indices */
    float *inverse_bind;  /* joint_count x 16, column-major */
};

struct gltf_scene {
    char name[GLTF_NAME]; /* the scene's name, or "scene N" */
    char generator[128];  /* asset.generator: the tool that wrote the file ("" when unsaid) */
    int index;
    int node_count;       /* every node of the file (in_scene marks the chosen scene's) */
    struct gltf_node *nodes;
    int camera_count;
    struct gltf_camera *cameras;
    int light_count;
    struct gltf_light *lights;
    int animation_count;
    struct gltf_animation *animations;
    int skin_count;
    struct gltf_skin *skins;
};

/* The scene named `name` (NULL: the one numbered `index`; index < 0: the
 * file's default scene, else its first). A node with two parents, a cycle,
 * a tree deeper than 256, a bad camera or light, and animation keys that
 * are not finite, go backwards, or outrun their accessor are errors naming
 * the file and what is wrong. */
bool gltf_file_scene(const struct gltf_file *file, const char *name, int index, struct gltf_scene *out,
                     struct error *err);
void gltf_scene_free(struct gltf_scene *scene);

#ifdef __cplusplus
}
#endif

#endif
