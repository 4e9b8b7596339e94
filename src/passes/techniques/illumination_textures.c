/* illumination_textures: refractive caustics through illumination
 * textures on virtual planes (Iwasaki, Dobashi, Yoshimoto, Nishita). Each
 * glass object's light transport table (scene/transport.c: per vertex and
 * incident direction, where the light leaves and how much of it) gives,
 * for the light's direction at each vertex in the object's frame, the
 * outgoing rays; the three rays of a surface triangle sweep an
 * illumination volume (§4.1, after Nishita et al.). Virtual planes
 * perpendicular to the average transmitted direction cut the volumes into
 * intersection triangles, drawn additively into one illumination texture
 * per plane with eq. 3's intensity L_in cos(theta) F_t S cos(gamma) /
 * (S_0 cos(delta)), cos(gamma) per pixel from the targets' normal map seen
 * by a virtual camera along that direction (§4.2). A receiver point seen
 * by the camera reads the two planes around its depth (§4.3, Fig. 5),
 * unless the targets' depth map says the light is blocked first. Nothing
 * here depends on the camera: a camera-only change reuses the textures and
 * only the last step runs.
 *
 * Targets are the objects of `targets`, or every visible diffuse object,
 * sharing one set of planes (the paper sets planes per target object: one
 * set keeps the occlusion between targets, a teapot shadowing the floor
 * from the caustic light, which separate sets would lose); the virtual
 * camera's square covers where the transmitted rays cross the planes. A focus on a plane (S_0 ->
 * 0) is capped at half a texel's area: no caustic can be sharper than the
 * texture resolves, as caustic volumes cap theirs by the grid; an
 * intersection triangle smaller than a texel is drawn as a point holding
 * its flux, which rasterizing it could miss. The virtual camera's square
 * covers where 99% of the transmitted flux crosses the planes. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/array.h"
#include "core/hash.h"
#include "gl/gl_param_block.h"
#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/helpers/caustic_coverage.h"
#include "passes/helpers/illumination_geometry.h"
#include "passes/helpers/shadow_inputs.h"
#include "passes/helpers/virtual_camera.h"
#include "scene/transport.h"

#define ILLUM_MAX_REFRACTORS 8

/* A glass mesh whose longest edge is more than this fraction of its
 * bounding diagonal is subdivided for its table (scene/mesh_subdivide.c):
 * 1/16 splits a cube's faces into 16 x 16 (3,072 triangles, a 15 MB table
 * at table = 16) and leaves the default spheres (128 segments) alone. */
#define ILLUM_EDGE_FRACTION (1.0f / 16.0f)
#define ILLUM_MAX_TABLE_TRIANGLES 8192

/* The C mirror of IlluminationMapParams (map.frag, std140; issue 54): the
 * virtual planes' depths (a float array's elements 16 bytes apart), their
 * count and the shadow test's tolerance. */
struct illumination_map_params {
    float plane_depth[ILLUM_MAX_PLANES][4]; /* [0] only */
    int32_t planes;
    float bias;
    int32_t pad[2];
};
static const struct gl_block_member illumination_map_params_members[] = {
    {"u_plane_depth[0]", offsetof(struct illumination_map_params, plane_depth)},
    {"u_planes", offsetof(struct illumination_map_params, planes)},
    {"u_bias", offsetof(struct illumination_map_params, bias)},
};

struct illum_state {
    struct gl_param_block params; /* IlluminationMapParams, this frame's */
    struct transport_table tables[ILLUM_MAX_REFRACTORS];
    /* each table's paths traced exactly where a triangle's vertices' paths
     * part (illumination_geometry.c), made with the table */
    struct transport_tracer *tracers[ILLUM_MAX_REFRACTORS];
    bool *flat[ILLUM_MAX_REFRACTORS]; /* illum_flat_vertices of each table's mesh, made with its tracer */
    uint64_t tracer_key[ILLUM_MAX_REFRACTORS];
    /* the mesh each table samples: the object's, or `fine`'s subdivision of it */
    const struct mesh *table_mesh[ILLUM_MAX_REFRACTORS];
    struct mesh_table_fine fine[ILLUM_MAX_REFRACTORS];
    int table_count;
    struct gl_texture target, target_depth, textures, receiver_depth;
    struct gl_framebuffer target_fb, texture_fb, map_fb;
    GLuint vbo, vao;
    size_t vbo_capacity;
    int size, planes;
    bool valid;
    uint64_t key;              /* what the textures were made from */
    /* the virtual camera and planes of the last build */
    struct virtual_camera vc;
    struct caustic_coverage coverage; /* what it left dark under glass, measured once */
    float plane_depth[ILLUM_MAX_PLANES];
    bool reused;
};

