/* Thin-walled glass in front of what a view technique draws (see
 * thin_glass_over.h). */
#include "passes/helpers/thin_glass_over.h"

#include "graph/medium_gpu.h"
#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"

bool thin_glass_in_scene(const struct scene *scene)
{
    for (int i = 0; i < scene->object_count; i++)
        if (scene->objects[i]->visible && object_is(scene->objects[i], OBJECT_ROLE_THIN))
            return true;
    return false;
}

static bool is_surface(const struct object *o, unsigned roles, const struct object *only)
{
    return o->visible && (only ? o == only : object_is(o, roles));
}

/* The nearest visible surface's depth: the surfaces drawn depth-tested
 * (not written) against the scene's depth, their depth kept by min
 * blending in a colour target, 1 where none shows. Front and back faces:
 * a camera inside the glass sees its back faces. */
static bool draw_surfaces(struct thin_glass_over *s, struct pass_frame *f, const struct gl_texture *scene_depth,
                          unsigned roles, struct object *only, struct error *err)
{
    struct renderer *r = f->renderer;
    if (!s->surface_fb.id && (!gl_framebuffer_create(&s->surface_fb, err) || !gl_framebuffer_create(&s->color_fb, err)))
        return false;
    if (!s->surface.id || s->surface.width != f->width || s->surface.height != f->height) {
        gl_texture_destroy(&s->surface);
        if (!gl_texture_create(&s->surface, GL_TEXTURE_2D, GL_R32F, f->width, f->height, 1, err))
            return false;
    }
    const struct gl_texture *targets[1] = {&s->surface};
    struct gl_program *prog;
    if (!gl_framebuffer_attach(&s->surface_fb, targets, NULL, 1, scene_depth, -1, err) ||
        !gl_program_get(&r->programs, "common/object.vert", "common/surface_depth.frag", NULL, &prog, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->surface_fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    const float far[4] = {1, 1, 1, 1};
    gl.ClearNamedFramebufferfv(s->surface_fb.id, GL_COLOR, 0, far);
    gl.Disable(GL_CULL_FACE);
    if (scene_depth)
        gl.Enable(GL_DEPTH_TEST);
    else
        gl.Disable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LEQUAL);
    gl.DepthMask(GL_FALSE);
    gl.Enablei(GL_BLEND, 0);
    gl.BlendEquation(GL_MIN);
    for (int i = 0; i < f->scene->object_count; i++)
        if (is_surface(f->scene->objects[i], roles, only))
            renderer_draw_object(r, f->scene, prog, f->scene->objects[i]);
    gl.BlendEquation(GL_FUNC_ADD);
    gl.Disablei(GL_BLEND, 0);
    return gl_check("the surfaces behind the panes", err);
}

bool thin_glass_draw(struct thin_glass_over *s, struct pass *p, struct pass_frame *f, enum thin_glass_panes which,
                     GLuint framebuffer, const struct gl_texture *color, const struct gl_texture *scene_depth, unsigned roles,
                     struct object *only, struct error *err)
{
    if (!thin_glass_in_scene(f->scene))
        return true;
    struct renderer *r = f->renderer;
    bool surfaces = false;
    for (int i = 0; i < f->scene->object_count && which != THIN_GLASS_ALL; i++)
        surfaces = surfaces || is_surface(f->scene->objects[i], roles, only);
    if (!surfaces && which == THIN_GLASS_OVER_SURFACES)
        return true;
    if (!surfaces)
        which = THIN_GLASS_ALL;
    if (which != THIN_GLASS_ALL && !draw_surfaces(s, f, scene_depth, roles, only, err))
        return false;
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "common/object.vert", "common/thin_glass.frag", NULL, &prog, err))
        return false;
    if (color) {
        const struct gl_texture *targets[1] = {color};
        if (!gl_framebuffer_attach(&s->color_fb, targets, NULL, 1, scene_depth, -1, err))
            return false;
        framebuffer = s->color_fb.id;
    }
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl.Viewport(0, 0, f->width, f->height);
    shadow_inputs_bind(p, f, prog); /* the diffuse share of a partly transmissive pane */
    if (!medium_gpu_bind(r, f->scene, prog, err))
        return false;
    gl_program_bind_texture(prog, "u_surface_depth", which != THIN_GLASS_ALL ? s->surface.id : r->dummy_2d.id);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_panes"), (GLint)which);
    if (scene_depth)
        gl.Enable(GL_DEPTH_TEST);
    else
        gl.Disable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_FALSE);
    gl.Disable(GL_CULL_FACE);
    gl.Enablei(GL_BLEND, 0);
    gl.BlendFunci(0, GL_ONE, GL_SRC1_COLOR);
    renderer_draw_objects(r, f->scene, prog, DRAW_THIN);
    gl.Disablei(GL_BLEND, 0);
    gl.DepthMask(GL_TRUE);
    return gl_check("thin-walled glass", err);
}

void thin_glass_over_release(struct thin_glass_over *s)
{
    gl_texture_destroy(&s->surface);
    gl_framebuffer_destroy(&s->surface_fb);
    gl_framebuffer_destroy(&s->color_fb);
}
