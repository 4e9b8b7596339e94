/* impostors: Hu & Qin's impostors of the nearby objects (§2.2.1, Fig. 12),
 * a building block (issue 54; impostors.h says what the set holds and who
 * reads it). */
#include "passes/blocks/impostors.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "graph/frame.h"
#include "graph/medium_gpu.h"
#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"

/* common/object.vert projected by the impostor's parallel view (set_impostor_view) */
#define IMPOSTOR_VIEW "#define OBJECT_VIEW_PROJ\n"

const struct record_type IMPOSTOR_SET_RECORD = {"impostor_set"};

static void impostors_release(struct impostor_set *set)
{
    gl_texture_destroy(&set->depth);
    gl_texture_destroy(&set->color);
    gl_texture_destroy(&set->color_previous);
    gl_texture_destroy(&set->depth_buffer);
    gl_framebuffer_destroy(&set->fb);
    if (set->ubo && gl_api_ready())
        gl.DeleteBuffers(1, &set->ubo);
    memset(set, 0, sizeof *set);
}

int impostors_find(const struct impostor_set *set, const struct object *object)
{
    for (int i = 0; i < set->count; i++)
        if (set->items[i].object == object)
            return i;
    return -1;
}

/* The parallel projection along the impostor's axis, from the refractor's
 * side (Fig. 12), and its per-impostor uniforms. */
static void set_impostor_view(const struct gl_program *prog, const struct impostor *im)
{
    vec3 eye = vec3_sub(im->center, vec3_scale(im->axis, 2.0f * im->half));
    mat4 view = mat4_look_at(eye, im->center, im->up);
    mat4 proj = mat4_ortho(-im->half, im->half, -im->half, im->half, 0.0f, 4.0f * im->half);
    mat4 vp = mat4_mul(proj, view);
    gl.ProgramUniformMatrix4fv(prog->id, gl_program_uniform(prog, "u_object_view_proj"), 1, GL_FALSE, vp.m);
    gl.ProgramUniform3f(prog->id, gl_program_uniform(prog, "u_impostor_center"), im->center.x, im->center.y,
                        im->center.z);
    gl.ProgramUniform3f(prog->id, gl_program_uniform(prog, "u_impostor_axis"), im->axis.x, im->axis.y, im->axis.z);
}

/* The receivers (visible diffuse objects, at most IMPOSTOR_MAX) around
 * `refractor_center`, each rendered at size x size; with `include_specular`
 * the reflectors and refractors too, their colour the environment they
 * reflect and refract (the recursion's level 0). They are lit as shade
 * lights (common/surface_light.glsl), through the shadow maps `owner` has
 * as inputs (none: unshadowed) and the frame's medium. */
