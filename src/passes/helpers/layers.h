/* Depth layers of the refractors seen from one view (Chaudhari 2008, §3.3-
 * 3.4): per-pixel depth bounds, surface voxelization into bit slices
 * between them, the set bits peeled in order into a layered depth image
 * (up to `layers` per pixel), and per layer the mesh's own normal, exact
 * depth and which refractor it belongs to. Shared by layered_refraction
 * (the camera's view) and layered_caustics (the light's view). Three
 * geometry draws per view: bounds, voxels, attributes. */
#ifndef CAUSTICA_LAYERS_H
#define CAUSTICA_LAYERS_H

#include <stdbool.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "gl/gl_param_block.h"
#include "gl/gl_program.h"
#include "gl/gl_texture.h"
#include "scene/light_view.h"
#include "scene/scene.h"

#define LAYERS_MAX 32        /* depth layers per pixel (the thesis's 32: 8 render targets x 4 channels) */
#define LAYERS_MAX_VOXELS 1024 /* slices per pixel: 8 RGBA32UI words */
#define LAYERS_MAX_SLOTS 64  /* refractive objects one view tells apart */
#define LAYERS_RADIUS_SCALE 1.02f /* a light's view widens the refractors' bounding sphere by 2% */

struct renderer;

/* std430 mirror of LayerMaterial in shaders/layers/layers.glsl */
struct layers_material_gpu {
    float ior, ideal, pad0, pad1;
    float absorption[4];
};

/* The record type a layer set is published as (depth_layers' `layers`,
 * graph/pass.h). */
struct record_type;
extern const struct record_type LAYER_SET_RECORD;

struct layer_set {
    int width, height, voxels, layers;
    bool built;                /* built this frame (false: nothing refracts in its view, read nothing) */
    bool exact_depth;          /* depths from the attribute pass (else the voxels' slice centres) */
    struct gl_texture bounds;  /* rg32f: max depth, max -depth (per-pixel Zmax and -Zmin, §3.3) */
    struct gl_texture bits;    /* rgba32ui array: voxels / 128 words of slice bits (§3.3) */
    struct gl_texture depth;   /* r32f array [layers]: eye depth of each layer (§3.4.2) */
    struct gl_texture normal;  /* rgba32f array [layers]: world normal, w = refractor slot */
    struct gl_texture info;    /* rg32ui: layers captured, surfaces dropped (more than `layers`) */
    GLuint ranges;             /* ssbo: per layer min and max depth (float bits), then the largest count */
    GLuint materials;          /* ssbo: per slot ior, ideal, absorption */
    struct gl_framebuffer bounds_fb, bits_fb;
    mat4 view, proj, inv_view, inv_proj;
    bool ortho;
    int slots;                 /* refractors in the set */
    struct object *slot_objects[LAYERS_MAX_SLOTS]; /* borrowed */
    int draws;                 /* geometry draws the last build made */
    long triangles;            /* triangles those draws rasterized */
    /* What the producer decided, for its readers to take rather than redo
     * (issue 54): from a light, its slot in the frame's lights (-1: the
     * camera's set), the refractors' box the view was fit to, the view as
     * fit (layers_light_view; its half sides, or half angle, over the
     * buffer are a texel) and the box's bounding radius widened as the fit
     * widens it (LAYERS_RADIUS_SCALE). */
    int light_slot;
    vec3 lo, hi;
    struct light_view light_view;
    float radius;
    /* owned: the uniform block LayerView (layers/layers.glsl) of this set's
     * view, projection, their inverses, size and counts, uploaded once by
     * layers_build and bound by every program that reads the set (issue 54;
     * a pointer, so that a reader holding the set const binds it) */
    struct gl_param_block *view_block;
};

void layers_init(struct layer_set *ls);
void layers_release(struct layer_set *ls);
/* Builds the layers of every visible glass/water object seen through
 * `view` and `proj` at width x height. */
/* `timed` (may be NULL): the pass whose stages (pass_stage_end) this names. */
struct pass;
bool layers_build(struct layer_set *ls, struct renderer *r, const struct scene *scene, mat4 view, mat4 proj,
                  int width, int height, int voxels, int layers, bool exact_depth, struct pass *timed,
                  struct error *err);
