/* The scene: meshes, objects, materials, lights, camera and environment.
 * Meshes, objects, lights, environments and media are reference counted:
 * the Lua userdata holds one reference, and whatever keeps a pointer
 * (an object its mesh, the scene its members, a pass its light) holds
 * another, so that no order of release, a script calling a __gc early
 * included, frees one that is still in use.
 * Every live change bumps a version, which is how the graph knows what it
 * can reuse from the last frame. */
#ifndef CAUSTICA_SCENE_H
#define CAUSTICA_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/vecmath.h"

#define SCENE_MAX_MORPH_TARGETS 8
#define SCENE_MAX_GPU_LIGHTS 32

enum material_kind { MATERIAL_DIFFUSE, MATERIAL_GLASS, MATERIAL_MIRROR, MATERIAL_WATER };

enum texture_wrap { TEXTURE_REPEAT, TEXTURE_CLAMP, TEXTURE_MIRROR };

/* An 8-bit RGBA image a material samples (scene/texture.c): a PNG or JPEG
 * file, a glTF image, or a procedural one (checker). Row 0 is the image's
 * top row, at v = 0, as glTF's texture coordinates have it. Colour slots
 * (base colour, emission) read the texels as sRGB and linearize them before
 * filtering; the normal slot reads them as they are. The GPU uploads the
 * same texels (graph/texture_cache.c) and the reference samples them with
 * the same filter (texture_sample). */
struct texture {
    int references;
    uint64_t serial; /* unique for the process: the renderer's texture cache keys its GPU copy by it */
    char name[512];  /* the file, "checker", or "file.glb image 2" */
    int width, height;
    uint8_t *texels;  /* owned, width * height * 4 */
    bool nearest;     /* magnification: nearest texel (else bilinear) */
    bool mipmaps;     /* minification through mipmaps on the GPU, and in the reference where a
                         pixel's footprint is known (texture_sample_grad) */
    enum texture_wrap wrap_s, wrap_t;
    /* The reference's copy of the chain glGenerateMipmap makes: levels 1..
     * one after the other, 8-bit RGBA, averaged as linear values [0] or
     * as sRGB colours decoded first [1] (texture_build_mips; NULL until). */
    uint8_t *mip_chain[2];
    int levels; /* 1 + floor(log2(the longer side)) once a chain is built */
};

/* Where a material reads a texture: which texture coordinate set, and
 * KHR_texture_transform's offset, rotation and scale as the 3x2 matrix
 * uv' = (m[0] u + m[2] v + m[4], m[1] u + m[3] v + m[5]). */
struct texture_ref {
    struct texture *texture; /* a reference, or NULL */
    int texcoord;            /* 0 or 1 */
    float transform[6];
    float scale;             /* normal maps: the normalTexture scale */
};

