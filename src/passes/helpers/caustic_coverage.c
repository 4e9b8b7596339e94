/* The measure of what a caustics pass left dark under glass (issue 52):
 * caustic_coverage.h says what and why. One compute pass over the camera's
 * receivers against the refractors' depth from the light (the pass's own,
 * else one depth-only draw of them) and a read-back of two counters, once a
 * pass instance. */
#include "passes/helpers/caustic_coverage.h"

#include <string.h>

#include "core/log.h"
#include "gl/gl_buffer.h"
#include "gl/gl_program.h"
#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/helpers/layers.h"
#include "scene/light_view.h"

#define COVERAGE_SIZE 512 /* the refractors' depth from the light, texels a side */

void caustic_coverage_init(struct caustic_coverage *c)
{
    memset(c, 0, sizeof *c);
}

void caustic_coverage_release(struct caustic_coverage *c)
{
    gl_texture_destroy(&c->depth);
    gl_framebuffer_destroy(&c->fb);
    gl_buffer_destroy(&c->counters);
    caustic_coverage_init(c);
}

static bool ensure_targets(struct caustic_coverage *c, struct error *err)
{
    if (c->depth.id)
        return true;
    return gl_texture_create(&c->depth, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, COVERAGE_SIZE, COVERAGE_SIZE, 1, err) &&
           gl_framebuffer_create(&c->fb, err) && gl_framebuffer_attach(&c->fb, NULL, NULL, 0, &c->depth, -1, err);
}

/* "object 3 (glass)" where one refractor is in the scene, else what they are. */
static void refractor_names(const struct scene *scene, char *out, size_t size)
{
    int count = 0, last = -1;
    for (int i = 0; i < scene->object_count; i++)
        if (scene->objects[i]->visible && layers_is_refractor(scene->objects[i]))
            count++, last = i;
    if (count == 1)
        snprintf(out, size, "object %d (%s)", last + 1, object_role_name(object_role(scene->objects[last])));
    else
        snprintf(out, size, "%s", layers_refractors_named(scene));
}

/* The refractors' depth from the light where the pass has none of its own:
 * one draw of them through the layers' fit of their box. */
static bool draw_refractors(struct caustic_coverage *c, struct pass *p, struct pass_frame *f,
                            const struct frame_light *light, struct caustic_coverage_view *out, bool *fitted,
                            struct error *err)
{
    *fitted = false;
    vec3 lo, hi;
    if (!scene_role_bounds(f->scene, OBJECT_ROLE_REFRACTOR, &lo, &hi))
        return true;
    /* where the view cannot be fit (a light inside their sphere) there is
     * nothing to say */
    struct light_view lv;
    struct error ignored;
    if (!layers_light_view(light, lo, hi, &lv, p->desc->name, &ignored))
        return true;
    struct renderer *r = f->renderer;
    if (!ensure_targets(c, err))
        return false;
    struct gl_program *draw;
    /* the one object vertex shader, projecting by the light's matrix */
    if (!gl_program_get(&r->programs, "common/object.vert", "caustic_coverage/refractors.frag",
                        "#define OBJECT_VIEW_PROJ\n", &draw, err))
        return false;
    mat4 light_view_proj = mat4_mul(lv.proj, lv.view);
    gl.ProgramUniformMatrix4fv(draw->id, gl_program_uniform(draw, "u_object_view_proj"), 1, GL_FALSE,
                               light_view_proj.m);
    gl.BindFramebuffer(GL_FRAMEBUFFER, c->fb.id);
    gl.Viewport(0, 0, COVERAGE_SIZE, COVERAGE_SIZE);
    gl.Enable(GL_DEPTH_TEST);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    for (int i = 0; i < f->scene->object_count; i++) {
        struct object *o = f->scene->objects[i];
        if (o->visible && layers_is_refractor(o))
            renderer_draw_object(r, f->scene, draw, o);
    }
    gl.Disable(GL_DEPTH_TEST);
    *out = (struct caustic_coverage_view){.layers = false, .depth = c->depth.id, .view = lv.view, .proj = lv.proj};
    *fitted = true;
    return true;
}