static bool impostors_build(struct impostor_set *set, struct pass *owner, struct pass_frame *f, vec3 refractor_center,
                            int size, bool include_specular, uint64_t key, struct error *err)
{
    struct renderer *r = f->renderer;
    const struct scene *scene = f->scene;
    set->built = false; /* until this build completes */
    int count = 0;
    struct impostor items[IMPOSTOR_MAX];
    for (int i = 0; i < scene->object_count && count < IMPOSTOR_MAX; i++) {
        struct object *o = scene->objects[i];
        if (!object_is(o, include_specular ? OBJECT_ROLE_RECEIVER | OBJECT_ROLE_SPECULAR : OBJECT_ROLE_RECEIVER))
            continue;
        vec3 lo, hi;
        object_world_bounds(o, &lo, &hi);
        struct impostor *im = &items[count++];
        im->object = o;
        im->specular = object_is(o, OBJECT_ROLE_SPECULAR);
        im->center = vec3_scale(vec3_add(lo, hi), 0.5f);
        im->half = fmaxf(0.5f * vec3_length(vec3_sub(hi, lo)), 1e-3f);
        im->axis = vec3_normalize_or(vec3_sub(im->center, refractor_center), vec3_make(0, -1, 0));
        /* A floor (a box a twentieth as thick vertically as it is wide)
         * looks straight along its normal, turned away from the refractors:
         * its parameterization is then even across it, and the rays reaching
         * it from above are near the axis, where the search is exact. From
         * the refractors' centre the axis met a floor obliquely whenever a
         * second specular object stood to the side (Fig. 24 g's mirror
         * teapot cut the sphere's caustic to a crescent; issue 8). Walls keep
         * the centre's axis: along their own normal, the photons from above
         * meet them edge-on and Fig. 28's back wall went dark below. */
        vec3 extent = vec3_sub(hi, lo);
        if (extent.y < extent.x && extent.y <= extent.z && extent.y < 0.05f * fmaxf(extent.x, extent.z))
            im->axis = vec3_make(0.0f, im->axis.y < 0.0f ? -1.0f : 1.0f, 0.0f);
        /* up and right chosen so that the parallel projection below (a
         * look-at along the axis) has right as its screen x and up as its y */
        vec3 hint = fabsf(im->axis.y) > 0.9f ? vec3_make(0, 0, 1) : vec3_make(0, 1, 0);
        im->up = vec3_normalize_or(vec3_sub(hint, vec3_scale(im->axis, vec3_dot(im->axis, hint))), vec3_make(0, 1, 0));
        im->right = vec3_cross(im->axis, im->up);
    }
    if (set->size != size || set->count != count || !set->depth.id) {
        impostors_release(set);
        if (count == 0)
            return true;
        if (!gl_texture_create(&set->depth, GL_TEXTURE_2D_ARRAY, GL_R32F, size, size, count, err) ||
            !gl_texture_create(&set->color, GL_TEXTURE_2D_ARRAY, GL_RGBA16F, size, size, count, err) ||
            !gl_texture_create(&set->color_previous, GL_TEXTURE_2D_ARRAY, GL_RGBA16F, size, size, count, err) ||
            !gl_texture_create(&set->depth_buffer, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, size, size, 1, err) ||
            !gl_framebuffer_create(&set->fb, err))
            return false;
        gl.CreateBuffers(1, &set->ubo);
        gl.NamedBufferStorage(set->ubo, IMPOSTOR_MAX * sizeof(struct impostor_gpu), NULL, GL_DYNAMIC_STORAGE_BIT);
        set->size = size;
    }
    set->count = count;
    memcpy(set->items, items, sizeof items);
    struct impostor_gpu gpu[IMPOSTOR_MAX];
    memset(gpu, 0, sizeof gpu);
    for (int k = 0; k < count; k++) {
        const struct impostor *im = &items[k];
        gpu[k] = (struct impostor_gpu){{im->center.x, im->center.y, im->center.z, im->half},
                                       {im->axis.x, im->axis.y, im->axis.z, 0},
                                       {im->right.x, im->right.y, im->right.z, 0},
                                       {im->up.x, im->up.y, im->up.z, 0}};
    }
    gl.NamedBufferSubData(set->ubo, 0, sizeof gpu, gpu);

    /* Lambert's program and its glTF-BRDF variant (renderer_draw_lit's
     * pair), each object drawn by the one for its material */
    struct gl_program *progs[2];
    if (!renderer_lit_programs(r, scene, "common/object.vert", "impostors/impostor.frag", IMPOSTOR_VIEW, progs, err))
        return false;
    for (int k = 0; k < 2 && progs[k]; k++) {
        shadow_inputs_bind(owner, f, progs[k]);
        if (!medium_gpu_bind(r, scene, progs[k], err))
            return false;
    }
    gl.Enable(GL_DEPTH_TEST);
    gl.Viewport(0, 0, size, size);
    for (int k = 0; k < count; k++) {
        const struct impostor *im = &items[k];
        const struct gl_texture *colors[2] = {&set->depth, &set->color};
        int layers[2] = {k, k};
        if (!gl_framebuffer_attach(&set->fb, colors, layers, 2, &set->depth_buffer, -1, err))
            return false;
        gl.BindFramebuffer(GL_FRAMEBUFFER, set->fb.id);
        const float empty[4] = {IMPOSTOR_EMPTY, 0, 0, 0}, black[4] = {0, 0, 0, 0};
        gl.ClearNamedFramebufferfv(set->fb.id, GL_COLOR, 0, empty);
        gl.ClearNamedFramebufferfv(set->fb.id, GL_COLOR, 1, black);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        const struct material *mat = &im->object->material;
        struct gl_program *prog =
            progs[1] && mat->pbr && material_role(mat) == OBJECT_ROLE_RECEIVER ? progs[1] : progs[0];
        set_impostor_view(prog, im);
        renderer_draw_object(r, scene, prog, im->object);
    }
    gl.Disable(GL_DEPTH_TEST);
    if (!gl_check("building impostors", err))
        return false;
    set->built = true;
    set->built_key = key;
    return true;
}

