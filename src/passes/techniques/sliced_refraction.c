/* sliced_refraction: the refracted view through glass by sliced object
 * images (Iwasaki et al. §3, after their [13]). The viewing ray entering
 * at each glass vertex is followed through the object by the same light
 * transport table the illumination textures use (looked up in the
 * object's frame for the direction from the eye), giving where and in
 * which direction it leaves. Virtual planes perpendicular to the average
 * leaving direction cut the targets (the diffuse objects) into slabs; each
 * slab is drawn into its own sliced object image, projected on its nearer
 * plane by an orthographic camera along that direction. Each pixel of the
 * glass then follows its interpolated leaving ray to the planes in order
 * and shows the first slice that holds a target there, else the
 * environment. A slice's texel shows what the camera shows at that point
 * where the camera sees it (caustics and shadows included, when the input
 * has them), else the point's unshadowed Lambert shading. Rigid glass
 * only (the table is the base shape's); the output is the input with the
 * glass drawn over it, as `refraction`'s. */
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
#include "passes/helpers/shadow_inputs.h"
#include "passes/helpers/thin_glass_over.h"
#include "passes/helpers/virtual_camera.h"
#include "scene/transport.h"

#define SLICED_MAX_REFRACTORS 8
#define SLICED_MAX_SLICES 16
/* Subdivided for the table as illumination_textures' (a cube's faces into
 * 16 x 16): each vertex's viewing ray is one path, interpolated across its
 * triangles, and a cube's 12 triangles cannot hold a face whose rays leave
 * by the back and by a side (the reference's bands of side light were
 * missing at IOR 1.5). */
#define SLICED_EDGE_FRACTION (1.0f / 16.0f)
#define SLICED_MAX_TABLE_TRIANGLES 8192

/* The table's mesh of one glass object, on the GPU: the glass is drawn
 * with it, one viewing ray a vertex (glass.vert reads them by index). */
struct sliced_surface {
    GLuint vao, positions, normals, indices;
    GLsizei index_count;
    uint64_t serial; /* the mesh they hold */
};

/* The C mirror of SlicedGlassParams (glass.frag, std140; issue 54): the
 * slabs' planes (a float array's elements 16 bytes apart) and the switches. */
struct sliced_glass_params {
    float plane[SLICED_MAX_SLICES + 1][4]; /* along the virtual camera's axis, [0] only */
    int32_t slices_count, reflection, pad[2];
};
static const struct gl_block_member sliced_glass_params_members[] = {
    {"u_plane[0]", offsetof(struct sliced_glass_params, plane)},
    {"u_slices_count", offsetof(struct sliced_glass_params, slices_count)},
    {"u_reflection", offsetof(struct sliced_glass_params, reflection)},
};

struct sliced_state {
    struct gl_param_block params; /* SlicedGlassParams, this frame's */
    struct transport_table tables[SLICED_MAX_REFRACTORS];
    struct mesh_table_fine fine[SLICED_MAX_REFRACTORS];
    const struct mesh *table_mesh[SLICED_MAX_REFRACTORS];
    struct sliced_surface surfaces[SLICED_MAX_REFRACTORS];
    GLuint exits[SLICED_MAX_REFRACTORS];
    size_t exit_capacity[SLICED_MAX_REFRACTORS];
    struct gl_texture slices, slice_depth;
    struct gl_framebuffer slice_fb, out_fb;
    struct thin_glass_over panes;
    int size, count;
};

enum sliced_param { SR_COLOR, SR_DEPTH, SR_SLICES, SR_SIZE, SR_TABLE, SR_REFLECTION };

static const struct pass_param_desc params[] = {
    [SR_COLOR] = {.name = "color", .type = PASS_PARAM_INPUT, .required = true,
     .help = "the scene without the glass (`shade { specular = false }`, with caustics if it has them)"},
    [SR_DEPTH] = {.name = "depth", .type = PASS_PARAM_INPUT, .default_beside = "color", .default_output = "depth",
     .help = "its depth (default: the depth output of the pass that made color)"},
    [SR_SLICES] = {.name = "slices", .type = PASS_PARAM_INTEGER, .default_number = 6, .min = 1, .max = SLICED_MAX_SLICES,
     .help = "sliced object images (the paper: 6, 1 for Fig. 1)"},
    [SR_SIZE] = {.name = "size", .type = PASS_PARAM_INTEGER, .default_number = 512, .min = 16, .max = 4096,
     .help = "their size"},
    [SR_TABLE] = {.name = "table", .type = PASS_PARAM_INTEGER, .default_number = 16, .min = 2, .max = 64,
     .help = "the light transport table's directions per side (shared with illumination_textures' cache)"},
    [SR_REFLECTION] = {.name = "reflection", .type = PASS_PARAM_BOOLEAN, .default_number = 1,
     .help = "add the Fresnel reflection of the environment at the front surface"},
};

