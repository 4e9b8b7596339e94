/* What every pass shares: the shader programs, the per-frame uniform block
 * (camera, time, lights at BINDING_FRAME), the environment at UNIT_ENVIRONMENT,
 * drawing the scene's objects, and presenting (tone mapping) the result. */
#ifndef CAUSTICA_RENDERER_H
#define CAUSTICA_RENDERER_H

#include <stdbool.h>
#include <stdint.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "gl/gl_program.h"
#include "gl/gl_texture.h"
#include "graph/frame.h"
#include "graph/mesh_cache.h"
#include "graph/texture_cache.h"
#include "io/image.h"
#include "scene/scene.h"


/* std140 mirror of `Frame` in shaders/common/frame.glsl. */
struct renderer_gpu_light {
    float position[4];  /* xyz, w = kind (0 point, 1 directional, 2 spot) */
    float direction[4]; /* xyz, w = cos(outer angle) */
    float intensity[4]; /* rgb, w = cos(inner angle) */
};

struct renderer_frame_uniforms {
    float view[16], proj[16], view_proj[16], inv_view_proj[16];
    float camera_pos[4]; /* xyz, w = time */
    float viewport[4];   /* width, height, 1/width, 1/height */
    float background[4]; /* rgb, w = 1 when an environment map is bound */
    float ambient[4];
    int32_t counts[4];   /* x = lights, y = frame */
    struct renderer_gpu_light lights[SCENE_MAX_GPU_LIGHTS];
};

enum tonemap_operator { TONEMAP_CLAMP, TONEMAP_REINHARD, TONEMAP_ACES };

struct renderer {
    char root[1024]; /* the project folder holding shaders/ and lua/ */
    struct gl_program_cache programs;
    GLuint frame_ubo;
    GLuint empty_vao;
    struct gl_texture dummy_2d, dummy_cube, dummy_depth;
    struct gl_texture brdf_table; /* core/brdf.c's ambient table, uploaded when a glTF surface is first drawn */
    struct renderer_frame_uniforms uniforms; /* uploaded from `frame` */
    struct frame frame;                      /* this frame's snapshot (graph/frame.h) */
    /* presenting */
    struct gl_texture present_texture;
    struct gl_framebuffer present_fb;
    GLuint deform_queries[2];
    double deform_ms; /* GPU time of the last frame's morphs and deformers */
    struct mesh_cache meshes; /* the GPU copies of meshes and objects */
    struct texture_cache textures; /* the GPU copies of material textures */
    long draw_calls, draw_triangles; /* objects drawn by renderer_draw_objects, ever (passes take differences) */
    struct gl_texture environment; /* the cube map of the scene's environment ... */
    uint64_t environment_serial;   /* ... of this serial (0: none uploaded) */
    struct gl_texture medium_density; /* the scene's medium's density grid (graph/medium_gpu.c) ... */
    const struct medium *medium_uploaded; /* ... of this medium ... */
    uint64_t medium_version;              /* ... at this version */
};

bool renderer_create(struct renderer *r, const char *root, struct error *err);
void renderer_destroy(struct renderer *r);
/* Builds the frame snapshot, uploads what the scene needs, runs morphs and
 * deformers, fills the frame uniforms from the snapshot. Call once per
 * frame before graph_execute. */
bool renderer_begin_frame(struct renderer *r, struct scene *scene, int width, int height, int frame, double time,
                          struct error *err);
/* Back to a known GL state between passes. */
void renderer_reset_state(struct renderer *r);

enum renderer_draw_filter {
    DRAW_ALL = 0,
    DRAW_CASTERS = 1,   /* objects that cast shadows */
    DRAW_DIFFUSE = 2,   /* diffuse materials only */
    DRAW_SPECULAR = 4,  /* glass, water, mirror only */
    DRAW_OPAQUE = 8,    /* not the alpha-blended surfaces (material.alpha_blend) */
    DRAW_BLENDED = 16,  /* the alpha-blended surfaces only, the farthest from the eye first */
    DRAW_LAMBERT = 32,  /* not the surfaces drawn by glTF's BRDF (material.pbr) */
    DRAW_PBR = 64,      /* those surfaces only */
    DRAW_THIN = 128,    /* thin-walled glass only, the farthest from the eye first (every filter but
                         * DRAW_ALL leaves it out otherwise) */
};
/* A lighting program and its glTF-BRDF variant (compiled with GLTF_BRDF
 * defined, common/surface_light.glsl): progs[0] always, progs[1] only
 * where a visible diffuse surface of the scene is drawn by glTF's BRDF
 * (else NULL). Two programs, not a branch on a uniform: llvmpipe runs both
 * sides of a branch, which cost the Lambert surfaces 11% of a frame when
 * the BRDF's was one program with theirs. */