enum illum_param { IT_LIGHT, IT_PLANES, IT_SIZE, IT_TABLE, IT_INTERNAL, IT_TARGETS, IT_SHADOW };
enum { INTERNAL_NONE, INTERNAL_FIRST };

static const struct pass_param_desc params[] = {
    [IT_LIGHT] = {.name = "light", .type = PASS_PARAM_LIGHT, .required = true,
     .help = "the light (directional or point; a linear light as its point samples, accumulated, Fig. 6d)"},
    [IT_PLANES] = {.name = "planes", .type = PASS_PARAM_INTEGER, .default_number = 16, .min = 1, .max = ILLUM_MAX_PLANES,
     .help = "virtual planes across the targets (§4.2; the paper uses 4: too few where a focus lies between them, see docs/techniques/iwasaki.md)"},
    [IT_SIZE] = {.name = "size", .type = PASS_PARAM_INTEGER, .default_number = 256, .min = 16, .max = 4096,
     .help = "illumination texture size (the paper uses 512; 256 is the bench's best here: finer texels leave more sub-texel triangles as points)"},
    [IT_TABLE] = {.name = "table", .type = PASS_PARAM_INTEGER, .default_number = 16, .min = 2, .max = 64,
     .help = "light transport table: incident directions per side of its octahedral map (table^2 directions per vertex)"},
    [IT_INTERNAL] = {.name = "internal", .type = PASS_PARAM_ENUM, .default_string = "first", .choices = "none|first",
     .help = "paths with total internal reflection: the first one followed (a cube at IOR 2.42 lights its floor "
             "where none left a black band; a ball never reflects inside), or none (the paper's)"},
    [IT_TARGETS] = {.name = "targets", .type = PASS_PARAM_OBJECT_LIST,
     .help = "the diffuse objects that receive the caustics (default: every visible diffuse object)"},
    [IT_SHADOW] = SHADOW_PARAM_PANES("an illumination volume"),
};

static bool illum_declare(struct pass *p, struct error *err)
{
    return pass_declare_output(p, "irradiance", GL_RGBA32F, GL_TEXTURE_2D, 0, 0, err);
}

static bool illum_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct illum_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    s->params = GL_PARAM_BLOCK_OF("IlluminationMapParams",
                                  illumination_map_params_members, struct illumination_map_params);
    p->state = s;
    if (!gl_framebuffer_create(&s->target_fb, err) || !gl_framebuffer_create(&s->texture_fb, err) ||
        !gl_framebuffer_create(&s->map_fb, err))
        return false;
    gl.CreateVertexArrays(1, &s->vao);
    for (GLuint a = 0; a < ILLUM_VERTEX_FLOATS / 3; a++) {
        gl.EnableVertexArrayAttrib(s->vao, a);
        gl.VertexArrayAttribFormat(s->vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
        gl.VertexArrayAttribBinding(s->vao, a, 0);
    }
    return gl_check("illumination_textures", err);
}

static void release_targets(struct illum_state *s)
{
    gl_texture_destroy(&s->target);
    gl_texture_destroy(&s->target_depth);
    gl_texture_destroy(&s->textures);
    gl_texture_destroy(&s->receiver_depth);
}

