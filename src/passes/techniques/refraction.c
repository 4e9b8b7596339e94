/* refraction: two-sided image-space refraction of environment maps,
 * Hu & Qin §2.1 (method "huqin"), with Wyman's 2005 method as the baseline
 * it improves on (method "wyman").
 *
 * Initial pass: normals and depths of the front- and back-facing surfaces
 * of the refractive objects (glass, water) into buffers. Rendering pass,
 * per fragment of the visible front surface: T1 from Snell at P1; for
 * "huqin", the dividing pixel p_e by a binary search along the projected
 * T1 (Fig. 7) decides whether P2 lies on the back- or the front-facing
 * surface (§2.1.2), and d_T comes from the iterative depth-buffer lookup
 * of Fig. 9 (§2.1.3); for "wyman", d_T interpolates the view-ray
 * thickness d_V and a precomputed per-vertex thickness d_N by the angles
 * (Wyman 2005). N2 comes from the matching normal buffer (§2.1.4); T2 goes
 * into the environment. Total internal reflection at either interface
 * reflects (never a NaN); every loop has a cap. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_buffer.h"
#include "gl/gl_param_block.h"
#include "graph/frame.h"
#include "graph/medium_gpu.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/blocks/distance_map.h"
#include "passes/blocks/impostors.h"
#include "passes/helpers/layers.h"
#include "passes/helpers/shadow_inputs.h"
#include "passes/helpers/thin_glass_over.h"
#include "scene/scene.h"

#define MAX_ITERATIONS 16
#define MAX_SEARCH_STEPS 16

struct refraction_state {
    const struct impostor_set *impostors; /* the impostors block's, this frame (NULL: the lookup reads none) */
    struct thin_glass_over panes;
    struct gl_framebuffer front_fb, back_fb, out_fb;
    struct gl_texture front_normal, back_normal, front_depth, back_depth;
    /* rough glass: the input image and the `behind` image with mipmaps, for the
     * cone lookup of refract.frag's seen_rough (made when a refractor is rough) */
    struct gl_texture rough_scene, rough_behind;
    int width, height;
    struct gl_param_block params; /* refract.frag's RefractionParams, uploaded each frame */
};

/* The C mirror of refract.frag's RefractionParams block (std140: 4-byte
 * members in order; padded to the block's 16-byte multiple), uploaded in
 * one call a frame (issue 54: a pass's parameters as one block, as Frame
 * is, instead of a look-up by name per uniform). */
struct refraction_params {
    int32_t iterations;
    float tolerance;
    int32_t search_steps;
    int32_t correction;
    int32_t reflection;
    float reach;
    int32_t internal;
    int32_t pad;
};

static const struct gl_block_member refraction_params_members[] = {
    {"u_iterations", offsetof(struct refraction_params, iterations)},
    {"u_tolerance", offsetof(struct refraction_params, tolerance)},
    {"u_search_steps", offsetof(struct refraction_params, search_steps)},
    {"u_correction", offsetof(struct refraction_params, correction)},
    {"u_reflection", offsetof(struct refraction_params, reflection)},
    {"u_reach", offsetof(struct refraction_params, reach)},
    {"u_internal", offsetof(struct refraction_params, internal)},
};

/* The parameters by index (pass_int(p, ...), pass_light_at(p, ...)): `params`
 * below is filled with these as designated initializers, so the two cannot
 * drift apart. */
/* Choices of `method`, in the order of its `choices`. */
enum { REFRACTION_METHOD_HUQIN, REFRACTION_METHOD_WYMAN };
/* Choices of `lookup`. */
enum { REFRACTION_LOOKUP_SCENE, REFRACTION_LOOKUP_MAP, REFRACTION_LOOKUP_IMPOSTORS };

