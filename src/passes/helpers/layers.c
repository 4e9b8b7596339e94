/* Depth layers by voxelization and peeling (Chaudhari 2008, §3.3-3.5).
 * Where this departs from the thesis, and why:
 * - Slice bits are ORed with GL's logic op on RGBA32UI targets, not added
 *   with blending: two fragments in one slice set the bit once instead of
 *   carrying into the next slice (§3.3's overflow), and 32-bit words need
 *   no float conversion.
 * - Peeling walks the set bits in order with findLSB rather than a binary
 *   search for the n-th bit (§3.4.2): every bit is visited once per pixel.
 * - A third draw writes each layer's interpolated mesh normal, exact depth
 *   and refractor (the slice tells its layer index by a popcount of the
 *   bits below it). The thesis's depth-gradient normals (eq. 3.2) remain
 *   available to the tracer; the voxel depths too (`exact_depth` false).
 *   The refractor index lets every object keep its own IOR and absorption
 *   (§4.1 suggests bits per voxel per material).
 * - Per-layer depth ranges for restricting the search (§3.7) are exact
 *   atomic min/max over the layer, not a reduced MIP level. */
#include "passes/helpers/layers.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/helpers/shadow_inputs.h"

const struct record_type LAYER_SET_RECORD = {"layer_set"};

void layers_init(struct layer_set *ls) { memset(ls, 0, sizeof *ls); }

/* The C mirror of LayerView (shaders/layers/layers.glsl, std140). */
struct layer_view_params {
    float view[16], proj[16], inv_view[16], inv_proj[16];
    int32_t size[2];
    int32_t voxels, layers, exact_depth, pad[3];
};
static const struct gl_block_member layer_view_members[] = {
    {"u_layer_view", offsetof(struct layer_view_params, view)},
    {"u_layer_proj", offsetof(struct layer_view_params, proj)},
    {"u_layer_inv_view", offsetof(struct layer_view_params, inv_view)},
    {"u_layer_inv_proj", offsetof(struct layer_view_params, inv_proj)},
    {"u_layer_size", offsetof(struct layer_view_params, size)},
    {"u_voxels", offsetof(struct layer_view_params, voxels)},
    {"u_layers", offsetof(struct layer_view_params, layers)},
    {"u_exact_depth", offsetof(struct layer_view_params, exact_depth)},
};

/* This set's LayerView, uploaded in one call after each build. */
static bool upload_view(struct layer_set *ls, struct error *err)
{
    if (!ls->view_block) {
        ls->view_block = malloc(sizeof *ls->view_block);
        if (!ls->view_block)
            return error_set(err, "out of memory");
        *ls->view_block = GL_PARAM_BLOCK_OF("LayerView", layer_view_members, struct layer_view_params);
    }
    struct layer_view_params values = {.size = {ls->width, ls->height}, .voxels = ls->voxels,
                                       .layers = ls->layers, .exact_depth = ls->exact_depth ? 1 : 0};
    memcpy(values.view, ls->view.m, sizeof values.view);
    memcpy(values.proj, ls->proj.m, sizeof values.proj);
    memcpy(values.inv_view, ls->inv_view.m, sizeof values.inv_view);
    memcpy(values.inv_proj, ls->inv_proj.m, sizeof values.inv_proj);
    return gl_param_block_upload(ls->view_block, &values, err);
}

static void release_targets(struct layer_set *ls)
{
    gl_texture_destroy(&ls->bounds);
    gl_texture_destroy(&ls->bits);
    gl_texture_destroy(&ls->depth);
    gl_texture_destroy(&ls->normal);
    gl_texture_destroy(&ls->info);
}

void layers_release(struct layer_set *ls)
{
    release_targets(ls);
    gl_framebuffer_destroy(&ls->bounds_fb);
    gl_framebuffer_destroy(&ls->bits_fb);
    if (gl_api_ready()) {
        if (ls->ranges)
            gl.DeleteBuffers(1, &ls->ranges);
        if (ls->materials)
            gl.DeleteBuffers(1, &ls->materials);
    }
    if (ls->view_block) {
        gl_param_block_release(ls->view_block);
        free(ls->view_block);
    }
    layers_init(ls);
}

bool layers_is_refractor(const struct object *o)
{
    return object_is(o, OBJECT_ROLE_REFRACTOR);
}

int layers_light_slot(const struct layer_set *ls, struct error *err)
{
    if (ls->light_slot < 0)
        error_set(err, "its light_layers are the camera's (a depth_layers { view = \"light\" } pass's layers expected)");
    return ls->light_slot;
}

