/* layered_refraction: refraction through every interface of deforming
 * objects (Chaudhari 2008). Each frame the refractors are voxelized into
 * bit slices between per-pixel depth bounds (§3.3), up to `layers` depth
 * layers are peeled from the bits (§3.4.2), and per pixel of the first
 * layer a ray is traced through them (§3.6-3.8, shaders/layers/trace.glsl):
 * Snell's law at each interface, total internal reflection, absorption.
 * The ray that leaves sees the scene behind (the input image and depth,
 * searched in screen space), else the nearby objects' impostors (Hu & Qin
 * §2.2, shared with `refraction`: what is off screen), else the
 * environment. No precomputation: a mesh
 * that deforms, morphs or is replaced costs the same as a rigid one. The
 * output is the input with the refractors drawn over it, like
 * `refraction`, so a script swaps one for the other. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_param_block.h"
#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/blocks/impostors.h"
#include "passes/helpers/layers.h"
#include "passes/helpers/thin_glass_over.h"

/* The C mirror of LayeredRefractionParams (refract.frag, std140; issue 54). */
struct layered_refraction_params {
    int32_t lookup_scene, reflection, internal, camera_ortho;
};
static const struct gl_block_member layered_refraction_params_members[] = {
    {"u_lookup_scene", offsetof(struct layered_refraction_params, lookup_scene)},
    {"u_reflection", offsetof(struct layered_refraction_params, reflection)},
    {"u_internal", offsetof(struct layered_refraction_params, internal)},
    {"u_camera_ortho", offsetof(struct layered_refraction_params, camera_ortho)},
};

struct layered_refraction_state {
    struct gl_param_block params; /* LayeredRefractionParams, this frame's */
    struct gl_framebuffer out_fb;
    struct thin_glass_over panes;
};

enum { LOOKUP_SCENE, LOOKUP_ENVIRONMENT };
enum { NORMALS_MESH, NORMALS_GRADIENT };
enum { DEPTHS_EXACT, DEPTHS_VOXEL };

enum layered_refraction_param {
    LR_COLOR,
    LR_DEPTH,
    LR_LAYERS,
    LR_VOXELS,
    LR_SEARCH,
    LR_STEPS,
    LR_NORMALS,
    LR_DELTA,
    LR_DEPTHS,
    LR_LOOKUP,
    LR_REFLECTION,
    LR_INTERFACES,
    LR_NEARBY,
    LR_IMPOSTOR,
    LR_INTERNAL,
    LR_CAMERA_LAYERS,
    LR_IMPOSTORS,
};

static const struct pass_param_desc params[] = {
    [LR_COLOR] = {.name = "color", .type = PASS_PARAM_INPUT, .required = true,
     .help = "the scene to draw over; `shade { specular = false }` so that rays leaving the glass find what is behind it"},
    [LR_DEPTH] = {.name = "depth", .type = PASS_PARAM_INPUT, .default_beside = "color", .default_output = "depth",
     .help = "its depth (default: the depth output of the pass that made color)"},
    [LR_LAYERS] = LAYERS_PARAM_LAYERS(16, "depth layers kept per pixel (§3.4.2; surfaces past them are dropped and counted in `info`)"),
    [LR_VOXELS] = LAYERS_PARAM_VOXELS("slices per pixel between its depth bounds (§3.3), a multiple of 128"),
    [LR_SEARCH] = LAYERS_PARAM_SEARCH("bisection steps per interface (§3.6: 5)"),
    [LR_STEPS] = LAYERS_PARAM_STEPS("linear steps along the ray before the bisection (finds the first crossing of a concave layer)"),
    [LR_NORMALS] = {.name = "normals", .type = PASS_PARAM_ENUM, .default_string = "mesh", .choices = "mesh|gradient",
     .help = "the mesh's interpolated normals, or eq. 3.2's perspective-corrected depth gradients"},
    [LR_DELTA] = {.name = "delta", .type = PASS_PARAM_INTEGER, .default_number = 1, .min = 1, .max = 4,
     .help = "pixel step of the depth gradients (eq. 3.2's delta, with normals = \"gradient\")"},
    [LR_DEPTHS] = LAYERS_PARAM_DEPTHS("each layer's depth: the fragment's own, or its voxel's centre (the thesis's)"),
    [LR_LOOKUP] = {.name = "lookup", .type = PASS_PARAM_ENUM, .default_string = "scene", .choices = "scene|environment",
     .help = "what a leaving ray sees: the input image (searched in screen space, then the environment) or the environment"},
    [LR_REFLECTION] = {.name = "reflection", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "add the Fresnel-weighted reflection at the first interface"},
    [LR_INTERFACES] = {.name = "interfaces", .type = PASS_PARAM_INTEGER, .default_number = 0, .min = 0, .max = 66,
     .help = "most interfaces a ray meets before it is stopped (0: 2 x layers + 2)"},
    [LR_NEARBY] = {.name = "nearby", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "where the screen has nothing (off screen, hidden), look up the nearby objects' impostors (Hu & Qin §2.2)"},
    [LR_IMPOSTOR] = {.name = "impostor", .type = PASS_PARAM_INTEGER, .default_number = 256, .min = 16, .max = 4096,
     .help = "impostor texture size"},
    [LR_INTERNAL] = {.name = "internal", .type = PASS_PARAM_INTEGER, .default_number = 2, .min = 0, .max = 4,
     .help = "further marches of the light an exit reflects back inside, each from where the last one left, while "
             "a hundredth of the pixel's light is in it (0: the thesis's one path, which drops it); unless set, only where "
             "a refractor's IOR is 2 or more or below 1 (else 0: they cost a tenth of the pass)"},
    [LR_CAMERA_LAYERS] = {.name = "camera_layers", .type = PASS_PARAM_INPUT, .block = "depth_layers",
     .bundle = &LAYER_SET_RECORD, .default_output = "layers",
     .help = "the camera's depth layers (a depth_layers { view = \"camera\" } pass's `layers`): by default the graph "
             "adds one at `layers`, `voxels` and `depths`"},
    [LR_IMPOSTORS] = {.name = "impostors", .type = PASS_PARAM_INPUT, .block = "impostors",
     .bundle = &IMPOSTOR_SET_RECORD, .default_output = "set",
     .help = "the nearby objects' impostors (an impostors pass's `set`), read where `nearby`: by default the graph "
             "adds one of `impostor` texels, shared with refraction and photon_caustics where they want the same"},
};