struct material {
    enum material_kind kind;
    vec3 color;      /* diffuse albedo, or the tint of a mirror */
    float ior;       /* glass, water */
    vec3 absorption; /* Beer-Lambert coefficient per RGB, 1/scene units */
    vec3 emission;   /* diffuse: radiance it emits (seen, directly or through glass; it lights nothing) */
    bool ideal;      /* fresnel = false: an ideal interface, all light refracts (reflects only under TIR) */
    float roughness; /* glass, water: GGX roughness as glTF has it (alpha = roughness^2); 0: smooth */
    vec3 tint;       /* glass, water: what light passing through is multiplied by, once (entering):
                      * glTF's base colour as KHR_materials_transmission's tint; 1 1 1: clear */
    float thickness; /* glass: KHR_materials_volume's thicknessFactor (mesh units), the path length
                      * a pass that sees one interface only absorbs over (shade); 0: none given */
    float transmission; /* glass, water: the share of the surface that is the interface (glTF's
                         * transmissionFactor); the rest is diffuse of `color`. 1: all glass */
    bool thin;          /* glass: thin-walled (glTF's glass without KHR_materials_volume): one
                         * surface, seen from both sides, that reflects F and lets (1 - F) x tint
                         * through undeviated (OBJECT_ROLE_THIN); the base colour texture, the
                         * normal map and alpha apply to it as to a diffuse surface */
    /* Textures (diffuse surfaces only): colour x base_color, the shading
     * normal from a tangent-space normal map, emission x emissive. A
     * material holds a reference to each: copy materials with
     * material_assign and drop them with material_release. */
    struct texture_ref base_color, normal, emissive;
    /* Glass and water: `transmission` x this texture's red channel (linear)
     * per texel (glTF's transmissionTexture); no texture: uniform. */
    struct texture_ref transmission_map;
    /* Glass: `thickness` x this texture's green channel (linear) per texel
     * (KHR_materials_volume's thicknessTexture), where a pass stands in for
     * the volume by it (shade's one interface); no texture: uniform. */
    struct texture_ref thickness_map;
    /* glTF's metallic-roughness model on a diffuse surface (issue 50; the
     * BRDF is core/brdf.c and common/brdf.glsl): pbr set, the surface is
     * drawn by glTF's BRDF with `metallic` and `roughness` (perceptual)
     * scaled per texel by metallic_roughness's B and G, `ior` (its
     * dielectric reflectance), and occlusion's R on the ambient sky,
     * strength `occlusion_strength`. Unset (a script's diffuse): Lambert. */
    bool pbr;
    float metallic;
    float specular;      /* KHR_materials_specular: the dielectric's specular weight (1 without) ... */
    vec3 specular_color; /* ... and colour (F0 x this, at most 1) */
    struct texture_ref metallic_roughness, occlusion;
    float occlusion_strength;
    /* KHR_materials_specular's textures: specular x specular_map's A and
     * specular_color x specular_color_map's RGB (sRGB), per texel */
    struct texture_ref specular_map, specular_color_map;
    /* KHR_materials_clearcoat on a pbr surface: a second, colourless GGX
     * lobe over the material (core/brdf.h), weight clearcoat x
     * clearcoat_map's R, roughness clearcoat_roughness x
     * clearcoat_roughness_map's G (both linear), its own normal map
     * (clearcoat_normal, with its scale) or else the geometry's normal.
     * clearcoat 0: none. */
    float clearcoat, clearcoat_roughness;
    struct texture_ref clearcoat_map, clearcoat_roughness_map, clearcoat_normal;
    /* Cut-outs (glTF alphaMode MASK, diffuse surfaces): where alpha x the
     * base colour texture's alpha is below alpha_cutoff the surface is not
     * there, for the camera, the shadow map and the reference alike.
     * alpha_cutoff 0: opaque. alpha_blend (glTF's BLEND): the surface is
     * there with probability alpha x texture alpha, a stochastic cut-out
     * (the GPU by an ordered dither per pixel, the reference per ray),
     * which is alpha blending in expectation. */
    float alpha, alpha_cutoff;
    bool alpha_blend;
    /* glTF's doubleSided false on a diffuse surface or thin glass: its back
     * faces are not seen by the camera (shade discards them, the
     * reference's eye paths pass through them); they still cast shadows.
     * A script's materials are two-sided. */
    bool single_sided;
    /* A material read from a file (scene/mesh_gltf.c): its name there, and
     * what the file asks for that caustica does not render, for `info`
     * ("roughness 0.49 (drawn smooth), transmissionTexture"). Empty for a
     * script's materials, which are rendered as they are. */
    char source[64];
    char ignored[1600]; /* (never cut: the file's `unread`, at most 1023, and the loader's own phrases) */
};

struct texture *texture_create(const char *name, int width, int height, struct error *err);
/* A checker of `squares` x `squares` squares over uv [0,1]^2, one texel
 * each, sampled nearest and repeating: sharp edges on both renderers. */
struct texture *texture_create_checker(int squares, vec3 a, vec3 b, struct error *err);
/* Decodes a PNG or JPEG file (PNG: libpng, JPEG: libjpeg); `max_bytes`
 * bounds its texels before they are allocated (0: only the decoder's caps). */
struct texture *texture_load(const char *path, unsigned long long max_bytes, struct error *err);
/* Decodes PNG or JPEG bytes (by their signature); `name` for messages. */
struct texture *texture_decode(const char *name, const uint8_t *bytes, size_t size, unsigned long long max_bytes,
                               struct error *err);
/* The bytes of a texture's texels (what a script is charged for it). */
size_t texture_bytes(const struct texture *t);
void texture_retain(struct texture *t);
void texture_destroy(struct texture *t);
/* The identity transform, texcoord 0, scale 1, no texture. */
void texture_ref_init(struct texture_ref *ref);
/* The filtered value at uv, as the GPU samples level 0: bilinear (or
 * nearest) with the wrap modes, colour texels linearized first when `srgb`. */