static void illum_destroy(struct pass *p)
{
    struct illum_state *s = p->state;
    if (!s)
        return;
    for (int i = 0; i < ILLUM_MAX_REFRACTORS; i++) {
        transport_table_release(&s->tables[i]);
        transport_tracer_destroy(s->tracers[i]);
        free(s->flat[i]);
        mesh_table_fine_release(&s->fine[i]);
    }
    release_targets(s);
    caustic_coverage_release(&s->coverage);
    gl_framebuffer_destroy(&s->target_fb);
    gl_framebuffer_destroy(&s->texture_fb);
    gl_framebuffer_destroy(&s->map_fb);
    if (gl_api_ready()) {
        if (s->vbo)
            gl.DeleteBuffers(1, &s->vbo);
        if (s->vao)
            gl.DeleteVertexArrays(1, &s->vao);
    }
    gl_param_block_release(&s->params);
    free(s);
    p->state = NULL;
}

/* The objects whose caustics it makes: closed glass (the light transport
 * tables are per vertex of a closed object, §4.2); leaves_out says so of
 * the others. */
#define ILLUM_REFRACTORS OBJECT_ROLE_GLASS
static bool is_refractor(const struct object *o) { return object_is(o, ILLUM_REFRACTORS); }
/* A receiver of the caustics: one of `targets` when given, else any visible diffuse object. */
static bool is_target(const struct pass *p, const struct object *o)
{
    if (!object_is(o, OBJECT_ROLE_RECEIVER))
        return false;
    const struct pass_value *v = &p->values[IT_TARGETS];
    if (v->object_count == 0)
        return true;
    for (int k = 0; k < v->object_count; k++)
        if (v->objects[k] == o)
            return true;
    return false;
}

/* The targets, each drawn with `prog`. */
static void draw_targets(const struct pass *p, struct renderer *r, const struct scene *scene,
                         const struct gl_program *prog)
{
    for (int i = 0; i < scene->object_count; i++)
        if (is_target(p, scene->objects[i]))
            renderer_draw_object(r, scene, prog, scene->objects[i]);
}

/* Everything the textures depend on: the light, the glass, the targets and
 * the parameters (pass_frame_key without the camera). */
static uint64_t texture_key(struct pass *p, const struct pass_frame *f)
{
    return pass_frame_key(p, f, PASS_DEPENDS_GEOMETRY);
}

static enum pass_need illum_needed(struct pass *p, struct pass_frame *f, char *why, size_t whylen)
{
    struct illum_state *s = p->state;
    struct light *light = pass_light_at(p, IT_LIGHT);
    if (!s || !light)
        return PASS_RUN;
    char tables[256] = "";
    size_t bytes = 0, vertices = 0;
    double seconds = 0.0;
    bool all_cached = s->table_count > 0;
    int subdivided = 0;
    for (int i = 0; i < s->table_count; i++) {
        subdivided += s->fine[i].fine && s->table_mesh[i] == s->fine[i].fine;
        bytes += s->tables[i].bytes;
        vertices += s->tables[i].vertex_count;
        seconds += s->tables[i].build_seconds;
        all_cached = all_cached && s->tables[i].from_cache;
    }
    if (s->table_count > 0)
        snprintf(tables, sizeof tables, "; transport tables: %d, %zu vertices x %d directions, %.1f MB, %s in %.2f s%s%s",
                 s->table_count, vertices, s->tables[0].resolution * s->tables[0].resolution, (double)bytes / 1048576.0,
                 all_cached ? "read from the cache" : "traced", seconds,
                 subdivided ? " (coarse meshes subdivided for their tables)" : "",
                 s->tables[0].resolution < pass_int(p, IT_TABLE) ? " (fewer directions than `table` asks, to fit: a fine mesh)"
                                                                 : "");
    bool reuse = pass_frame_reusable(f, s->valid, s->key, texture_key(p, f));
    snprintf(why, whylen, "%s%s",
             reuse ? "the illumination textures are reused (light, glass and targets unchanged: only the mapping runs)"
                   : "the illumination textures are made again (the light, the glass or a target changed)",
             tables);
    return PASS_RUN;
}

