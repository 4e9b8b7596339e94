/* glossy_reflection: the scene in the glossy reflections of glTF's BRDF
 * surfaces (issue 50). `shade` lights a glossy lobe by the environment
 * about its mirror direction, prefiltered (common/surface_light.glsl's
 * surface_glossy_environment); where that direction meets another object
 * on screen this pass puts the object there instead: each BRDF surface is
 * drawn again over the input image (its depth test against what the
 * camera sees), each lobe's mirror direction (the base's, a clearcoat's)
 * marched through the input's depth
 * (layers/scene_trace.glsl, as refraction's scene lookup), and the lobe's
 * albedo x (what the march meets, blurred by the lobe's width through the
 * input's mipmaps - the environment shade put there) added. Rays that leave
 * the image or meet nothing keep the environment. The reference traces the
 * lobes themselves (ref_sppm.c's glossy_radiance). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/helpers/layers.h"
#include "scene/scene.h"

struct glossy_reflection_state {
    struct gl_framebuffer fb;
    struct gl_texture scene_mips; /* the input colour with mipmaps (the blur of a lobe's width) */
    struct gl_texture depth;      /* a copy of the input depth to march through (it is also the depth attachment) */
};

enum glossy_reflection_param { GLOSSY_COLOR, GLOSSY_DEPTH };

static const struct pass_param_desc params[] = {
    [GLOSSY_COLOR] = {.name = "color", .type = PASS_PARAM_INPUT, .required = true,
     .help = "the scene as shade drew it (its glossy lobes reflecting the environment)"},
    [GLOSSY_DEPTH] = {.name = "depth", .type = PASS_PARAM_INPUT, .default_beside = "color", .default_output = "depth",
     .help = "its depth buffer; default: the depth output of the pass that made color"},
};

static bool glossy_reflection_declare(struct pass *p, struct error *err)
{
    return pass_declare_output(p, "color", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool glossy_reflection_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct glossy_reflection_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    p->state = s;
    return gl_framebuffer_create(&s->fb, err);
}

static void glossy_reflection_destroy(struct pass *p)
{
    struct glossy_reflection_state *s = p->state;
    if (!s)
        return;
    gl_framebuffer_destroy(&s->fb);
    gl_texture_destroy(&s->scene_mips);
    gl_texture_destroy(&s->depth);
    free(s);
    p->state = NULL;
}

static bool scene_has_brdf(const struct scene *scene)
{
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        if (o->visible && o->material.pbr && material_role(&o->material) == OBJECT_ROLE_RECEIVER)
            return true;
    }
    return false;
}

static bool glossy_reflection_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct glossy_reflection_state *s = p->state;
    struct renderer *r = f->renderer;
    struct graph_resource *in_color = pass_frame_input(p, f, "color"), *in_depth = pass_frame_input(p, f, "depth");
    const struct gl_texture *targets[1] = {&f->outputs[0]->texture};
    bool brdf = scene_has_brdf(f->scene);
    if (!gl_framebuffer_attach(&s->fb, targets, NULL, 1, brdf ? &in_depth->texture : NULL, -1, err) ||
        !renderer_draw_copy(r, s->fb.id, f->width, f->height, in_color->texture.id, err))
        return false;
    if (!brdf)
        return true; /* nothing glossy: the image as it is */
    struct gl_program *progs[2];
    if (!gl_texture_copy(&s->scene_mips, &in_color->texture, true, err) ||
        !gl_texture_copy(&s->depth, &in_depth->texture, false, err) ||
        !renderer_lit_programs(r, f->scene, "common/object.vert", "glossy_reflection/glossy.frag", NULL, progs, err))
        return false;
    if (!progs[1])
        return true;
    struct gl_program *prog = progs[1];
    gl_program_bind_texture(prog, "u_scene_mips", s->scene_mips.id);
    gl_program_bind_texture(prog, "u_scene_depth", s->depth.id);
    layers_bind_scene_trace(prog, f->scene);
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LEQUAL); /* the surface the camera sees, drawn again */
    gl.DepthMask(GL_FALSE);
    gl.Enable(GL_BLEND);
    gl.BlendEquation(GL_FUNC_ADD);
    gl.BlendFunc(GL_ONE, GL_ONE); /* + albedo x (the scene met - the environment shade put there) */
    renderer_draw_lit(r, f->scene, progs[0], prog, DRAW_DIFFUSE);
    gl.Disable(GL_BLEND);
    gl.DepthMask(GL_TRUE);
    gl.DepthFunc(GL_LESS);
    return gl_check("glossy reflections", err);
}

/* The pass adds the reflected scene over its input, where the panes shade
 * blended are already: a pane in front of a glossy surface does not dim or
 * tint what it adds (said only where the scene has BRDF surfaces). */
static const char *glossy_reflection_leaves_out(const struct pass *p, const struct scene *scene,
                                                const struct object *o)
{
    (void)p;
    if (!object_is(o, OBJECT_ROLE_THIN))
        return NULL;
    for (int i = 0; i < scene->object_count; i++)
        if (scene->objects[i]->material.pbr && object_is(scene->objects[i], OBJECT_ROLE_RECEIVER))
            return "where this pane lies in front of a glossy surface, the reflection this pass adds there is "
                   "neither dimmed nor tinted by it (the reference sees the reflection through the pane)";
    return NULL;
}

const struct pass_desc glossy_reflection_pass = {
    .leaves_out = glossy_reflection_leaves_out,
    .name = "glossy_reflection",
    .summary = "the scene on screen in the glossy reflections of glTF's BRDF surfaces (screen-space, over shade)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = glossy_reflection_declare,
    .create = glossy_reflection_create,
    .execute = glossy_reflection_execute,
    .destroy = glossy_reflection_destroy,
};