vec3 texture_sample(const struct texture_ref *ref, const float uv[2], bool srgb);
/* The texture's alpha at uv with the same filter (1 without a texture). */
float texture_sample_alpha(const struct texture_ref *ref, const float uv[2]);
/* Makes the mip chain texture_sample_grad reads (once per texture and
 * colour space; not thread-safe: the reference builds it before its
 * threads start). Nothing to do for a texture without mipmaps. */
bool texture_build_mips(struct texture *t, bool srgb, struct error *err);
/* The value at uv as GL's trilinear filter reads it where the texture
 * coordinates change by duv = (du/dx, dv/dx, du/dy, dv/dy) from one pixel
 * to the next (before the reference's transform, which is applied to
 * both): the level of detail of the OpenGL 4.5 specification §8.14 (the
 * longer of the two derivatives, isotropic), linear between two levels;
 * level 0 as texture_sample where the texture is magnified, has no
 * mipmaps or no chain for `srgb`. RGB in rgba[0..2], alpha in rgba[3]. */
void texture_sample_grad(const struct texture_ref *ref, const float uv[2], const float duv[4], bool srgb,
                         float rgba[4]);
void texture_ref_apply(const struct texture_ref *ref, const float uv[2], float out[2]);

void material_init(struct material *m, enum material_kind kind);
/* *dst = *src, retaining src's textures and releasing dst's old ones. */
void material_assign(struct material *dst, const struct material *src);
void material_release(struct material *m);
bool material_has_textures(const struct material *m);
/* Every texture slot a material has, and whether each holds colours (read
 * as sRGB: base colour, emission, specular colour) or data (linear). */
enum { MATERIAL_TEXTURE_SLOTS = 12 };
void material_texture_slots(const struct material *m, const struct texture_ref *slots[MATERIAL_TEXTURE_SLOTS],
                            bool srgb[MATERIAL_TEXTURE_SLOTS]);

struct mesh {
    int references;
    uint64_t serial;        /* unique for the process: the renderer's mesh cache keys its GPU copy by it */
    char name[512]; /* the file it came from, or the procedural kind */
    bool has_material;      /* the file gave one: objects use it unless the script picks another */
    struct material material;
    /* A file whose primitives use several materials: one part per material
     * (its triangles, their vertices, its material), owned. The mesh's own
     * arrays keep the whole; an object made from it is a group of one part
     * object each (struct object), which is what passes and the reference
     * see. 0 and NULL when one material (or none) serves the whole mesh. */
    int part_count;
    struct mesh **parts;
    char material_name[64]; /* the file's name of the material it was made with ("" for none) */
    size_t vertex_count, index_count;
    float *positions, *normals; /* vertex_count * 3 each */
    float *texcoords[2];        /* vertex_count * 2 each, or NULL: glTF TEXCOORD_0/1, generated for procedural shapes */
    float *colors;              /* vertex_count * 4: glTF's COLOR_0 (linear RGBA, multiplies the base colour), or NULL */
    float *tangents;            /* vertex_count * 4: a normal map's tangent (xyz along increasing u, w its
                                 * handedness), glTF's TANGENT or made at load; (0 0 0 1): none there; or NULL */
    float *joints, *joint_weights; /* vertex_count * 4 each: a glTF skin's JOINTS_0 and WEIGHTS_0 (weights
                                    * summing to 1, or 0 0 0 0: unskinned), or NULL (c.gltf.load) */
    int joint_count;                /* the largest joint index + 1 (0 without a skin) */
    uint32_t *indices;
    int target_count;
    float *target_positions, *target_normals; /* target_count * vertex_count * 3 deltas */
    float default_weights[SCENE_MAX_MORPH_TARGETS];
    vec3 bounds_min, bounds_max; /* of the base shape */
    float morph_extent;          /* largest |delta| over the targets, to bound morphs */
    /* > 0: made by mesh_create_sphere, the tessellation of a sphere of this
     * radius about the origin, which the reference traces as the sphere
     * itself (ref_scene.c); 0: any other mesh */
    float sphere_radius;
    float *thickness;          /* per-vertex d_N for Wyman's refraction, made on demand (owned) */
    /* The GPU copies live in the renderer's mesh cache (graph/mesh_cache.c). */
};

