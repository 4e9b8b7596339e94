/* beam_caustics: Liktor & Dachsbacher, "Real-Time Volume Caustics with
 * Adaptive Beam Tracing" (I3D 2011). Light focused by glass or water into
 * a participating medium (volume caustics) and onto surfaces (surface
 * caustics), from beams of light rather than photons:
 *   1. the light's view of the specular surfaces (§4.1: here the depth
 *      layers of passes/helpers/layers.c, so each edge ray is traced through every
 *      interface, with total internal reflection: §6's two-sided
 *      refraction and more);
 *   2. the edge rays of the finest lattice of a projected grid, traced
 *      once (shaders/beam_caustics/trace.comp), with their extrusion
 *      lengths against a distance impostor of the receivers (§4.3, §6);
 *   3. the hierarchical projected grid (§4.2): `grid` x `grid` cells
 *      refined `refine` times by the split oracle in compute shaders with
 *      an append buffer and indirect dispatches (refine.comp);
 *   4. the beams and their bounding volumes (§4.3, build.comp): beam
 *      space, the area function, six-triangle tight volumes or prisms;
 *   5. the volumes rasterized (§5, volume.vert/frag): inscattered radiance
 *      (`inscatter`, for volume_light's `add`) and surface caustics
 *      (`irradiance`, low-pass filtered, for shade's `caustics`).
 * Nothing is precomputed; the light, the refractors and the medium may move.
 * `--timings` prints the stages and a line with the beams, the prisms and
 * the fragments the volumes rasterized (the paper's fill rate, §4.3). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/log.h"
#include "gl/gl_api.h"
#include "gl/gl_buffer.h"
#include "gl/gl_param_block.h"
#include "graph/frame.h"
#include "graph/medium_gpu.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "graph/temporal.h"
#include "passes/blocks/distance_map.h"
#include "passes/helpers/caustic_coverage.h"
#include "passes/helpers/layers.h"
#include "passes/helpers/shadow_inputs.h"

#define BEAMS_MAX_LATTICE 512     /* grid x 2^(refine + edges): the finest lattice's cells per side */
#define BEAMS_MAX_BEAMS (1 << 18)  /* beams one frame may build (64 MB); more are dropped and reported */
#define BEAMS_VERTEX_BYTES 144    /* struct BeamVertex in shaders/beam_caustics/beams.glsl: 9 vec4 */
#define BEAMS_BEAM_BYTES 272      /* struct Beam: 17 vec4 */
#define BEAMS_ADJACENCY_STRIDE 16 /* uints per lattice vertex in the adjacency lists (beams.glsl) */
#define BEAMS_DISTANCE_SIZE 256   /* the distance impostor's faces */
/* Counter offsets of beams.glsl (uint index). */
enum {
    COUNT_DISPATCH = 0, COUNT_IN = 3, COUNT_NEXT = 4, COUNT_KEPT = 5, COUNT_BEAMS = 6,
    COUNT_DRAW = 8, COUNT_BUILD = 12, COUNT_OVERFLOW = 15, COUNT_PRISMS = 16, COUNT_WHOLE = 17, COUNT_PARTED = 18,
    COUNT_SIZE = 20
};

/* The C mirror of BeamParams (shaders/beam_caustics/beams.glsl, std140):
 * the pass's values for one frame, every stage's, uploaded in one call
 * (issue 54: 34 look-ups by name and calls a frame before). */
struct beam_params {
    float light_origin[4];    /* xyz: a point light's position; w = 1: a directional light */
    float distance_center[3]; /* the receivers' distance impostor's centre */
    float distance_range;     /* the longest an edge ray is traced */
    float jitter[2];          /* the lattice's offset this frame (issue 32) */
    int32_t lattice, refine, capacity, beam_capacity, kept_offset;
    int32_t light, light_ortho, free_levels, reflection, volumes, samples, surface, smooth;
    float focus, pixels, normal_cos, depth_jump, cutoff, max_focus;
    int32_t pad[3];
};

#define BEAM_PARAM(field, name) {name, offsetof(struct beam_params, field)}
static const struct gl_block_member beam_params_members[] = {
    BEAM_PARAM(light_origin, "u_light_origin"), BEAM_PARAM(distance_center, "u_distance_center"),
    BEAM_PARAM(distance_range, "u_distance_range"), BEAM_PARAM(jitter, "u_jitter"),
    BEAM_PARAM(lattice, "u_lattice"), BEAM_PARAM(refine, "u_refine"), BEAM_PARAM(capacity, "u_capacity"),
    BEAM_PARAM(beam_capacity, "u_beam_capacity"), BEAM_PARAM(kept_offset, "u_kept_offset"),
    BEAM_PARAM(light, "u_light"), BEAM_PARAM(light_ortho, "u_light_ortho"), BEAM_PARAM(free_levels, "u_free"),
    BEAM_PARAM(reflection, "u_reflection"), BEAM_PARAM(volumes, "u_volumes"), BEAM_PARAM(samples, "u_samples"),
    BEAM_PARAM(surface, "u_surface"), BEAM_PARAM(smooth, "u_smooth"), BEAM_PARAM(focus, "u_focus"),
    BEAM_PARAM(pixels, "u_pixels"), BEAM_PARAM(normal_cos, "u_normal_cos"), BEAM_PARAM(depth_jump, "u_depth_jump"),
    BEAM_PARAM(cutoff, "u_cutoff"), BEAM_PARAM(max_focus, "u_max_focus"),
};
#undef BEAM_PARAM

