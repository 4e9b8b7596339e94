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
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.UseProgram(prog->id);
    for (int i = 0; i < p->input_count; i++) {
        gl.BindTextureUnit((GLuint)i, f->inputs[i]->texture.id);
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, p->inputs[i].name), i);
    }
    const struct pass_value *u = &p->values[FULLSCREEN_UNIFORMS];
    for (int i = 0; u && i < u->list_count; i++) {
        GLint loc = gl_program_uniform(prog, u->keys[i]);
        const float *v = u->vectors[i];
        switch (u->vector_sizes[i]) {
        case 1: gl.ProgramUniform1f(prog->id, loc, v[0]); break;
        case 2: gl.ProgramUniform2f(prog->id, loc, v[0], v[1]); break;
        case 3: gl.ProgramUniform3f(prog->id, loc, v[0], v[1], v[2]); break;
        default: gl.ProgramUniform4f(prog->id, loc, v[0], v[1], v[2], v[3]); break;
        }
    }
    gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_time"), (float)f->time);
    renderer_draw_fullscreen(f->renderer);
    return true;
}

const struct pass_desc fullscreen_pass = {
    .name = "fullscreen",
    .summary = "a user-written fragment shader over the whole frame",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = fullscreen_declare_io,
    .create = fullscreen_create,
    .execute = fullscreen_execute,
    .destroy = fullscreen_destroy,
};