static bool ensure_targets(struct illum_state *s, int size, int planes, int w, int h, struct error *err)
{
    if (s->target.id && s->size == size && s->planes == planes && s->receiver_depth.width == w &&
        s->receiver_depth.height == h)
        return true;
    release_targets(s);
    s->size = size;
    s->planes = planes;
    s->valid = false;
    if (!gl_texture_create(&s->target, GL_TEXTURE_2D, GL_RGBA32F, size, size, 1, err) ||
        !gl_texture_create(&s->target_depth, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, size, size, 1, err) ||
        !gl_texture_create(&s->textures, GL_TEXTURE_2D_ARRAY, GL_RGBA32F, size, size, planes, err) ||
        !gl_texture_create(&s->receiver_depth, GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, w, h, 1, err))
        return false;
    gl.TextureParameteri(s->target.id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TextureParameteri(s->target.id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    const struct gl_texture *tc[1] = {&s->target};
    return gl_framebuffer_attach(&s->target_fb, tc, NULL, 1, &s->target_depth, -1, err);
}

/* §4.1: the volumes of every glass object for one light sample
 * (illumination_geometry.c). */
static bool collect_volumes(struct illum_state *s, const struct frame *fr, const struct scene *scene,
                            const struct frame_light *light, struct illum_volume_list *out, struct error *err)
{
    int t = 0;
    for (int i = 0; i < scene->object_count && t < s->table_count; i++) {
        struct object *o = scene->objects[i];
        if (!is_refractor(o))
            continue;
        const struct frame_object *fo = frame_object_of(fr, o);
        if (!illum_volumes_collect(s->table_mesh[t], &s->tables[t], s->tracers[t], s->flat[t],
                                   fo ? fo->model : object_model_matrix(o), light, out, err))
            return false;
        t++;
    }
    return true;
}

/* Builds the tables (when new), the virtual camera, the planes and the
 * illumination textures. */
/* What a tracer traces: the mesh and the material's optics. */
static uint64_t tracer_key(const struct mesh *m, const struct material *mat, enum transport_internal internal)
{
    float optics[6] = {mat->ior, mat->ideal ? 1.0f : 0.0f, mat->absorption.x, mat->absorption.y, mat->absorption.z,
                       (float)internal};
    return hash_fnv1a(hash_fnv1a(HASH_FNV1A_BASIS, &m->serial, sizeof m->serial), optics, sizeof optics);
}

/* §3: the tables, one per glass object (built once per mesh, IOR,
 * resolution), and their tracers for the exact paths on flat faces. */
static bool ensure_tables(struct illum_state *s, struct pass *p, const struct scene *scene, struct error *err)
{
    int resolution = pass_int(p, IT_TABLE);
    enum transport_internal internal = pass_choice(p, IT_INTERNAL) == INTERNAL_FIRST ? TRANSPORT_INTERNAL_FIRST
                                                                                    : TRANSPORT_INTERNAL_NONE;
    s->table_count = 0;
    p->report[0] = '\0';
    for (int i = 0; i < scene->object_count && s->table_count < ILLUM_MAX_REFRACTORS; i++) {
        struct object *o = scene->objects[i];
        if (!is_refractor(o))
            continue;
        int k = s->table_count++;
        const struct mesh *m = s->table_mesh[k] =
            mesh_table_mesh(&s->fine[k], o->mesh, ILLUM_EDGE_FRACTION, ILLUM_MAX_TABLE_TRIANGLES, err);
        if (!m)
            return false;
        struct transport_table *t = &s->tables[k];
        /* a fine mesh gets fewer directions, so its table fits (said in info and --timings) */
        if (!transport_table_ensure(t, m, &o->material, resolution, internal, i + 1, p->report, sizeof p->report, err))
            return false;
        uint64_t key = tracer_key(m, &o->material, internal);
        if (!s->tracers[k] || s->tracer_key[k] != key) {
            transport_tracer_destroy(s->tracers[k]);
            free(s->flat[k]);
            s->tracers[k] = NULL;
            s->flat[k] = NULL;
            if (!transport_tracer_create(&s->tracers[k], m, &o->material, internal, err) ||
                !(s->flat[k] = illum_flat_vertices(m, err)))
                return false;
            s->tracer_key[k] = key;
        }
    }
    return true;
}

/* The planes span the depths the virtual camera sees of the targets
 * within its square (read back: size^2 texels), not the targets' whole
 * bounds: a large receiver (a floor) seen at a slant would otherwise
 * spread the planes over depths no caustic reaches. */
static void spread_over_seen(struct illum_state *s, int size, int planes, float *pd, struct error *err)
{
    float *texels = malloc((size_t)size * (size_t)size * 4 * sizeof(float));
    if (texels && gl_texture_read_rgba32f(&s->target, 0, texels, err)) {
        float seen_min = INFINITY, seen_max = -INFINITY;
        for (size_t i = 0; i < (size_t)size * (size_t)size; i++) {
            float z = texels[i * 4 + 3];
            if (z < 1e29f) {
                seen_min = fminf(seen_min, z);
                seen_max = fmaxf(seen_max, z);
            }
        }
        if (seen_min <= seen_max)
            illum_planes_spread(seen_min, seen_max, planes, pd);
    }
    free(texels);
}

/* The targets' normal map and depth from the virtual camera (§4.2). */
static bool draw_target_map(struct illum_state *s, struct pass *p, struct renderer *r, const struct scene *scene,
                            int size, struct error *err)
{
    struct gl_program *target;
    if (!gl_program_get(&r->programs, "illumination_textures/target.vert", "illumination_textures/target.frag", NULL,
                        &target, err))
        return false;
    virtual_camera_set(target, &s->vc);
    const float no_target[4] = {0, 0, 0, 1e30f};
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->target_fb.id);
    gl.Viewport(0, 0, size, size);
    gl.ClearNamedFramebufferfv(s->target_fb.id, GL_COLOR, 0, no_target);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    draw_targets(p, r, scene, target);
    renderer_reset_state(r);
    return true;
}

/* The intersection triangles' vertices, the points after them, in one
 * buffer. */
static void upload_intersections(struct illum_state *s, const struct illum_intersections *x)
{
    size_t n = x->triangle_vertices, np = x->point_vertices;
    size_t tri_bytes = n * ILLUM_VERTEX_FLOATS * sizeof(float), point_bytes = np * ILLUM_VERTEX_FLOATS * sizeof(float);
    size_t bytes = tri_bytes + point_bytes;
    if (bytes > s->vbo_capacity) {
        if (s->vbo)
            gl.DeleteBuffers(1, &s->vbo);
        gl.CreateBuffers(1, &s->vbo);
        gl.NamedBufferStorage(s->vbo, (GLsizeiptr)bytes, NULL, GL_DYNAMIC_STORAGE_BIT);
        s->vbo_capacity = bytes;
        gl.VertexArrayVertexBuffer(s->vao, 0, s->vbo, 0, ILLUM_VERTEX_FLOATS * sizeof(float));
    }
    if (tri_bytes)
        gl.NamedBufferSubData(s->vbo, 0, (GLsizeiptr)tri_bytes, x->triangles);
    if (point_bytes)
        gl.NamedBufferSubData(s->vbo, (GLintptr)tri_bytes, (GLsizeiptr)point_bytes, x->points);
}

static bool build_textures(struct pass *p, struct pass_frame *f, int slot, struct error *err)
{
    struct illum_state *s = p->state;
    struct renderer *r = f->renderer;
    const struct scene *scene = f->scene;
    int planes = pass_int(p, IT_PLANES), size = s->size;
    if (!ensure_tables(s, p, scene, err))
        return false;
    pass_stage_end(p, "tables");
    struct illum_volume_list vols = {0};
    int first = r->frame.light_first[slot], entries = r->frame.light_entries[slot];
    for (int e = 0; e < entries; e++) /* a linear light: each point sample's volumes (Fig. 6d) */
        if (!collect_volumes(s, &r->frame, scene, &r->frame.lights[first + e], &vols, err)) {
            free(vols.items);
            return false;
        }
    const float zero[4] = {0, 0, 0, 0};
    gl.ClearTexImage(s->textures.id, 0, GL_RGBA, GL_FLOAT, zero);
    vec3 d = illum_mean_direction(&vols); /* the average transmitted direction, weighted by flux */
    vec3 lo, hi;
    bool any_target = false;
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        if (!is_target(p, o))
            continue;
        vec3 olo, ohi;
        object_world_bounds(o, &olo, &ohi);
        lo = any_target ? vec3_min(lo, olo) : olo;
        hi = any_target ? vec3_max(hi, ohi) : ohi;
        any_target = true;
    }
    if (vols.count == 0 || !any_target) {
        free(vols.items);
        s->planes = 0;
        return true;
    }
    /* the virtual camera (§4.2): along d, U and V spanning its planes */
    struct virtual_camera axes;
    virtual_camera_axes(&axes, d);
    vec3 u = axes.u, v = axes.v;
    float dmin = INFINITY, dmax = -INFINITY;
    for (int c = 0; c < 8; c++) {
        vec3 corner = vec3_make(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
        float z = vec3_dot(corner, d);
        dmin = fminf(dmin, z);
        dmax = fmaxf(dmax, z);
    }
    float pd[ILLUM_MAX_PLANES];
    illum_planes_spread(dmin, dmax, planes, pd);
    /* the square where 99% of the flux crosses the planes, no larger than
     * the targets' own extent */
    float cu, cv, half;
    if (!illum_flux_square(&vols, d, u, v, pd, planes, 0.5f * vec3_length(vec3_sub(hi, lo)), &cu, &cv, &half)) {
        free(vols.items);
        s->planes = 0;
        return true;
    }
    s->vc.d = d, s->vc.u = u, s->vc.v = v;
    s->vc.center[0] = cu, s->vc.center[1] = cv, s->vc.half = half;
    float pad = 0.01f * (dmax - dmin) + 1e-4f;
    s->vc.near = dmin - pad, s->vc.far = dmax + pad;
    memcpy(s->plane_depth, pd, sizeof pd);
    s->planes = planes;
    struct gl_program *illum;
    if (!draw_target_map(s, p, r, scene, size, err) ||
        !gl_program_get(&r->programs, "illumination_textures/illumination.vert",
                        "illumination_textures/illumination.frag", NULL, &illum, err)) {
        free(vols.items);
        return false;
    }
    virtual_camera_set(illum, &s->vc);
    spread_over_seen(s, size, planes, pd, err);
    memcpy(s->plane_depth, pd, sizeof pd);
    pass_stage_end(p, "targets");
    /* §4.2: intersection triangles, eq. 3 without cos(gamma) at each vertex */
    struct illum_intersections x;
    bool made = illum_intersect(&vols, d, u, v, pd, planes, cu, cv, half, size, &x, err);
    free(vols.items);
    if (!made)
        return false;
    size_t n = x.triangle_vertices;
    upload_intersections(s, &x);
    illum_intersections_release(&x);
    pass_stage_end(p, "volumes");

    /* each plane's illumination texture: its intersection triangles, added */
    gl.Viewport(0, 0, size, size);
    gl.UseProgram(illum->id);
    gl.BindVertexArray(s->vao);
    gl_program_bind_texture(illum, "u_target", s->target.id);
    /* the panes between the light and the glass (the shadow map's pane filter) */
    shadow_inputs_bind(p, f, illum);
    gl.ProgramUniform1i(illum->id, gl_program_uniform(illum, "u_light"), first);
    gl.Enable(GL_BLEND);
    gl.BlendFunc(GL_ONE, GL_ONE);
    for (int pl = 0; pl < planes; pl++) {
        const struct gl_texture *layer[1] = {&s->textures};
        int layer_index[1] = {pl};
        if (!gl_framebuffer_attach(&s->texture_fb, layer, layer_index, 1, NULL, -1, err))
            return false;
        gl.BindFramebuffer(GL_FRAMEBUFFER, s->texture_fb.id);
        if (x.count[pl] > 0)
            gl.DrawArrays(GL_TRIANGLES, (GLint)x.first[pl], (GLsizei)x.count[pl]);
        if (x.point_count[pl] > 0)
            gl.DrawArrays(GL_POINTS, (GLint)(n + x.point_first[pl]), (GLsizei)x.point_count[pl]);
    }
    renderer_reset_state(r);
    pass_stage_end(p, "textures");
    return gl_check("illumination textures", err);
}

static bool illum_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct illum_state *s = p->state;
    struct renderer *r = f->renderer;
    struct graph_resource *out = f->outputs[0];
    const float zero[4] = {0, 0, 0, 0};
    gl_texture_clear(&out->texture, zero);
    struct light *light = pass_light_at(p, IT_LIGHT);
    int slot = scene_light_index(f->scene, light);
    if (slot < 0 || slot >= SCENE_MAX_GPU_LIGHTS)
        return true; /* the light is not in the scene: no caustics */
    if (!ensure_targets(s, pass_int(p, IT_SIZE), pass_int(p, IT_PLANES), f->width, f->height, err))
        return false;
    pass_stage_begin(p);
    uint64_t key = texture_key(p, f);
    s->reused = pass_frame_reusable(f, s->valid, s->key, key);
    if (!s->reused) {
        if (!build_textures(p, f, slot, err))
            return false;
        s->valid = true;
        s->key = key;
    }
    if (s->planes == 0)
        return true; /* no light through the glass reaches a target */

    /* §4.3: the receivers seen by the camera read the textures */
    struct gl_program *map;
    if (!gl_program_get(&r->programs, "common/object.vert", "illumination_textures/map.frag", NULL, &map,
                        err))
        return false;
    virtual_camera_set(map, &s->vc);
    /* the shadow test's tolerance: a few texels of depth along a surface at 60 degrees */
    struct illumination_map_params values = {
        .planes = s->planes, .bias = 4.0f * 2.0f * s->vc.half / (float)s->size + 1e-3f * (s->vc.far - s->vc.near)};
    for (int i = 0; i < s->planes; i++)
        values.plane_depth[i][0] = s->plane_depth[i];
    if (!gl_param_block_upload(&s->params, &values, err) || !gl_param_block_bind(&s->params, map, err))
        return false;
    const struct gl_texture *oc[1] = {&out->texture};
    if (!gl_framebuffer_attach(&s->map_fb, oc, NULL, 1, &s->receiver_depth, -1, err))
        return false;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->map_fb.id);
    gl.Viewport(0, 0, f->width, f->height);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    gl_program_bind_texture(map, "u_target", s->target.id);
    gl_program_bind_texture(map, "u_textures", s->textures.id);
    /* glass objects are drawn too, writing depth only: what is behind them
     * is the refraction pass's to show, not this one's */
    draw_targets(p, r, f->scene, map);
    gl.Disable(GL_DEPTH_TEST);
    pass_stage_end(p, s->reused ? "mapping (textures reused)" : "mapping");
    return gl_check("illumination_textures", err) &&
           caustic_coverage_check(&s->coverage, p, f, &f->snapshot->lights[f->snapshot->light_first[slot]],
                                  NULL, s->receiver_depth.id, 0, &out->texture,
                                  "raise `size` (the textures' texels) or `table` (directions per vertex)", err);
}