struct beam_caustics_state {
    const struct layer_set *layers; /* this frame's, the depth_layers block's */
    struct gl_param_block params;   /* BeamParams, this frame's values */
    GLuint vertices, cells, beams, counters, adjacency;
    int lattice, grid, refine, reflection; /* what the buffers were made for */
    int cell_capacity, beam_capacity;
    const struct distance_map *distance; /* the receivers' distance impostor (the distance_map block's, this frame) */
    GLuint receiver_normal, receiver_depth; /* this frame's, the receivers block's */
    struct gl_texture irradiance_raw, irradiance_half;
    struct gl_framebuffer volumes_fb, blur_fb;
    GLuint fragments_query; /* GL_SAMPLES_PASSED around the volumes' draw: the fill rate */
    int width, height;
    /* accumulate > 1 (issue 32): the last frames' surface caustics and
     * inscattered light, the lattice's jitter this frame, and the light
     * and geometry the last frame was built from */
    struct temporal_history irradiance_history, inscatter_history;
    struct caustic_coverage coverage; /* what it left dark under glass, measured once */
    float jitter[2];
    uint64_t key;
    bool valid;
};

enum beam_caustics_param {
    BC_LIGHT,
    BC_GRID,
    BC_REFINE,
    BC_EDGES,
    BC_BUFFER,
    BC_LAYERS,
    BC_VOXELS,
    BC_REFLECTION,
    BC_VOLUMES,
    BC_FOCUS,
    BC_PIXELS,
    BC_CUTOFF,
    BC_MAX_FOCUS,
    BC_SAMPLES,
    BC_SURFACE,
    BC_SMOOTH,
    BC_BLUR,
    BC_RECEIVERS,
    BC_RECEIVER_DEPTH,
    BC_LIGHT_LAYERS,
    BC_ACCUMULATE,
    BC_SHADOW,
    BC_DISTANCE_MAP,
};

