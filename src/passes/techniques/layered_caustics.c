/* layered_caustics: caustics through every interface (Chaudhari 2008
 * §4.1, Figs. 4.5-4.6). The refractors' depth layers are taken from the
 * light (passes/helpers/layers.c) and each texel of the first layer is a photon
 * traced through all of them like the camera's rays; the photons that
 * leave are traced in the camera's image of the receivers (eye-space
 * photon tracing, Kruger et al. 2006) and splatted with a small
 * normalised kernel into a screen-space flux image (Wyman & Davis 2006),
 * which becomes irradiance for `shade { caustics = ... }`. Nothing is
 * precomputed: the light, the refractors and their shapes may all move. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_buffer.h"
#include "gl/gl_param_block.h"
#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "graph/temporal.h"
#include "passes/helpers/caustic_coverage.h"
#include "passes/helpers/layers.h"
#include "passes/helpers/shadow_inputs.h"

/* The C mirror of LayeredCausticsParams (shaders/layered_caustics/
 * landed.glsl, std140): the frame's values for all three stages, uploaded
 * in one call (issue 54). */
struct layered_caustics_params {
    float jitter[2];
    int32_t buffer_size[2];
    int32_t light, light_ortho;
    float texel_area, texel_tan, fixed_point, pixel_tan, pixel_size, max_radius, stretch_limit;
    int32_t pad[3];
};

#define LC_PARAM(field, name) {name, offsetof(struct layered_caustics_params, field)}
static const struct gl_block_member layered_caustics_params_members[] = {
    LC_PARAM(jitter, "u_jitter"), LC_PARAM(buffer_size, "u_buffer_size"), LC_PARAM(light, "u_light"),
    LC_PARAM(light_ortho, "u_light_ortho"), LC_PARAM(texel_area, "u_texel_area"), LC_PARAM(texel_tan, "u_texel_tan"),
    LC_PARAM(fixed_point, "u_fixed_point"), LC_PARAM(pixel_tan, "u_pixel_tan"), LC_PARAM(pixel_size, "u_pixel_size"),
    LC_PARAM(max_radius, "u_max_radius"), LC_PARAM(stretch_limit, "u_stretch_limit"),
};
#undef LC_PARAM

struct layered_caustics_state {
    struct gl_param_block params; /* LayeredCausticsParams, this frame's */
    struct gl_framebuffer out_fb;
    struct gl_texture flux;
    struct gl_texture hits, photons; /* per photon: where it lands, its flux */
    GLuint landed; /* one count: the light that landed this frame (layered_caustics/landed.glsl) */
    int buffer;
    int width, height;
    /* accumulate > 1 (issue 32): the irradiance of the last frames while
     * the light and the geometry stand still, and what they were the last
     * frame (pass_frame_key) */
    struct temporal_history temporal;
    uint64_t key;
    bool valid;
    struct caustic_coverage coverage; /* what it left dark under glass, measured once */
};

enum layered_caustics_param {
    LC_LIGHT,
    LC_BUFFER,
    LC_LAYERS,
    LC_VOXELS,
    LC_SEARCH,
    LC_STEPS,
    LC_RADIUS,
    LC_RECEIVERS,
    LC_RECEIVER_DEPTH,
    LC_LIGHT_LAYERS,
    LC_ACCUMULATE,
    LC_SHADOW,
};

