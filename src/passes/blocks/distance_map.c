/* distance_map: the distance impostor around the refractors, a building
 * block (issue 54; distance_map.h says what it holds and who reads it).
 * Szirmay-Kalos et al. 2005 for refraction's lookups (two layers, lit) and
 * Liktor & Dachsbacher §4.3 / §6 for the beams' exits (distances alone). */
#include "passes/blocks/distance_map.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "graph/frame.h"
#include "graph/medium_gpu.h"
#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"
#include "passes/helpers/thin_glass_over.h"

/* common/object.vert projected by each cube face's matrix */
#define DISTANCE_MAP_VIEW "#define OBJECT_VIEW_PROJ\n"

const struct record_type DISTANCE_MAP_RECORD = {"distance_map"};

static void distance_map_release(struct distance_map *m)
{
    for (int layer = 0; layer < 2; layer++) {
        gl_texture_destroy(&m->color[layer]);
        gl_texture_destroy(&m->distance[layer]);
    }
    gl_texture_destroy(&m->depth_buffer);
    gl_framebuffer_destroy(&m->fb);
    memset(m, 0, sizeof *m);
}

/* Whether a visible diffuse object morphs, deforms or is simulated (the
 * map holds the diffuse objects only: a deforming glass dragon does not
 * make it stale). */
static bool diffuse_animated(const struct scene *scene)
{
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        if (object_is(o, OBJECT_ROLE_RECEIVER) && object_is_animated_geometry(o))
            return true;
    }
    return false;
}

/* A program that lights the map's surfaces from its centre: the shadow
 * maps of the block's inputs (none: unshadowed), the medium, the centre. */
static bool bind_lighting(const struct gl_program *prog, struct pass *block, struct pass_frame *f, vec3 center,
                          struct error *err)
{
    shadow_inputs_bind(block, f, prog);
    if (!medium_gpu_bind(f->renderer, f->scene, prog, err))
        return false;
    gl.ProgramUniform3f(prog->id, gl_program_uniform(prog, "u_center"), center.x, center.y, center.z);
    return true;
}

/* The state every face of a map is drawn in: depth-tested, both sides. */
static void begin_faces(int size)
{
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_CULL_FACE);
    gl.Viewport(0, 0, size, size);
}

/* Renders the map around `center` (size x size per face): the visible
 * diffuse objects lit as `shade` lights them (Lambert, ambient, emission),
 * shadowed by the shadow maps of the block's inputs when it has any
 * (shadow_inputs). */