/* Iwasaki et al. build the light transport table per vertex of a closed
 * glass object (§4.2): a water surface or a mirror has none. */
static const char *illumination_textures_leaves_out(const struct pass *p, const struct scene *scene,
                                                    const struct object *o)
{
    (void)p;
    if (object_is(o, OBJECT_ROLE_WATER))
        return "the light transport tables are made for closed glass objects (Iwasaki et al. 4.2), not a water "
               "surface: no caustics through it (photon_caustics, caustic_volumes or layered_caustics make them)";
    if (object_is(o, OBJECT_ROLE_MIRROR))
        return "only glass refracts light into the illumination textures: no caustics off a mirror "
               "(photon_caustics makes them)";
    if (object_is(o, OBJECT_ROLE_THIN))
        return shadow_inputs_pane_left_out(p, scene, o);
    return pass_refractor_left_out(o, true);
}

const struct pass_desc illumination_textures_pass = {
    .technique = PASS_TECHNIQUE_CAUSTICS,
    .surface_caustics_only = true,
    .name = "illumination_textures",
    .leaves_out = illumination_textures_leaves_out,
    .summary = "Iwasaki et al.: caustics through illumination textures on virtual planes and a light transport table",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = illum_declare,
    .create = illum_create,
    .execute = illum_execute,
    .needed = illum_needed,
    .destroy = illum_destroy,
};