bool caustic_coverage_check(struct caustic_coverage *c, struct pass *p, struct pass_frame *f,
                            const struct frame_light *light, const struct caustic_coverage_view *view,
                            GLuint receiver_depth, GLuint receiver_normal, const struct gl_texture *irradiance,
                            const char *remedy, struct error *err)
{
    if (c->checked)
        return true;
    struct caustic_coverage_view drawn;
    if (!view || !view->depth) {
        bool fitted;
        if (!draw_refractors(c, p, f, light, &drawn, &fitted, err))
            return false;
        if (!fitted)
            return true;
        view = &drawn;
    }
    c->checked = true;
    struct renderer *r = f->renderer;
    if (!c->counters) {
        const unsigned zero[2] = {0, 0};
        if (!gl_buffer_create(&c->counters, zero, sizeof zero, GL_DYNAMIC_STORAGE_BIT, err))
            return false;
    }
    mat4 light_view_proj = mat4_mul(view->proj, view->view);

    struct gl_program *count;
    if (!gl_program_get_compute(&r->programs, "caustic_coverage/count.comp",
                                view->layers ? "#define LAYER_DEPTHS\n" : NULL, NULL, &count, err))
        return false;
    const unsigned zero[2] = {0, 0};
    if (!gl_buffer_update(c->counters, zero, sizeof zero, err))
        return false;
    gl.UseProgram(count->id);
    gl_program_bind_texture(count, "u_receiver_depth", receiver_depth);
    if (receiver_normal)
        gl_program_bind_texture(count, "u_receiver_normal", receiver_normal);
    gl.ProgramUniform1i(count->id, gl_program_uniform(count, "u_has_normal"), receiver_normal ? 1 : 0);
    gl_program_bind_texture(count, "u_irradiance", irradiance->id);
    if (view->layers) {
        gl_program_bind_texture(count, "u_layer_depth", view->depth);
        gl_program_bind_texture(count, "u_layer_info", view->info);
        gl.ProgramUniformMatrix4fv(count->id, gl_program_uniform(count, "u_light_view"), 1, GL_FALSE,
                                   view->view.m);
    } else {
        gl_program_bind_texture(count, "u_refractor_depth", view->depth);
        if (view->normal)
            gl_program_bind_texture(count, "u_refractor_normal", view->normal);
        gl.ProgramUniform1i(count->id, gl_program_uniform(count, "u_has_refractor_normal"), view->normal ? 1 : 0);
    }
    gl_program_bind_storage(count, "Coverage", c->counters);
    gl.ProgramUniformMatrix4fv(count->id, gl_program_uniform(count, "u_light_view_proj"), 1, GL_FALSE,
                               light_view_proj.m);
    gl.ProgramUniform1i(count->id, gl_program_uniform(count, "u_light_kind"), (int)light->kind);
    gl.ProgramUniform3f(count->id, gl_program_uniform(count, "u_light_position"), light->position.x,
                        light->position.y, light->position.z);
    gl.ProgramUniform3f(count->id, gl_program_uniform(count, "u_light_direction"), light->direction.x,
                        light->direction.y, light->direction.z);
    gl.ProgramUniform1f(count->id, gl_program_uniform(count, "u_cos_outer"),
                        light->kind == LIGHT_SPOT ? light->cos_outer : -2.0f);
    gl_program_dispatch(count, f->width, f->height, 1, GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    unsigned counters[2];
    if (!gl_buffer_read(c->counters, counters, sizeof counters, err))
        return false;
    unsigned shadow = counters[0], dark = counters[1];
    /* Glass keeps parts of its shadow dark (a cube of IOR 2.42 tilted in
     * the sun: a quarter of it), but exact light reaches nearly all of it;
     * where a third or more is dark the pass's samples lie too far apart
     * (a ball resting on its floor: 59-95% at the defaults, where the
     * exact trace lights all but a few pixels, thinly) */
    if (dark >= 16 && dark * 10u > shadow * 3u) {
        char names[64];
        refractor_names(f->scene, names, sizeof names);
        log_warn("%s '%s': %u of the %u pixels in the shadow of %s (%.0f%%) got none of the light through it, "
                 "which an exact trace spreads over nearly all of it (thinly where the light grazes a rim, as under "
                 "a ball resting on its floor): left black between samples too far apart; %s",
                 p->desc->name, p->name, dark, shadow, names, 100.0 * dark / shadow, remedy);
    }
    return gl_check(p->desc->name, err);
}