static const struct pass_param_desc params[] = {
    [BC_LIGHT] = {.name = "light", .type = PASS_PARAM_LIGHT, .required = true,
     .help = "the light (directional, point or spot; a linear light is traced from its midpoint)"},
    [BC_GRID] = {.name = "grid", .type = PASS_PARAM_INTEGER, .default_number = 16, .min = 1, .max = BEAMS_MAX_LATTICE,
     .help = "cells per side of the coarse projected grid in the light's view (§4.1), which spans the refractors' "
             "outline: a cell is that width / (grid x 2^refine) on them. One value cannot serve every scene: waves "
             "want cells under a quarter of their length (grid >= 4 x the water's width / (wavelength x 2^refine); "
             "16 over water 6 wide with waves 1 long left ripples 0.25 off, docs/OPTICS_MATRIX.md)"},
    [BC_REFINE] = {.name = "refine", .type = PASS_PARAM_INTEGER, .default_number = 1, .min = 0, .max = 8,
     .help = "adaptive refinement steps (§4.2) on every criterion of the split oracle"},
    [BC_EDGES] = {.name = "edges", .type = PASS_PARAM_INTEGER, .default_number = 0, .min = 0, .max = 6,
     .help = "further refinement at silhouettes only (the glass's, or between paths through different "
             "interfaces); grid x 2^(refine + edges) is at most 512"},
    [BC_BUFFER] = LAYERS_PARAM_BUFFER("the light's view of the specular surfaces, buffer x buffer texels (the G-buffer of §4.1)"),
    [BC_LAYERS] = LAYERS_PARAM_LAYERS(8, "depth layers per texel of the light's view (interfaces an edge ray can cross)"),
    [BC_VOXELS] = LAYERS_PARAM_VOXELS("slices per texel of the light's view, a multiple of 128"),
    [BC_REFLECTION] = {.name = "reflection", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "beams reflected off the first interface too (§6)"},
    [BC_VOLUMES] = {.name = "volumes", .type = PASS_PARAM_ENUM, .default_string = "tight", .choices = "tight|prism",
     .help = "bounding volumes: the paper's six triangles (falling back to the prism where a side is ambiguous) "
             "or Ernst et al.'s prism always (§4.3, Figs. 5-6)"},
    [BC_FOCUS] = {.name = "focus", .type = PASS_PARAM_NUMBER, .default_number = 0.25, .min = 0, .max = 1,
     .help = "split a beam whose cross-section shrinks below this fraction of its base (convergent first, §4.2)"},
    [BC_PIXELS] = {.name = "pixels", .type = PASS_PARAM_NUMBER, .default_number = 24, .min = 1, .max = 1e6,
     .help = "split a beam wider than this many pixels where its central ray passes nearest the camera (§4.2)"},
    [BC_CUTOFF] = {.name = "cutoff", .type = PASS_PARAM_NUMBER, .default_number = 0.01, .min = 0, .max = 1,
     .help = "a beam ends where, diverging, its flux density falls below this fraction of its base's or of "
             "the light's own, whichever is less (§4.3; a beam past a focus too; 0: at the receivers)"},
    [BC_MAX_FOCUS] = {.name = "max_focus", .type = PASS_PARAM_NUMBER, .default_number = 1000, .min = 1, .max = 1e9,
     .help = "the bound on a focus: a beam's flux density is at most this many times its density at its "
             "wider end (A(y) -> 0 stays finite)"},
    [BC_SAMPLES] = {.name = "samples", .type = PASS_PARAM_INTEGER, .default_number = 0, .min = 0, .max = 64,
     .help = "samples along a view ray's interval in a beam (0: the paper's one midpoint in a homogeneous medium, "
             "4 in a density grid)"},
    [BC_SURFACE] = {.name = "surface", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "surface caustics from the same beams (§5.3)"},
    [BC_SMOOTH] = {.name = "smooth", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "surface caustics from a flux density per edge ray, averaged over the beams that share it (Ernst et "
             "al. 2005; the lattice keeps the adjacency), continuous across beams; false: one per beam (§7)"},
    [BC_BLUR] = {.name = "blur", .type = PASS_PARAM_NUMBER, .default_number = 1.0, .min = 0, .max = 32,
     .help = "the surface caustics' low-pass filter: a Gaussian of this many pixels (0: none; it hides the cracks "
             "where beams of different levels meet, and blurs a sharp caustic: docs/techniques/liktor_dachsbacher.md)"},
    [BC_RECEIVERS] = {.name = "receivers", .type = PASS_PARAM_INPUT, .block = "receivers", .default_output = "normal",
     .help = "the camera's receivers (a receivers pass's normal): by default the graph adds one, shared with the other "
             "caustics passes"},
    [BC_RECEIVER_DEPTH] = {.name = "receiver_depth", .type = PASS_PARAM_INPUT, .default_beside = "receivers",
     .default_output = "depth", .help = "their depth, which clips the beams (by default beside `receivers`)"},
    [BC_LIGHT_LAYERS] = {.name = "light_layers", .type = PASS_PARAM_INPUT, .block = "depth_layers", .bundle = &LAYER_SET_RECORD,
     .default_output = "layers",
     .help = "the light's depth layers (a depth_layers pass's `layers`): by default the graph adds one for `light` at "
             "`buffer`, `layers` and `voxels`, shared with layered_caustics for the same light"},
    [BC_ACCUMULATE] = {.name = "accumulate", .type = PASS_PARAM_INTEGER, .default_number = 1, .min = 1, .max = 64,
     .help = "temporal accumulation while the light and the geometry stand still: the projected grid moves by a "
             "sub-cell jitter every frame and the surface caustics and inscattered light (where a receiver lies behind "
             "it) average the last this many frames; while they move, every frame stands alone; 1: none "
             "(docs/TEMPORAL.md)"},
    [BC_SHADOW] = SHADOW_PARAM_PANES("a beam"),
    [BC_DISTANCE_MAP] = {.name = "distance_map", .type = PASS_PARAM_INPUT, .block = "distance_map",
     .bundle = &DISTANCE_MAP_RECORD, .default_output = "map",
     .help = "the receivers' distance impostor the beams' exits are traced against (a distance_map pass's `map`, "
             "content = \"distances\", around = \"refractors\"): by default the graph adds one of 256 texels a face"},
};