/* The vertices and indices the procedural mesh of these parameters has
 * (the lathe's at most: repeated profile points are dropped), so that a
 * caller can check its memory before the mesh is made. Parameters outside
 * the creators' ranges give what the creators would refuse anyway. */
void mesh_sphere_counts(int segments, size_t *vertices, size_t *indices);
void mesh_grid_counts(int cells_x, int cells_z, size_t *vertices, size_t *indices);
void mesh_torus_counts(int segments, int sides, size_t *vertices, size_t *indices);
void mesh_lathe_counts(int points, int segments, size_t *vertices, size_t *indices);
/* Procedural meshes. Each returns a mesh owned by the caller (mesh_destroy). */
struct mesh *mesh_create_sphere(float radius, int segments, struct error *err);
struct mesh *mesh_create_plane(float size, int subdivisions, struct error *err);
struct mesh *mesh_create_box(vec3 size, struct error *err);
struct mesh *mesh_create_grid(float size, int resolution, struct error *err);
/* A size_x by size_z grid of cells_x by cells_z cells in the xz plane, +y up. */
struct mesh *mesh_create_grid_xz(float size_x, float size_z, int cells_x, int cells_z, struct error *err);
struct mesh *mesh_create_torus(float radius, float tube, int segments, int sides, struct error *err);
/* Surfaces of revolution about +y (scene/mesh_lathe.c): `count` (radius,
 * height) pairs, in either order; a point on the axis closes the surface
 * there. Creases over ~35 degrees keep two normals. u runs around, v along
 * the profile (0 at its top). Centred like the box: a cylinder or cone of
 * height h spans y in [-h/2, h/2], the cone's apex at the top. */
struct mesh *mesh_create_lathe(const char *name, const float *profile, int count, int segments, struct error *err);
/* Tangents by MikkTSpace's construction (scene/mesh_tangents.c) for the
 * vertices of triangles [first_index, first_index + index_count) whose
 * tangent is zero (the file gave none), from texture coordinates `set`;
 * a vertex its triangles map both ways is split in two. */
bool mesh_make_tangents(struct mesh *m, size_t first_index, size_t index_count, int set, struct error *err);
struct mesh *mesh_create_cylinder(float radius, float height, int segments, struct error *err);
struct mesh *mesh_create_cone(float radius, float height, int segments, struct error *err);
/* `texture_budget`: the bytes its material's textures may take together,
 * checked before each is decoded (0: only the decoder's caps). */
struct mesh *mesh_load_gltf(const char *path, unsigned long long texture_budget, struct error *err);
/* Mesh `index` of a parsed file (io/gltf.h), in its own frame, named `path`
 * (the file's, with the mesh's name) in messages. */
struct gltf_file;
struct mesh *mesh_load_gltf_mesh(const struct gltf_file *file, const char *path, int index,
                                 unsigned long long texture_budget, struct error *err);
/* The bytes of the textures a mesh's material holds. */
size_t mesh_texture_bytes(const struct mesh *m);
/* The triangles `first_index/3 ...` of `count` ranges (index ranges into
 * whole->indices) as a mesh of their own: the vertices they use (texture
 * coordinates and morph targets included), renumbered (scene/mesh_parts.c). */
struct mesh *mesh_create_part(const struct mesh *whole, const char *name, const size_t *first_index,
                              const size_t *index_count, int count, struct error *err);
/* Takes ownership of the arrays (malloc'd). */
struct mesh *mesh_create_from_arrays(const char *name, float *positions, float *normals, size_t vertex_count,
                                     uint32_t *indices, size_t index_count, struct error *err);
void mesh_compute_bounds(struct mesh *mesh);
/* Midpoint subdivision (scene/mesh_subdivide.c): the longest edge; how many
 * levels (each triangle into four) bring it to max_edge without passing
 * max_triangles; a new mesh (positions, normals, indices only) `levels`
 * levels finer, owned by the caller (mesh_destroy), or NULL on error. */
float mesh_longest_edge(const struct mesh *mesh);
/* Whether p (the mesh's frame, or the world for the object) is inside the
 * closed mesh: the parity of a ray's crossings (scene/mesh_inside.c). The
 * object's base shape under its transform: morphs and deformers are not
 * applied. */
bool mesh_contains_point(const struct mesh *mesh, vec3 p);
/* The same, true only where rays in two opposite directions both say
 * inside (a closed surface around p, never an open sheet beside it) and
 * the nearest surface faces outwards (a solid, not a room around p). */