enum refraction_param {
    REFRACTION_METHOD,
    REFRACTION_COLOR,
    REFRACTION_DEPTH,
    REFRACTION_ITERATIONS,
    REFRACTION_TOLERANCE,
    REFRACTION_SEARCH_STEPS,
    REFRACTION_REFLECTION,
    REFRACTION_NEARBY,
    REFRACTION_IMPOSTOR,
    REFRACTION_CORRECTION,
    REFRACTION_RECURSION,
    REFRACTION_LOOKUP,
    REFRACTION_SHADOW,
    REFRACTION_INTERNAL,
    REFRACTION_DISTANCE_MAP,
    REFRACTION_IMPOSTORS,
    REFRACTION_BEHIND,
    REFRACTION_BEHIND_DEPTH,
};

static const struct pass_param_desc params[] = {
    [REFRACTION_METHOD] = {.name = "method", .type = PASS_PARAM_ENUM, .default_string = "huqin", .choices = "huqin|wyman",
     .help = "huqin (Hu & Qin 2007) or wyman (Wyman 2005, the baseline)"},
    [REFRACTION_COLOR] = {.name = "color", .type = PASS_PARAM_INPUT, .required = true, .help = "the scene image to draw over"},
    [REFRACTION_DEPTH] = {.name = "depth", .type = PASS_PARAM_INPUT, .default_beside = "color", .default_output = "depth",
     .help = "its depth (the refractors' front surfaces); default: the depth output of the pass that made color"},
    [REFRACTION_ITERATIONS] = {.name = "iterations", .type = PASS_PARAM_INTEGER, .default_number = 3, .min = 0, .max = MAX_ITERATIONS,
     .help = "iterations of the d_T lookup (Fig. 9); 0 keeps the first estimate"},
    [REFRACTION_TOLERANCE] = {.name = "tolerance", .type = PASS_PARAM_NUMBER, .default_number = 1e-4, .min = 0, .max = 1,
     .help = "stop the d_T iteration when a step is below this (scene units)"},
    [REFRACTION_SEARCH_STEPS] = {.name = "search_steps", .type = PASS_PARAM_INTEGER, .default_number = 8, .min = 1, .max = MAX_SEARCH_STEPS,
     .help = "binary search steps for the dividing pixel p_e (Fig. 7)"},
    [REFRACTION_REFLECTION] = {.name = "reflection", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "add the Fresnel-weighted reflection (Fig. 24 a-e show refraction alone)"},
    [REFRACTION_NEARBY] = {.name = "nearby", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "reflect and refract the nearby (diffuse) objects, not only the environment (§2.2; how: lookup)"},
    [REFRACTION_IMPOSTOR] = {.name = "impostor", .type = PASS_PARAM_INTEGER, .default_number = 256, .min = 16, .max = 4096,
     .help = "impostor texture size (the rectangles', or each face of the distance map)"},
    [REFRACTION_CORRECTION] = {.name = "correction", .type = PASS_PARAM_INTEGER, .default_number = 3, .min = 0, .max = 16,
     .help = "iterations of the impostor correction (Fig. 16); 0 uses the rectangle's point"},
    [REFRACTION_RECURSION] = {.name = "recursion", .type = PASS_PARAM_INTEGER, .default_number = 0, .min = 0, .max = 4,
     .help = "levels of recursive reflection/refraction through the reflectors' own impostors (Fig. 1b, 24g; "
             "uses the impostors whatever the lookup)"},
    [REFRACTION_LOOKUP] = {.name = "lookup", .type = PASS_PARAM_ENUM, .default_string = "scene",
     .choices = "scene|map|impostors",
     .help = "how a ray leaving the glass finds the nearby objects: scene = the input image searched in screen "
             "space (exact where it shows what the ray meets), then a two-layer distance map around the refractors "
             "(Szirmay-Kalos et al. 2005: floors and walls too); map = the distance map alone; impostors = the "
             "paper's one rectangle per object "
             "(§2.2), which large receivers break (docs/techniques/hu_qin.md)"},
    [REFRACTION_SHADOW] = {.name = "shadow", .type = PASS_PARAM_INPUT_LIST, .max = SHADOW_INPUTS_MAX,
     .record = &SHADOW_MAP_RECORD,
     .help = "shadow maps for lighting the distance map's surfaces and the diffuse share of partly "
             "transmissive glass as shade does (e.g. \"shadow.depth\"); without them they are unshadowed"},
    [REFRACTION_INTERNAL] = {.name = "internal", .type = PASS_PARAM_INTEGER, .default_number = 4, .min = 1, .max = 8,
     .help = "interfaces a path meets from its first way out on: 1 = the paper's two interfaces (a total internal "
             "reflection leaves along its reflection); more follow total internal reflections and the Fresnel-"
             "reflected part inside (huqin only)"},
    [REFRACTION_DISTANCE_MAP] = {.name = "distance_map", .type = PASS_PARAM_INPUT, .block = "distance_map",
     .bundle = &DISTANCE_MAP_RECORD, .default_output = "map",
     .help = "the distance map the lookups \"scene\" and \"map\" read (a distance_map pass's `map`, content = "
             "\"radiance\"): by default the graph adds one of `impostor` texels a face, lit through `shadow`, "
             "shared with any reader that wants the same"},
    [REFRACTION_IMPOSTORS] = {.name = "impostors", .type = PASS_PARAM_INPUT, .block = "impostors",
     .bundle = &IMPOSTOR_SET_RECORD, .default_output = "set",
     .help = "the nearby objects' impostors the lookup \"impostors\" and recursion read (an impostors pass's "
             "`set`): by default the graph adds one of `impostor` texels at `recursion`, lit through `shadow`, "
             "shared with any reader that wants the same"},
    [REFRACTION_BEHIND] = {.name = "behind", .type = PASS_PARAM_INPUT, .block = "shade", .default_output = "color",
     .help = "the lookup \"scene\"'s image of what lies behind the glass where `color` shows the glass itself (a "
             "shade pass's `color` with specular = false): by default the graph adds one lit through `shadow`, "
             "shared with any reader that wants the same"},
    [REFRACTION_BEHIND_DEPTH] = {.name = "behind_depth", .type = PASS_PARAM_INPUT, .default_beside = "behind",
     .default_output = "depth", .help = "its depth; default: the depth output of the pass that made behind"},
};

