/* caustic_volumes: Sandberg & Falemo's water caustics. Every triangle of
 * the water surface and the three light rays refracted at its vertices
 * bound a caustic volume (§3.2); the volumes are built on the GPU each
 * frame (a compute shader), drawn with additive blending, depth writes off
 * and back-face culling (§3.5), and each fragment tests the receiver point
 * seen at its pixel against its volume by cutting the volume with the
 * horizontal plane through the point (§3.3). Inside, it adds the
 * irradiance I0 exp(-c d) F_P, F_P the ratio of the generator triangle's
 * area to the cut triangle's (§3.4). For a camera under water, inside the
 * volumes, the front faces are culled instead of the back ones.
 *
 * Departures, each for a reason: the pass writes caustic *irradiance* into
 * a texture that `shade` multiplies by the receiver's albedo / pi (instead
 * of radiance straight into the frame buffer), so it composes with any
 * shading; the irradiance is converted from the horizontal cut to the
 * receiver's own normal (exact for a floor, and right for the pots and the
 * bunny of Fig. 3/7); and F_P is capped (parameter `cap`, by default a
 * quarter of the grid's resolution: a caustic cannot be sharper than the
 * generator grid resolves), so focusing never gives Inf. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_param_block.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"
#include "scene/scene.h"
#include "scene/water.h"

#define VOLUME_VEC4S 10 /* per volume: top[3], dir[3], bottom[3], flux (std430) */

/* The C mirror of CausticVolumesParams (shaders/caustic_volumes/
 * volume.glsl, std140): both passes' values, uploaded in one call (issue 54). */
struct caustic_volumes_params {
    float model[16], normal_matrix[16];
    float attenuation[3], ior;
    int32_t water_resolution[2], resolution[2];
    int32_t triangles, light;
    float ideal, bottom, cap;
    int32_t pad[3];
};

#define CV_PARAM(field, name) {name, offsetof(struct caustic_volumes_params, field)}
static const struct gl_block_member caustic_volumes_params_members[] = {
    CV_PARAM(model, "u_model"), CV_PARAM(normal_matrix, "u_normal_matrix"), CV_PARAM(attenuation, "u_attenuation"),
    CV_PARAM(ior, "u_ior"), CV_PARAM(water_resolution, "u_water_resolution"), CV_PARAM(resolution, "u_resolution"),
    CV_PARAM(triangles, "u_triangles"), CV_PARAM(light, "u_light"), CV_PARAM(ideal, "u_ideal"),
    CV_PARAM(bottom, "u_bottom"), CV_PARAM(cap, "u_cap"),
};
#undef CV_PARAM

struct caustic_volumes_state {
    struct gl_param_block params; /* CausticVolumesParams, this frame's */
    struct gl_framebuffer volumes_fb;
    GLuint volumes;      /* SSBO, owned */
    size_t capacity;     /* volumes it holds */
};

/* The parameters by index (pass_int(p, ...), pass_light_at(p, ...)): `params`
 * below is filled with these as designated initializers, so the two cannot
 * drift apart. */
enum caustic_volumes_param {
    VOLUMES_LIGHT,
    VOLUMES_WATER,
    VOLUMES_CAP,
    VOLUMES_RESOLUTION,
    VOLUMES_RECEIVERS,
    VOLUMES_RECEIVER_POSITION,
    VOLUMES_SHADOW,
};

static const struct pass_param_desc params[] = {
    [VOLUMES_LIGHT] = {.name = "light", .type = PASS_PARAM_LIGHT, .required = true, .help = "a directional or point light"},
    [VOLUMES_WATER] = {.name = "water", .type = PASS_PARAM_OBJECT, .required = true, .help = "the water surface (c.water{...})"},
    [VOLUMES_CAP] = {.name = "cap", .type = PASS_PARAM_NUMBER, .default_number = 0, .min = 0, .max = 1e6,
     .help = "largest flux ratio F_P (0: a quarter of the generator grid's resolution)"},
    [VOLUMES_RESOLUTION] = {.name = "resolution", .type = PASS_PARAM_INTEGER, .default_number = 0, .min = 0, .max = 4096,
     .help = "generator grid, vertices along the water's longer side, resampled from the surface (0: the water's own grid)"},
    [VOLUMES_RECEIVERS] = {.name = "receivers", .type = PASS_PARAM_INPUT, .block = "receivers", .default_output = "normal",
     .help = "the camera's receivers (a receivers pass's normal; §3.5's pass 1): by default the graph adds one with "
             "positions, shared with the other caustics passes"},
    [VOLUMES_RECEIVER_POSITION] = {.name = "receiver_position", .type = PASS_PARAM_INPUT, .default_beside = "receivers",
     .default_output = "position", .help = "their world positions (by default beside `receivers`: a receivers pass "
                                           "with position = true)"},
    [VOLUMES_SHADOW] = SHADOW_PARAM_PANES("a surface triangle's volume"),
};

