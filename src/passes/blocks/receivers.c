/* receivers: the camera's receiver G-buffer, a building block (issue 26).
 * What the camera sees of the diffuse surfaces, as shade { specular =
 * false } draws them (glass and water are drawn later, by the passes that
 * refract this image): their depth, their world normal facing the camera
 * and, when a reader asks, their world position. beam_caustics clips its
 * beams at this depth and lights these normals (Liktor & Dachsbacher
 * §5.3), caustic_volumes cuts its volumes at these positions (Sandberg &
 * Falemo §3.5, pass 1), layered_caustics searches its photons' landing
 * points in it (Chaudhari 2008 §4.1). The graph adds one when a script
 * names none, shared by every caustics pass of the frame: one draw of the
 * diffuse objects instead of one per technique. */
#include <stdlib.h>

#include "graph/pass.h"
#include "graph/renderer.h"

struct receivers_state {
    struct gl_framebuffer fb;
};

enum receivers_param {
    RECEIVERS_POSITION,
};

static const struct pass_param_desc params[] = {
    [RECEIVERS_POSITION] = {.name = "position", .type = PASS_PARAM_BOOLEAN, .default_number = 0, .merge_or = true,
     .help = "also the receivers' world positions (output `position`: caustic_volumes reads them)"},
};

static bool receivers_declare(struct pass *p, struct error *err)
{
    return pass_declare_output(p, "normal", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err) &&
           pass_declare_output(p, "depth", GL_DEPTH_COMPONENT32F, GL_TEXTURE_2D, 0, 0, err) &&
           (!pass_flag(p, RECEIVERS_POSITION) ||
            pass_declare_output(p, "position", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err));
}

static bool receivers_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct receivers_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    p->state = s;
    return gl_framebuffer_create(&s->fb, err);
}

static void receivers_destroy(struct pass *p)
{
    struct receivers_state *s = p->state;
    if (!s)
        return;
    gl_framebuffer_destroy(&s->fb);
    free(s);
    p->state = NULL;
}

static bool receivers_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct receivers_state *s = p->state;
    struct graph_resource *normal = pass_frame_output(p, f, "normal"), *depth = pass_frame_output(p, f, "depth"),
                          *position = pass_frame_output(p, f, "position");
    /* read texel by texel: a normal must not blend across a silhouette */
    gl.TextureParameteri(normal->texture.id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TextureParameteri(normal->texture.id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    const struct gl_texture *targets[2] = {&normal->texture, position ? &position->texture : NULL};
    if (!gl_framebuffer_attach(&s->fb, targets, NULL, position ? 2 : 1, &depth->texture, -1, err))
        return false;
    struct gl_program *program;
    if (!gl_program_get(&f->renderer->programs, "common/object.vert", "receivers/receivers.frag", NULL, &program, err))
        return false;
    const float zero[4] = {0, 0, 0, 0};
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.ClearNamedFramebufferfv(s->fb.id, GL_COLOR, 0, zero);
    if (position)
        gl.ClearNamedFramebufferfv(s->fb.id, GL_COLOR, 1, zero);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    renderer_draw_objects(f->renderer, f->scene, program, DRAW_DIFFUSE);
    return true;
}

/* What the camera sees of the diffuse objects: made again only when the
 * camera or the geometry changed (the graph's reuse by version). */
static unsigned receivers_depends(const struct pass *p)
{
    (void)p;
    return PASS_DEPENDS_CAMERA | PASS_DEPENDS_GEOMETRY;
}

const struct pass_desc receivers_pass = {
    .depends = receivers_depends,
    .name = "receivers",
    .summary = "building block: the camera's receiver G-buffer (diffuse depth, normal, position), shared by the caustics passes",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = receivers_declare,
    .create = receivers_create,
    .execute = receivers_execute,
    .destroy = receivers_destroy,
};