static bool beam_caustics_declare(struct pass *p, struct error *err)
{
    int lattice = pass_int(p, BC_GRID) << (pass_int(p, BC_REFINE) + pass_int(p, BC_EDGES));
    if (lattice > BEAMS_MAX_LATTICE)
        return error_set(err, "bad argument 'refine' to 'beam_caustics' (grid x 2^(refine + edges) = %d is more "
                              "than %d: use fewer refinement steps, fewer edge steps or a coarser grid)",
                         lattice, BEAMS_MAX_LATTICE);
    return pass_declare_output(p, "inscatter", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err) &&
           pass_declare_output(p, "irradiance", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool beam_caustics_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct beam_caustics_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("BeamParams", beam_params_members, struct beam_params);
    p->state = s;
    gl.GenQueries(1, &s->fragments_query);
    return gl_framebuffer_create(&s->volumes_fb, err) &&
           gl_framebuffer_create(&s->blur_fb, err);
}

static void release_buffers(struct beam_caustics_state *s)
{
    gl_buffer_destroy(&s->vertices);
    gl_buffer_destroy(&s->cells);
    gl_buffer_destroy(&s->beams);
    gl_buffer_destroy(&s->counters);
    gl_buffer_destroy(&s->adjacency);
    s->lattice = 0;
}

static void release_targets(struct beam_caustics_state *s)
{
    gl_texture_destroy(&s->irradiance_raw);
    gl_texture_destroy(&s->irradiance_half);
    s->width = s->height = 0;
}

static void beam_caustics_destroy(struct pass *p)
{
    struct beam_caustics_state *s = p->state;
    if (!s)
        return;
    release_buffers(s);
    release_targets(s);
    caustic_coverage_release(&s->coverage);
    gl_param_block_release(&s->params);
    temporal_release(&s->irradiance_history);
    temporal_release(&s->inscatter_history);
    gl_framebuffer_destroy(&s->volumes_fb);
    gl_framebuffer_destroy(&s->blur_fb);
    if (s->fragments_query && gl_api_ready())
        gl.DeleteQueries(1, &s->fragments_query);
    free(s);
    p->state = NULL;
}

static enum pass_need beam_caustics_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    (void)p;
    bool specular = false;
    for (int i = 0; i < f->scene->object_count; i++)
        if (layers_is_refractor(f->scene->objects[i]))
            specular = true;
    if (!specular)
        snprintf(why, whylen, "no glass or water in the scene: no beams (zero inscatter and irradiance)");
    else if (!medium_gpu_present(f->scene))
        snprintf(why, whylen, "no participating medium (scene.medium): surface caustics only, zero inscatter");
    return PASS_RUN;
}

static bool ensure_buffers(struct beam_caustics_state *s, int grid, int refine, bool reflection, struct error *err)
{
    int lattice = grid << refine;
    if (s->vertices && s->lattice == lattice && s->grid == grid && s->refine == refine &&
        s->reflection == (int)reflection)
        return true;
    release_buffers(s);
    s->cell_capacity = lattice * lattice;
    s->beam_capacity = 2 * s->cell_capacity * (reflection ? 2 : 1);
    if (s->beam_capacity > BEAMS_MAX_BEAMS)
        s->beam_capacity = BEAMS_MAX_BEAMS;
    size_t vertices = (size_t)(lattice + 1) * (size_t)(lattice + 1);
    if (!gl_buffer_create(&s->vertices, NULL, vertices * BEAMS_VERTEX_BYTES, 0, err) ||
        !gl_buffer_create(&s->cells, NULL, ((size_t)s->cell_capacity * 3 + (size_t)grid * (size_t)grid) * sizeof(GLuint),
                          GL_DYNAMIC_STORAGE_BIT, err) ||
        !gl_buffer_create(&s->beams, NULL, (size_t)s->beam_capacity * BEAMS_BEAM_BYTES, 0, err) ||
        !gl_buffer_create(&s->counters, NULL, COUNT_SIZE * sizeof(GLuint), GL_DYNAMIC_STORAGE_BIT, err) ||
        !gl_buffer_create(&s->adjacency, NULL, vertices * BEAMS_ADJACENCY_STRIDE * sizeof(GLuint), 0, err))
        return false;
    /* the coarse grid's cells, after the two level lists and the kept list:
     * level 0 reads them, so they are written once */
    GLuint *level0 = malloc((size_t)grid * (size_t)grid * sizeof *level0);
    if (!level0)
        return error_set(err, "out of memory");
    for (int y = 0; y < grid; y++)
        for (int x = 0; x < grid; x++)
            level0[y * grid + x] = ((GLuint)x << 14) | (GLuint)y;
    gl.NamedBufferSubData(s->cells, (GLintptr)((size_t)s->cell_capacity * 3 * sizeof(GLuint)),
                          (GLsizeiptr)((size_t)grid * (size_t)grid * sizeof *level0), level0);
    free(level0);
    s->lattice = lattice;
    s->grid = grid;
    s->refine = refine;
    s->reflection = reflection;
    return true;
}

static bool ensure_targets(struct beam_caustics_state *s, int w, int h, struct error *err)
{
    if (s->irradiance_raw.id && s->width == w && s->height == h)
        return true;
    release_targets(s);
    if (!gl_texture_create(&s->irradiance_raw, GL_TEXTURE_2D, GL_RGBA32F, w, h, 1, err) ||
        !gl_texture_create(&s->irradiance_half, GL_TEXTURE_2D, GL_RGBA32F, w, h, 1, err))
        return false;
    s->width = w;
    s->height = h;
    return true;
}

/* Every program of the folder includes beams.glsl; each binds the buffers
 * it uses (a program's unused block has no binding). */