bool renderer_lit_programs(struct renderer *r, const struct scene *scene, const char *vert, const char *frag,
                           const char *defines, struct gl_program *progs[2], struct error *err);
/* renderer_draw_objects for a lighting pass: the surfaces drawn by glTF's
 * BRDF with `pbr` (renderer_lit_programs' variant; NULL: none in the
 * scene), the rest with `plain`. */
void renderer_draw_lit(struct renderer *r, const struct scene *scene, const struct gl_program *plain,
                       const struct gl_program *pbr, unsigned filter);
/* Draws the visible objects with `program`, setting u_model,
 * u_normal_matrix, u_object_role, u_color, u_ior, u_absorption,
 * u_object_id. */
void renderer_draw_objects(struct renderer *r, const struct scene *scene, const struct gl_program *program,
                           unsigned filter);
/* The same for one object, whatever its material. */
void renderer_draw_object(struct renderer *r, const struct scene *scene, const struct gl_program *program,
                          struct object *object);
void renderer_draw_fullscreen(struct renderer *r);
/* The first surface of every visible object (glass, water and mirrors
 * too) at the frame's camera, for an EXR: R 1 where a surface covers the
 * pixel and 0 where only the background or environment shows (its alpha),
 * G the distance along the view axis (+inf where none: its Z), B the
 * object's id + 1 (0 none: its objectId). `out` is made here, rows top to
 * bottom. */
bool renderer_first_surface(struct renderer *r, const struct scene *scene, int width, int height, struct image *out,
                            struct error *err);
/* `texture` copied over the whole of `framebuffer` (its colour attachments
 * as set), depth test off: a pass that passes its input through. */
bool renderer_draw_copy(struct renderer *r, GLuint framebuffer, int width, int height, GLuint texture,
                        struct error *err);

/* A user fragment shader over the whole of `fb` (its targets attached):
 * inputs on texture units 0.. with their samplers set, uniforms by name
 * (1 to 4 floats), u_time. What c.pass.fullscreen and a custom pass's
 * ctx:fullscreen both draw with. */
#define RENDERER_MAX_SHADER_INPUTS 16
struct renderer_shader_input {
    const char *sampler;
    GLuint texture;
};
struct renderer_shader_uniform {
    const char *name;
    int size;
    float value[4];
};
void renderer_run_fullscreen(struct renderer *r, const struct gl_program *program, GLuint framebuffer, int width,
                             int height, const struct renderer_shader_input *inputs, int input_count,
                             const struct renderer_shader_uniform *uniforms, int uniform_count, double time);
/* First GPU light slot of `light` (an area light fills several), or -1 when
 * it is not in the scene or past SCENE_MAX_GPU_LIGHTS. */
int renderer_light_slot(const struct renderer *r, const struct scene *scene, const struct light *light);

/* Tone maps a linear texture into 8-bit sRGB and reads it back (rows top to bottom). */
bool renderer_present_bytes(struct renderer *r, const struct gl_texture *linear, float exposure,
                            enum tonemap_operator op, uint8_t *rgba, struct error *err);
/* Tone maps into the window's framebuffer (size fb_width x fb_height). */
bool renderer_present_window(struct renderer *r, const struct gl_texture *linear, float exposure,
                             enum tonemap_operator op, int fb_width, int fb_height,
                             struct error *err);
bool tonemap_parse(const char *name, enum tonemap_operator *out);

/* graph/deform.c: morphs and deformers into each object's buffers. */
bool deform_update(struct renderer *r, struct scene *scene, double time, struct error *err);

#endif