bool mesh_encloses_point(const struct mesh *mesh, vec3 p);
int mesh_subdivision_levels(const struct mesh *mesh, float max_edge, size_t max_triangles);
struct mesh *mesh_create_subdivided(const struct mesh *mesh, int levels, struct error *err);
/* The mesh a light transport table samples (Iwasaki et al. §3, a path per
 * vertex): the object's own, or its subdivision where a triangle's edge is
 * longer than edge_fraction of the mesh's bounding diagonal (a cube's
 * corners' paths leave by different faces: its 12 triangles interpolate
 * one path across a face that sends light out of two), kept in `fine`
 * while the mesh is the same. Shared by illumination_textures and
 * sliced_refraction. NULL on error. */
struct mesh_table_fine {
    struct mesh *fine;
    uint64_t of; /* the serial of the mesh `fine` subdivides */
    int levels;
};
const struct mesh *mesh_table_mesh(struct mesh_table_fine *c, const struct mesh *mesh, float edge_fraction,
                                   size_t max_triangles, struct error *err);
void mesh_table_fine_release(struct mesh_table_fine *c);
/* d_N per vertex into mesh->thickness (scene/thickness.c, Embree). */
bool mesh_compute_thickness(struct mesh *mesh, struct error *err);
void mesh_retain(struct mesh *mesh);
/* Drops one reference; the last one frees the mesh and its GL buffers. */
void mesh_destroy(struct mesh *mesh);

const char *material_kind_name(enum material_kind kind);

/* What a surface is to light transport: the one predicate every pass, the
 * graph's lint and the reference choose objects by. A pass names the roles
 * it handles (its descriptor's `draws`, a caustics pass's refractors) and
 * says which it leaves out; none decides from material kinds itself. */
enum object_role {
    OBJECT_ROLE_RECEIVER = 1u, /* diffuse: lit, shadowed, receives caustics */
    OBJECT_ROLE_GLASS = 2u,    /* a closed refractor */
    OBJECT_ROLE_WATER = 4u,    /* a water surface: refracts, its medium below */
    OBJECT_ROLE_MIRROR = 8u,
    OBJECT_ROLE_THIN = 16u,    /* thin-walled glass: light crosses it undeviated (material.thin) */
};
#define OBJECT_ROLE_REFRACTOR (OBJECT_ROLE_GLASS | OBJECT_ROLE_WATER)
#define OBJECT_ROLE_SPECULAR (OBJECT_ROLE_REFRACTOR | OBJECT_ROLE_MIRROR)
/* The material's role (one bit). */
unsigned material_role(const struct material *m);
/* Surfaces whose textures, normal map and alpha both renderers read: a
 * diffuse surface's, and thin glass's (its base colour tints). */
bool material_is_textured_surface(const struct material *m);
/* "receiver", "glass", "water", "mirror" or "thin glass" for one role bit. */
const char *object_role_name(unsigned role);

enum deform_kind { DEFORM_NONE, DEFORM_WAVE, DEFORM_GLSL };

struct deformer {
    enum deform_kind kind;
    float amplitude, frequency, speed; /* wave: p.y += a * sin(f * dot(p.xz, dir) - speed * t) */
    vec3 direction;
    char *glsl;          /* owned: "vec3 deform(vec3 p, float t) { ... }" */
    char origin[600];    /* "script.lua:12" where the deformer was made, for error messages */
};

struct water;

struct object {
    int references;
    uint64_t serial; /* unique for the process (the mesh cache's key) */
    int id;
    struct water *water; /* owned: a simulated water surface drives this object's vertices */
    struct mesh *mesh; /* a reference */
    struct material material;
    vec3 position, scale;
    quat rotation;
    bool visible, cast_shadows;
    float morph_weights[SCENE_MAX_MORPH_TARGETS];
    /* A skinned mesh's joint matrices (joint_matrix_count x 16, column-major,
     * the joint's world matrix times its inverse bind matrix; owned), set by
     * c.gltf.load's animations: the skin is applied after the morphs, before
     * a deformer (graph/deform.c), and the object's own transform after it. */
    float *joint_matrices;
    int joint_matrix_count;
    vec3 skin_min, skin_max; /* the box of the skinned base shape (object_set_joint_matrices) */
    struct deformer deform;
    uint64_t version;
    /* An object of a mesh with parts is a group: it holds one part object
     * per part (owned references), and the scene holds the parts, never
     * the group. Whatever a script sets on the group is copied onto its
     * parts at once (object_sync_parts); a part's `group` points back
     * (not a reference). */
    struct object **parts;
    int part_count;
    struct object *group;
    /* This frame's matrices are in the frame snapshot (graph/frame.h), its
     * animated vertices in the renderer's mesh cache. */
};