/* One level of recursive reflection/refraction (Hu & Qin §2.2, Fig. 1b,
 * 24g): the specular objects' impostors are drawn again, reflecting and
 * refracting the impostors of the previous level. */
static bool impostors_recurse(struct impostor_set *set, struct renderer *r, const struct scene *scene,
                              struct error *err)
{
    if (set->count == 0)
        return true;
    /* this level reads the previous one's colours */
    gl.CopyImageSubData(set->color.id, GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, set->color_previous.id, GL_TEXTURE_2D_ARRAY, 0, 0,
                        0, 0, set->size, set->size, set->count);
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "common/object.vert", "impostors/impostor_recursive.frag", IMPOSTOR_VIEW,
                        &prog, err))
        return false;
    gl_program_bind_storage(prog, "Impostors", set->ubo);
    gl_program_bind_texture(prog, "u_impostor_depth", set->depth.id);
    gl_program_bind_texture(prog, "u_impostor_color", set->color_previous.id);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_impostor_count"), set->count);
    gl.Enable(GL_DEPTH_TEST);
    gl.Viewport(0, 0, set->size, set->size);
    for (int k = 0; k < set->count; k++) {
        const struct impostor *im = &set->items[k];
        if (!im->specular)
            continue;
        const struct gl_texture *colors[2] = {&set->depth, &set->color};
        int layers[2] = {k, k};
        if (!gl_framebuffer_attach(&set->fb, colors, layers, 2, &set->depth_buffer, -1, err))
            return false;
        gl.BindFramebuffer(GL_FRAMEBUFFER, set->fb.id);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        set_impostor_view(prog, im);
        gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_skip_impostor"), k); /* it does not see itself */
        renderer_draw_object(r, scene, prog, im->object);
    }
    gl.Disable(GL_DEPTH_TEST);
    return gl_check("recursive impostors", err);
}

/* The block's parameters by index. */
enum impostors_param { IM_SIZE, IM_SPECULAR, IM_RECURSION, IM_SHADOW };

static const struct pass_param_desc params[] = {
    [IM_SIZE] = {.name = "size", .type = PASS_PARAM_INTEGER, .default_number = 256, .min = 16, .max = 4096,
     .help = "texels per side of each impostor's texture"},
    [IM_SPECULAR] = {.name = "specular", .type = PASS_PARAM_BOOLEAN, .default_number = 0,
     .help = "the reflectors and refractors too, their colour the environment they reflect and refract (level 0 "
             "of the recursion; on whenever recursion is)"},
    [IM_RECURSION] = {.name = "recursion", .type = PASS_PARAM_INTEGER, .default_number = 0, .min = 0, .max = 4,
     .help = "levels of the reflectors' and refractors' impostors drawn again reflecting and refracting the "
             "previous level's (Hu & Qin Fig. 1b, 24g); made again every frame"},
    [IM_SHADOW] = {.name = "shadow", .type = PASS_PARAM_INPUT_LIST, .max = SHADOW_INPUTS_MAX,
     .record = &SHADOW_MAP_RECORD,
     .help = "shadow maps that light the impostors as shade's light the scene (e.g. \"shadow.depth\"); without "
             "them they are unshadowed"},
};