static bool refraction_declare(struct pass *p, struct error *err)
{
    /* color, depth and shadow0.. are declared from the descriptor (pass_declare). */
    /* tir: r = total internal reflection at the paper's two interfaces (1
     * or 0; 0 off the refractors), g = all the path met (`internal`);
     * exit: rgb = the direction the path first leaves the refractor in,
     * a = 1 on a refractor.
     * Debug outputs to hold against theory and against `reference --aov
     * tir`, which traces the same two interfaces exactly. */
    return pass_declare_output(p, "color", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err) &&
           pass_declare_output(p, "tir", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err) &&
           pass_declare_output(p, "exit", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool refraction_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct refraction_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("RefractionParams", refraction_params_members, struct refraction_params);
    p->state = s;
    return gl_framebuffer_create(&s->front_fb, err) && gl_framebuffer_create(&s->back_fb, err) &&
           gl_framebuffer_create(&s->out_fb, err);
}

static void release_targets(struct refraction_state *s)
{
    gl_texture_destroy(&s->front_normal);
    gl_texture_destroy(&s->back_normal);
    gl_texture_destroy(&s->front_depth);
    gl_texture_destroy(&s->back_depth);
    gl_texture_destroy(&s->rough_scene);
    gl_texture_destroy(&s->rough_behind);
}

static void refraction_destroy(struct pass *p)
{
    struct refraction_state *s = p->state;
    if (!s)
        return;
    release_targets(s);
    thin_glass_over_release(&s->panes);
    gl_framebuffer_destroy(&s->front_fb);
    gl_framebuffer_destroy(&s->back_fb);
    gl_framebuffer_destroy(&s->out_fb);
    gl_param_block_release(&s->params);
    free(s);
    p->state = NULL;
}

/* Glass and water refract; mirrors are drawn here too, reflecting nearby
 * objects through the impostors (which `shade` cannot). */
static bool is_refractive(const struct object *o)
{
    return object_is(o, OBJECT_ROLE_SPECULAR);
}

/* Never left out (its output is read later): with no refractive object in
 * the scene, or none in the camera's view, it only copies its input through. */
static enum pass_need refraction_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    (void)p;
    bool any = false;
    for (int i = 0; i < f->scene->object_count; i++)
        any = any || is_refractive(f->scene->objects[i]);
    if (!any)
        snprintf(why, whylen, "passes the image through: no refractive object in the scene");
    else if (!scene_specular_in_view(f->scene, f->snapshot->view_proj))
        snprintf(why, whylen, "passes the image through: no refractive object in the camera's view");
    return PASS_RUN;
}