static bool caustic_volumes_declare(struct pass *p, struct error *err)
{
    struct object *w = pass_object_at(p, VOLUMES_WATER);
    if (!w->water)
        return error_set(err, "bad argument 'water' to 'caustic_volumes' (a water surface from c.water{...} expected, got "
                              "an ordinary object)");
    struct light *l = pass_light_at(p, VOLUMES_LIGHT);
    if (l->kind != LIGHT_DIRECTIONAL && l->kind != LIGHT_POINT)
        return error_set(err, "bad argument 'light' to 'caustic_volumes' (a directional or point light expected, got a "
                              "%s light)", light_kind_name(l->kind));
    return pass_declare_output(p, "irradiance", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool caustic_volumes_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct caustic_volumes_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("CausticVolumesParams",
                                  caustic_volumes_params_members, struct caustic_volumes_params);
    p->state = s;
    return gl_framebuffer_create(&s->volumes_fb, err);
}

static void caustic_volumes_destroy(struct pass *p)
{
    struct caustic_volumes_state *s = p->state;
    if (!s)
        return;
    gl_framebuffer_destroy(&s->volumes_fb);
    if (s->volumes && gl_api_ready())
        gl.DeleteBuffers(1, &s->volumes);
    gl_param_block_release(&s->params);
    free(s);
    p->state = NULL;
}

/* The scene does not ask for caustics when the water is hidden or the sun
 * is below its horizon: the pass is left out of the frame (its irradiance
 * reads as zero). */
static enum pass_need caustic_volumes_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    (void)f;
    struct object *water = pass_object_at(p, VOLUMES_WATER);
    struct light *light = pass_light_at(p, VOLUMES_LIGHT);
    if (!water->visible) {
        snprintf(why, whylen, "left out: the water surface is hidden");
        return PASS_SKIP;
    }
    if (light->kind == LIGHT_DIRECTIONAL && light->direction.y >= 0.0f) {
        snprintf(why, whylen, "left out: the light is below the horizon, no light enters the water");
        return PASS_SKIP;
    }
    return PASS_RUN;
}