static void bind_beam_buffers(const struct gl_program *prog, const struct beam_caustics_state *s)
{
    gl_program_bind_storage(prog, "BeamVertices", s->vertices);
    gl_program_bind_storage(prog, "BeamCells", s->cells);
    gl_program_bind_storage(prog, "Beams", s->beams);
    gl_program_bind_storage(prog, "BeamCounters", s->counters);
    gl_program_bind_storage(prog, "BeamAdjacency", s->adjacency);
}

static bool run_advance(struct renderer *r, struct beam_caustics_state *s, int mode, struct error *err)
{
    struct gl_program *prog;
    if (!gl_program_get_compute(&r->programs, "beam_caustics/advance.comp", NULL, NULL, &prog, err))
        return false;
    gl.UseProgram(prog->id);
    bind_beam_buffers(prog, s);
    if (!gl_param_block_bind(&s->params, prog, err))
        return false;
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_mode"), mode);
    gl_program_dispatch(prog, 1, 1, 1, GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    return true;
}

/* Stages 2-4: edge rays, the adaptive grid, the beams. */
static bool build_beams(struct pass *p, struct pass_frame *f, float extent, struct error *err)
{
    struct beam_caustics_state *s = p->state;
    struct renderer *r = f->renderer;
    /* the edge rays of the finest lattice */
    struct gl_program *trace;
    if (!gl_program_get_compute(&r->programs, "beam_caustics/trace.comp", NULL, NULL, &trace, err))
        return false;
    gl.UseProgram(trace->id);
    struct layers_trace settings = {.search = 5, .steps = 8, .max_interfaces = 2 * s->layers->layers + 2,
                                    .layer_extent = extent};
    if (!layers_bind(s->layers, trace, f->scene, &settings, err))
        return false;
    bind_beam_buffers(trace, s);
    if (!gl_param_block_bind(&s->params, trace, err))
        return false;
    shadow_inputs_bind(p, f, trace); /* the panes between the light and the glass (its pane filter) */
    gl_program_bind_texture(trace, "u_distance", s->distance->distance[0].id);
    if (!medium_gpu_bind(r, f->scene, trace, err))
        return false;
    /* one edge ray per vertex of the finest lattice */
    gl_program_dispatch(trace, s->lattice + 1, s->lattice + 1, 1, GL_SHADER_STORAGE_BARRIER_BIT);
    pass_stage_end(p, "rays");

    /* the coarse grid, then `refine` levels of the oracle */
    int ncells = s->grid * s->grid;
    GLuint counters[COUNT_SIZE] = {0};
    counters[COUNT_DISPATCH] = (GLuint)((ncells + 63) / 64);
    counters[COUNT_DISPATCH + 1] = counters[COUNT_DISPATCH + 2] = 1;
    counters[COUNT_IN] = (GLuint)ncells;
    gl.NamedBufferSubData(s->counters, 0, sizeof counters, counters);
    struct gl_program *refine;
    if (!gl_program_get_compute(&r->programs, "beam_caustics/refine.comp", NULL, NULL, &refine, err))
        return false;
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, s->counters);
    for (int level = 0; level <= s->refine; level++) {
        gl.UseProgram(refine->id);
        bind_beam_buffers(refine, s);
        if (!gl_param_block_bind(&s->params, refine, err))
            return false;
        gl.ProgramUniform1i(refine->id, gl_program_uniform(refine, "u_in_offset"),
                            level == 0 ? 3 * s->cell_capacity : (level % 2) * s->cell_capacity);
        gl.ProgramUniform1i(refine->id, gl_program_uniform(refine, "u_out_offset"),
                            ((level + 1) % 2) * s->cell_capacity);
        gl.DispatchComputeIndirect((GLintptr)(COUNT_DISPATCH * sizeof(GLuint)));
        gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        if (!run_advance(r, s, 0, err))
            return false;
    }
    if (!run_advance(r, s, 1, err))
        return false;
    pass_stage_end(p, "refine");

    /* the beams of the kept cells, and each lattice vertex's list of them */
    const GLuint zero = 0;
    gl.ClearNamedBufferData(s->adjacency, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    struct gl_program *build;
    if (!gl_program_get_compute(&r->programs, "beam_caustics/build.comp", NULL, NULL, &build, err))
        return false;
    gl.UseProgram(build->id);
    bind_beam_buffers(build, s);
    if (!gl_param_block_bind(&s->params, build, err))
        return false;
    gl.DispatchComputeIndirect((GLintptr)(COUNT_BUILD * sizeof(GLuint)));
    gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    if (!run_advance(r, s, 2, err))
        return false;
    pass_stage_end(p, "beams");
    return true;
}

/* Stage 5: the bounding volumes rasterized, then the surface caustics'
 * low-pass filter. */
static bool draw_volumes(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct beam_caustics_state *s = p->state;
    struct renderer *r = f->renderer;
    struct graph_resource *inscatter = pass_frame_output(p, f, "inscatter"),
                          *irradiance = pass_frame_output(p, f, "irradiance");
    const struct gl_texture *targets[2] = {&inscatter->texture, &s->irradiance_raw};
    if (!gl_framebuffer_attach(&s->volumes_fb, targets, NULL, 2, NULL, -1, err))
        return false;
    const float zero[4] = {0, 0, 0, 0};
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->volumes_fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.ClearNamedFramebufferfv(s->volumes_fb.id, GL_COLOR, 0, zero);
    gl.ClearNamedFramebufferfv(s->volumes_fb.id, GL_COLOR, 1, zero);
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "beam_caustics/volume.vert", "beam_caustics/volume.frag", NULL, &prog, err))
        return false;
    gl.UseProgram(prog->id);
    bind_beam_buffers(prog, s);
    if (!gl_param_block_bind(&s->params, prog, err))
        return false;
    gl_program_bind_texture(prog, "u_scene_depth", s->receiver_depth);
    gl_program_bind_texture(prog, "u_scene_normal", s->receiver_normal);
    if (!medium_gpu_bind(r, f->scene, prog, err))
        return false;
    gl.Disable(GL_DEPTH_TEST);
    gl.DepthMask(GL_FALSE);
    gl.Enable(GL_BLEND);
    gl.BlendFunc(GL_ONE, GL_ONE);
    gl.Enable(GL_CULL_FACE);
    gl.CullFace(GL_FRONT); /* the volumes' back faces: one fragment per pixel and beam, the eye inside or not */
    gl.BindVertexArray(r->empty_vao);
    gl.BindBuffer(GL_DRAW_INDIRECT_BUFFER, s->counters);
    gl.BeginQuery(GL_SAMPLES_PASSED, s->fragments_query);
    gl.DrawArraysIndirect(GL_TRIANGLES, (const void *)(uintptr_t)(COUNT_DRAW * sizeof(GLuint)));
    gl.EndQuery(GL_SAMPLES_PASSED);
    gl.BindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    renderer_reset_state(r);
    pass_stage_end(p, "volumes");

    /* the surface caustics' low-pass filter, separable */
    struct gl_program *blur;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", "beam_caustics/blur.frag", NULL, &blur, err))
        return false;
    gl.UseProgram(blur->id);
    gl.ProgramUniform1f(blur->id, gl_program_uniform(blur, "u_sigma"), (float)pass_real(p, BC_BLUR));
    gl_program_bind_texture(blur, "u_scene_depth", s->receiver_depth);
    gl_program_bind_texture(blur, "u_scene_normal", s->receiver_normal);
    const struct gl_texture *src[2] = {&s->irradiance_raw, &s->irradiance_half};
    const struct gl_texture *dst[2] = {&s->irradiance_half, &irradiance->texture};
    for (int k = 0; k < 2; k++) {
        const struct gl_texture *t[1] = {dst[k]};
        if (!gl_framebuffer_attach(&s->blur_fb, t, NULL, 1, NULL, -1, err))
            return false;
        gl.BindFramebuffer(GL_FRAMEBUFFER, s->blur_fb.id);
        gl_program_bind_texture(blur, "u_image", src[k]->id);
        gl.ProgramUniform2f(blur->id, gl_program_uniform(blur, "u_direction"), k == 0 ? 1.0f : 0.0f,
                            k == 0 ? 0.0f : 1.0f);
        renderer_draw_fullscreen(r);
    }
    pass_stage_end(p, "filter");
    return true;
}

