/* environment: the scene's environment cube map (or background colour)
 * seen through the camera, as a background image for later passes. */
#include <stdlib.h>

#include "graph/pass.h"
#include "graph/renderer.h"

struct environment_state {
    struct gl_framebuffer fb;
};

static bool environment_declare(struct pass *p, struct error *err)
{
    return pass_declare_output(p, "color", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool environment_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct environment_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    p->state = s;
    return gl_framebuffer_create(&s->fb, err);
}

static void environment_destroy_state(struct pass *p)
{
    struct environment_state *s = p->state;
    if (!s)
        return;
    gl_framebuffer_destroy(&s->fb);
    free(s);
    p->state = NULL;
}

static bool environment_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct environment_state *s = p->state;
    struct gl_program *prog;
    if (!gl_program_get(&f->renderer->programs, "common/fullscreen.vert", "environment/environment.frag", NULL, &prog,
                        err))
        return false;
    const struct gl_texture *colors[1] = {&f->outputs[0]->texture};
    if (!gl_framebuffer_attach(&s->fb, colors, NULL, 1, NULL, -1, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.UseProgram(prog->id);
    renderer_draw_fullscreen(f->renderer);
    return true;
}

const struct pass_desc environment_pass = {
    .name = "environment",
    .summary = "the environment (or background colour) seen through the camera",
    .params = NULL,
    .param_count = 0,
    .declare = environment_declare,
    .create = environment_create,
    .execute = environment_execute,
    .destroy = environment_destroy_state,
};
