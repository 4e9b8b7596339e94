#include "passes/helpers/impostors.h"

#include <math.h>
#include <string.h>

#include "graph/frame.h"
#include "graph/medium_gpu.h"
#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"

/* common/object.vert projected by the impostor's parallel view (set_impostor_view) */
#define IMPOSTOR_VIEW "#define OBJECT_VIEW_PROJ\n"

void impostors_release(struct impostor_set *set)
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

uint64_t impostors_key(const struct pass *p, const struct pass_frame *f)
{
    return pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY | PASS_DEPENDS_LIGHTS);
}

bool impostors_current(const struct impostor_set *set, const struct pass_frame *f, uint64_t key)
{
    return pass_frame_reusable(f, set->built, set->built_key, key);
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

bool impostors_build(struct impostor_set *set, struct pass *owner, struct pass_frame *f, vec3 refractor_center,
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

bool impostors_recurse(struct impostor_set *set, struct renderer *r, const struct scene *scene, struct error *err)
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