bool impostors_configure_block(struct pass *block, int size, int recursion, const struct pass *reader,
                               int reader_shadow, struct error *err)
{
    if (!pass_set_number(block, "size", size, err) || !pass_set_boolean(block, "specular", recursion > 0, err) ||
        !pass_set_number(block, "recursion", recursion, err))
        return false;
    return shadow_inputs_give(block, reader, reader_shadow, err);
}

static bool impostors_declare(struct pass *p, struct error *err)
{
    /* shadow0.. are declared from the descriptor (pass_declare) */
    return pass_declare_bundle(p, "set", &IMPOSTOR_SET_RECORD, err);
}

static bool impostors_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    p->state = calloc(1, sizeof(struct impostor_set));
    return p->state ? true : error_set(err, "out of memory");
}

static void impostors_destroy(struct pass *p)
{
    if (!p->state)
        return;
    impostors_release(p->state);
    free(p->state);
    p->state = NULL;
}

/* The centre the impostors' axes leave from (the glass, water and
 * mirrors' box's middle, §2.2.1's O_R) and the key a set is made under:
 * the block's pass_frame_key with the geometry and the lights (Hu & Qin
 * §4's reuse in a static scene) and the centre. False: nothing specular. */
static bool set_frame(const struct pass *p, const struct pass_frame *f, vec3 *center, uint64_t *key)
{
    vec3 lo, hi;
    if (!scene_role_bounds(f->scene, OBJECT_ROLE_SPECULAR, &lo, &hi))
        return false;
    *center = vec3_scale(vec3_add(lo, hi), 0.5f);
    *key = pass_key_mix(pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY | PASS_DEPENDS_LIGHTS), center, sizeof *center);
    return true;
}

static enum pass_need impostors_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    struct impostor_set *set = p->state;
    vec3 center;
    uint64_t key;
    if (!set_frame(p, f, &center, &key)) {
        set->built = false;
        snprintf(why, whylen, "the scene has no visible glass, water or mirror for its objects to stand around");
        return PASS_SKIP;
    }
    /* recursion redraws the specular impostors' colours: made every frame */
    if (pass_int(p, IM_RECURSION) == 0 && pass_frame_reusable(f, set->built, set->built_key, key)) {
        snprintf(why, whylen, "reuses its impostors: its parameters, the geometry and the lights did not change");
        return PASS_REUSE;
    }
    return PASS_RUN;
}

static bool impostors_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct impostor_set *set = p->state;
    pass_frame_output(p, f, "set")->record = set;
    vec3 center;
    uint64_t key;
    if (!set_frame(p, f, &center, &key)) {
        set->built = false;
        return true;
    }
    int levels = pass_int(p, IM_RECURSION);
    if (!impostors_build(set, p, f, center, pass_int(p, IM_SIZE), levels > 0 || pass_flag(p, IM_SPECULAR), key, err))
        return false;
    for (int level = 0; level < levels; level++)
        if (!impostors_recurse(set, f->renderer, f->scene, err))
            return false;
    snprintf(p->report, sizeof p->report, "%d impostors of %d x %d texels%s", set->count, set->size, set->size,
             levels ? ", drawn again for each level of recursion" : "");
    return true;
}

const struct pass_desc impostors_pass = {
    .name = "impostors",
    .summary = "building block: Hu & Qin's impostors of the nearby objects around the specular ones (§2.2.1), "
               "shared by refraction, layered_refraction and photon_caustics",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = impostors_declare,
    .create = impostors_create,
    .execute = impostors_execute,
    .needed = impostors_needed,
    .destroy = impostors_destroy,
};