const char *layers_refractors_named(const struct scene *scene)
{
    bool water = false, glass = false;
    for (int k = 0; k < scene->object_count; k++) {
        water = water || object_is(scene->objects[k], OBJECT_ROLE_WATER);
        glass = glass || object_is(scene->objects[k], OBJECT_ROLE_GLASS);
    }
    return water && glass ? "the glass and water" : water ? "the water" : "the glass";
}

const char *layers_leaves_out(const struct pass *p, const struct scene *scene, const struct object *o)
{
    if (object_is(o, OBJECT_ROLE_THIN))
        return shadow_inputs_pane_left_out(p, scene, o);
    if (object_is(o, OBJECT_ROLE_MIRROR))
        return "the light's depth layers hold glass and water only: no caustics off a mirror (photon_caustics "
               "makes them)";
    return pass_refractor_left_out(o, true);
}

static bool ensure_targets(struct layer_set *ls, int w, int h, int voxels, int layers, struct error *err)
{
    if (ls->bounds.id && ls->width == w && ls->height == h && ls->voxels == voxels && ls->layers == layers)
        return true;
    release_targets(ls);
    if (!ls->bounds_fb.id && (!gl_framebuffer_create(&ls->bounds_fb, err) || !gl_framebuffer_create(&ls->bits_fb, err)))
        return false;
    if (!ls->ranges) {
        gl.CreateBuffers(1, &ls->ranges);
        gl.NamedBufferStorage(ls->ranges, (GLsizeiptr)((2 * LAYERS_MAX + 4) * sizeof(GLuint)), NULL,
                              GL_DYNAMIC_STORAGE_BIT);
        gl.CreateBuffers(1, &ls->materials);
        gl.NamedBufferStorage(ls->materials, (GLsizeiptr)(LAYERS_MAX_SLOTS * sizeof(struct layers_material_gpu)), NULL,
                              GL_DYNAMIC_STORAGE_BIT);
    }
    ls->width = w;
    ls->height = h;
    ls->voxels = voxels;
    ls->layers = layers;
    int words = voxels / 128;
    if (!gl_texture_create(&ls->bounds, GL_TEXTURE_2D, GL_RG32F, w, h, 1, err) ||
        !gl_texture_create(&ls->bits, GL_TEXTURE_2D_ARRAY, GL_RGBA32UI, w, h, words, err) ||
        !gl_texture_create(&ls->depth, GL_TEXTURE_2D_ARRAY, GL_R32F, w, h, layers, err) ||
        !gl_texture_create(&ls->normal, GL_TEXTURE_2D_ARRAY, GL_RGBA32F, w, h, layers, err) ||
        !gl_texture_create(&ls->info, GL_TEXTURE_2D, GL_RG32UI, w, h, 1, err))
        return false;
    /* The layer arrays are read texel by texel (a layer's neighbour may be
     * another surface): no filtering. */
    gl.TextureParameteri(ls->depth.id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TextureParameteri(ls->depth.id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TextureParameteri(ls->normal.id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TextureParameteri(ls->normal.id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TextureParameteri(ls->bounds.id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TextureParameteri(ls->bounds.id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    const struct gl_texture *bc[1] = {&ls->bounds};
    if (!gl_framebuffer_attach(&ls->bounds_fb, bc, NULL, 1, NULL, -1, err))
        return false;
    const struct gl_texture *wc[8];
    int wl[8];
    for (int i = 0; i < words; i++) {
        wc[i] = &ls->bits;
        wl[i] = i;
    }
    return gl_framebuffer_attach(&ls->bits_fb, wc, wl, words, NULL, -1, err);
}

/* Each refractor alone, with its slot for the attribute pass. */
static void draw_refractors(struct layer_set *ls, struct renderer *r, const struct scene *scene,
                            const struct gl_program *prog)
{
    for (int s = 0; s < ls->slots; s++) {
        gl.ProgramUniform1i(prog->id, gl_program_uniform_optional(prog, "u_slot"), s); /* the bounds draw has none */
        renderer_draw_object(r, scene, prog, ls->slot_objects[s]);
        ls->draws++;
        ls->triangles += (long)(ls->slot_objects[s]->mesh->index_count / 3);
    }
}

/* The refractors' slots: each one's IOR and absorption for the traces. */
static void upload_materials(struct layer_set *ls, const struct scene *scene)
{
    ls->slots = 0;
    struct layers_material_gpu mats[LAYERS_MAX_SLOTS];
    memset(mats, 0, sizeof mats);
    for (int i = 0; i < scene->object_count && ls->slots < LAYERS_MAX_SLOTS; i++) {
        struct object *o = scene->objects[i];
        if (!layers_is_refractor(o))
            continue;
        struct layers_material_gpu *m = &mats[ls->slots];
        m->ior = o->material.ior;
        m->ideal = o->material.ideal ? 1.0f : 0.0f;
        m->absorption[0] = o->material.absorption.x;
        m->absorption[1] = o->material.absorption.y;
        m->absorption[2] = o->material.absorption.z;
        ls->slot_objects[ls->slots++] = o;
    }
    gl.NamedBufferSubData(ls->materials, 0, (GLsizeiptr)sizeof mats, mats);
}

bool layers_build(struct layer_set *ls, struct renderer *r, const struct scene *scene, mat4 view, mat4 proj,
                  int width, int height, int voxels, int layers, bool exact_depth, struct pass *timed,
                  struct error *err)
{
    if (voxels < 128 || voxels > LAYERS_MAX_VOXELS || voxels % 128 != 0)
        return error_set(err, "layers: voxels must be a multiple of 128 in 128..%d (got %d)", LAYERS_MAX_VOXELS,
                         voxels);
    if (layers < 1 || layers > LAYERS_MAX)
        return error_set(err, "layers: layers must be in 1..%d (got %d)", LAYERS_MAX, layers);
    if (!ensure_targets(ls, width, height, voxels, layers, err))
        return false;
    ls->exact_depth = exact_depth;
    ls->built = true;
    ls->view = view;
    ls->proj = proj;
    mat4_inverse(view, &ls->inv_view);
    mat4_inverse(proj, &ls->inv_proj);
    ls->ortho = proj.m[11] == 0.0f; /* [2][3]: -1 for a perspective projection */
    ls->draws = 0;
    ls->triangles = 0;
    upload_materials(ls, scene);
    if (!upload_view(ls, err))
        return false;

    struct gl_program *bounds, *voxelize, *attributes, *peel, *ranges;
    if (!gl_program_get(&r->programs, "layers/layers.vert", "layers/bounds.frag", NULL, &bounds, err) ||
        !gl_program_get(&r->programs, "layers/layers.vert", "layers/voxelize.frag", NULL, &voxelize, err) ||
        !gl_program_get(&r->programs, "layers/layers.vert", "layers/attributes.frag", NULL, &attributes, err) ||
        !gl_program_get_compute(&r->programs, "layers/peel.comp", NULL, NULL, &peel, err) ||
        !gl_program_get_compute(&r->programs, "layers/ranges.comp", NULL, NULL, &ranges, err))
        return false;
    gl.Viewport(0, 0, width, height);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);

    /* §3.3, first pass: per-pixel bounds by MAX blending of (d, -d). */
    const float empty[4] = {-1e30f, -1e30f, 0, 0};
    gl.BindFramebuffer(GL_FRAMEBUFFER, ls->bounds_fb.id);
    gl.ClearNamedFramebufferfv(ls->bounds_fb.id, GL_COLOR, 0, empty);
    gl.Enable(GL_BLEND);
    gl.BlendEquation(GL_MAX);
    if (!gl_param_block_bind(ls->view_block, bounds, err))
        return false;
    draw_refractors(ls, r, scene, bounds);
    gl.BlendEquation(GL_FUNC_ADD);
    gl.Disable(GL_BLEND);
    if (timed)
        pass_stage_end(timed, "bounds");

    /* §3.3, second pass: one bit per fragment in its slice between the
     * pixel's bounds, ORed into the words. */
    const GLuint zero_u[4] = {0, 0, 0, 0};
    gl.ClearTexImage(ls->bits.id, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, zero_u);
    gl.BindFramebuffer(GL_FRAMEBUFFER, ls->bits_fb.id);
    gl.Enable(GL_COLOR_LOGIC_OP);
    gl.LogicOp(GL_OR);
    gl_program_bind_texture(voxelize, "u_bounds", ls->bounds.id);
    if (!gl_param_block_bind(ls->view_block, voxelize, err))
        return false;
    draw_refractors(ls, r, scene, voxelize);
    gl.Disable(GL_COLOR_LOGIC_OP);
    gl.LogicOp(GL_COPY);
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    if (timed)
        pass_stage_end(timed, "voxelize");

    /* §3.4.2: peel the set bits in order into the layer arrays. */
    GLuint init[2 * LAYERS_MAX + 4];
    for (int k = 0; k < LAYERS_MAX; k++) {
        init[2 * k] = 0x7f7fffffu; /* FLT_MAX's bits: atomicMin from above */
        init[2 * k + 1] = 0u;
    }
    init[2 * LAYERS_MAX] = 0u; /* the largest layer count */
    init[2 * LAYERS_MAX + 1] = init[2 * LAYERS_MAX + 2] = init[2 * LAYERS_MAX + 3] = 0u;
    gl.NamedBufferSubData(ls->ranges, 0, (GLsizeiptr)sizeof init, init);
    const float zero_f[4] = {0, 0, 0, 0};
    gl.ClearTexImage(ls->normal.id, 0, GL_RGBA, GL_FLOAT, zero_f);
    gl.UseProgram(peel->id);
    if (!gl_param_block_bind(ls->view_block, peel, err))
        return false;
    gl_program_bind_texture(peel, "u_bounds", ls->bounds.id);
    gl_program_bind_texture(peel, "u_bits", ls->bits.id);
    gl_program_bind_image(peel, "u_depth", ls->depth.id, GL_TRUE, GL_WRITE_ONLY, GL_R32F);
    gl_program_bind_image(peel, "u_info", ls->info.id, GL_FALSE, GL_WRITE_ONLY, GL_RG32UI);
    gl_program_dispatch(peel, width, height, 1, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    if (timed)
        pass_stage_end(timed, "peel");

    /* The attributes: each fragment's layer is the count of set bits below
     * its slice; it writes its normal, refractor and exact depth there. */
    gl.BindFramebuffer(GL_FRAMEBUFFER, ls->bounds_fb.id);
    gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl_program_bind_texture(attributes, "u_bounds", ls->bounds.id);
    gl_program_bind_texture(attributes, "u_bits", ls->bits.id);
    gl_program_bind_image(attributes, "u_depth", ls->depth.id, GL_TRUE, GL_WRITE_ONLY, GL_R32F);
    gl_program_bind_image(attributes, "u_normal", ls->normal.id, GL_TRUE, GL_WRITE_ONLY, GL_RGBA32F);
    if (!gl_param_block_bind(ls->view_block, attributes, err))
        return false;
    draw_refractors(ls, r, scene, attributes);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    if (timed)
        pass_stage_end(timed, "attributes");

    /* §3.7: each layer's depth range, to bound the search along a ray. */
    gl.UseProgram(ranges->id);
    gl_program_bind_texture(ranges, "u_depth", ls->depth.id);
    gl_program_bind_texture(ranges, "u_info", ls->info.id);
    gl_program_bind_storage(ranges, "Ranges", ls->ranges);
    if (!gl_param_block_bind(ls->view_block, ranges, err))
        return false;
    gl_program_dispatch(ranges, width, height, 1, GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    if (timed)
        pass_stage_end(timed, "ranges");
    renderer_reset_state(r);
    return gl_check("depth layers", err);
}

bool layers_bind(const struct layer_set *ls, const struct gl_program *prog, const struct scene *scene,
                 const struct layers_trace *trace, struct error *err)
{
    gl_program_bind_texture(prog, "u_bounds", ls->bounds.id);
    gl_program_bind_texture(prog, "u_layer_depth", ls->depth.id);
    gl_program_bind_texture(prog, "u_layer_normal", ls->normal.id);
    gl_program_bind_texture(prog, "u_layer_info", ls->info.id);
    gl_program_bind_storage(prog, "LayerRanges", ls->ranges);
    gl_program_bind_storage(prog, "LayerMaterials", ls->materials);
    if (!gl_param_block_bind(ls->view_block, prog, err))
        return false;
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_search"), trace->search);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_steps"), trace->steps);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_gradient"), trace->gradient);
    gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, "u_max_interfaces"), trace->max_interfaces);
    gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_layer_extent"), trace->layer_extent);
    layers_bind_scene_trace(prog, scene);
    return true;
}

void layers_bind_scene_trace(const struct gl_program *prog, const struct scene *scene)
{
    /* optional: a program that traces the layers alone (beam_caustics'
     * trace.comp) has no scene trace */
    vec3 lo = {0, 0, 0}, hi = {0, 0, 0};
    scene_bounds(scene, &lo, &hi);
    gl.ProgramUniform1f(prog->id, gl_program_uniform_optional(prog, "u_scene_extent"),
                        fmaxf(vec3_length(vec3_sub(hi, lo)), 1e-4f) * 1.5f);
    gl.ProgramUniform1i(prog->id, gl_program_uniform_optional(prog, "u_scene_steps"), 64);
    /* what a ray can meet there: the diffuse objects (none: an empty box) */
    if (!scene_role_bounds(scene, OBJECT_ROLE_RECEIVER, &lo, &hi)) {
        lo = vec3_make(1e30f, 1e30f, 1e30f);
        hi = vec3_make(-1e30f, -1e30f, -1e30f);
    }
    gl.ProgramUniform3f(prog->id, gl_program_uniform_optional(prog, "u_scene_lo"), lo.x, lo.y, lo.z);
    gl.ProgramUniform3f(prog->id, gl_program_uniform_optional(prog, "u_scene_hi"), hi.x, hi.y, hi.z);
}

bool layers_configure_block(struct pass *block, struct light *light, int buffer, int layers, int voxels,
                            struct error *err)
{
    int light_param = pass_param_index(block->desc, "light");
    if (light_param < 0)
        return error_set(err, "the layers' block '%s' has no light", block->desc->name);
    pass_set_light(block, light_param, light);
    block->values[light_param].set = true;
    return pass_set_number(block, "buffer", buffer, err) && pass_set_number(block, "layers", layers, err) &&
           pass_set_number(block, "voxels", voxels, err);
}

bool layers_configure_camera_block(struct pass *block, int layers, int voxels, bool exact_depth, struct error *err)
{
    return pass_set_enum(block, "view", "camera", err) && pass_set_number(block, "layers", layers, err) &&
           pass_set_number(block, "voxels", voxels, err) &&
           pass_set_enum(block, "depths", exact_depth ? "exact" : "voxel", err);
}

/* The layers' margins: the eye of an orthographic view three radii back,
 * planes from half a radius to six; a perspective view 2% wider than the
 * sphere, its near plane 10% before it and its far 10% of a radius past. */
static const struct light_view_margins layers_margins = {
    .radius_scale = LAYERS_RADIUS_SCALE, .eye_radii = 3.0f, .ortho_near_radii = 0.5f, .ortho_far_radii = 6.0f,
    .fov_scale = 1.02f, .near_scale = 0.9f, .far_radii = 1.1f, .inside_half_angle = 0.0f,
    .up_z_when_vertical = true,
};

bool layers_light_view(const struct frame_light *fl, vec3 lo, vec3 hi, struct light_view *v, const char *pass_name,
                       struct error *err)
{
    vec3 center = vec3_scale(vec3_add(lo, hi), 0.5f);
    float radius = 0.5f * vec3_length(vec3_sub(hi, lo));
    if (!light_view_fit(fl->kind == LIGHT_DIRECTIONAL, fl->position, fl->direction, center, radius, &layers_margins, v))
        return error_set(err, "%s: the light is inside the refractors' bounding sphere "
                              "(move it out, or use a directional light)", pass_name);
    if (!v->ortho)
        return true;
    /* Along a directional light, the square around the sphere narrows to
     * the box's own outline: water 6 wide under a sun 2 degrees up is a
     * strip 0.2 high in the light's view, and the square gave it 9 of 256
     * rows (a few photons and one row of beam cells carried all its light:
     * the floor came out in dotted bands, a third of it black). The strip
     * gets every row, and its texels are as wide on the water as they are
     * long. Kept at least a fiftieth of the square, so that a face seen
     * exactly edge-on still has a view. */
    float r = v->half_extent, half_w = 0.0f, half_h = 0.0f;
    for (int k = 0; k < 8; k++) {
        vec3 corner = vec3_make(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        vec3 q = mat4_transform_point(v->view, corner);
        half_w = fmaxf(half_w, fabsf(q.x));
        half_h = fmaxf(half_h, fabsf(q.y));
    }
    half_w = fminf(fmaxf(half_w * layers_margins.radius_scale, 0.02f * r), r);
    half_h = fminf(fmaxf(half_h * layers_margins.radius_scale, 0.02f * r), r);
    v->half_width = half_w;
    v->half_height = half_h;
    v->proj = mat4_ortho(-half_w, half_w, -half_h, half_h, layers_margins.ortho_near_radii * r,
                         layers_margins.ortho_far_radii * r);
    return true;
}
