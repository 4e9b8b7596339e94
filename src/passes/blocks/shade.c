/* shade: the scene in linear radiance. Diffuse surfaces get Lambert direct
 * light (shadowed by the shadow maps given), the uniform ambient and any
 * caustic irradiance; specular ones (glass, water, mirror) a single-
 * interface approximation (Fresnel-weighted environment reflection and
 * refraction) that the refraction passes replace. Also writes the depth,
 * normal and position buffers later passes read. With a participating
 * medium, direct light is attenuated on its way through it (the view path
 * is volume_light's). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "graph/pass.h"
#include "graph/medium_gpu.h"
#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"
#include "passes/helpers/thin_glass_over.h"

#define SHADE_MAX_CAUSTICS 4 /* caustics inputs (sampler units 9-12) */

struct shade_state {
    struct gl_framebuffer fb;
    struct thin_glass_over panes;
};

/* The parameters by index (pass_int(p, ...), pass_light_at(p, ...)): `params`
 * below is filled with these as designated initializers, so the two cannot
 * drift apart. */
enum shade_param {
    SHADE_SHADOW,
    SHADE_BACKGROUND,
    SHADE_CAUSTICS,
    SHADE_SPECULAR,
};

static const struct pass_param_desc params[] = {
    [SHADE_SHADOW] = {.name = "shadow", .type = PASS_PARAM_INPUT_LIST, .max = SHADOW_INPUTS_MAX, .record = &SHADOW_MAP_RECORD,
     .help = "shadow map(s) from shadow_map passes, e.g. \"shadow.depth\" or {\"s1.depth\", \"s2.depth\"}"},
    [SHADE_BACKGROUND] = {.name = "background", .type = PASS_PARAM_INPUT,
     .help = "an image to draw behind the objects (default: the scene's environment or background colour)"},
    [SHADE_CAUSTICS] = {.name = "caustics", .type = PASS_PARAM_INPUT_LIST, .max = SHADE_MAX_CAUSTICS,
     .help = "screen-space caustic irradiance added on diffuse surfaces (one or a list, summed: several lights)"},
    [SHADE_SPECULAR] = {.name = "specular", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "draw glass, water and mirrors (false: leave them to a later pass)"},
};