static bool layered_refraction_declare(struct pass *p, struct error *err)
{
    /* info: r = layers captured at the pixel, g = surfaces dropped past
     * `layers`, b = interfaces the pixel's ray met, a = total internal
     * reflections among them (+ 100 when the interface cap stopped it). */
    return pass_declare_output(p, "color", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err) &&
           pass_declare_output(p, "info", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool layered_refraction_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct layered_refraction_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("LayeredRefractionParams",
                                  layered_refraction_params_members, struct layered_refraction_params);
    p->state = s;
    return gl_framebuffer_create(&s->out_fb, err);
}

static void layered_refraction_destroy(struct pass *p)
{
    struct layered_refraction_state *s = p->state;
    if (!s)
        return;
    thin_glass_over_release(&s->panes);
    gl_framebuffer_destroy(&s->out_fb);
    gl_param_block_release(&s->params);
    free(s);
    p->state = NULL;
}

static enum pass_need layered_refraction_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    (void)p;
    bool any = false;
    for (int i = 0; i < f->scene->object_count; i++)
        any = any || layers_is_refractor(f->scene->objects[i]);
    if (!any)
        snprintf(why, whylen, "passes the image through: no glass or water in the scene");
    else if (!scene_specular_in_view(f->scene, f->snapshot->view_proj))
        snprintf(why, whylen, "passes the image through: no glass or water in the camera's view");
    return PASS_RUN;
}

