/* shadow_map: depth as seen from one light. Directional lights get an
 * orthographic map fitted to the scene's bounds, spot lights a perspective
 * one over their cone, point and linear lights a cube map of distances
 * (a linear light's from its midpoint). The map is reused while neither
 * the light nor any caster changed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"
#include "scene/light_view.h"
#include "scene/scene.h"

struct shadow_state {
    struct gl_framebuffer fb;
    struct gl_texture cube_depth; /* depth buffer for the cube faces */
    bool valid;
    uint64_t key;                /* pass_frame_key of what the map was made from */
    struct shadow_record record; /* what the depth texture carries for its readers */
    /* 2D maps of a scene with thin-walled glass: what the panes let
     * through (RGB) and the nearest pane's depth (A), made with the map */
    struct gl_texture filter;
    struct gl_framebuffer filter_fb;
};

/* The parameters by index (pass_int(p, ...), pass_light_at(p, ...)): `params`
 * below is filled with these as designated initializers, so the two cannot
 * drift apart. */
enum shadow_map_param {
    SHADOW_LIGHT,
    SHADOW_SIZE,
    SHADOW_BIAS,
};

static const struct pass_param_desc params[] = {
    [SHADOW_LIGHT] = {.name = "light", .type = PASS_PARAM_LIGHT, .required = true, .help = "the light whose shadows to render"},
    [SHADOW_SIZE] = {.name = "size", .type = PASS_PARAM_INTEGER, .default_number = 1024, .min = 16, .max = 8192,
     .help = "width and height of the map in texels"},
    [SHADOW_BIAS] = {.name = "bias", .type = PASS_PARAM_NUMBER, .default_number = 0.003, .min = 0, .max = 1,
     .help = "depth bias in scene units against self-shadowing"},
};

static bool is_cube(const struct light *l) { return l->kind == LIGHT_POINT || l->kind == LIGHT_LINEAR; }

static bool shadow_declare(struct pass *p, struct error *err)
{
    struct light *l = pass_light_at(p, SHADOW_LIGHT);
    int size = pass_int(p, SHADOW_SIZE);
    if (is_cube(l))
        return pass_declare_output_record(p, "depth", &SHADOW_MAP_RECORD, GL_R32F, GL_TEXTURE_CUBE_MAP, size, size, err);
    return pass_declare_output_record(p, "depth", &SHADOW_MAP_RECORD, GL_DEPTH_COMPONENT32F, GL_TEXTURE_2D, size, size,
                                      err);
}

static bool shadow_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct shadow_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    p->state = s;
    if (!gl_framebuffer_create(&s->fb, err))
        return false;
    if (is_cube(pass_light_at(p, SHADOW_LIGHT))) {
        int size = pass_int(p, SHADOW_SIZE);
        if (!gl_texture_create(&s->cube_depth, GL_TEXTURE_CUBE_MAP, GL_DEPTH_COMPONENT32F, size, size, 6, err))
            return false;
    }
    return true;
}

static void shadow_destroy(struct pass *p)
{
    struct shadow_state *s = p->state;
    if (!s)
        return;
    gl_framebuffer_destroy(&s->fb);
    gl_texture_destroy(&s->cube_depth);
    gl_framebuffer_destroy(&s->filter_fb);
    gl_texture_destroy(&s->filter);
    free(s);
    p->state = NULL;
}

static enum pass_need shadow_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    struct shadow_state *s = p->state;
    struct light *l = pass_light_at(p, SHADOW_LIGHT);
    (void)l;
    /* Hu & Qin §4: in a static scene shadow maps are reused, not redrawn
     * (the light, by its version, is a parameter; only casters that animate
     * count, not every animated object). */
    if (s->valid && s->key == pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY) && !f->snapshot->casters_animated &&
        f->outputs[0]->record == &s->record) {
        snprintf(why, whylen, "reused: the light and the casters did not change since the last frame");
        return PASS_REUSE;
    }
    return PASS_RUN;
}

/* Casters that let a share of the light through: thin glass, and glTF's
 * alphaMode BLEND surfaces, diffuse, glass or mirrors (what passes them is
 * 1 - alpha) */
static bool scene_has_filtering_casters(const struct scene *scene)
{
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        if (o->cast_shadows && o->visible &&
            (object_is(o, OBJECT_ROLE_THIN) || o->material.alpha_blend))
            return true;
    }
    return false;
}