/* Draws each refractive object alone (its d_N buffer bound for Wyman's);
 * with `inside`, only those whose inside[i] is `which`. With `blend`, a
 * surface of glTF's alphaMode BLEND is blended over the colour by its alpha
 * (refract.frag's o_color.a; the other outputs are written whole). */
static bool draw_refractors(struct renderer *r, const struct scene *scene, const struct gl_program *prog,
                            bool wyman, bool blend, const struct impostor_set *impostors, const bool *inside,
                            bool which, struct error *err)
{
    for (int i = 0; i < scene->object_count; i++) {
        struct object *o = scene->objects[i];
        if (!is_refractive(o) || (inside && inside[i] != which))
            continue;
        struct mesh *m = o->mesh;
        if (wyman) {
            if (!mesh_compute_thickness(m, err))
                return false;
            GLuint thickness;
            if (!mesh_cache_thickness(&r->meshes, m, &thickness, err))
                return false;
            gl_program_bind_storage(prog, "Thickness", thickness);
        }
        if (impostors)
            gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_skip_impostor"), impostors_find(impostors, o));
        bool blended = blend && o->material.alpha_blend;
        if (blended) {
            gl.Enablei(GL_BLEND, 0);
            gl.BlendFunci(0, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        }
        /* glass or a mirror with holes (alphaMode MASK) shows its far side
         * through them: its back faces too, each kept where no front face
         * lies nearer (refract.frag's far_side) */
        bool holed = blend && !inside && o->material.alpha_cutoff > 0.0f;
        if (holed)
            gl.Disable(GL_CULL_FACE);
        renderer_draw_object(r, scene, prog, o);
        if (holed)
            gl.Enable(GL_CULL_FACE);
        if (blended)
            gl.Disablei(GL_BLEND, 0);
    }
    return true;
}

/* Is a visible refractor or mirror rough (material.roughness > 0)? */
static bool scene_has_rough_glass(const struct scene *scene)
{
    for (int i = 0; i < scene->object_count; i++)
        if (object_is(scene->objects[i], OBJECT_ROLE_SPECULAR) && scene->objects[i]->material.roughness > 0.0f)
            return true;
    return false;
}

static bool ensure_targets(struct refraction_state *s, int w, int h, struct error *err)
{
    if (s->front_normal.id && s->width == w && s->height == h)
        return true;
    release_targets(s);
    s->width = w;
    s->height = h;
    if (!gl_texture_create(&s->front_normal, GL_TEXTURE_2D, GL_RGBA32F, w, h, 1, err) ||
        !gl_texture_create(&s->back_normal, GL_TEXTURE_2D, GL_RGBA32F, w, h, 1, err) ||
        !gl_texture_create(&s->front_depth, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, w, h, 1, err) ||
        !gl_texture_create(&s->back_depth, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, w, h, 1, err))
        return false;
    const struct gl_texture *fc[1] = {&s->front_normal}, *bc[1] = {&s->back_normal};
    return gl_framebuffer_attach(&s->front_fb, fc, NULL, 1, &s->front_depth, -1, err) &&
           gl_framebuffer_attach(&s->back_fb, bc, NULL, 1, &s->back_depth, -1, err);
}

/* Initial pass (Hu & Qin §2.1): the refractors' front- and back-facing
 * normals and depths. */
static bool draw_surfaces(struct refraction_state *s, struct pass_frame *f, bool wyman, const char *defines,
                          struct error *err)
{
    struct renderer *r = f->renderer;
    struct gl_program *surf;
    if (!gl_program_get(&r->programs, "refraction/refract.vert", "refraction/surfaces.frag", defines, &surf, err))
        return false;
    const float zero[4] = {0, 0, 0, 0};
    gl.Enable(GL_DEPTH_TEST);
    gl.Enable(GL_CULL_FACE);
    gl.Viewport(0, 0, f->width, f->height);
    for (int side = 0; side < 2; side++) {
        struct gl_framebuffer *fb = side == 0 ? &s->front_fb : &s->back_fb;
        gl.BindFramebuffer(GL_FRAMEBUFFER, fb->id);
        gl.ClearNamedFramebufferfv(fb->id, GL_COLOR, 0, zero);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        gl.CullFace(side == 0 ? GL_BACK : GL_FRONT);
        if (!draw_refractors(r, f->scene, surf, wyman, false, NULL, NULL, false, err))
            return false;
    }
    gl.Disable(GL_CULL_FACE);
    return true;
}

/* What a ray leaving the glass looks up, all made by blocks before this
 * pass: the distance map (and, for the screen lookup, the `behind` image:
 * the diffuse objects from the camera without the glass), or §2.2.1's
 * impostors of the nearby (diffuse) objects around the refractors' centre. */
static bool make_lookup(struct refraction_state *s, struct pass *p, struct pass_frame *f, bool distance, bool nearby,
                        struct error *err)
{
    s->impostors = NULL;
    if (distance)
        return true;
    if (!nearby)
        return true;
    s->impostors = pass_frame_record(p, f, "impostors", &IMPOSTOR_SET_RECORD);
    return s->impostors ? true
                        : error_set(err, "its impostors ('%s') were not made this frame",
                                    pass_frame_input(p, f, "impostors")->name);
}

/* The distance map and the input image for the rays that leave the glass
 * (scene_trace.glsl: the screen first where `screen`, then the map). */
static bool bind_distance_lookup(struct refraction_state *s, struct pass *p, const struct gl_program *prog,
                                 struct pass_frame *f, const struct gl_texture *in_color,
                                 const struct gl_texture *in_depth, struct error *err)
{
    const struct distance_map *map = pass_frame_record(p, f, "distance_map", &DISTANCE_MAP_RECORD);
    if (!map || !map->built || map->content != DISTANCE_MAP_RADIANCE)
        return error_set(err, "its distance map ('%s') %s", pass_frame_input(p, f, "distance_map")->name,
                         !map || !map->built ? "was not made this frame (nothing to centre it on: a script's map "
                                               "around = \"refractors\" with mirrors alone?)"
                                             : "holds distances alone: the lookups need content = \"radiance\"");
    gl_program_bind_texture(prog, "u_distance_color", map->color[0].id);
    gl_program_bind_texture(prog, "u_distance_distance", map->distance[0].id);
    gl_program_bind_texture(prog, "u_distance_color_behind", map->color[1].id);
    gl_program_bind_texture(prog, "u_distance_distance_behind", map->distance[1].id);
    gl.ProgramUniform3f(prog->id, gl_program_uniform(prog, "u_distance_center"), map->center.x, map->center.y,
                        map->center.z);
    /* the input image first: what the camera sees where the ray goes, and
     * behind the glass it shows (the `behind` block: lookup "scene" alone) */
    struct graph_resource *behind = pass_frame_input(p, f, "behind"), *behind_depth = pass_frame_input(p, f, "behind_depth");
    GLuint behind_id = behind ? behind->texture.id : f->renderer->dummy_2d.id;
    gl_program_bind_texture(prog, "u_scene", in_color->id);
    gl_program_bind_texture(prog, "u_scene_depth", behind_depth ? behind_depth->texture.id : f->renderer->dummy_depth.id);
    gl_program_bind_texture(prog, "u_behind", behind_id);
    gl_program_bind_texture(prog, "u_input_depth", in_depth->id);
    bool rough = behind && scene_has_rough_glass(f->scene);
    if (rough && (!gl_texture_copy(&s->rough_scene, in_color, true, err) ||
                  !gl_texture_copy(&s->rough_behind, &behind->texture, true, err)))
        return false;
    gl_program_bind_texture(prog, "u_scene_mips", rough ? s->rough_scene.id : in_color->id);
    gl_program_bind_texture(prog, "u_behind_mips", rough ? s->rough_behind.id : behind_id);
    layers_bind_scene_trace(prog, f->scene);
    /* a surface the camera sees at more than about 63 degrees (its depth
     * changing by two pixel widths a pixel) is asked of the distance map
     * when the ray looks at it from elsewhere (scene_trace.glsl) */
    gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_scene_grazing"), 2.0f);
    return true;
}

/* The distance map is read by the lookups "scene" and "map" (without
 * recursion, which uses the impostors whatever the lookup). */
static bool uses_distance_map(const struct pass *p)
{
    return pass_flag(p, REFRACTION_NEARBY) && pass_choice(p, REFRACTION_LOOKUP) != REFRACTION_LOOKUP_IMPOSTORS &&
           pass_int(p, REFRACTION_RECURSION) == 0;
}

/* The lookup "scene" searches the input image first, and the `behind`
 * image where the input shows the glass itself. */
static bool uses_screen_lookup(const struct pass *p)
{
    return uses_distance_map(p) && pass_choice(p, REFRACTION_LOOKUP) == REFRACTION_LOOKUP_SCENE;
}

static unsigned refraction_draws(const struct pass *p)
{
    (void)p;
    return OBJECT_ROLE_SPECULAR;
}

static bool refraction_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct refraction_state *s = p->state;
    struct renderer *r = f->renderer;
    bool wyman = pass_choice(p, REFRACTION_METHOD) == REFRACTION_METHOD_WYMAN;
    struct graph_resource *in_color = pass_frame_input(p, f, "color"), *in_depth = pass_frame_input(p, f, "depth");
    const float clear[4] = {0, 0, 0, 0};
    if (!scene_specular_in_view(f->scene, f->snapshot->view_proj)) {
        /* nothing to refract on screen: the image as it is (no impostors, no surfaces) */
        const struct gl_texture *only[1] = {&f->outputs[0]->texture};
        if (!gl_framebuffer_attach(&s->out_fb, only, NULL, 1, NULL, -1, err))
            return false;
        gl_texture_clear(&f->outputs[1]->texture, clear);
        gl_texture_clear(&f->outputs[2]->texture, clear);
        return renderer_draw_copy(r, s->out_fb.id, f->width, f->height, in_color->texture.id, err);
    }
    if (!ensure_targets(s, f->width, f->height, err))
        return false;
    bool nearby = pass_flag(p, REFRACTION_NEARBY);
    bool distance = uses_distance_map(p);
    bool screen = uses_screen_lookup(p);
    char defines[128];
    snprintf(defines, sizeof defines, "%s%s%s%s", wyman ? "#define WYMAN 1\n" : "", nearby ? "#define NEARBY 1\n" : "",
             distance ? "#define DISTANCE_MAP 1\n" : "", screen ? "#define SCREEN_LOOKUP 1\n" : "");
    vec3 lo = {0, 0, 0}, hi = {0, 0, 0};
    scene_role_bounds(f->scene, OBJECT_ROLE_SPECULAR, &lo, &hi); /* (something specular is in view) */
    if (!make_lookup(s, p, f, distance, nearby, err) || !draw_surfaces(s, f, wyman, defines, err))
        return false;
    const float zero[4] = {0, 0, 0, 0};

    /* Rendering pass: the input image, then the refractors' visible front
     * surfaces refracting the environment (depth-tested against the input). */
    const struct gl_texture *oc[3] = {&f->outputs[0]->texture, &f->outputs[1]->texture, &f->outputs[2]->texture};
    if (!gl_framebuffer_attach(&s->out_fb, oc, NULL, 3, &in_depth->texture, -1, err))
        return false;
    gl_texture_clear(&f->outputs[1]->texture, zero);
    gl_texture_clear(&f->outputs[2]->texture, zero);
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->out_fb.id);
    /* the copy of the input writes the colour only; the refractors all three */
    static const GLenum color_only[3] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE};
    static const GLenum all_outputs[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    gl.NamedFramebufferDrawBuffers(s->out_fb.id, 3, color_only);
    if (!renderer_draw_copy(r, s->out_fb.id, f->width, f->height, in_color->texture.id, err))
        return false;
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "refraction/refract.vert", "refraction/refract.frag", defines, &prog, err))
        return false;
    shadow_inputs_bind(p, f, prog); /* the diffuse share of partly transmissive glass */
    if (!medium_gpu_bind(r, f->scene, prog, err))
        return false;
    gl.NamedFramebufferDrawBuffers(s->out_fb.id, 3, all_outputs);
    gl_program_bind_texture(prog, "u_front_normal", s->front_normal.id);
    gl_program_bind_texture(prog, "u_back_normal", s->back_normal.id);
    gl_program_bind_texture(prog, "u_front_depth", s->front_depth.id);
    gl_program_bind_texture(prog, "u_back_depth", s->back_depth.id);
    if (distance && !bind_distance_lookup(s, p, prog, f, &in_color->texture, &in_depth->texture, err))
        return false;
    const struct impostor_set *imp = nearby && !distance ? s->impostors : NULL;
    if (imp && imp->count > 0) {
        gl_program_bind_storage(prog, "Impostors", imp->ubo);
        gl_program_bind_texture(prog, "u_impostor_depth", imp->depth.id);
        gl_program_bind_texture(prog, "u_impostor_color", imp->color.id);
    }
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_impostor_count"), imp ? imp->count : 0);
    /* the parameters, as one block (struct refraction_params) */
    const struct refraction_params values = {
        .iterations = (int32_t)pass_int(p, REFRACTION_ITERATIONS),
        .tolerance = (float)pass_real(p, REFRACTION_TOLERANCE),
        .search_steps = (int32_t)pass_int(p, REFRACTION_SEARCH_STEPS),
        .correction = (int32_t)pass_int(p, REFRACTION_CORRECTION),
        .reflection = pass_flag(p, REFRACTION_REFLECTION),
        .reach = fmaxf(vec3_length(vec3_sub(hi, lo)), 1e-4f),
        .internal = (int32_t)pass_int(p, REFRACTION_INTERNAL),
    };
    if (!gl_param_block_upload(&s->params, &values, err) || !gl_param_block_bind(&s->params, prog, err))
        return false;
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LEQUAL);
    gl.DepthMask(GL_FALSE);
    gl.Enable(GL_CULL_FACE);
    gl.CullFace(GL_BACK);
    /* A camera inside a glass or water object sees none of its front faces
     * (an orthographic one may see some, in front of the pixels whose rays
     * start outside it): that object is drawn again by its back faces, each
     * pixel's path starting inside where no front face of it is nearer
     * (refract.frag's u_camera_inside). */
    bool *inside = calloc((size_t)f->scene->object_count + 1, sizeof *inside);
    if (!inside)
        return error_set(err, "refraction: out of memory");
    bool any_inside = false;
    for (int i = 0; i < f->scene->object_count; i++) {
        const struct object *o = f->scene->objects[i];
        inside[i] = object_is(o, OBJECT_ROLE_REFRACTOR) &&
                    object_contains_point(o, f->snapshot->eye);
        any_inside = any_inside || inside[i];
    }
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_camera_inside"), 0);
    bool ok = draw_refractors(r, f->scene, prog, wyman, true, imp, NULL, false, err);
    if (ok && any_inside && !wyman) {
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_camera_inside"), 1);
        gl.CullFace(GL_FRONT);
        ok = draw_refractors(r, f->scene, prog, wyman, true, imp, inside, true, err);
        gl.CullFace(GL_BACK);
    }
    free(inside);
    /* the panes in front of the glass, over it (shade drew them under it) */
    return ok && thin_glass_draw(&s->panes, p, f, THIN_GLASS_OVER_SURFACES, 0, &f->outputs[0]->texture, in_depth ? &in_depth->texture : NULL,
                                      refraction_draws(p), NULL, err);
}

