/* volume_light: the participating medium seen by the camera (Liktor &
 * Dachsbacher 2011, §7 and Fig. 8 B): the colour behind attenuated by the
 * medium along each pixel's ray, single scattering of the lights' direct
 * light added (shadowed by the shadow maps given, attenuated on its way
 * in), and radiance images such as beam_caustics' volume caustics added
 * on top. Without a medium in the scene it copies its colour (plus the
 * added images). */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "gl/gl_param_block.h"
#include "graph/medium_gpu.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"

#define VOLUME_LIGHT_MAX_ADD 4 /* the sampler array u_add */

/* The C mirror of VolumeLightParams (volume_light.frag, std140; issue 54). */
struct volume_light_params {
    int32_t add_count, steps, pad[2];
};
static const struct gl_block_member volume_light_params_members[] = {
    {"u_add_count", offsetof(struct volume_light_params, add_count)},
    {"u_steps", offsetof(struct volume_light_params, steps)},
};

struct volume_light_state {
    struct gl_param_block params; /* VolumeLightParams, this frame's */
    struct gl_framebuffer fb;
};

enum volume_light_param {
    VL_COLOR,
    VL_DEPTH,
    VL_SHADOW,
    VL_ADD,
    VL_STEPS,
};

static const struct pass_param_desc params[] = {
    [VL_COLOR] = {.name = "color", .type = PASS_PARAM_INPUT, .required = true,
     .help = "the scene's surfaces (e.g. \"shade.color\"), attenuated by the medium in front of them"},
    [VL_DEPTH] = {.name = "depth", .type = PASS_PARAM_INPUT, .default_beside = "color", .default_output = "depth",
     .help = "its depth buffer; default: the depth output of the pass that made color"},
    [VL_SHADOW] = {.name = "shadow", .type = PASS_PARAM_INPUT_LIST, .max = SHADOW_INPUTS_MAX, .record = &SHADOW_MAP_RECORD,
     .help = "shadow map(s) of the lights, shadowing the light in the medium (a light without one is unshadowed)"},
    [VL_ADD] = {.name = "add", .type = PASS_PARAM_INPUT_LIST, .max = VOLUME_LIGHT_MAX_ADD,
     .help = "radiance images added on top, e.g. \"beams.inscatter\" (volume caustics)"},
    [VL_STEPS] = {.name = "steps", .type = PASS_PARAM_INTEGER, .default_number = 32, .min = 1, .max = 1024,
     .help = "samples along each pixel's ray through the medium (jittered per pixel)"},
};

static bool volume_light_declare(struct pass *p, struct error *err)
{
    /* shadow0.. and add0.. are declared from the descriptor (pass_declare). */
    return pass_declare_output(p, "color", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool volume_light_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct volume_light_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("VolumeLightParams", volume_light_params_members, struct volume_light_params);
    p->state = s;
    return gl_framebuffer_create(&s->fb, err);
}

static void volume_light_destroy(struct pass *p)
{
    struct volume_light_state *s = p->state;
    if (!s)
        return;
    gl_framebuffer_destroy(&s->fb);
    gl_param_block_release(&s->params);
    free(s);
    p->state = NULL;
}

static enum pass_need volume_light_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    (void)p;
    if (!medium_gpu_present(f->scene))
        snprintf(why, whylen, "no participating medium in the scene (scene.medium): copies its colour");
    return PASS_RUN;
}

static bool volume_light_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct volume_light_state *s = p->state;
    struct renderer *r = f->renderer;
    struct graph_resource *color = pass_frame_input(p, f, "color"), *depth = pass_frame_input(p, f, "depth");
    struct graph_resource *out = f->outputs[0];
    const struct gl_texture *targets[1] = {&out->texture};
    if (!gl_framebuffer_attach(&s->fb, targets, NULL, 1, NULL, -1, err))
        return false;
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", "volume_light/volume_light.frag", NULL, &prog, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.UseProgram(prog->id);
    gl_program_bind_texture(prog, "u_color", color->texture.id);
    gl_program_bind_texture(prog, "u_depth", depth ? depth->texture.id : r->dummy_depth.id);
    int nadd = 0;
    for (int i = 0; i < VOLUME_LIGHT_MAX_ADD; i++) {
        char slot[32];
        snprintf(slot, sizeof slot, "add%d", i);
        struct graph_resource *a = pass_frame_input(p, f, slot);
        gl_program_bind_texture_at(prog, "u_add", i, a ? a->texture.id : r->dummy_2d.id);
        if (a)
            nadd = i + 1;
    }
    const struct volume_light_params values = {.add_count = nadd, .steps = pass_int(p, VL_STEPS)};
    if (!gl_param_block_upload(&s->params, &values, err) || !gl_param_block_bind(&s->params, prog, err))
        return false;
    shadow_inputs_bind(p, f, prog);
    if (!medium_gpu_bind(r, f->scene, prog, err))
        return false;
    gl.Disable(GL_DEPTH_TEST);
    renderer_draw_fullscreen(r);
    return gl_check("volume_light", err);
}

const struct pass_desc volume_light_pass = {
    .name = "volume_light",
    .summary = "Liktor & Dachsbacher Fig. 8: the medium's single scattering of direct light, shadowed, over the "
               "attenuated surfaces, plus volume caustics",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = volume_light_declare,
    .create = volume_light_create,
    .execute = volume_light_execute,
    .needed = volume_light_needed,
    .destroy = volume_light_destroy,
};