static bool caustic_volumes_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct caustic_volumes_state *s = p->state;
    struct renderer *r = f->renderer;
    struct object *water = pass_object_at(p, VOLUMES_WATER);
    struct light *light = pass_light_at(p, VOLUMES_LIGHT);
    int light_index = renderer_light_slot(f->renderer, f->scene, light);
    if (light_index < 0)
        return error_set(err, "its light was never added to the scene (use scene:add(light))");
    struct graph_resource *irr = pass_frame_output(p, f, "irradiance"), *pos = pass_frame_input(p, f, "receiver_position"),
                          *nrm = pass_frame_input(p, f, "receivers");
    if (!pos || !nrm)
        return error_set(err, "the receivers' positions and normals were not made this frame");
    const float zero[4] = {0, 0, 0, 0};

    /* The caustic volumes, built on the GPU from this frame's surface,
     * resampled (bilinearly) onto the generator grid. */
    const struct water *w = water->water;
    int gen_x = w->nx, gen_z = w->nz;
    if (pass_int(p, VOLUMES_RESOLUTION) >= 2) /* the same aspect as the water's own grid */
        water_grid_counts(pass_int(p, VOLUMES_RESOLUTION), w->size_x, w->size_z, &gen_x, &gen_z);
    int gen_res = gen_x > gen_z ? gen_x : gen_z;
    size_t triangles = (size_t)(gen_x - 1) * (size_t)(gen_z - 1) * 2;
    if (s->capacity < triangles) {
        if (s->volumes)
            gl.DeleteBuffers(1, &s->volumes);
        gl.CreateBuffers(1, &s->volumes);
        gl.NamedBufferStorage(s->volumes, (GLsizeiptr)(triangles * VOLUME_VEC4S * 4 * sizeof(float)), NULL, 0);
        s->capacity = triangles;
    }
    vec3 lo, hi;
    scene_bounds(f->scene, &lo, &hi);
    float bottom = lo.y - 0.01f - 0.01f * (hi.y - lo.y); /* just below the deepest receiver (§3.5) */
    double cap = pass_real(p, VOLUMES_CAP) > 0 ? pass_real(p, VOLUMES_CAP) : 0.25 * gen_res;
    struct gl_program *build;
    if (!gl_program_get_compute(&r->programs, "caustic_volumes/build.comp", NULL, NULL, &build, err))
        return false;
    /* The water's vertices of this frame (the simulation fills them). */
    struct gpu_object *surface = mesh_cache_object(&r->meshes, water, err);
    if (!surface)
        return false;
    gl.UseProgram(build->id);
    gl_program_bind_storage(build, "Positions", surface->deformed_positions);
    gl_program_bind_storage(build, "Normals", surface->deformed_normals);
    gl_program_bind_storage(build, "Volumes", s->volumes);
    const struct frame_object *fw = frame_object_of(f->snapshot, water);
    if (!fw)
        return error_set(err, "caustic_volumes: the water surface is not in the scene (scene:add it)");
    struct caustic_volumes_params values = {
        .attenuation = {water->material.absorption.x, water->material.absorption.y, water->material.absorption.z},
        .ior = water->material.ior,
        .water_resolution = {w->nx, w->nz},
        .resolution = {gen_x, gen_z},
        .triangles = (int32_t)triangles,
        .light = light_index,
        .ideal = water->material.ideal ? 1.0f : 0.0f,
        .bottom = bottom,
        .cap = (float)cap,
    };
    memcpy(values.model, fw->model.m, sizeof values.model);
    memcpy(values.normal_matrix, fw->normal_matrix.m, sizeof values.normal_matrix);
    if (!gl_param_block_upload(&s->params, &values, err) || !gl_param_block_bind(&s->params, build, err))
        return false;
    shadow_inputs_bind(p, f, build); /* the panes between the light and the water (its pane filter) */
    gl_program_dispatch(build, (int)triangles, 1, 1, GL_SHADER_STORAGE_BARRIER_BIT);

    /* Pass 2 (§3.5): additive blending, no depth writes, one side culled.
     * A convex volume covers each of its pixels with exactly one front face
     * and one back face while the camera is outside it: above the water we
     * cull back faces as the paper does. A camera under water is inside
     * most volumes, where the front faces are behind it; there we cull the
     * front faces instead and keep the back ones, which still cover each
     * pixel once. */
    bool camera_above = f->scene->camera.eye.y > water->position.y;
    const struct gl_texture *irr_target[1] = {&irr->texture};
    if (!gl_framebuffer_attach(&s->volumes_fb, irr_target, NULL, 1, NULL, -1, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->volumes_fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.ClearNamedFramebufferfv(s->volumes_fb.id, GL_COLOR, 0, zero);
    struct gl_program *draw;
    if (!gl_program_get(&r->programs, "caustic_volumes/volume.vert", "caustic_volumes/volume.frag", NULL, &draw, err))
        return false;
    gl.UseProgram(draw->id);
    gl_program_bind_storage(draw, "Volumes", s->volumes);
    gl_program_bind_texture(draw, "u_positions", pos->texture.id);
    gl_program_bind_texture(draw, "u_normals", nrm->texture.id);
    if (!gl_param_block_bind(&s->params, draw, err))
        return false;
    gl.Enable(GL_BLEND);
    gl.BlendEquation(GL_FUNC_ADD);
    gl.BlendFunc(GL_ONE, GL_ONE);
    gl.DepthMask(GL_FALSE);
    gl.Enable(GL_CULL_FACE);
    gl.CullFace(camera_above ? GL_BACK : GL_FRONT);
    gl.FrontFace(GL_CCW);
    gl.BindVertexArray(r->empty_vao);
    gl.DrawArrays(GL_TRIANGLES, 0, (GLsizei)(triangles * 24));
    gl.BindVertexArray(0);
    return true;
}

/* Sandberg & Falemo's volumes hang from one water surface's triangles. */
static const char *caustic_volumes_leaves_out(const struct pass *p, const struct scene *scene,
                                              const struct object *o)
{
    if (object_is(o, OBJECT_ROLE_WATER))
        return o == pass_object_at(p, VOLUMES_WATER)
                   ? NULL
                   : "only the water surface named by `water` makes caustic volumes: no caustics through this one "
                     "(add a caustic_volumes pass for it)";
    if (object_is(o, OBJECT_ROLE_THIN))
        return shadow_inputs_pane_left_out(p, scene, o); /* undeviated: no caustic of its own */
    return "caustic volumes are built from the water surface named by `water` alone: no caustics through glass "
           "or off a mirror (photon_caustics or layered_caustics make them)";
}

/* The receivers it reads (issue 26): with their world positions, which
 * §3.5 cuts the volumes at. */
static bool caustic_volumes_configure_block(const struct pass *p, int param, struct pass *block, struct error *err)
{
    (void)p;
    (void)param;
    return pass_set_boolean(block, "position", true, err);
}

const struct pass_desc caustic_volumes_pass = {
    .technique = PASS_TECHNIQUE_WATER_CAUSTICS,
    .surface_caustics_only = true,
    .name = "caustic_volumes",
    .leaves_out = caustic_volumes_leaves_out,
    .configure_block = caustic_volumes_configure_block,
    .summary = "Sandberg & Falemo: water caustics as volumes per surface triangle (irradiance for shade)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = caustic_volumes_declare,
    .create = caustic_volumes_create,
    .execute = caustic_volumes_execute,
    .needed = caustic_volumes_needed,
    .destroy = caustic_volumes_destroy,
};