/* Issue 32: this frame's surface caustics and inscattered light blended
 * with the last frames' while the light and the geometry stand still
 * (temporal.h). The inscattered light is kept where a receiver lies behind
 * it (the history is reprojected by the receivers' depth): against the sky
 * a beam is this frame's alone. */
static bool accumulate_outputs(struct pass *p, struct pass_frame *f, int accumulate, bool still,
                               const struct gl_texture *depth, struct error *err)
{
    struct beam_caustics_state *s = p->state;
    int held = 0;
    if (!temporal_accumulate(&s->irradiance_history, f->renderer, f->snapshot,
                             &pass_frame_output(p, f, "irradiance")->texture, depth, NULL, still, accumulate, &held,
                             err) ||
        !temporal_accumulate(&s->inscatter_history, f->renderer, f->snapshot,
                             &pass_frame_output(p, f, "inscatter")->texture, depth, NULL, still, accumulate, NULL, err))
        return false;
    pass_stage_end(p, "accumulate");
    size_t used = strlen(p->report);
    if (used + 8 < sizeof p->report)
        snprintf(p->report + used, sizeof p->report - used, "; accumulated: %s",
                 held == 0 ? "the history starts (the light or the geometry moved)"
                           : "the light and geometry still, frames averaged");
    return true;
}