/* Rough glass is blurred where the ray that leaves finds the input image
 * (the scene lookup's cone, refract.frag's seen_rough); the distance map,
 * the impostors and the environment are read as through smooth glass. */
static const char *refraction_leaves_out(const struct pass *p, const struct scene *scene, const struct object *o)
{
    if (object_is(o, OBJECT_ROLE_THIN))
        return pass_flag(p, REFRACTION_NEARBY) && pass_choice(p, REFRACTION_LOOKUP) == REFRACTION_LOOKUP_IMPOSTORS
                   ? "a pane is not among the nearby objects' impostors: it is not seen through the glass or in a "
                     "mirror (lookup = \"scene\" or \"map\" see it)"
                   : NULL;
    bool rough = object_is_rough_refractor(o) || (object_is(o, OBJECT_ROLE_MIRROR) && o->material.roughness > 0.0f);
    if (rough && pass_choice(p, REFRACTION_LOOKUP) != REFRACTION_LOOKUP_SCENE)
        return pass_refractor_holds(scene, o,
                                    "its roughness: only lookup = \"scene\" blurs the view through rough glass; this "
                                    "lookup draws it smooth");
    return pass_refractor_holds(scene, o, NULL);
}

static bool refraction_reads_block(const struct pass *p, int param)
{
    if (param == REFRACTION_DISTANCE_MAP)
        return uses_distance_map(p);
    if (param == REFRACTION_BEHIND)
        return uses_screen_lookup(p);
    if (param == REFRACTION_IMPOSTORS)
        return pass_flag(p, REFRACTION_NEARBY) && !uses_distance_map(p);
    return true;
}