static bool distance_map_update(struct distance_map *m, struct renderer *r, struct pass *block,
                                struct pass_frame *f, vec3 center, int size, uint64_t key, struct error *err)
{
    const struct scene *scene = f->scene;
    m->built = false;
    if (m->size != size || !m->color[0].id) {
        distance_map_release(m);
        for (int layer = 0; layer < 2; layer++) {
            if (!gl_texture_create(&m->color[layer], GL_TEXTURE_CUBE_MAP, GL_RGBA16F, size, size, 6, err) ||
                !gl_texture_create(&m->distance[layer], GL_TEXTURE_CUBE_MAP, GL_R32F, size, size, 6, err))
                return false;
            gl.TextureParameteri(m->distance[layer].id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            gl.TextureParameteri(m->distance[layer].id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            gl.TextureParameteri(m->color[layer].id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            gl.TextureParameteri(m->color[layer].id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            for (int k = 0; k < 2; k++) {
                GLuint id = k ? m->distance[layer].id : m->color[layer].id;
                gl.TextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
                gl.TextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
                gl.TextureParameteri(id, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
            }
        }
        if (!gl_texture_create(&m->depth_buffer, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, size, size, 1, err) ||
            !gl_framebuffer_create(&m->fb, err))
            return false;
        m->size = size;
    }
    /* Lambert's program and, where the scene has glTF-BRDF surfaces, its
     * variant for them (renderer_draw_lit), set up alike */
    struct gl_program *progs[2];
    if (!renderer_lit_programs(r, scene, "common/object.vert", "distance_map/distance.frag", DISTANCE_MAP_VIEW, progs,
                               err))
        return false;
    for (int k = 0; k < 2 && progs[k]; k++) {
        /* lit as shade lights (common/surface_light.glsl) */
        if (!bind_lighting(progs[k], block, f, center, err))
            return false;
    }
    /* Thin-walled glass over the diffuse surfaces it lies in front of, as
     * shade blends it (common/thin_glass.frag, seen from the centre): a pane
     * behind the glass tints what a ray that leaves the glass finds there. */
    struct gl_program *panes = NULL;
    if (thin_glass_in_scene(scene)) {
        if (!gl_program_get(&r->programs, "common/object.vert", "common/thin_glass.frag",
                            DISTANCE_MAP_VIEW "#define VIEW_FROM_CENTER 1\n", &panes, err))
            return false;
        if (!bind_lighting(panes, block, f, center, err))
            return false;
        gl.ProgramUniform1i(panes->id, gl_program_uniform(panes, "u_panes"), 0);
        gl_program_bind_texture(panes, "u_surface_depth", r->dummy_2d.id);
    }
    /* near: a hundredth of the scene's size around the centre (what is
     * nearer than that is inside the refractor); far: the whole scene */
    vec3 lo, hi;
    float extent = scene_bounds(scene, &lo, &hi) ? vec3_length(vec3_sub(hi, lo)) : 10.0f;
    float reach = fmaxf(vec3_length(vec3_sub(hi, center)), vec3_length(vec3_sub(lo, center)));
    float far = fmaxf(fmaxf(extent, reach) * 2.0f, 1e-2f);
    mat4 proj = mat4_perspective(90.0f, 1.0f, fmaxf(far * 1e-5f, 1e-4f), far);
    begin_faces(size);
    for (int i = 0; i < 12; i++) {
        int layer = i / 6, face = i % 6;
        mat4 vp = mat4_mul(proj, mat4_cube_face_view(center, face));
        for (int k = 0; k < 2 && progs[k]; k++) {
            struct gl_program *prog = progs[k];
            /* the second layer reads the first's distances (what to peel) */
            gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_layer"), layer);
            gl_program_bind_texture(prog, "u_first", layer ? m->distance[0].id : r->dummy_cube.id);
            gl.ProgramUniformMatrix4fv(prog->id, gl_program_uniform(prog, "u_object_view_proj"), 1, GL_FALSE, vp.m);
        }
        const struct gl_texture *colors[2] = {&m->color[layer], &m->distance[layer]};
        int layers[2] = {face, face};
        if (!gl_framebuffer_attach(&m->fb, colors, layers, 2, &m->depth_buffer, -1, err))
            return false;
        gl.BindFramebuffer(GL_FRAMEBUFFER, m->fb.id);
        const float black[4] = {0.0f, 0.0f, 0.0f, 0.0f}, none[4] = {1e30f, 0.0f, 0.0f, 0.0f}; /* no surface */
        gl.ClearNamedFramebufferfv(m->fb.id, GL_COLOR, 0, black);
        gl.ClearNamedFramebufferfv(m->fb.id, GL_COLOR, 1, none);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        renderer_draw_lit(r, scene, progs[0], progs[1], DRAW_DIFFUSE);
        if (panes) {
            /* the colour alone (dual-source blending writes one draw buffer), the distance kept */
            static const GLenum color_only[2] = {GL_COLOR_ATTACHMENT0, GL_NONE};
            gl.NamedFramebufferDrawBuffers(m->fb.id, 2, color_only);
            gl.ProgramUniformMatrix4fv(panes->id, gl_program_uniform(panes, "u_object_view_proj"), 1, GL_FALSE, vp.m);
            gl.DepthMask(GL_FALSE);
            gl.Enablei(GL_BLEND, 0);
            gl.BlendFunci(0, GL_ONE, GL_SRC1_COLOR);
            renderer_draw_objects(r, scene, panes, DRAW_THIN);
            gl.Disablei(GL_BLEND, 0);
            gl.DepthMask(GL_TRUE);
            static const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
            gl.NamedFramebufferDrawBuffers(m->fb.id, 2, both);
        }
    }
    gl.DepthFunc(GL_LESS);
    if (!gl_check("building the distance map", err))
        return false;
    m->center = center;
    m->range = 0.0f;
    m->content = DISTANCE_MAP_RADIANCE;
    m->built = true;
    m->built_key = key;
    return true;
}

/* The distances alone (layer 0, no colour) around `center` out to `range`:
 * the receivers' distance impostor beam_caustics traces its exits against
 * (Szirmay-Kalos et al. 2005; Liktor & Dachsbacher §4.3). No surface within
 * the range reads as the range; the faces are filtered (linear), as the
 * beams' march expects. */
static bool distance_map_update_distances(struct distance_map *m, struct renderer *r, struct pass_frame *f,
                                          vec3 center, int size, float range, uint64_t key, struct error *err)
{
    const struct scene *scene = f->scene;
    m->built = false;
    if (m->size != size || !m->distance[0].id || m->color[0].id) {
        distance_map_release(m);
        if (!gl_texture_create(&m->distance[0], GL_TEXTURE_CUBE_MAP, GL_R32F, size, size, 6, err) ||
            !gl_texture_create(&m->depth_buffer, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, size, size, 1, err) ||
            !gl_framebuffer_create(&m->fb, err))
            return false;
        m->size = size;
    }
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "common/object.vert", "distance_map/distances.frag", DISTANCE_MAP_VIEW, &prog, err))
        return false;
    gl.UseProgram(prog->id);
    gl.ProgramUniform3f(prog->id, gl_program_uniform(prog, "u_center"), center.x, center.y, center.z);
    mat4 proj = mat4_perspective(90.0f, 1.0f, fmaxf(range * 1e-5f, 1e-5f), range);
    begin_faces(size);
    for (int face = 0; face < 6; face++) {
        const struct gl_texture *colors[1] = {&m->distance[0]};
        int layers[1] = {face};
        if (!gl_framebuffer_attach(&m->fb, colors, layers, 1, &m->depth_buffer, -1, err))
            return false;
        gl.BindFramebuffer(GL_FRAMEBUFFER, m->fb.id);
        const float none[4] = {range, range, range, range};
        gl.ClearNamedFramebufferfv(m->fb.id, GL_COLOR, 0, none);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        mat4 vp = mat4_mul(proj, mat4_cube_face_view(center, face));
        gl.ProgramUniformMatrix4fv(prog->id, gl_program_uniform(prog, "u_object_view_proj"), 1, GL_FALSE, vp.m);
        renderer_draw_objects(r, scene, prog, DRAW_DIFFUSE);
    }
    renderer_reset_state(r);
    if (!gl_check("building the distance impostor", err))
        return false;
    m->center = center;
    m->range = range;
    m->content = DISTANCE_MAP_DISTANCES;
    m->built = true;
    m->built_key = key;
    return true;
}

/* The block's parameters by index (pass_int(p, DM_SIZE)). */
enum distance_map_param { DM_CONTENT, DM_SIZE, DM_AROUND, DM_SHADOW };
enum { AROUND_SPECULAR, AROUND_REFRACTORS }; /* the choices of `around`, in order */

static const struct pass_param_desc params[] = {
    [DM_CONTENT] = {.name = "content", .type = PASS_PARAM_ENUM, .default_string = "radiance",
     .choices = "radiance|distances",
     .help = "radiance: two layers of the diffuse surfaces seen from the centre, lit as shade lights them, with their "
             "distances (refraction's lookups); distances: the nearest surface's distance alone, filtered, out past "
             "the whole scene (beam_caustics' exits)"},
    [DM_SIZE] = {.name = "size", .type = PASS_PARAM_INTEGER, .default_number = 256, .min = 16, .max = 4096,
     .help = "texels per side of each cube face"},
    [DM_AROUND] = {.name = "around", .type = PASS_PARAM_ENUM, .default_string = "specular",
     .choices = "specular|refractors",
     .help = "its centre: the middle of the box of the visible glass, water and mirrors (refraction's), or of the "
             "glass and water alone (beam_caustics')"},
    [DM_SHADOW] = {.name = "shadow", .type = PASS_PARAM_INPUT_LIST, .max = SHADOW_INPUTS_MAX,
     .record = &SHADOW_MAP_RECORD,
     .help = "shadow maps that light the radiance as shade's light the scene (e.g. \"shadow.depth\"); without them "
             "it is unshadowed"},
};

bool distance_map_configure_block(struct pass *block, enum distance_map_content content, int size, unsigned around,
                                  const struct pass *reader, int reader_shadow, struct error *err)
{
    if (!pass_set_enum(block, "content", content == DISTANCE_MAP_RADIANCE ? "radiance" : "distances", err) ||
        !pass_set_number(block, "size", size, err) ||
        !pass_set_enum(block, "around", around == OBJECT_ROLE_REFRACTOR ? "refractors" : "specular", err))
        return false;
    return shadow_inputs_give(block, reader, reader_shadow, err);
}

static bool distance_map_declare(struct pass *p, struct error *err)
{
    /* shadow0.. are declared from the descriptor (pass_declare) */
    return pass_declare_bundle(p, "map", &DISTANCE_MAP_RECORD, err);
}

static bool distance_map_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    p->state = calloc(1, sizeof(struct distance_map));
    return p->state ? true : error_set(err, "out of memory");
}

static void distance_map_destroy(struct pass *p)
{
    if (!p->state)
        return;
    distance_map_release(p->state);
    free(p->state);
    p->state = NULL;
}

/* This frame's centre, range (distances: past the whole scene from the
 * centre) and the key a map is made under: the block's pass_frame_key
 * with what its content depends on, the centre, size and range. False:
 * nothing to centre it on. */
static bool map_frame(const struct pass *p, const struct pass_frame *f, vec3 *center, float *range, uint64_t *key)
{
    vec3 lo, hi;
    unsigned around = pass_choice(p, DM_AROUND) == AROUND_SPECULAR ? OBJECT_ROLE_SPECULAR : OBJECT_ROLE_REFRACTOR;
    if (!scene_role_bounds(f->scene, around, &lo, &hi))
        return false;
    *center = vec3_scale(vec3_add(lo, hi), 0.5f);
    *range = 0.0f;
    bool radiance = pass_choice(p, DM_CONTENT) == DISTANCE_MAP_RADIANCE;
    vec3 slo, shi;
    if (!radiance && scene_bounds(f->scene, &slo, &shi))
        *range = fmaxf(2.0f * (vec3_length(vec3_sub(shi, slo)) +
                               vec3_length(vec3_sub(*center, vec3_scale(vec3_add(slo, shi), 0.5f)))),
                       1e-3f);
    int size = pass_int(p, DM_SIZE);
    uint64_t k = pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY | (radiance ? PASS_DEPENDS_LIGHTS : 0u));
    k = pass_key_mix(k, center, sizeof *center);
    k = pass_key_mix(k, &size, sizeof size);
    *key = pass_key_mix(k, range, sizeof *range);
    return true;
}

/* A static scene keeps the last map; only the receivers' animation counts
 * (a deforming glass dragon does not make it stale). */
static enum pass_need distance_map_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    struct distance_map *m = p->state;
    vec3 center;
    float range;
    uint64_t key;
    if (!map_frame(p, f, &center, &range, &key)) {
        m->built = false;
        snprintf(why, whylen, "the scene has no visible %s to centre it on",
                 pass_choice(p, DM_AROUND) == AROUND_SPECULAR ? "glass, water or mirror" : "glass or water");
        return PASS_SKIP;
    }
    if (m->built && m->built_key == key && !diffuse_animated(f->scene)) {
        snprintf(why, whylen, "reuses its map: its parameters, the receivers%s did not change",
                 pass_choice(p, DM_CONTENT) == DISTANCE_MAP_RADIANCE ? ", the lights" : "");
        return PASS_REUSE;
    }
    return PASS_RUN;
}