static const struct pass_param_desc params[] = {
    [LC_LIGHT] = {.name = "light", .type = PASS_PARAM_LIGHT, .required = true,
     .help = "the light (directional, point or spot; a linear light is traced from its midpoint)"},
    [LC_BUFFER] = LAYERS_PARAM_BUFFER("the light's view of the refractors, buffer x buffer photons over their "
                                      "outline: where the camera sees a receiver much smaller than that outline "
                                      "(water 100 wide seen 1 wide), its photons land far apart and each covers "
                                      "many pixels (exact on smooth light, blurred on sharp); raise it by the ratio "
                                      "to keep them a pixel or two apart"),
    [LC_LAYERS] = LAYERS_PARAM_LAYERS(8, "depth layers per photon texel"),
    [LC_VOXELS] = LAYERS_PARAM_VOXELS("slices per texel, a multiple of 128"),
    [LC_SEARCH] = LAYERS_PARAM_SEARCH("bisection steps per interface"),
    [LC_STEPS] = LAYERS_PARAM_STEPS("linear steps along a photon before the bisection"),
    [LC_RADIUS] = {.name = "radius", .type = PASS_PARAM_NUMBER, .default_number = 4, .min = 0.5, .max = 32,
     .help = "each photon is spread over its footprint from its neighbours' landing points (a second-order ray differential), at most 2 x radius pixels along a side unless its neighbours on both sides say the light is spread smoothly (then up to the image's width)"},
    [LC_RECEIVERS] = {.name = "receivers", .type = PASS_PARAM_INPUT, .block = "receivers", .default_output = "normal",
     .help = "the camera's receivers (a receivers pass's normal), where the photons land: by default the graph adds "
             "one, shared with the other caustics passes"},
    [LC_RECEIVER_DEPTH] = {.name = "receiver_depth", .type = PASS_PARAM_INPUT, .default_beside = "receivers",
     .default_output = "depth", .help = "their depth (by default beside `receivers`)"},
    [LC_LIGHT_LAYERS] = {.name = "light_layers", .type = PASS_PARAM_INPUT, .block = "depth_layers", .bundle = &LAYER_SET_RECORD,
     .default_output = "layers",
     .help = "the light's depth layers (a depth_layers pass's `layers`): by default the graph adds one for `light` at "
             "`buffer`, `layers` and `voxels`, shared with beam_caustics for the same light"},
    [LC_ACCUMULATE] = {.name = "accumulate", .type = PASS_PARAM_INTEGER, .default_number = 1, .min = 1, .max = 64,
     .help = "temporal accumulation while the light and the geometry stand still: each photon starts at a sub-texel "
             "jitter within its light texel, a new one every frame, and the irradiance averages the last this many "
             "frames; while they move, every frame stands alone; 1: none (docs/TEMPORAL.md)"},
    [LC_SHADOW] = SHADOW_PARAM_PANES("a photon"),
};

static bool layered_caustics_declare(struct pass *p, struct error *err)
{
    return pass_declare_output(p, "irradiance", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool layered_caustics_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct layered_caustics_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("LayeredCausticsParams",
                                  layered_caustics_params_members, struct layered_caustics_params);
    p->state = s;
    return gl_framebuffer_create(&s->out_fb, err);
}

static void release_targets(struct layered_caustics_state *s)
{
    gl_texture_destroy(&s->flux);
    gl_texture_destroy(&s->hits);
    gl_texture_destroy(&s->photons);
    gl_buffer_destroy(&s->landed);
}

static void layered_caustics_destroy(struct pass *p)
{
    struct layered_caustics_state *s = p->state;
    if (!s)
        return;
    release_targets(s);
    temporal_release(&s->temporal);
    gl_framebuffer_destroy(&s->out_fb);
    caustic_coverage_release(&s->coverage);
    gl_param_block_release(&s->params);
    free(s);
    p->state = NULL;
}

static enum pass_need layered_caustics_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    (void)p;
    for (int i = 0; i < f->scene->object_count; i++)
        if (layers_is_refractor(f->scene->objects[i]))
            return PASS_RUN;
    snprintf(why, whylen, "no glass or water in the scene: no caustics (zero irradiance)");
    return PASS_RUN;
}

static bool ensure_targets(struct layered_caustics_state *s, int w, int h, int buffer, struct error *err)
{
    if (s->flux.id && s->width == w && s->height == h && s->buffer == buffer)
        return true;
    release_targets(s);
    s->width = w;
    s->height = h;
    s->buffer = buffer;
    /* layer 0: photons through the object; 1: reflected off its first interface */
    if (!gl_texture_create(&s->hits, GL_TEXTURE_2D_ARRAY, GL_RGBA32F, buffer, buffer, 2, err) ||
        !gl_texture_create(&s->photons, GL_TEXTURE_2D_ARRAY, GL_RGBA32F, buffer, buffer, 2, err))
        return false;
    const GLuint none = 0;
    return gl_texture_create(&s->flux, GL_TEXTURE_2D_ARRAY, GL_R32UI, w, h, 3, err) &&
           gl_buffer_create(&s->landed, &none, sizeof none, GL_DYNAMIC_STORAGE_BIT, err);
}