/* Thin-walled glass casts a coloured shadow: the panes drawn from the light
 * into the filter texture, their colours multiplied and the least depth
 * kept (shadow_map/thin_filter.frag), which common/shadows.glsl applies
 * to receivers behind the nearest pane. Thin glass is not in the depth map
 * (renderer_draw_objects leaves it out of DRAW_CASTERS). The blended
 * surfaces (alphaMode BLEND) are drawn into it the same way, each letting
 * 1 - alpha through: a smooth partial shadow where the depth map's dither
 * made a dotted one (shadow.frag leaves them out of a 2D map). */
static bool shadow_thin_filter(struct pass_frame *f, struct shadow_state *s, int size, struct error *err)
{
    struct renderer *r = f->renderer;
    if (!s->filter.id && (!gl_texture_create(&s->filter, GL_TEXTURE_2D, GL_RGBA16F, size, size, 1, err) ||
                          !gl_framebuffer_create(&s->filter_fb, err)))
        return false;
    const struct gl_texture *colors[1] = {&s->filter};
    struct gl_program *prog;
    if (!gl_framebuffer_attach(&s->filter_fb, colors, NULL, 1, NULL, -1, err) ||
        !gl_program_get(&r->programs, "common/object.vert", "shadow_map/thin_filter.frag",
                        "#define OBJECT_VIEW_PROJ\n", &prog, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->filter_fb.id);
    const float clear[4] = {1.0f, 1.0f, 1.0f, 2.0f}; /* all light passes; no pane (depths are at most 1) */
    gl.ClearNamedFramebufferfv(s->filter_fb.id, GL_COLOR, 0, clear);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    gl.Enablei(GL_BLEND, 0);
    gl.BlendEquationSeparatei(0, GL_FUNC_ADD, GL_MIN);
    gl.BlendFuncSeparatei(0, GL_ZERO, GL_SRC_COLOR, GL_ONE, GL_ONE);
    gl.ProgramUniformMatrix4fv(prog->id, gl_program_uniform(prog, "u_object_view_proj"), 1, GL_FALSE,
                               s->record.matrix.m);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_light_index"), s->record.light_index);
    renderer_draw_objects(r, f->scene, prog, DRAW_THIN | DRAW_CASTERS);
    renderer_draw_objects(r, f->scene, prog, DRAW_BLENDED | DRAW_CASTERS);
    gl.BlendEquationSeparatei(0, GL_FUNC_ADD, GL_FUNC_ADD);
    gl.BlendFunci(0, GL_ONE, GL_ZERO);
    gl.Disablei(GL_BLEND, 0);
    gl.Enable(GL_DEPTH_TEST);
    return true;
}

static bool shadow_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct shadow_state *s = p->state;
    struct renderer *r = f->renderer;
    struct light *l = pass_light_at(p, SHADOW_LIGHT);
    struct graph_resource *out = f->outputs[0];
    int size = out->texture.width;
    if (scene_light_index(f->scene, l) < 0)
        return error_set(err, "its light was never added to the scene (use scene:add(light))");
    struct shadow_record *rec = &s->record;
    out->record = NULL; /* until the map is made */
    rec->light_index = renderer_light_slot(r, f->scene, l);
    rec->kind = (int)l->kind;

    vec3 lo, hi;
    bool any = scene_bounds(f->scene, &lo, &hi);
    if (f->scene->medium) {
        /* the medium's box too: volume_light shadows the light in all of it */
        lo = any ? vec3_min(lo, f->scene->medium->box_min) : f->scene->medium->box_min;
        hi = any ? vec3_max(hi, f->scene->medium->box_max) : f->scene->medium->box_max;
    }
    vec3 center = vec3_scale(vec3_add(lo, hi), 0.5f);
    float radius = 0.5f * vec3_length(vec3_sub(hi, lo)) + 1e-3f;
    float bias = (float)pass_real(p, SHADOW_BIAS);

    struct gl_program *prog;
    const char *defines = is_cube(l) ? "#define SHADOW_DISTANCE 1\n" : "";
    if (!gl_program_get(&r->programs, "shadow_map/shadow.vert", "shadow_map/shadow.frag", defines, &prog, err))
        return false;
    GLint loc_light_vp = gl_program_uniform(prog, "u_light_view_proj");
    gl.Enable(GL_DEPTH_TEST);
    gl.Viewport(0, 0, size, size);

    if (!is_cube(l)) {
        mat4 view, proj;
        vec3 dir = vec3_normalize_or(l->direction, vec3_make(0, -1, 0));
        if (l->kind == LIGHT_DIRECTIONAL) {
            /* the whole scene's sphere, the eye two radii back */
            static const struct light_view_margins margins = {
                .radius_scale = 1.0f, .eye_radii = 2.0f, .ortho_near_radii = 0.0f, .ortho_far_radii = 4.0f};
            struct light_view lv;
            light_view_fit(true, l->position, dir, center, radius, &margins, &lv);
            view = lv.view;
            proj = lv.proj;
            rec->range = 4.0f * radius;
        } else {
            view = mat4_look_at(l->position, vec3_add(l->position, dir), vec3_make(0, 1, 0));
            float far = vec3_length(vec3_sub(center, l->position)) + radius;
            float fov = fminf(2.0f * l->angle + 2.0f, 179.0f);
            proj = mat4_perspective(fov, 1.0f, fmaxf(far * 1e-3f, 1e-3f), fmaxf(far, 1e-2f));
            rec->range = far;
        }
        rec->matrix = mat4_mul(proj, view);
        if (!gl_framebuffer_attach(&s->fb, NULL, NULL, 0, &out->texture, -1, err))
            return false;
        gl.BindFramebuffer(GL_FRAMEBUFFER, s->fb.id);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        /* Slope-scaled offset against acne; the constant bias is applied when sampling. */
        gl.Enable(GL_POLYGON_OFFSET_FILL);
        gl.PolygonOffset(1.5f, 2.0f);
        gl.ProgramUniformMatrix4fv(prog->id, loc_light_vp, 1, GL_FALSE, rec->matrix.m);
        renderer_draw_objects(r, f->scene, prog, DRAW_CASTERS);
        gl.Disable(GL_POLYGON_OFFSET_FILL);
        rec->filter = 0;
        if (scene_has_filtering_casters(f->scene)) {
            if (!shadow_thin_filter(f, s, size, err))
                return false;
            rec->filter = s->filter.id;
        }
    } else {
        rec->filter = 0; /* (leaves_out says what a cube map leaves of thin glass) */
        vec3 pos = light_center(l);
        float range = vec3_length(vec3_sub(center, pos)) + radius;
        range = fmaxf(range, 1e-2f);
        rec->range = range;
        rec->matrix = mat4_translate(vec3_scale(pos, -1.0f));
        mat4 proj = mat4_perspective(90.0f, 1.0f, fmaxf(range * 1e-4f, 1e-3f), range);
        gl.ProgramUniform3f(prog->id, gl_program_uniform(prog, "u_light_position"), pos.x, pos.y, pos.z);
        gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_range"), range);
        for (int face = 0; face < 6; face++) {
            const struct gl_texture *colors[1] = {&out->texture};
            int layers[1] = {face};
            if (!gl_framebuffer_attach(&s->fb, colors, layers, 1, &s->cube_depth, face, err))
                return false;
            gl.BindFramebuffer(GL_FRAMEBUFFER, s->fb.id);
            const float far_value[4] = {1.0f, 1.0f, 1.0f, 1.0f};
            gl.ClearNamedFramebufferfv(s->fb.id, GL_COLOR, 0, far_value);
            gl.Clear(GL_DEPTH_BUFFER_BIT);
            mat4 vp = mat4_mul(proj, mat4_cube_face_view(pos, face)); /* OpenGL's face order */
            gl.ProgramUniformMatrix4fv(prog->id, loc_light_vp, 1, GL_FALSE, vp.m);
            renderer_draw_objects(r, f->scene, prog, DRAW_CASTERS);
        }
    }
    rec->bias = bias;
    out->record = rec;
    s->valid = true;
    s->key = pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY);
    return true;
}

static const char *shadow_map_leaves_out(const struct pass *p, const struct scene *scene, const struct object *o)
{
    (void)scene;
    if (object_is(o, OBJECT_ROLE_THIN) && o->cast_shadows && is_cube(pass_light_at(p, SHADOW_LIGHT)))
        return "a point or linear light's cube map casts no shadow of thin-walled glass: the light passes it whole "
               "(without its Fresnel loss and tint; a directional or spot light's map filters it)";
    return NULL;
}

const struct pass_desc shadow_map_pass = {
    .leaves_out = shadow_map_leaves_out,
    .name = "shadow_map",
    .summary = "depth from a light: 2D for directional and spot lights, a distance cube map for point and linear lights",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = shadow_declare,
    .create = shadow_create,
    .execute = shadow_execute,
    .needed = shadow_needed,
    .destroy = shadow_destroy,
};