/* This frame's BeamParams: the light, the lattice, the distance impostor
 * and the pass's parameters, for every stage (one upload). */
static bool upload_params(struct pass *p, struct pass_frame *f, const struct frame_light *fl, bool ortho, int slot,
                          vec3 center, float range, struct error *err)
{
    struct beam_caustics_state *s = p->state;
    int samples = pass_int(p, BC_SAMPLES);
    if (samples == 0)
        samples = f->scene->medium && f->scene->medium->grid ? 4 : 1;
    const struct beam_params values = {
        .light_origin = {fl->position.x, fl->position.y, fl->position.z, ortho ? 1.0f : 0.0f},
        .distance_center = {center.x, center.y, center.z},
        .distance_range = range,
        .jitter = {s->jitter[0], s->jitter[1]}, /* a still scene's lattice moved by this frame's sub-cell offset */
        .lattice = s->lattice,
        .refine = s->refine,
        .capacity = s->cell_capacity,
        .beam_capacity = s->beam_capacity,
        .kept_offset = 2 * s->cell_capacity,
        .light = slot,
        .light_ortho = ortho ? 1 : 0,
        .free_levels = pass_int(p, BC_REFINE),
        .reflection = pass_flag(p, BC_REFLECTION) ? 1 : 0,
        .volumes = pass_choice(p, BC_VOLUMES),
        .samples = samples,
        .surface = pass_flag(p, BC_SURFACE) ? 1 : 0,
        .smooth = pass_flag(p, BC_SMOOTH) ? 1 : 0,
        .focus = (float)pass_real(p, BC_FOCUS),
        .pixels = (float)pass_real(p, BC_PIXELS),
        /* surface discontinuities (§4.2): normals more than 20 degrees
         * apart, or a depth step steeper than 80 degrees across the light's view */
        .normal_cos = cosf(20.0f * (float)MATH_PI / 180.0f),
        .depth_jump = tanf(80.0f * (float)MATH_PI / 180.0f),
        .cutoff = (float)pass_real(p, BC_CUTOFF),
        .max_focus = (float)pass_real(p, BC_MAX_FOCUS),
    };
    return gl_param_block_upload(&s->params, &values, err);
}