static bool distance_map_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct distance_map *m = p->state;
    pass_frame_output(p, f, "map")->record = m;
    vec3 center;
    float range;
    uint64_t key;
    if (!map_frame(p, f, &center, &range, &key)) {
        m->built = false;
        return true;
    }
    int size = pass_int(p, DM_SIZE);
    bool radiance = pass_choice(p, DM_CONTENT) == DISTANCE_MAP_RADIANCE;
    if (radiance ? !distance_map_update(m, f->renderer, p, f, center, size, key, err)
                 : !distance_map_update_distances(m, f->renderer, f, center, size, range, key, err))
        return false;
    snprintf(p->report, sizeof p->report, "%s around (%.3g, %.3g, %.3g), %d x %d texels a face",
             radiance ? "two layers of radiance and distance" : "distances", (double)center.x, (double)center.y,
             (double)center.z, size, size);
    return true;
}

const struct pass_desc distance_map_pass = {
    .name = "distance_map",
    .summary = "building block: a cube map of the receivers' radiance and distance around the refractors "
               "(Szirmay-Kalos et al. 2005), shared by refraction's lookups and beam_caustics' exits",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = distance_map_declare,
    .create = distance_map_create,
    .execute = distance_map_execute,
    .needed = distance_map_needed,
    .destroy = distance_map_destroy,
};