/* Each photon splatted over its own footprint (its neighbours' landing
 * points: footprint.glsl), its flux added in fixed point per pixel. */
static bool splat_photons(struct layered_caustics_state *s, struct renderer *r, int buffer, GLuint receiver_normal,
                          struct error *err)
{
    struct gl_program *splat;
    if (!gl_program_get_compute(&r->programs, "layered_caustics/splat.comp", NULL, NULL, &splat, err))
        return false;
    gl.UseProgram(splat->id);
    gl_program_bind_image(splat, "u_hits", s->hits.id, GL_TRUE, GL_READ_ONLY, GL_RGBA32F);
    gl_program_bind_image(splat, "u_photons", s->photons.id, GL_TRUE, GL_READ_ONLY, GL_RGBA32F);
    gl_program_bind_image(splat, "u_flux", s->flux.id, GL_TRUE, GL_READ_WRITE, GL_R32UI);
    gl_program_bind_texture(splat, "u_receiver_normal", receiver_normal);
    if (!gl_param_block_bind(&s->params, splat, err))
        return false;
    gl_program_bind_storage(splat, "LandedFlux", s->landed);
    /* Accumulating, each frame's photons still cover their whole cells:
     * with the splats as boxes that tile (box_taps.glsl), a focused photon
     * covering a quarter x quarter of its cell (so that 16 jitters tile a
     * grid 4 x 4 as fine, the rule while splats were bilinear tents) made
     * the ball's 32 x 32 photons worse over 16 frames, 0.102 -> 0.120
     * against a 64-iteration truth, where whole cells stay at 0.103
     * (docs/TEMPORAL.md). */
    gl_program_dispatch(splat, buffer, buffer, 2, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    return true;
}

/* Flux per pixel -> irradiance. */
static bool resolve_flux(struct layered_caustics_state *s, struct pass_frame *f, struct graph_resource *out,
                         GLuint receiver_depth, GLuint receiver_normal, struct error *err)
{
    struct renderer *r = f->renderer;
    struct gl_program *resolve;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", "layered_caustics/resolve.frag", NULL, &resolve, err))
        return false;
    const struct gl_texture *oc_tex[1] = {&out->texture};
    if (!gl_framebuffer_attach(&s->out_fb, oc_tex, NULL, 1, NULL, -1, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->out_fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.UseProgram(resolve->id);
    gl_program_bind_texture(resolve, "u_receiver_depth", receiver_depth);
    gl_program_bind_texture(resolve, "u_receiver_normal", receiver_normal);
    gl_program_bind_image(resolve, "u_flux", s->flux.id, GL_TRUE, GL_READ_ONLY, GL_R32UI);
    gl_program_bind_storage(resolve, "LandedFlux", s->landed);
    if (!gl_param_block_bind(&s->params, resolve, err))
        return false;
    renderer_draw_fullscreen(r);
    return true;
}

/* Accumulating (issue 32), while the light and the geometry stand still:
 * every photon starts at this frame's sub-texel offset within its light
 * texel, so 16 frames' photons interleave into a grid 4 x 4 as dense.
 * The layers stay as they are (other passes read them); the photon's
 * first interface is interpolated there (layer_trace_at). While
 * anything moves, the photons start at the texels' centres and each
 * frame stands alone: one frame's photons, spread over their
 * footprints, are not noise to average, and a history dragged after
 * the light lagged and dimmed the focus (measured, docs/TEMPORAL.md). */
static bool photons_jitter(struct layered_caustics_state *s, struct pass *p, struct pass_frame *f, int accumulate,
                           float jitter[2])
{
    uint64_t key = pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY);
    bool still = pass_frame_reusable(f, s->valid, s->key, key);
    s->key = key;
    s->valid = true;
    if (!still)
        temporal_reset(&s->temporal);
    jitter[0] = jitter[1] = 0.0f;
    if (accumulate > 1 && still)
        temporal_jitter(&s->temporal, &jitter[0], &jitter[1]);
    return still;
}

/* Temporal accumulation (issue 32) while the light and the geometry stand
 * still (docs/TEMPORAL.md). */
static bool accumulate_frames(struct layered_caustics_state *s, struct pass *p, struct pass_frame *f,
                              struct graph_resource *out, struct graph_resource *depth, bool still, int accumulate,
                              struct error *err)
{
    struct renderer *r = f->renderer;
    int held = 0;
    if (!temporal_accumulate(&s->temporal, r, f->snapshot, &out->texture, &depth->texture, NULL, still, accumulate,
                             &held, err))
        return false;
    pass_stage_end(p, "accumulate");
    snprintf(p->report, sizeof p->report, "accumulated: %s",
             held == 0 ? "the history starts (the light or the geometry moved)" : "the light and geometry still, frames averaged");
    return true;
}

/* This frame's LayeredCausticsParams: the light side's `values` and the
 * camera's pixel (resolve.frag's irradiance per pixel area). */
static bool upload_params(struct layered_caustics_state *s, const struct pass_frame *f,
                          struct layered_caustics_params values, struct error *err)
{
    const struct camera *cam = &f->scene->camera;
    values.pixel_tan = 2.0f * tanf(cam->fov * 0.5f * (float)MATH_PI / 180.0f) / (float)f->height;
    values.pixel_size = cam->ortho_width > 0.0f ? cam->ortho_width / (float)f->width : 0.0f;
    return gl_param_block_upload(&s->params, &values, err);
}

static bool layered_caustics_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct layered_caustics_state *s = p->state;
    struct renderer *r = f->renderer;
    struct graph_resource *out = f->outputs[0];
    const float zero[4] = {0, 0, 0, 0};
    gl_texture_clear(&out->texture, zero);
    int accumulate = pass_int(p, LC_ACCUMULATE);
    if (accumulate <= 1)
        temporal_reset(&s->temporal);
    /* the building blocks' outputs, made earlier in this frame */
    const struct layer_set *ls = pass_frame_record(p, f, "light_layers", &LAYER_SET_RECORD);
    struct graph_resource *normal = pass_frame_input(p, f, "receivers"), *depth = pass_frame_input(p, f, "receiver_depth");
    if (!ls || !normal || !depth)
        return error_set(err, "its light's layers or the receivers were not made this frame");
    if (!ls->built)
        return true; /* the layers' light is not in the scene, or nothing refracts: no caustics */
    int slot = layers_light_slot(ls, err);
    if (slot < 0)
        return false;
    GLuint receiver_normal = normal->texture.id, receiver_depth = depth->texture.id;
    int buffer = ls->width;
    if (!ensure_targets(s, f->width, f->height, buffer, err))
        return false;

    /* The light's view of the refractors, as the layers' producer fit it. */
    const struct frame_light *fl = &f->snapshot->lights[slot];
    const struct light_view lv = ls->light_view;
    bool ortho = lv.ortho;
    mat4 proj = lv.proj;
    float orad = ls->radius;
    float texel_area = 0.0f, texel_tan = 0.0f;
    if (ortho) {
        texel_area = (2.0f * lv.half_width / (float)buffer) * (2.0f * lv.half_height / (float)buffer);
    } else {
        texel_tan = 2.0f * lv.half_extent / (float)buffer;
    }
    pass_stage_begin(p);

    /* Photons: traced through the light's layers, then onto the receivers. */
    double total = light_view_flux_bound(fmaxf(fmaxf(fl->intensity.x, fl->intensity.y), fl->intensity.z), &proj);
    /* No pixel can gather more than all the light through the refractors:
     * that fits below 2^32 with room to spare. The photons add up the light
     * that lands, and the splat spreads that much over the same counts
     * (landed.glsl). */
    float fixed_point = (float)(1.0e9 / fmax(total, 1e-20));
    const GLuint zero_u[4] = {0, 0, 0, 0};
    gl.ClearTexImage(s->flux.id, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, zero_u);
    if (!gl_buffer_update(s->landed, zero_u, sizeof zero_u[0], err))
        return false;
    struct gl_program *photons;
    if (!gl_program_get_compute(&r->programs, "layered_caustics/photons.comp", NULL, NULL, &photons, err))
        return false;
    gl.UseProgram(photons->id);
    struct layers_trace trace = {
        .search = pass_int(p, LC_SEARCH),
        .steps = pass_int(p, LC_STEPS),
        .max_interfaces = 2 * ls->layers + 2,
        .layer_extent = 2.0f * orad,
    };
    if (!layers_bind(ls, photons, f->scene, &trace, err))
        return false;
    gl_program_bind_texture(photons, "u_scene_depth", receiver_depth);
    gl_program_bind_texture(photons, "u_receiver_normal", receiver_normal);
    shadow_inputs_bind(p, f, photons); /* the panes between the light and the glass (its pane filter) */
    float jitter[2];
    bool still = photons_jitter(s, p, f, accumulate, jitter);
    float max_radius = (float)pass_real(p, LC_RADIUS);
    /* The longest a footprint's side may stretch where its neighbours say
     * the light is spread smoothly (footprint.glsl): photons land up to
     * the image's width apart where the light's view spans much more than
     * the camera's (a pool seen close up; water 100 wide seen 1 wide at
     * 256 x 256: photons 100 pixels apart, and a quarter of the image left
     * the floor a black grid carrying dotted squares of light). */
    int longest_side = f->width > f->height ? f->width : f->height;
    float stretch_limit = fmaxf(32.0f, (float)longest_side);
    /* A photon may start far outside the camera's view and land inside it,
     * or past its edge and still spread into it: the receivers go on past
     * the edge as far as a footprint reaches (scene_trace.glsl), so the
     * photons just inside have both neighbours (with one, a footprint is
     * clamped to 2 x radius: black bands along the image's edges where
     * photons landed 30 pixels apart). */
    gl.ProgramUniform1f(photons->id, gl_program_uniform(photons, "u_scene_guard"),
                        fmaxf(2.0f * max_radius, stretch_limit) + 1.0f);
    const struct layered_caustics_params values = {
        .jitter = {jitter[0], jitter[1]},
        .buffer_size = {buffer, buffer},
        .light = slot,
        .light_ortho = ortho ? 1 : 0,
        .texel_area = texel_area,
        .texel_tan = texel_tan,
        .fixed_point = fixed_point,
        .max_radius = max_radius,
        .stretch_limit = stretch_limit,
    };
    if (!upload_params(s, f, values, err) || !gl_param_block_bind(&s->params, photons, err))
        return false;
    gl_program_bind_storage(photons, "LandedFlux", s->landed);
    gl_program_bind_image(photons, "u_hits", s->hits.id, GL_TRUE, GL_WRITE_ONLY, GL_RGBA32F);
    gl_program_bind_image(photons, "u_photons", s->photons.id, GL_TRUE, GL_WRITE_ONLY, GL_RGBA32F);
    gl_program_dispatch(photons, buffer, buffer, 1, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    pass_stage_end(p, "photons");

    if (!splat_photons(s, r, buffer, receiver_normal, err))
        return false;
    pass_stage_end(p, "splat");
    if (!resolve_flux(s, f, out, receiver_depth, receiver_normal, err))
        return false;
    pass_stage_end(p, "resolve");
    if (!gl_check("layered_caustics", err) ||
        !caustic_coverage_check(&s->coverage, p, f, fl,
                                &(struct caustic_coverage_view){.layers = true, .depth = ls->depth.id,
                                                                .info = ls->info.id, .view = ls->view, .proj = ls->proj},
                                receiver_depth, receiver_normal, &out->texture,
                                "raise `buffer` (the photons' spacing) or `radius`", err))
        return false;
    return accumulate <= 1 || accumulate_frames(s, p, f, out, depth, still, accumulate, err);
}

/* The blocks it reads (issue 26): the light's layers at this pass's size
 * (beam_caustics for the same light and size shares them); the receivers
 * as they come. */
static bool layered_caustics_configure_block(const struct pass *p, int param, struct pass *block, struct error *err)
{
    if (param != LC_LIGHT_LAYERS)
        return true;
    return layers_configure_block(block, pass_light_at(p, LC_LIGHT), pass_int(p, LC_BUFFER), pass_int(p, LC_LAYERS),
                                  pass_int(p, LC_VOXELS), err);
}

const struct pass_desc layered_caustics_pass = {
    .technique = PASS_TECHNIQUE_CAUSTICS,
    .name = "layered_caustics",
    .leaves_out = layers_leaves_out,
    .configure_block = layered_caustics_configure_block,
    .summary = "Chaudhari 2008: caustics through every interface, photons traced through the light's depth layers",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = layered_caustics_declare,
    .create = layered_caustics_create,
    .execute = layered_caustics_execute,
    .needed = layered_caustics_needed,
    .destroy = layered_caustics_destroy,
};