/* One reference to the new object; it takes one to `mesh`. A mesh with
 * parts makes a group of part objects, each with its part's material. */
struct object *object_create(struct mesh *mesh);
/* Copies a group's transform, flags, morph weights, deformer and version
 * onto its parts (nothing for an object without parts); false when out of
 * memory for a deformer's source. */
bool object_sync_parts(struct object *group);
/* Copies `count` joint matrices (16 floats each) into the object (0: no
 * skin); false when out of memory (the object keeps what it had). */
bool object_set_joint_matrices(struct object *obj, const float *matrices, int count);
/* Sets the material of a group's parts (or of the object itself). */
void object_set_material(struct object *obj, const struct material *m);
void object_retain(struct object *obj);
/* Drops one reference; the last one frees it (and its mesh reference). */
void object_destroy(struct object *obj);
/* Morphs or deforms this frame? */
bool object_is_animated_geometry(const struct object *obj);
mat4 object_model_matrix(const struct object *obj);
bool object_contains_point(const struct object *obj, vec3 p);
bool object_encloses_point(const struct object *obj, vec3 p);
void object_world_bounds(const struct object *obj, vec3 *lo, vec3 *hi);
/* The object's role (material_role), 0 while it is invisible. */
unsigned object_role(const struct object *obj);
/* True when the object has one of `roles` (a mask of OBJECT_ROLE_*). */
bool object_is(const struct object *obj, unsigned roles);
/* Visible glass or water with material.roughness > 0 (rough transmission:
 * the reference samples it, refraction's scene lookup blurs it, and the
 * other passes say through leaves_out that they draw it smooth). */
bool object_is_rough_refractor(const struct object *obj);
/* Visible glass or water whose material.tint is not white. */
bool object_is_tinted_refractor(const struct object *obj);
/* Visible glass or water with material.transmission < 1 or a transmission texture. */
bool object_is_partly_diffuse_refractor(const struct object *obj);

enum light_kind { LIGHT_POINT, LIGHT_DIRECTIONAL, LIGHT_SPOT, LIGHT_LINEAR };

struct light {
    int references;
    enum light_kind kind;
    vec3 position;  /* point, spot; start of a linear light */
    vec3 end;       /* linear: end of the segment */
    vec3 direction; /* directional (direction light travels), spot (axis) */
    vec3 intensity; /* point/spot/linear: W/sr (all samples together); directional: irradiance */
    float angle;    /* spot: outer half-angle, degrees */
    float softness; /* spot: fraction of the cone over which it fades */
    int samples;    /* linear: number of point lights */
    bool cast_shadows;
    uint64_t version;
};

struct light *light_create(enum light_kind kind);
void light_retain(struct light *light);
/* Where a light's shadow map and photons start: its position, a linear
 * light's midpoint. */
vec3 light_center(const struct light *light);
/* The most light a light's view can hold: `intensity` (its largest
 * channel: radiant intensity, or irradiance for a directional light) times
 * the solid angle of the perspective frustum `proj` (or the area of the
 * orthographic one). Photon passes scale their fixed-point sums by it: no
 * texel can gather more, and a bound of all the light around a point
 * (4 pi) left a narrow frustum's photons a few counts each, rounded away. */
double light_view_flux_bound(float intensity, const mat4 *proj);
/* Drops one reference; the last one frees it. */
void light_destroy(struct light *light);
const char *light_kind_name(enum light_kind kind);

struct camera {
    vec3 eye, target, up;
    float fov, znear, zfar;
    float ortho_width;  /* > 0: an orthographic camera this wide (scene units; the height follows the
                         * image's aspect), looking along target - eye; 0: perspective with `fov` */
    uint64_t version;
};

struct environment {
    int references;
    uint64_t serial; /* unique for the process: the renderer keys its cube map by it */
    char path[512];
    int size;
    float *faces[6]; /* owned: linear RGB float, size*size*3 each, +X -X +Y -Y +Z -Z */
};