static bool layered_refraction_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct layered_refraction_state *s = p->state;
    struct renderer *r = f->renderer;
    struct graph_resource *in_color = pass_frame_input(p, f, "color"), *in_depth = pass_frame_input(p, f, "depth");
    const struct layer_set *ls = pass_frame_record(p, f, "camera_layers", &LAYER_SET_RECORD);
    if (!ls)
        return error_set(err, "the camera's depth layers were not made this frame");
    int layers = ls->layers;
    const float zero[4] = {0, 0, 0, 0};
    gl_texture_clear(&f->outputs[1]->texture, zero);

    /* the image as it is, then the refractors over it */
    const struct gl_texture *oc[2] = {&f->outputs[0]->texture, &f->outputs[1]->texture};
    vec3 lo, hi;
    if (!scene_role_bounds(f->scene, OBJECT_ROLE_SPECULAR, &lo, &hi) || !scene_specular_in_view(f->scene, f->snapshot->view_proj) ||
        !ls->built)
        return gl_framebuffer_attach(&s->out_fb, oc, NULL, 1, NULL, -1, err) &&
               renderer_draw_copy(r, s->out_fb.id, f->width, f->height, in_color->texture.id, err);
    pass_stage_begin(p);
    bool nearby = pass_flag(p, LR_NEARBY);
    const struct impostor_set *impostors = nearby ? pass_frame_record(p, f, "impostors", &IMPOSTOR_SET_RECORD) : NULL;
    if (nearby && !impostors)
        return error_set(err, "its impostors ('%s') were not made this frame", pass_frame_input(p, f, "impostors")->name);

    if (!gl_framebuffer_attach(&s->out_fb, oc, NULL, 2, NULL, -1, err))
        return false;
    static const GLenum color_only[2] = {GL_COLOR_ATTACHMENT0, GL_NONE};
    static const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl.NamedFramebufferDrawBuffers(s->out_fb.id, 2, color_only);
    if (!renderer_draw_copy(r, s->out_fb.id, f->width, f->height, in_color->texture.id, err))
        return false;
    gl.NamedFramebufferDrawBuffers(s->out_fb.id, 2, both);

    /* The marches of the light exits reflect back inside (`internal`) cost
     * a tenth of the pass where none is needed (their state rides along the
     * whole trace): unless the script sets `internal`, they are compiled in
     * only where a refractor's IOR is 2 or more, or below 1, where most
     * paths meet total internal reflection and the exits after it reflect
     * much of the light (the IOR 2.42 cube: 198 -> 1,438 of 2,051 such
     * pixels within 10% of the reference). */
    int internal = pass_int(p, LR_INTERNAL);
    if (!p->values[LR_INTERNAL].set) {
        bool strong = false;
        for (int i = 0; i < f->scene->object_count; i++) {
            const struct object *o = f->scene->objects[i];
            strong = strong || (layers_is_refractor(o) && (o->material.ior >= 2.0f || o->material.ior < 1.0f));
        }
        internal = strong ? internal : 0;
    }
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", "layered_refraction/refract.frag",
                        internal > 0 ? "#define LAYER_TRACE_SPLIT\n" : NULL, &prog, err))
        return false;
    gl.UseProgram(prog->id);
    struct layers_trace trace = {
        .search = pass_int(p, LR_SEARCH),
        .steps = pass_int(p, LR_STEPS),
        .gradient = pass_choice(p, LR_NORMALS) == NORMALS_GRADIENT ? pass_int(p, LR_DELTA) : 0,
        .max_interfaces = pass_int(p, LR_INTERFACES) > 0 ? pass_int(p, LR_INTERFACES) : 2 * layers + 2,
        .layer_extent = fmaxf(vec3_length(vec3_sub(hi, lo)), 1e-4f) * 1.01f,
    };
    if (!layers_bind(ls, prog, f->scene, &trace, err))
        return false;
    gl_program_bind_texture(prog, "u_scene", in_color->texture.id);
    gl_program_bind_texture(prog, "u_scene_depth", in_depth->texture.id);
    const struct layered_refraction_params values = {
        .lookup_scene = pass_choice(p, LR_LOOKUP) == LOOKUP_SCENE ? 1 : 0,
        .reflection = pass_flag(p, LR_REFLECTION),
        .internal = internal,
        .camera_ortho = f->scene->camera.ortho_width > 0.0f,
    };
    if (!gl_param_block_upload(&s->params, &values, err) || !gl_param_block_bind(&s->params, prog, err))
        return false;
    if (impostors && impostors->count > 0) {
        gl_program_bind_storage(prog, "Impostors", impostors->ubo);
        gl_program_bind_texture(prog, "u_impostor_depth", impostors->depth.id);
        gl_program_bind_texture(prog, "u_impostor_color", impostors->color.id);
    }
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_impostor_count"), impostors ? impostors->count : 0);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_correction"), 3);
    renderer_draw_fullscreen(r);
    pass_stage_end(p, "trace");
    /* the panes in front of the glass, over it (shade drew them under it) */
    return gl_check("layered_refraction", err) &&
           thin_glass_draw(&s->panes, p, f, THIN_GLASS_OVER_SURFACES, 0, &f->outputs[0]->texture, in_depth ? &in_depth->texture : NULL,
                                OBJECT_ROLE_GLASS | OBJECT_ROLE_WATER, NULL, err);
}

/* Its camera's layers come from a depth_layers block (issue 26) at this
 * pass's layers, voxels and depths. */
static bool layered_refraction_configure_block(const struct pass *p, int param, struct pass *block, struct error *err)
{
    if (param == LR_IMPOSTORS) /* unshadowed, as this pass has no shadow maps */
        return impostors_configure_block(block, pass_int(p, LR_IMPOSTOR), 0, p, -1, err);
    return layers_configure_camera_block(block, pass_int(p, LR_LAYERS), pass_int(p, LR_VOXELS),
                                         pass_choice(p, LR_DEPTHS) == DEPTHS_EXACT, err);
}

static unsigned layered_refraction_draws(const struct pass *p)
{
    (void)p;
    return OBJECT_ROLE_GLASS | OBJECT_ROLE_WATER;
}

/* Every interface is traced at its interpolated normal, all the light
 * refracted: rough or partly diffuse glass as smooth, clear glass. */
static const char *layered_refraction_leaves_out(const struct pass *p, const struct scene *scene,
                                                 const struct object *o)
{
    (void)p;
    return pass_refractor_holds(scene, o, pass_refractor_left_out(o, false));
}

static bool layered_refraction_reads_block(const struct pass *p, int param)
{
    return param != LR_IMPOSTORS || pass_flag(p, LR_NEARBY);
}

const struct pass_desc layered_refraction_pass = {
    .reads_block = layered_refraction_reads_block,
    .technique = PASS_TECHNIQUE_VIEW,
    .leaves_out = layered_refraction_leaves_out,
    .draws = layered_refraction_draws,
    .color_behind_refractors = true,
    .configure_block = layered_refraction_configure_block,
    .name = "layered_refraction",
    .summary = "Chaudhari 2008: refraction through every interface of deforming objects by voxelization and depth-layer peeling",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = layered_refraction_declare,
    .create = layered_refraction_create,
    .execute = layered_refraction_execute,
    .needed = layered_refraction_needed,
    .destroy = layered_refraction_destroy,
};