/* Its distance map: lit radiance around the glass, water and mirrors'
 * centre, at `impostor` texels a face, through this pass's shadow maps. */
static bool refraction_configure_block(const struct pass *p, int param, struct pass *block, struct error *err)
{
    if (param == REFRACTION_IMPOSTORS)
        return impostors_configure_block(block, pass_int(p, REFRACTION_IMPOSTOR), pass_int(p, REFRACTION_RECURSION), p,
                                         REFRACTION_SHADOW, err);
    if (param == REFRACTION_BEHIND) /* the diffuse objects alone, lit as shade lights them */
        return pass_set_boolean(block, "specular", false, err) && shadow_inputs_give(block, p, REFRACTION_SHADOW, err);
    if (param != REFRACTION_DISTANCE_MAP)
        return true;
    return distance_map_configure_block(block, DISTANCE_MAP_RADIANCE, pass_int(p, REFRACTION_IMPOSTOR),
                                        OBJECT_ROLE_SPECULAR, p, REFRACTION_SHADOW, err);
}

const struct pass_desc refraction_pass = {
    .reads_block = refraction_reads_block,
    .configure_block = refraction_configure_block,
    .technique = PASS_TECHNIQUE_VIEW,
    .leaves_out = refraction_leaves_out,
    .behind_glass_without_caustics = true,
    .draws = refraction_draws,
    .name = "refraction",
    .summary = "Hu & Qin two-sided image-space refraction of the environment (or Wyman 2005's baseline)",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = refraction_declare,
    .create = refraction_create,
    .execute = refraction_execute,
    .needed = refraction_needed,
    .destroy = refraction_destroy,
};