struct environment *environment_load(const char *folder, struct error *err);
/* Radiance the environment sends along `dir`. */
vec3 environment_lookup(const struct environment *env, vec3 dir);
void environment_retain(struct environment *env);
/* Drops one reference; the last one frees it. */
void environment_destroy(struct environment *env);

/* A participating medium filling an axis-aligned box (outside dielectric
 * objects, which keep their own absorption): coefficients at density 1,
 * a Henyey-Greenstein phase function, and a density that is a constant or
 * a grid over the box (trilinear). */
struct medium {
    int references;
    vec3 sigma_s, sigma_a; /* per unit length at density 1 */
    float g;               /* Henyey-Greenstein asymmetry, -1 < g < 1 (0 = isotropic) */
    vec3 box_min, box_max;
    float density;         /* homogeneous density (when grid is NULL) */
    int nx, ny, nz;
    float *grid;           /* owned: nx*ny*nz densities at the cell corners, x fastest */
    float max_density;     /* majorant for tracking */
    uint64_t version;
};

struct medium *medium_create(void);
void medium_retain(struct medium *m);
/* Drops one reference; the last one frees it. */
void medium_destroy(struct medium *m);
/* A density grid of nx*ny*nz corner samples over the box from
 * density(user, p); false with a message when a value is negative or not
 * finite. Sets max_density. */
bool medium_sample_grid(struct medium *m, int nx, int ny, int nz, double (*density)(void *user, vec3 p), void *user,
                        struct error *err);
/* Density at world point p (0 outside the box). */
float medium_density(const struct medium *m, vec3 p);

struct scene {
    struct camera camera;
    struct medium *medium;     /* a reference, may be NULL */
    vec3 background;           /* radiance of the background when there is no environment */
    vec3 ambient;              /* radiance of a uniform ambient sky, unoccluded */
    struct environment *environment; /* a reference, may be NULL */
    struct object **objects;   /* a reference each */
    int object_count, object_capacity;
    struct light **lights;     /* a reference each */
    int light_count, light_capacity;
    uint64_t version;          /* bumped when objects/lights are added or removed */
    int next_object_id;
};

void scene_init(struct scene *scene);
/* Drops the scene's references and leaves it empty (safe to call twice). */
void scene_release(struct scene *scene);
/* Adds the object, or a group's parts. */
bool scene_object_add(struct scene *scene, struct object *obj, struct error *err);
bool scene_light_add(struct scene *scene, struct light *light, struct error *err);
void scene_object_remove(struct scene *scene, struct object *obj);
void scene_light_remove(struct scene *scene, struct light *light);
/* Replace the environment or medium (NULL for none), moving the references. */
void scene_set_environment(struct scene *scene, struct environment *env);
void scene_set_medium(struct scene *scene, struct medium *medium);
/* Bounds of every visible object, after its transform (morphs included
 * conservatively). Returns false for an empty scene. */
bool scene_bounds(const struct scene *scene, vec3 *lo, vec3 *hi);
/* Does any visible glass, water or mirror's box reach into the view of
 * `view_proj` (a camera's)? The refraction passes pass their image
 * through when none does. */
bool scene_specular_in_view(const struct scene *scene, mat4 view_proj);
/* Does the object's world box reach into the view of `view_proj`? */
bool object_in_view(const struct object *o, mat4 view_proj);
/* Bounds of the visible objects with one of `roles` (a mask of
 * OBJECT_ROLE_*: OBJECT_ROLE_SPECULAR for glass, water and mirrors,
 * OBJECT_ROLE_REFRACTOR for what the depth layers hold, OBJECT_ROLE_RECEIVER
 * for the diffuse ones): the one role predicate a fit and a drawing both
 * choose objects by (object_is); false (and lo, hi left as they were) when
 * there are none. */
bool scene_role_bounds(const struct scene *scene, unsigned roles, vec3 *lo, vec3 *hi);
/* Position of `light` in scene->lights, or -1 when it was never added. */
int scene_light_index(const struct scene *scene, const struct light *light);
/* Sum of object versions and the scene version: changes when any caster moves. */
uint64_t scene_geometry_version(const struct scene *scene);
/* Changes whenever a light is added, removed or changed (what a pass that
 * caches lit surfaces, such as impostors or the distance map, checks). */
uint64_t scene_lights_version(const struct scene *scene);

#endif