static bool sliced_declare(struct pass *p, struct error *err)
{
    return pass_declare_output(p, "color", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool sliced_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct sliced_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("SlicedGlassParams", sliced_glass_params_members, struct sliced_glass_params);
    p->state = s;
    return gl_framebuffer_create(&s->slice_fb, err) && gl_framebuffer_create(&s->out_fb, err);
}

static void surface_release(struct sliced_surface *g)
{
    if (g->vao && gl_api_ready())
        gl.DeleteVertexArrays(1, &g->vao);
    gl_buffer_destroy(&g->positions);
    gl_buffer_destroy(&g->normals);
    gl_buffer_destroy(&g->indices);
    *g = (struct sliced_surface){0};
}

/* The mesh's positions, normals and triangles on the GPU (again only when
 * it is another mesh). */
static bool surface_upload(struct sliced_surface *g, const struct mesh *m, struct error *err)
{
    if (g->vao && g->serial == m->serial)
        return true;
    surface_release(g);
    size_t vec3s = m->vertex_count * 3 * sizeof(float);
    if (!gl_buffer_create(&g->positions, m->positions, vec3s, 0, err) ||
        !gl_buffer_create(&g->normals, m->normals, vec3s, 0, err) ||
        !gl_buffer_create(&g->indices, m->indices, m->index_count * sizeof(uint32_t), 0, err))
        return false;
    gl.CreateVertexArrays(1, &g->vao);
    GLuint buffers[2] = {g->positions, g->normals};
    for (GLuint a = 0; a < 2; a++) {
        gl.EnableVertexArrayAttrib(g->vao, a);
        gl.VertexArrayAttribFormat(g->vao, a, 3, GL_FLOAT, GL_FALSE, 0);
        gl.VertexArrayAttribBinding(g->vao, a, a);
        gl.VertexArrayVertexBuffer(g->vao, a, buffers[a], 0, 3 * sizeof(float));
    }
    gl.VertexArrayElementBuffer(g->vao, g->indices);
    g->index_count = (GLsizei)m->index_count;
    g->serial = m->serial;
    return true;
}

static void sliced_destroy(struct pass *p)
{
    struct sliced_state *s = p->state;
    if (!s)
        return;
    for (int i = 0; i < SLICED_MAX_REFRACTORS; i++) {
        transport_table_release(&s->tables[i]);
        mesh_table_fine_release(&s->fine[i]);
        surface_release(&s->surfaces[i]);
        if (s->exits[i] && gl_api_ready())
            gl.DeleteBuffers(1, &s->exits[i]);
    }
    gl_texture_destroy(&s->slices);
    gl_texture_destroy(&s->slice_depth);
    gl_framebuffer_destroy(&s->slice_fb);
    gl_framebuffer_destroy(&s->out_fb);
    thin_glass_over_release(&s->panes);
    gl_param_block_release(&s->params);
    free(s);
    p->state = NULL;
}

/* The objects it refracts through: closed glass (Iwasaki et al. §3 slice the
 * scene around a closed object); water and mirrors are another pass's. */
#define SLICED_REFRACTORS OBJECT_ROLE_GLASS
static bool is_refractor(const struct object *o) { return object_is(o, SLICED_REFRACTORS); }

/* Per glass vertex (std430 Exit in glass.vert): exit point (w = 1 where a
 * path exists), direction, transmittance. */
static bool viewing_rays(struct sliced_state *s, int k, const struct object *o, const struct frame *fr,
                         const struct scene *scene, vec3 *dir_sum, vec3 *exit_sum, int *exit_count, struct error *err)
{
    const struct mesh *m = s->table_mesh[k];
    const struct frame_object *fo = frame_object_of(fr, o);
    mat4 model = fo ? fo->model : object_model_matrix(o), inverse;
    if (!mat4_inverse(model, &inverse))
        inverse = mat4_identity();
    size_t n = m->vertex_count;
    float *data = calloc(n * 12, sizeof(float));
    if (!data)
        return error_set(err, "sliced_refraction: out of memory");
    bool ortho = scene->camera.ortho_width > 0.0f;
    vec3 forward = vec3_normalize_or(vec3_sub(scene->camera.target, scene->camera.eye), vec3_make(0, 0, -1));
    for (size_t v = 0; v < n; v++) {
        vec3 pw = mat4_transform_point(model, vec3_make(m->positions[v * 3], m->positions[v * 3 + 1], m->positions[v * 3 + 2]));
        vec3 dw = ortho ? forward : vec3_normalize_or(vec3_sub(pw, fr->eye), forward);
        vec3 lp, ld, tr;
        float *e = data + v * 12;
        if (transport_lookup(&s->tables[k], v, vec3_normalize_or(mat4_transform_dir(inverse, dw), dw), &lp, &ld, &tr)) {
            vec3 ep = mat4_transform_point(model, lp), ed = vec3_normalize_or(mat4_transform_dir(model, ld), dw);
            e[0] = ep.x, e[1] = ep.y, e[2] = ep.z, e[3] = 1.0f;
            e[4] = ed.x, e[5] = ed.y, e[6] = ed.z;
            e[8] = tr.x, e[9] = tr.y, e[10] = tr.z;
            *dir_sum = vec3_add(*dir_sum, ed);
            *exit_sum = vec3_add(*exit_sum, ep);
            (*exit_count)++;
        }
    }
    size_t bytes = n * 12 * sizeof(float);
    if (bytes > s->exit_capacity[k]) {
        if (s->exits[k])
            gl.DeleteBuffers(1, &s->exits[k]);
        gl.CreateBuffers(1, &s->exits[k]);
        gl.NamedBufferStorage(s->exits[k], (GLsizeiptr)bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
        s->exit_capacity[k] = bytes;
    }
    gl.NamedBufferSubData(s->exits[k], 0, (GLsizeiptr)bytes, data);
    free(data);
    return true;
}

/* The virtual planes along the average leaving direction, across the
 * targets; the square over the targets' extent (§3). `planes`: count + 1. */
static void fit_planes(const struct scene *scene, vec3 dir_sum, vec3 exit_sum, int exit_count, int count,
                       struct virtual_camera *out, float *planes)
{
    struct virtual_camera vc;
    virtual_camera_axes(&vc, vec3_normalize_or(dir_sum, vec3_normalize_or(vec3_sub(scene->camera.target,
                                                                                   scene->camera.eye), vec3_make(0, 0, -1))));
    vec3 lo = {0, 0, 0}, hi = {0, 0, 0};
    bool any = false;
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        if (!object_is(o, OBJECT_ROLE_RECEIVER))
            continue;
        vec3 olo, ohi;
        object_world_bounds(o, &olo, &ohi);
        lo = any ? vec3_min(lo, olo) : olo;
        hi = any ? vec3_max(hi, ohi) : ohi;
        any = true;
    }
    float dmin = INFINITY, dmax = -INFINITY, umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
    for (int c = 0; any && c < 8; c++) {
        vec3 corner = vec3_make(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
        float z = vec3_dot(corner, vc.d), cu = vec3_dot(corner, vc.u), cv = vec3_dot(corner, vc.v);
        dmin = fminf(dmin, z), dmax = fmaxf(dmax, z);
        umin = fminf(umin, cu), umax = fmaxf(umax, cu), vmin = fminf(vmin, cv), vmax = fmaxf(vmax, cv);
    }
    if (!any)
        dmin = dmax = umin = umax = vmin = vmax = 0.0f;
    vc.center[0] = 0.5f * (umin + umax), vc.center[1] = 0.5f * (vmin + vmax);
    vc.half = fmaxf(0.5f * fmaxf(umax - umin, vmax - vmin) * 1.02f, 1e-4f);
    float pad = 0.01f * (dmax - dmin) + 1e-4f;
    vc.near = dmin - pad, vc.far = dmax + pad;
    /* the slabs start where the viewing rays leave the glass: what lies in
     * front of it is not seen through it */
    if (exit_count > 0) {
        float start = vec3_dot(vec3_scale(exit_sum, 1.0f / (float)exit_count), vc.d);
        if (start > vc.near && start < vc.far)
            vc.near = start;
    }
    for (int i = 0; i <= count; i++)
        planes[i] = vc.near + (vc.far - vc.near) * (float)i / (float)count;
    *out = vc;
}

/* The sliced object images (Iwasaki et al. §3): the diffuse objects
 * between each pair of planes, seen along the virtual camera. */
static bool draw_slices(struct sliced_state *s, struct pass *p, struct pass_frame *f, const struct virtual_camera *vc,
                        const float *planes, int count, int size, const struct gl_texture *in_color,
                        const struct gl_texture *in_depth, struct error *err)
{
    struct renderer *r = f->renderer;
    const struct scene *scene = f->scene;
    if (!s->slices.id || s->size != size || s->count != count) {
        gl_texture_destroy(&s->slices);
        gl_texture_destroy(&s->slice_depth);
        if (!gl_texture_create(&s->slices, GL_TEXTURE_2D_ARRAY, GL_RGBA16F, size, size, count, err) ||
            !gl_texture_create(&s->slice_depth, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, size, size, 1, err))
            return false;
        s->size = size;
        s->count = count;
    }
    struct gl_program *slice;
    if (!gl_program_get(&r->programs, "illumination_textures/target.vert", "sliced_refraction/slice.frag", NULL, &slice,
                        err))
        return false;
    virtual_camera_set(slice, vc);
    /* the slices' own lighting (common/surface_light.glsl): this pass has no
     * shadow maps (u_shadow_total 0), the medium it has */
    shadow_inputs_bind(p, f, slice);
    if (!medium_gpu_bind(r, scene, slice, err))
        return false;
    gl_program_bind_texture(slice, "u_scene", in_color->id);
    gl_program_bind_texture(slice, "u_scene_depth", in_depth->id);
    const float clear[4] = {0, 0, 0, 0};
    for (int i = 0; i < count; i++) {
        const struct gl_texture *layer[1] = {&s->slices};
        int index[1] = {i};
        if (!gl_framebuffer_attach(&s->slice_fb, layer, index, 1, &s->slice_depth, -1, err))
            return false;
        gl.BindFramebuffer(GL_FRAMEBUFFER, s->slice_fb.id);
        gl.Viewport(0, 0, size, size);
        gl.ClearNamedFramebufferfv(s->slice_fb.id, GL_COLOR, 0, clear);
        gl.Clear(GL_DEPTH_BUFFER_BIT);
        gl.Enable(GL_DEPTH_TEST);
        gl.ProgramUniform2f(slice->id, gl_program_uniform(slice, "u_slab"), planes[i], planes[i + 1]);
        renderer_draw_objects(r, scene, slice, DRAW_DIFFUSE);
    }
    renderer_reset_state(r);
    return true;
}

static bool sliced_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct sliced_state *s = p->state;
    struct renderer *r = f->renderer;
    const struct scene *scene = f->scene;
    struct graph_resource *in_color = pass_frame_input(p, f, "color"), *in_depth = pass_frame_input(p, f, "depth");
    struct graph_resource *out = f->outputs[0];
    int count = pass_int(p, SR_SLICES), size = pass_int(p, SR_SIZE), resolution = pass_int(p, SR_TABLE);

    /* the input as it is, then the glass over it */
    const struct gl_texture *oc[1] = {&out->texture};
    if (!gl_framebuffer_attach(&s->out_fb, oc, NULL, 1, &in_depth->texture, -1, err) ||
        !renderer_draw_copy(r, s->out_fb.id, f->width, f->height, in_color->texture.id, err))
        return false;

    /* the viewing rays through each glass object (§3: the table) */
    pass_stage_begin(p);
    vec3 dir_sum = {0, 0, 0}, exit_sum = {0, 0, 0};
    int k = 0, exit_count = 0;
    p->report[0] = '\0';
    for (int i = 0; i < scene->object_count && k < SLICED_MAX_REFRACTORS; i++) {
        struct object *o = scene->objects[i];
        if (!is_refractor(o))
            continue;
        const struct mesh *m = s->table_mesh[k] =
            mesh_table_mesh(&s->fine[k], o->mesh, SLICED_EDGE_FRACTION, SLICED_MAX_TABLE_TRIANGLES, err);
        /* a fine mesh gets fewer directions, so its table fits (said in the report) */
        if (!m || !transport_table_ensure(&s->tables[k], m, &o->material, resolution, TRANSPORT_INTERNAL_NONE, i + 1,
                                          p->report, sizeof p->report, err) ||
            !surface_upload(&s->surfaces[k], m, err))
            return false;
        if (!viewing_rays(s, k, o, f->snapshot, scene, &dir_sum, &exit_sum, &exit_count, err))
            return false;
        k++;
    }
    pass_stage_end(p, "viewing rays");
    if (k == 0)
        return true;

    struct virtual_camera vc;
    float planes[SLICED_MAX_SLICES + 1];
    fit_planes(scene, dir_sum, exit_sum, exit_count, count, &vc, planes);

    if (!draw_slices(s, p, f, &vc, planes, count, size, &in_color->texture, &in_depth->texture, err))
        return false;
    pass_stage_end(p, "slices");
    struct gl_program *glass;
    if (!gl_program_get(&r->programs, "sliced_refraction/glass.vert", "sliced_refraction/glass.frag", NULL, &glass, err))
        return false;
    virtual_camera_set(glass, &vc);

    /* the glass: its front surface shows the slices along its leaving rays */
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->out_fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LEQUAL);
    gl.DepthMask(GL_FALSE);
    gl.Enable(GL_CULL_FACE);
    gl.CullFace(GL_BACK);
    gl_program_bind_texture(glass, "u_slices", s->slices.id);
    struct sliced_glass_params values = {.slices_count = count, .reflection = pass_flag(p, SR_REFLECTION)};
    for (int i = 0; i <= count; i++)
        values.plane[i][0] = planes[i];
    if (!gl_param_block_upload(&s->params, &values, err) || !gl_param_block_bind(&s->params, glass, err))
        return false;
    gl.UseProgram(glass->id);
    k = 0;
    for (int i = 0; i < scene->object_count && k < SLICED_MAX_REFRACTORS; i++) {
        struct object *o = scene->objects[i];
        if (!is_refractor(o))
            continue;
        const struct sliced_surface *g = &s->surfaces[k];
        gl_program_bind_storage(glass, "Exits", s->exits[k++]);
        const struct frame_object *fo = frame_object_of(f->snapshot, o);
        if (!o->visible || !fo)
            continue;
        gl.ProgramUniformMatrix4fv(glass->id, gl_program_uniform(glass, "u_model"), 1, GL_FALSE, fo->model.m);
        gl.ProgramUniformMatrix4fv(glass->id, gl_program_uniform(glass, "u_normal_matrix"), 1, GL_FALSE,
                                   fo->normal_matrix.m);
        gl.ProgramUniform1f(glass->id, gl_program_uniform(glass, "u_ior"), o->material.ior);
        gl.ProgramUniform1f(glass->id, gl_program_uniform(glass, "u_ideal"), o->material.ideal ? 1.0f : 0.0f);
        gl.BindVertexArray(g->vao);
        gl.DrawElements(GL_TRIANGLES, g->index_count, GL_UNSIGNED_INT, NULL);
    }
    gl.BindVertexArray(0);
    pass_stage_end(p, "glass");
    /* the panes in front of the glass, over it (shade drew them under it) */
    return gl_check("sliced_refraction", err) &&
           thin_glass_draw(&s->panes, p, f, THIN_GLASS_OVER_SURFACES, 0, &f->outputs[0]->texture, in_depth ? &in_depth->texture : NULL,
                                SLICED_REFRACTORS, NULL, err);
}

/* The sliced object images are mapped onto the glass's front faces
 * (Iwasaki et al. §3): a camera inside sees none of them. */
static const char *sliced_refraction_leaves_out(const struct pass *p, const struct scene *scene,
                                                const struct object *o)
{
    (void)p;
    if (is_refractor(o) && object_contains_point(o, scene->camera.eye))
        return "the camera is inside it: the sliced object images are seen through its front faces, none of which "
               "the camera sees, so the view through it is not refracted (refraction or layered_refraction trace it)";
    return pass_refractor_holds(scene, o, pass_refractor_left_out(o, false));
}

static unsigned sliced_refraction_draws(const struct pass *p)
{
    (void)p;
    return SLICED_REFRACTORS;
}

const struct pass_desc sliced_refraction_pass = {
    .technique = PASS_TECHNIQUE_VIEW,
    .draws = sliced_refraction_draws,
    .name = "sliced_refraction",
    .leaves_out = sliced_refraction_leaves_out,
    .summary = "Iwasaki et al.: the refracted view through glass by sliced object images and the light transport table",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = sliced_declare,
    .create = sliced_create,
    .execute = sliced_execute,
    .destroy = sliced_destroy,
};