static bool shade_declare(struct pass *p, struct error *err)
{
    /* shadow0.., background and caustics0.. are declared from the descriptor (pass_declare). */
    return pass_declare_output(p, "color", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err) &&
           pass_declare_output(p, "depth", GL_DEPTH_COMPONENT32F, GL_TEXTURE_2D, 0, 0, err) &&
           pass_declare_output(p, "normal", GL_RGBA16F, GL_TEXTURE_2D, 0, 0, err) &&
           pass_declare_output(p, "position", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool shade_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct shade_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    p->state = s;
    return gl_framebuffer_create(&s->fb, err);
}

static void shade_destroy(struct pass *p)
{
    struct shade_state *s = p->state;
    if (!s)
        return;
    gl_framebuffer_destroy(&s->fb);
    thin_glass_over_release(&s->panes);
    free(s);
    p->state = NULL;
}

static bool shade_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct shade_state *s = p->state;
    struct renderer *r = f->renderer;
    struct graph_resource *color = pass_frame_output(p, f, "color"), *depth = pass_frame_output(p, f, "depth"),
                          *normal = pass_frame_output(p, f, "normal"), *position = pass_frame_output(p, f, "position");
    const struct gl_texture *colors[3] = {&color->texture, &normal->texture, &position->texture};
    if (!gl_framebuffer_attach(&s->fb, colors, NULL, 3, &depth->texture, -1, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    const float zero[4] = {0, 0, 0, 0};
    gl.ClearNamedFramebufferfv(s->fb.id, GL_COLOR, 1, zero);
    gl.ClearNamedFramebufferfv(s->fb.id, GL_COLOR, 2, zero);
    gl.Clear(GL_DEPTH_BUFFER_BIT);

    /* Background: the given image, or the environment. */
    struct graph_resource *bg = pass_frame_input(p, f, "background");
    struct gl_program *bgprog;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", bg ? "common/copy.frag" : "environment/environment.frag",
                        NULL, &bgprog, err))
        return false;
    gl.UseProgram(bgprog->id);
    if (bg)
        gl_program_bind_texture(bgprog, "u_image", bg->texture.id);
    /* Only the colour attachment: the background has no normal or position. */
    const GLenum background_only[3] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE};
    const GLenum all_buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    gl.NamedFramebufferDrawBuffers(s->fb.id, 3, background_only);
    gl.DepthMask(GL_FALSE);
    renderer_draw_fullscreen(r);
    gl.DepthMask(GL_TRUE);
    gl.NamedFramebufferDrawBuffers(s->fb.id, 3, all_buffers);

    /* Objects: Lambert's program, and its glTF-BRDF variant where the
     * scene has such surfaces (renderer_draw_lit), set up alike. */
    struct gl_program *progs[2];
    if (!renderer_lit_programs(r, f->scene, "common/object.vert", "shade/shade.frag", NULL, progs, err))
        return false;
    for (int k = 0; k < 2 && progs[k]; k++) {
        struct gl_program *prog = progs[k];
        shadow_inputs_bind(p, f, prog);
        if (!medium_gpu_bind(r, f->scene, prog, err))
            return false;
        int ncaustics = 0;
        for (int i = 0; i < SHADE_MAX_CAUSTICS; i++) {
            char slot[32];
            snprintf(slot, sizeof slot, "caustics%d", i);
            struct graph_resource *c = pass_frame_input(p, f, slot);
            gl_program_bind_texture_at(prog, "u_caustics", i, c ? c->texture.id : r->dummy_2d.id);
            if (c)
                ncaustics = i + 1;
        }
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_has_caustics"), ncaustics);
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_blending"), 0);
    }
    gl.Enable(GL_DEPTH_TEST);
    unsigned which = pass_flag(p, SHADE_SPECULAR) ? DRAW_ALL : DRAW_DIFFUSE;
    renderer_draw_lit(r, f->scene, progs[0], progs[1], which | DRAW_OPAQUE);
    /* glTF's alphaMode BLEND: over the opaque surfaces, back to front, the
     * colour blended by alpha and the depth, normal and position left to
     * what lies behind (the passes that read them see through it; the
     * shadow map and the reference treat it as a stochastic cut-out,
     * common/material.glsl) */
    gl.Enablei(GL_BLEND, 0);
    gl.BlendFunci(0, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl.ColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.ColorMaski(2, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl.DepthMask(GL_FALSE);
    for (int k = 0; k < 2 && progs[k]; k++)
        gl.ProgramUniform1i(progs[k]->id, gl_program_uniform(progs[k], "u_blending"), 1);
    renderer_draw_lit(r, f->scene, progs[0], progs[1], which | DRAW_BLENDED);
    for (int k = 0; k < 2 && progs[k]; k++)
        gl.ProgramUniform1i(progs[k]->id, gl_program_uniform(progs[k], "u_blending"), 0);
    gl.DepthMask(GL_TRUE);
    gl.ColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.ColorMaski(2, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.Disablei(GL_BLEND, 0);
    /* Thin-walled glass (material.thin), last, back to front: each pane
     * adds its reflection and multiplies what lies behind it by what it
     * lets through (common/thin_glass.frag's two outputs, dual-source
     * blending), the depth, normal and position left to what lies behind,
     * as for the blended surfaces. Those in front of the glass, water and
     * mirrors a view technique draws over this image are that technique's
     * to draw (thin_glass_over.h). Dual-source blending writes one draw
     * buffer. */
    if (!thin_glass_in_scene(f->scene))
        return true;
    static const GLenum color_only[3] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE};
    gl.NamedFramebufferDrawBuffers(s->fb.id, 3, color_only);
    bool ok = thin_glass_draw(&s->panes, p, f, pass_flag(p, SHADE_SPECULAR) ? THIN_GLASS_ALL : THIN_GLASS_BEHIND_SURFACES,
                              s->fb.id, NULL, &depth->texture, OBJECT_ROLE_SPECULAR, NULL, err);
    gl.NamedFramebufferDrawBuffers(s->fb.id, 3, all_buffers);
    return ok;
}

static unsigned shade_draws(const struct pass *p)
{
    /* one interface of each; thin glass always (no other pass draws it) */
    return (pass_flag(p, SHADE_SPECULAR) ? OBJECT_ROLE_SPECULAR : 0u) | OBJECT_ROLE_THIN;
}

const struct pass_desc shade_pass = {
    .draws = shade_draws,
    .name = "shade",
    .summary = "Lambert + shadows + ambient in linear radiance, with depth, normal and position buffers",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = shade_declare,
    .create = shade_create,
    .execute = shade_execute,
    .destroy = shade_destroy,
};
