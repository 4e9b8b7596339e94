/* fullscreen: a user-written fragment shader over the whole frame. Inputs
 * are bound to samplers named after their slots (in the order given, units
 * 0..), outputs to fragment outputs in declaration order, uniforms set by
 * name. The shader path is relative to the script. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "graph/pass.h"
#include "graph/renderer.h"

struct fullscreen_state {
    struct gl_framebuffer fb;
};

/* The parameters by index (pass_int(p, ...), pass_light_at(p, ...)): `params`
 * below is filled with these as designated initializers, so the two cannot
 * drift apart. */
enum fullscreen_param {
    FULLSCREEN_SHADER,
    FULLSCREEN_INPUTS,
    FULLSCREEN_OUTPUTS,
    FULLSCREEN_UNIFORMS,
};

static const struct pass_param_desc params[] = {
    [FULLSCREEN_SHADER] = {.name = "shader", .type = PASS_PARAM_STRING, .required = true, .is_path = true,
     .help = "fragment shader file (GLSL 450, may #include \"common/frame.glsl\")"},
    [FULLSCREEN_INPUTS] = {.name = "inputs", .type = PASS_PARAM_INPUT_MAP, .help = "{sampler_name = \"pass.output\", ...}"},
    [FULLSCREEN_OUTPUTS] = {.name = "outputs", .type = PASS_PARAM_OUTPUT_MAP, .help = "{name = \"rgba32f\", ...}; default {color = \"rgba32f\"}"},
    [FULLSCREEN_UNIFORMS] = {.name = "uniforms", .type = PASS_PARAM_UNIFORM_MAP, .help = "{name = number or {x, y, z, w}, ...}"},
};

bool fullscreen_declare_io(struct pass *p, struct error *err);

/* Shared with the custom pass: named inputs and outputs from the maps. */
bool fullscreen_declare_io(struct pass *p, struct error *err)
{
    /* By name: the custom pass's parameters have other indices. */
    const struct pass_value *in = pass_value(p, "inputs");
    for (int i = 0; in && i < in->list_count; i++)
        if (!pass_declare_input(p, in->keys[i], in->list[i], err))
            return false;
    const struct pass_value *out = pass_value(p, "outputs");
    if (!out || out->list_count == 0)
        return pass_declare_output(p, "color", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
    for (int i = 0; i < out->list_count; i++) {
        GLenum format;
        if (!gl_format_parse(out->list[i], &format))
            return error_set(err, "bad argument 'outputs' to '%s' (output '%s': unknown format '%s'; use rgba8, "
                                  "rgba16f, rgba32f, rg16f, rg32f, r16f, r32f, r8)",
                             p->desc->name, out->keys[i], out->list[i]);
        if (gl_format_is_depth(format))
            return error_set(err, "bad argument 'outputs' to '%s' (output '%s': depth formats are not colour outputs)",
                             p->desc->name, out->keys[i]);
        if (!pass_declare_output(p, out->keys[i], format, GL_TEXTURE_2D, 0, 0, err))
            return false;
    }
    return true;
}

static bool fullscreen_create(struct pass *p, struct renderer *r, struct error *err)
{
    struct fullscreen_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    p->state = s;
    if (!gl_framebuffer_create(&s->fb, err))
        return false;
    /* Compile now so a broken shader is reported before the first frame. */
    struct gl_program *prog;
    return gl_program_get(&r->programs, "common/fullscreen.vert", pass_text(p, FULLSCREEN_SHADER), NULL, &prog, err);
}

static void fullscreen_destroy(struct pass *p)
{
    struct fullscreen_state *s = p->state;
    if (!s)
        return;
    gl_framebuffer_destroy(&s->fb);
    free(s);
    p->state = NULL;
}

static bool fullscreen_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct fullscreen_state *s = p->state;
    struct gl_program *prog;
    if (!gl_program_get(&f->renderer->programs, "common/fullscreen.vert", pass_text(p, FULLSCREEN_SHADER), NULL, &prog, err))
        return false;
    const struct gl_texture *colors[PASS_MAX_OUTPUTS];
    for (int o = 0; o < p->output_count; o++)
        colors[o] = &f->outputs[o]->texture;
    if (!gl_framebuffer_attach(&s->fb, colors, NULL, p->output_count, NULL, -1, err))
        return false;
    struct renderer_shader_input inputs[RENDERER_MAX_SHADER_INPUTS];
    int ninputs = 0;
    for (int i = 0; i < p->input_count && ninputs < RENDERER_MAX_SHADER_INPUTS; i++)
        inputs[ninputs++] = (struct renderer_shader_input){p->inputs[i].name, f->inputs[i]->texture.id};
    const struct pass_value *u = &p->values[FULLSCREEN_UNIFORMS];
    struct renderer_shader_uniform *uniforms = calloc((size_t)u->list_count + 1, sizeof *uniforms);
    if (!uniforms)
        return error_set(err, "out of memory");
    for (int i = 0; i < u->list_count; i++) {
        uniforms[i].name = u->keys[i];
        uniforms[i].size = u->vector_sizes[i];
        memcpy(uniforms[i].value, u->vectors[i], sizeof uniforms[i].value);
    }
    renderer_run_fullscreen(f->renderer, prog, s->fb.id, f->width, f->height, inputs, ninputs, uniforms, u->list_count,
                            f->time);
    free(uniforms);
    return true;
}

static unsigned fullscreen_draws(const struct pass *p)
{
    (void)p;
    return PASS_DRAWS_ANYTHING;
}

const struct pass_desc fullscreen_pass = {
    .draws = fullscreen_draws,
    .name = "fullscreen",
    .summary = "a user-written fragment shader over the whole frame",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = fullscreen_declare_io,
    .create = fullscreen_create,
    .execute = fullscreen_execute,
    .destroy = fullscreen_destroy,
};
