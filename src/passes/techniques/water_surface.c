/* water_surface: the third pass of Sandberg & Falemo §3.5. The image of
 * the pool's contents (with their caustics) is mapped onto the water
 * surface with texture coordinates from a virtual plane at the mean water
 * level (the displaced surface samples the image where the flat plane
 * would be: the paper's "illusion of refraction", Fig. 6), or, with
 * mapping = "refract", along the refracted ray down to the pool floor; the
 * environment is reflected with Fresnel weights. Seen from below, total internal
 * reflection shows the pool contents mirrored instead (never a NaN). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_param_block.h"
#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/helpers/thin_glass_over.h"
#include "scene/water.h"

/* The C mirror of WaterSurfaceParams (surface.frag, std140; issue 54). */
struct water_surface_params {
    float depth, level;
    int32_t refract_mapping, eye_in_water;
};
static const struct gl_block_member water_surface_params_members[] = {
    {"u_depth", offsetof(struct water_surface_params, depth)},
    {"u_level", offsetof(struct water_surface_params, level)},
    {"u_refract_mapping", offsetof(struct water_surface_params, refract_mapping)},
    {"u_eye_in_water", offsetof(struct water_surface_params, eye_in_water)},
};

struct water_surface_state {
    struct gl_param_block params; /* WaterSurfaceParams, this frame's */
    struct gl_framebuffer fb;
    struct thin_glass_over panes;
};

/* The parameters by index (pass_int(p, ...), pass_light_at(p, ...)): `params`
 * below is filled with these as designated initializers, so the two cannot
 * drift apart. */
/* Choices of `mapping`, in the order of its `choices`. */
enum { SURFACE_MAPPING_PLANE, SURFACE_MAPPING_REFRACT };

enum water_surface_param {
    SURFACE_WATER,
    SURFACE_COLOR,
    SURFACE_DEPTH,
    SURFACE_POSITION,
    SURFACE_MAPPING,
};

static const struct pass_param_desc params[] = {
    [SURFACE_WATER] = {.name = "water", .type = PASS_PARAM_OBJECT, .required = true, .help = "the water surface (c.water{...})"},
    [SURFACE_COLOR] = {.name = "color", .type = PASS_PARAM_INPUT, .required = true, .help = "the scene without the water surface"},
    [SURFACE_DEPTH] = {.name = "depth", .type = PASS_PARAM_INPUT, .default_beside = "color", .default_output = "depth",
     .help = "its depth buffer; default: the depth output of the pass that made color"},
    [SURFACE_POSITION] = {.name = "position", .type = PASS_PARAM_INPUT, .default_beside = "color",
     .default_output = "position",
     .help = "its world positions (for absorption); default: the position output of the pass that made color"},
    [SURFACE_MAPPING] = {.name = "mapping", .type = PASS_PARAM_ENUM, .default_string = "plane", .choices = "plane|refract",
     .help = "plane: the paper's texture coordinates from a virtual plane at the mean water level; refract: "
             "follow the refracted ray down to the pool floor"},
};

static bool water_surface_declare(struct pass *p, struct error *err)
{
    if (!pass_object_at(p, SURFACE_WATER)->water)
        return error_set(err, "bad argument 'water' to 'water_surface' (a water surface from c.water{...} expected)");
    return pass_declare_output(p, "color", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool water_surface_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct water_surface_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("WaterSurfaceParams", water_surface_params_members, struct water_surface_params);
    p->state = s;
    return gl_framebuffer_create(&s->fb, err);
}

static void water_surface_destroy(struct pass *p)
{
    struct water_surface_state *s = p->state;
    if (!s)
        return;
    gl_framebuffer_destroy(&s->fb);
    thin_glass_over_release(&s->panes);
    gl_param_block_release(&s->params);
    free(s);
    p->state = NULL;
}

static bool water_surface_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct water_surface_state *s = p->state;
    struct renderer *r = f->renderer;
    struct object *water = pass_object_at(p, SURFACE_WATER);
    struct graph_resource *in_color = pass_frame_input(p, f, "color"), *in_depth = pass_frame_input(p, f, "depth"),
                          *in_pos = pass_frame_input(p, f, "position"), *out = f->outputs[0];
    const struct gl_texture *targets[1] = {&out->texture};
    if (!gl_framebuffer_attach(&s->fb, targets, NULL, 1, NULL, -1, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    /* the scene as it is (absorbed on its way when the camera is under
     * water: inside the pool's box, below the mean level), then the
     * surface over it */
    vec3 eye = f->snapshot->eye, at = water->position;
    const struct water *w = water->water;
    bool under = eye.y < at.y && eye.y > at.y - w->depth && fabsf(eye.x - at.x) < 0.5f * w->size_x &&
                 fabsf(eye.z - at.z) < 0.5f * w->size_z;
    struct gl_program *copy;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert",
                        under ? "water_surface/underwater.frag" : "common/copy.frag", NULL, &copy, err))
        return false;
    gl.UseProgram(copy->id);
    gl_program_bind_texture(copy, "u_image", in_color->texture.id);
    gl_program_bind_texture(copy, "u_scene_position", in_pos->texture.id);
    vec3 c = water->material.absorption;
    /* underwater.frag's (copy.frag, above the water, has none) */
    gl.ProgramUniform3f(copy->id, gl_program_uniform_optional(copy, "u_absorption"), c.x, c.y, c.z);
    renderer_draw_fullscreen(r);
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "common/object.vert", "water_surface/surface.frag", NULL, &prog, err))
        return false;
    gl_program_bind_texture(prog, "u_scene", in_color->texture.id);
    gl_program_bind_texture(prog, "u_scene_depth", in_depth->texture.id);
    gl_program_bind_texture(prog, "u_scene_position", in_pos->texture.id);
    const struct water_surface_params values = {
        .depth = water->water->depth,
        .level = water->position.y,
        .refract_mapping = pass_choice(p, SURFACE_MAPPING) == SURFACE_MAPPING_REFRACT,
        .eye_in_water = under,
    };
    if (!gl_param_block_upload(&s->params, &values, err) || !gl_param_block_bind(&s->params, prog, err))
        return false;
    renderer_draw_object(r, f->scene, prog, water);
    /* the panes in front of the water, over it (shade drew them under it) */
    return thin_glass_draw(&s->panes, p, f, THIN_GLASS_OVER_SURFACES, 0, &out->texture, in_depth ? &in_depth->texture : NULL, 0, water,
                                err);
}

static unsigned water_surface_draws(const struct pass *p)
{
    (void)p;
    return OBJECT_ROLE_WATER;
}

const struct pass_desc water_surface_pass = {
    .technique = PASS_TECHNIQUE_WATER_VIEW,
    .draws = water_surface_draws,
    .name = "water_surface",
    .summary = "Sandberg & Falemo's third pass: refraction mapping of the pool through the surface, Fresnel reflection",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = water_surface_declare,
    .create = water_surface_create,
    .execute = water_surface_execute,
    .destroy = water_surface_destroy,
};