/* The settings of shaders/layers/trace.glsl (and scene_trace.glsl). */
struct layers_trace {
    int search;          /* bisection steps per interface */
    int steps;           /* linear steps before them */
    int gradient;        /* 0: mesh normals; d > 0: eq. 3.2's depth gradients with delta d */
    int max_interfaces;  /* the interface cap */
    float layer_extent;  /* the longest a segment inside the layers can be */
};

/* Binds the textures and buffers the tracer reads, and sets its uniforms
 * on `program`; rays leaving the layers are marched at most 1.5 times the
 * scene's bounding diameter, in 64 steps. */
bool layers_bind(const struct layer_set *ls, const struct gl_program *program, const struct scene *scene,
                 const struct layers_trace *trace, struct error *err);
bool layers_is_refractor(const struct object *o);
/* What a pass tracing the light through the layers leaves out of object o
 * (a mirror: the layers hold glass and water only), for pass_desc.leaves_out;
 * NULL when it handles it. */
const char *layers_leaves_out(const struct pass *p, const struct scene *scene, const struct object *o);
/* The slot of the light a reader's light layers were taken from, or -1
 * with an error where they are the camera's (a script may wire those in). */
int layers_light_slot(const struct layer_set *ls, struct error *err);
/* What the scene's refractors are, for a warning: "the glass", "the water"
 * or "the glass and water". */
const char *layers_refractors_named(const struct scene *scene);
/* The uniforms of shaders/layers/scene_trace.glsl (what a leaving ray sees
 * in the camera's image) and of common/scene_bounds.glsl on `program`:
 * marched at most 1.5 times the scene's bounding diameter in 64 steps, and
 * only inside the scene's box. */
void layers_bind_scene_trace(const struct gl_program *program, const struct scene *scene);

/* The layer group: the parameters every pass that builds or reads a layer
 * set takes, defined once (type, default, range, the voxels' multiple of
 * 128: one 32-bit word per RGBA channel, §3.3); each pass gives its own help
 * text, and a reader may keep another default layer count. */
#define LAYERS_PARAM_BUFFER(help_text)                                                                        \
    {.name = "buffer", .type = PASS_PARAM_INTEGER, .default_number = 256, .min = 16, .max = 4096,             \
     .help = help_text}
#define LAYERS_PARAM_LAYERS(default_layers, help_text)                                                        \
    {.name = "layers", .type = PASS_PARAM_INTEGER, .default_number = default_layers, .min = 1,                \
     .max = LAYERS_MAX, .help = help_text}
#define LAYERS_PARAM_VOXELS(help_text)                                                                        \
    {.name = "voxels", .type = PASS_PARAM_INTEGER, .default_number = 256, .min = 128, .max = LAYERS_MAX_VOXELS, \
     .multiple = 128, .help = help_text}
#define LAYERS_PARAM_DEPTHS(help_text)                                                                        \
    {.name = "depths", .type = PASS_PARAM_ENUM, .default_string = "exact", .choices = "exact|voxel",          \
     .help = help_text}
#define LAYERS_PARAM_SEARCH(help_text)                                                                        \
    {.name = "search", .type = PASS_PARAM_INTEGER, .default_number = 5, .min = 0, .max = 16, .help = help_text}
#define LAYERS_PARAM_STEPS(help_text)                                                                         \
    {.name = "steps", .type = PASS_PARAM_INTEGER, .default_number = 8, .min = 1, .max = 64, .help = help_text}

struct frame_light;
/* The depth_layers block a reader of `light`'s layers asks the graph for
 * (its configure_block): this light, buffer x buffer texels, `layers`
 * layers of `voxels` slices. */
struct light;
bool layers_configure_block(struct pass *block, struct light *light, int buffer, int layers, int voxels,
                            struct error *err);
/* The camera's depth_layers block (layered_refraction's): the frame's size,
 * `layers` layers of `voxels` slices, exact depths or the slices' own. */
bool layers_configure_camera_block(struct pass *block, int layers, int voxels, bool exact_depth, struct error *err);
/* A light's view of the refractors' box (lo, hi), through its bounding
 * sphere widened by 2% (light_view_fit with the layers' margins):
 * orthographic along a directional light, narrowed to the box's outline
 * (half_width x half_height, not square), else a perspective frustum from
 * the light's position just wide enough; an error naming `pass_name` when
 * the light is inside the sphere. Shared by depth_layers, layered_caustics
 * and beam_caustics. */
bool layers_light_view(const struct frame_light *fl, vec3 lo, vec3 hi, struct light_view *v, const char *pass_name,
                       struct error *err);

#endif