static bool beam_caustics_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct beam_caustics_state *s = p->state;
    const float zero[4] = {0, 0, 0, 0};
    gl_texture_clear(&pass_frame_output(p, f, "inscatter")->texture, zero);
    gl_texture_clear(&pass_frame_output(p, f, "irradiance")->texture, zero);
    p->report[0] = '\0';
    /* the building blocks' outputs, made earlier in this frame */
    s->layers = pass_frame_record(p, f, "light_layers", &LAYER_SET_RECORD);
    s->distance = pass_frame_record(p, f, "distance_map", &DISTANCE_MAP_RECORD);
    struct graph_resource *normal = pass_frame_input(p, f, "receivers"), *depth = pass_frame_input(p, f, "receiver_depth");
    if (!s->layers || !normal || !depth)
        return error_set(err, "its light's layers or the receivers were not made this frame");
    if (!s->layers->built)
        return true; /* the layers' light is not in the scene, or nothing refracts: no beams */
    if (!s->distance || !s->distance->built || s->distance->content != DISTANCE_MAP_DISTANCES)
        return error_set(err, "its distance map ('%s') %s", pass_frame_input(p, f, "distance_map")->name,
                         s->distance && s->distance->built ? "holds radiance: the beams' exits need content = "
                                                             "\"distances\""
                                                           : "was not made this frame");
    int slot = layers_light_slot(s->layers, err);
    if (slot < 0)
        return false;
    s->receiver_normal = normal->texture.id;
    s->receiver_depth = depth->texture.id;
    int grid = pass_int(p, BC_GRID), refine = pass_int(p, BC_REFINE);
    if (!ensure_buffers(s, grid, refine + pass_int(p, BC_EDGES), pass_flag(p, BC_REFLECTION), err) ||
        !ensure_targets(s, f->width, f->height, err))
        return false;
    /* the light's view of the refractors as the layers' producer fit it */
    const struct frame_light *fl = &f->snapshot->lights[slot];
    const struct light_view lv = s->layers->light_view;
    float extent = 2.0f * s->layers->radius;
    vec3 center = vec3_scale(vec3_add(s->layers->lo, s->layers->hi), 0.5f);
    /* the distance impostor (the block's, centred as the layers are) reaches past the whole scene */
    float range = s->distance->range;

    /* Accumulating (issue 32), while the light and the geometry stand still:
     * the whole lattice moves by this frame's sub-cell offset, so 16
     * frames' beams interleave into a grid 4 x 4 as fine. While anything
     * moves, each frame stands alone on the unmoved lattice: its beams are
     * not noise to average, and a history clipped after the light lost
     * light at the focus (measured, docs/TEMPORAL.md). */
    int accumulate = pass_int(p, BC_ACCUMULATE);
    uint64_t key = pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY);
    bool still = pass_frame_reusable(f, s->valid, s->key, key);
    s->key = key;
    s->valid = true;
    s->jitter[0] = s->jitter[1] = 0.0f;
    if (accumulate <= 1 || !still) {
        temporal_reset(&s->irradiance_history);
        temporal_reset(&s->inscatter_history);
    } else {
        temporal_jitter(&s->irradiance_history, &s->jitter[0], &s->jitter[1]);
    }
    if (!upload_params(p, f, fl, lv.ortho, slot, center, range, err))
        return false;
    pass_stage_begin(p);
    if (!build_beams(p, f, extent, err) || !draw_volumes(p, f, err))
        return false;

    GLuint counters[COUNT_SIZE];
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!gl_buffer_read(s->counters, counters, sizeof counters, err))
        return false;
    GLuint64 fragments = 0;
    gl.GetQueryObjectui64v(s->fragments_query, GL_QUERY_RESULT, &fragments);
    /* The light of triangles lit at every corner whose paths part (leave
     * by different faces, or one totally reflected inside) makes no beam
     * (§4.2 refines them `edges` levels): said, not dropped in silence.
     * Counted as light-plane area times the corners whose light lands in
     * the camera's view (VERTEX_SEEN), so light bound elsewhere is not
     * called lost. A tilted cube at IOR 2.42 loses 12% of the floor's light
     * against the exact trace at the defaults (the line says 13%); each
     * level of `edges` about halves it. */
    double lit = (double)counters[COUNT_WHOLE] + (double)counters[COUNT_PARTED];
    double parted = lit > 0.0 ? (double)counters[COUNT_PARTED] / lit : 0.0;
    char dropped[160] = "";
    if (parted > 0.05) {
        const char *through = layers_refractors_named(f->scene);
        snprintf(dropped, sizeof dropped, "; %.0f%% of the light through %s dropped where paths part", 100.0 * parted,
                 through);
        static bool warned; /* one line a run: a renderer and its passes are made more than once a run */
        if (!warned)
            log_warn("beam_caustics: %.0f%% of the light through %s that lands in view falls in cells whose corners' "
                     "light leaves by different faces or is totally reflected, and makes no beam; raise `edges` (now "
                     "%d: each level about halves it)",
                     100.0 * parted, through, pass_int(p, BC_EDGES));
        warned = true;
    }
    snprintf(p->report, sizeof p->report, "%u beams (%u prisms) from %u cells, %llu fragments%s%s", counters[COUNT_BEAMS],
             counters[COUNT_PRISMS], counters[COUNT_KEPT], (unsigned long long)fragments,
             counters[COUNT_OVERFLOW] ? " (some dropped: past the buffers' capacity)" : "", dropped);
    if (!gl_check("beam_caustics", err) ||
        !caustic_coverage_check(&s->coverage, p, f, fl,
                                &(struct caustic_coverage_view){.layers = true, .depth = s->layers->depth.id,
                                                                .info = s->layers->info.id, .view = s->layers->view,
                                                                .proj = s->layers->proj},
                                s->receiver_depth, s->receiver_normal,
                                &pass_frame_output(p, f, "irradiance")->texture,
                                "raise `grid` (the lattice's cells) or `edges` (cells refined along the light's "
                                "parting)", err))
        return false;
    return accumulate <= 1 || accumulate_outputs(p, f, accumulate, still, &depth->texture, err);
}

/* The blocks it reads (issue 26): the light's layers at this pass's size
 * (layered_caustics for the same light and size shares them); the
 * receivers as they come; the receivers' distances around the refractors
 * (issue 54: a block, no longer this pass's own). */
static bool beam_caustics_configure_block(const struct pass *p, int param, struct pass *block, struct error *err)
{
    if (param == BC_DISTANCE_MAP)
        return distance_map_configure_block(block, DISTANCE_MAP_DISTANCES, BEAMS_DISTANCE_SIZE, OBJECT_ROLE_REFRACTOR,
                                            p, -1, err);
    if (param != BC_LIGHT_LAYERS)
        return true;
    return layers_configure_block(block, pass_light_at(p, BC_LIGHT), pass_int(p, BC_BUFFER), pass_int(p, BC_LAYERS),
                                  pass_int(p, BC_VOXELS), err);
}

const struct pass_desc beam_caustics_pass = {
    .technique = PASS_TECHNIQUE_CAUSTICS,
    .volume_caustics = true,
    .name = "beam_caustics",
    .leaves_out = layers_leaves_out,
    .configure_block = beam_caustics_configure_block,
    .summary = "Liktor & Dachsbacher 2011: volume and surface caustics from adaptively refined beams of light",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = beam_caustics_declare,
    .create = beam_caustics_create,
    .execute = beam_caustics_execute,
    .needed = beam_caustics_needed,
    .destroy = beam_caustics_destroy,
};
