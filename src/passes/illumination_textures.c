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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/array.h"
#include "core/hash.h"
#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/virtual_camera.h"
#include "scene/transport.h"

#define ILLUM_MAX_REFRACTORS 8
#define ILLUM_MAX_PLANES 16
#define ILLUM_VERTEX_FLOATS 9 /* position, intensity, direction */

/* A glass mesh whose longest edge is more than this fraction of its
 * bounding diagonal is subdivided for its table (scene/mesh_subdivide.c):
 * 1/16 splits a cube's faces into 16 x 16 (3,072 triangles, a 15 MB table
 * at table = 16) and leaves the default spheres (128 segments) alone. */
#define ILLUM_EDGE_FRACTION (1.0f / 16.0f)
#define ILLUM_MAX_TABLE_TRIANGLES 8192

struct illum_state {
    struct transport_table tables[ILLUM_MAX_REFRACTORS];
    /* the mesh each table samples: the object's, or `fine`, its subdivision */
    const struct mesh *table_mesh[ILLUM_MAX_REFRACTORS];
    struct mesh *fine[ILLUM_MAX_REFRACTORS];
    uint64_t fine_of[ILLUM_MAX_REFRACTORS]; /* the serial of the mesh `fine` subdivides */
    int fine_levels[ILLUM_MAX_REFRACTORS];
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
    float plane_depth[ILLUM_MAX_PLANES];
    bool reused;
};

enum illum_param { IT_LIGHT, IT_PLANES, IT_SIZE, IT_TABLE, IT_INTERNAL, IT_TARGETS };
enum { INTERNAL_NONE, INTERNAL_FIRST };

static const struct pass_param_desc params[] = {
    [IT_LIGHT] = {.name = "light", .type = PASS_PARAM_LIGHT, .required = true,
     .help = "the light (directional or point; a linear light as its point samples, accumulated, Fig. 6d)"},
    [IT_PLANES] = {.name = "planes", .type = PASS_PARAM_INTEGER, .default_number = 16, .min = 1, .max = ILLUM_MAX_PLANES,
     .help = "virtual planes across the targets (§4.2; the paper uses 4: too few where a focus lies between them, see the README)"},
    [IT_SIZE] = {.name = "size", .type = PASS_PARAM_INTEGER, .default_number = 256, .min = 16, .max = 4096,
     .help = "illumination texture size (the paper uses 512; 256 is the bench's best here: finer texels leave more sub-texel triangles as points)"},
    [IT_TABLE] = {.name = "table", .type = PASS_PARAM_INTEGER, .default_number = 16, .min = 2, .max = 64,
     .help = "light transport table: incident directions per side of its octahedral map (table^2 directions per vertex)"},
    [IT_INTERNAL] = {.name = "internal", .type = PASS_PARAM_ENUM, .default_string = "none", .choices = "none|first",
     .help = "paths with total internal reflection: none (the paper's) or the first one followed"},
    [IT_TARGETS] = {.name = "targets", .type = PASS_PARAM_OBJECT_LIST,
     .help = "the diffuse objects that receive the caustics (default: every visible diffuse object)"},
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
    p->state = s;
    if (!gl_framebuffer_create(&s->target_fb, err) || !gl_framebuffer_create(&s->texture_fb, err) ||
        !gl_framebuffer_create(&s->map_fb, err))
        return false;
    gl.CreateVertexArrays(1, &s->vao);
    for (GLuint a = 0; a < 3; a++) {
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
        if (s->fine[i])
            mesh_destroy(s->fine[i]);
    }
    release_targets(s);
    gl_framebuffer_destroy(&s->target_fb);
    gl_framebuffer_destroy(&s->texture_fb);
    gl_framebuffer_destroy(&s->map_fb);
    if (gl_api_ready()) {
        if (s->vbo)
            gl.DeleteBuffers(1, &s->vbo);
        if (s->vao)
            gl.DeleteVertexArrays(1, &s->vao);
    }
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
        subdivided += s->table_mesh[i] == s->fine[i] && s->fine[i];
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

/* One illumination volume: the three outgoing rays of a surface triangle
 * and the flux through it. */
struct volume {
    vec3 o[3], d[3];
    vec3 flux;
};

struct volume_list {
    struct volume *items;
    int count, capacity;
};

/* One glass vertex this frame: where it is, and the light leaving for it. */
struct vertex_path {
    vec3 world, exit_position, exit_direction, transmittance;
    bool ok;
};

/* §4.1: the volumes of every glass object for one light sample. */
static bool collect_volumes(struct illum_state *s, const struct frame *fr, const struct scene *scene,
                            const struct frame_light *light, struct volume_list *out, struct error *err)
{
    int t = 0;
    for (int i = 0; i < scene->object_count && t < s->table_count; i++) {
        struct object *o = scene->objects[i];
        if (!is_refractor(o))
            continue;
        const struct mesh *m = s->table_mesh[t];
        const struct transport_table *table = &s->tables[t++];
        const struct frame_object *fo = frame_object_of(fr, o);
        mat4 model = fo ? fo->model : object_model_matrix(o), inverse;
        if (!mat4_inverse(model, &inverse))
            continue;
        size_t nv = m->vertex_count;
        struct vertex_path *vp = malloc(nv * sizeof *vp);
        if (!vp)
            return error_set(err, "illumination_textures: out of memory");
        for (size_t v = 0; v < nv; v++) {
            vec3 pw = mat4_transform_point(model, vec3_make(m->positions[v * 3], m->positions[v * 3 + 1],
                                                            m->positions[v * 3 + 2]));
            vec3 dw = light->kind == LIGHT_DIRECTIONAL ? light->direction
                                                        : vec3_normalize_or(vec3_sub(pw, light->position), vec3_make(0, -1, 0));
            /* the light's direction in the object's frame: a rotation or
             * translation of the object needs no new table */
            vec3 dl = vec3_normalize_or(mat4_transform_dir(inverse, dw), dw);
            vec3 lp, ld;
            vp[v].world = pw;
            vp[v].ok = transport_lookup(table, v, dl, &lp, &ld, &vp[v].transmittance);
            if (vp[v].ok) {
                vp[v].exit_position = mat4_transform_point(model, lp);
                vp[v].exit_direction = vec3_normalize_or(mat4_transform_dir(model, ld), dw);
            }
        }
        for (size_t k = 0; k + 2 < m->index_count; k += 3) {
            const struct vertex_path *a = &vp[m->indices[k]], *b = &vp[m->indices[k + 1]], *c = &vp[m->indices[k + 2]];
            if (!a->ok || !b->ok || !c->ok)
                continue;
            vec3 pa = a->world, pb = b->world, pc = c->world;
            vec3 cr = vec3_cross(vec3_sub(pb, pa), vec3_sub(pc, pa));
            float area2 = vec3_length(cr);
            if (!(area2 > 1e-20f))
                continue; /* a zero-area triangle carries no light */
            vec3 centre = vec3_scale(vec3_add(vec3_add(pa, pb), pc), 1.0f / 3.0f);
            vec3 dw = light->kind == LIGHT_DIRECTIONAL ? light->direction : vec3_normalize_or(vec3_sub(centre, light->position), vec3_make(0, -1, 0));
            float cos_theta = -vec3_dot(vec3_scale(cr, 1.0f / area2), dw);
            if (cos_theta <= 0.0f)
                continue; /* faces away from the light */
            /* eq. 1: L_in cos(theta) S, the flux through the triangle, times F_t */
            vec3 e = light->intensity;
            if (light->kind != LIGHT_DIRECTIONAL) {
                vec3 dd = vec3_sub(centre, light->position);
                e = vec3_scale(e, 1.0f / fmaxf(vec3_dot(dd, dd), 1e-12f));
                if (light->kind == LIGHT_SPOT) {
                    float ca = vec3_dot(dw, light->direction), lo = light->cos_outer;
                    float hi = fmaxf(light->cos_inner, lo + 1e-4f), x = fminf(fmaxf((ca - lo) / (hi - lo), 0.0f), 1.0f);
                    e = vec3_scale(e, x * x * (3.0f - 2.0f * x));
                }
            }
            vec3 ft = vec3_scale(vec3_add(vec3_add(a->transmittance, b->transmittance), c->transmittance), 1.0f / 3.0f);
            if (!array_grow((void **)&out->items, &out->capacity, out->count, sizeof *out->items, err)) {
                free(vp);
                return error_prefix(err, "illumination_textures");
            }
            out->items[out->count++] = (struct volume){
                .o = {a->exit_position, b->exit_position, c->exit_position},
                .d = {a->exit_direction, b->exit_direction, c->exit_direction},
                .flux = vec3_scale(vec3_mul(e, ft), 0.5f * area2 * cos_theta)};
        }
        free(vp);
    }
    return true;
}

static float clampf(float x, float lo, float hi) { return x < lo ? lo : x > hi ? hi : x; }

/* Whether the rasterizer would draw any fragment of the triangle with
 * texture-space (texel unit) corners a, b, c: a texel centre inside it.
 * Only asked of triangles a few texels across. */
static bool covers_a_texel_centre(const float a[2], const float b[2], const float c[2])
{
    float x0 = fminf(a[0], fminf(b[0], c[0])), x1 = fmaxf(a[0], fmaxf(b[0], c[0]));
    float y0 = fminf(a[1], fminf(b[1], c[1])), y1 = fmaxf(a[1], fmaxf(b[1], c[1]));
    float area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (area == 0.0f)
        return false;
    for (float y = floorf(y0 - 0.5f) + 0.5f; y <= y1; y += 1.0f)
        for (float x = floorf(x0 - 0.5f) + 0.5f; x <= x1; x += 1.0f) {
            float e0 = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
            float e1 = (c[0] - b[0]) * (y - b[1]) - (c[1] - b[1]) * (x - b[0]);
            float e2 = (a[0] - c[0]) * (y - c[1]) - (a[1] - c[1]) * (x - c[0]);
            if (area > 0.0f ? (e0 >= 0 && e1 >= 0 && e2 >= 0) : (e0 <= 0 && e1 <= 0 && e2 <= 0))
                return true;
        }
    return false;
}

struct weighted { float x, w; };

static int compare_weighted(const void *a, const void *b)
{
    float x = ((const struct weighted *)a)->x, y = ((const struct weighted *)b)->x;
    return (x > y) - (x < y);
}

/* The values below which fractions lo and hi of the weight lie. */
static void weighted_range(struct weighted *v, size_t n, float lo, float hi, float *a, float *b)
{
    qsort(v, n, sizeof *v, compare_weighted);
    double total = 0.0, run = 0.0;
    for (size_t i = 0; i < n; i++)
        total += v[i].w;
    *a = v[0].x, *b = v[n - 1].x;
    bool found_a = false;
    for (size_t i = 0; i < n; i++) {
        run += v[i].w;
        if (!found_a && run >= lo * total) {
            *a = v[i].x;
            found_a = true;
        }
        if (run >= hi * total) {
            *b = v[i].x;
            break;
        }
    }
}

/* Builds the tables (when new), the virtual camera, the planes and the
 * illumination textures. */
/* The mesh table k samples: the object's own, or its subdivision where its
 * triangles are coarse against it (kept while the object's mesh is the
 * same). NULL on error. */
static const struct mesh *table_mesh(struct illum_state *s, int k, const struct mesh *m, struct error *err)
{
    float diagonal = vec3_length(vec3_sub(m->bounds_max, m->bounds_min));
    int levels = mesh_subdivision_levels(m, ILLUM_EDGE_FRACTION * diagonal, ILLUM_MAX_TABLE_TRIANGLES);
    if (levels == 0) {
        s->table_mesh[k] = m;
        return m;
    }
    if (!s->fine[k] || s->fine_of[k] != m->serial || s->fine_levels[k] != levels) {
        if (s->fine[k])
            mesh_destroy(s->fine[k]);
        s->fine[k] = mesh_create_subdivided(m, levels, err);
        if (!s->fine[k])
            return NULL;
        s->fine_of[k] = m->serial;
        s->fine_levels[k] = levels;
    }
    s->table_mesh[k] = s->fine[k];
    return s->fine[k];
}

static bool build_textures(struct pass *p, struct pass_frame *f, int slot, struct error *err)
{
    struct illum_state *s = p->state;
    struct renderer *r = f->renderer;
    const struct scene *scene = f->scene;
    int resolution = pass_int(p, IT_TABLE), planes = pass_int(p, IT_PLANES), size = s->size;
    enum transport_internal internal = pass_choice(p, IT_INTERNAL) == INTERNAL_FIRST ? TRANSPORT_INTERNAL_FIRST
                                                                                    : TRANSPORT_INTERNAL_NONE;
    /* §3: the tables, one per glass object (built once per mesh, IOR, resolution) */
    s->table_count = 0;
    p->report[0] = '\0';
    for (int i = 0; i < scene->object_count && s->table_count < ILLUM_MAX_REFRACTORS; i++) {
        struct object *o = scene->objects[i];
        if (!is_refractor(o))
            continue;
        int k = s->table_count++;
        const struct mesh *m = table_mesh(s, k, o->mesh, err);
        if (!m)
            return false;
        struct transport_table *t = &s->tables[k];
        /* a fine mesh gets fewer directions, so its table fits (said in info and --timings) */
        if (!transport_table_ensure(t, m, &o->material, resolution, internal, i + 1, p->report, sizeof p->report, err))
            return false;
    }
    pass_stage_end(p, "tables");
    struct volume_list vols = {0};
    int first = r->frame.light_first[slot], entries = r->frame.light_entries[slot];
    for (int e = 0; e < entries; e++) /* a linear light: each point sample's volumes (Fig. 6d) */
        if (!collect_volumes(s, &r->frame, scene, &r->frame.lights[first + e], &vols, err)) {
            free(vols.items);
            return false;
        }
    /* the average transmitted direction, weighted by flux */
    vec3 sum = {0, 0, 0};
    for (int i = 0; i < vols.count; i++) {
        const struct volume *v = &vols.items[i];
        float w = v->flux.x + v->flux.y + v->flux.z;
        sum = vec3_add(sum, vec3_scale(vec3_add(vec3_add(v->d[0], v->d[1]), v->d[2]), w));
    }
    const float zero[4] = {0, 0, 0, 0};
    gl.ClearTexImage(s->textures.id, 0, GL_RGBA, GL_FLOAT, zero);
    vec3 d = vec3_normalize_or(sum, vec3_make(0, -1, 0));
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
    for (int i = 0; i < planes; i++)
        pd[i] = planes == 1 ? 0.5f * (dmin + dmax) : dmin + (dmax - dmin) * (float)i / (float)(planes - 1);
    /* the square where 99% of the flux crosses the planes */
    float umin = INFINITY, umax = -INFINITY, vmin = INFINITY, vmax = -INFINITY;
    struct weighted *wu = malloc((size_t)vols.count * (size_t)planes * sizeof *wu);
    struct weighted *wv = malloc((size_t)vols.count * (size_t)planes * sizeof *wv);
    size_t nw = 0;
    for (int i = 0; wu && wv && i < vols.count; i++)
        for (int pl = 0; pl < planes; pl++) {
            const struct volume *vol = &vols.items[i];
            vec3 o = vec3_scale(vec3_add(vec3_add(vol->o[0], vol->o[1]), vol->o[2]), 1.0f / 3.0f);
            vec3 dd = vec3_normalize_or(vec3_add(vec3_add(vol->d[0], vol->d[1]), vol->d[2]), d);
            float cd = vec3_dot(dd, d);
            float t = cd > 1e-4f ? (pd[pl] - vec3_dot(o, d)) / cd : -1.0f;
            if (!(t >= 0.0f) || !isfinite(t))
                continue;
            vec3 q = vec3_add(o, vec3_scale(dd, t));
            float w = vol->flux.x + vol->flux.y + vol->flux.z;
            wu[nw] = (struct weighted){vec3_dot(q, u), w};
            wv[nw] = (struct weighted){vec3_dot(q, v), w};
            nw++;
        }
    if (nw > 0) {
        weighted_range(wu, nw, 0.005f, 0.995f, &umin, &umax);
        weighted_range(wv, nw, 0.005f, 0.995f, &vmin, &vmax);
    }
    free(wu);
    free(wv);
    if (!(umin <= umax) || !(vmin <= vmax)) {
        free(vols.items);
        s->planes = 0;
        return true;
    }
    /* a square no larger than the targets' own extent */
    float target_half = 0.5f * vec3_length(vec3_sub(hi, lo));
    float half = clampf(0.5f * fmaxf(umax - umin, vmax - vmin) * 1.05f, 1e-4f, fmaxf(target_half, 1e-4f));
    float cu = 0.5f * (umin + umax), cv = 0.5f * (vmin + vmax);
    s->vc.d = d, s->vc.u = u, s->vc.v = v;
    s->vc.center[0] = cu, s->vc.center[1] = cv, s->vc.half = half;
    float pad = 0.01f * (dmax - dmin) + 1e-4f;
    s->vc.near = dmin - pad, s->vc.far = dmax + pad;
    memcpy(s->plane_depth, pd, sizeof pd);
    s->planes = planes;
    /* the targets' normal map and depth from the virtual camera */
    struct gl_program *target, *illum;
    if (!gl_program_get(&r->programs, "illumination_textures/target.vert", "illumination_textures/target.frag", NULL,
                        &target, err) ||
        !gl_program_get(&r->programs, "illumination_textures/illumination.vert",
                        "illumination_textures/illumination.frag", NULL, &illum, err))
        return false;
    virtual_camera_set(target, &s->vc);
    virtual_camera_set(illum, &s->vc);
    const float no_target[4] = {0, 0, 0, 1e30f};
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->target_fb.id);
    gl.Viewport(0, 0, size, size);
    gl.ClearNamedFramebufferfv(s->target_fb.id, GL_COLOR, 0, no_target);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    draw_targets(p, r, scene, target);
    renderer_reset_state(r);
    /* The planes span the depths the virtual camera sees of the targets
     * within its square (read back: size^2 texels), not the targets' whole
     * bounds: a large receiver (a floor) seen at a slant would otherwise
     * spread the planes over depths no caustic reaches. */
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
            for (int i = 0; i < planes; i++)
                pd[i] = planes == 1 ? 0.5f * (seen_min + seen_max)
                                    : seen_min + (seen_max - seen_min) * (float)i / (float)(planes - 1);
    }
    free(texels);
    memcpy(s->plane_depth, pd, sizeof pd);
    pass_stage_end(p, "targets");
    /* §4.2: intersection triangles, eq. 3 without cos(gamma) at each vertex */
    float texel = 2.0f * half / (float)size, texel_area = texel * texel;
    size_t nverts = (size_t)vols.count * (size_t)planes * 3;
    float *buf = malloc(nverts * ILLUM_VERTEX_FLOATS * sizeof(float));
    float *points = malloc((size_t)vols.count * (size_t)planes * 3 * ILLUM_VERTEX_FLOATS * sizeof(float));
    size_t plane_first[ILLUM_MAX_PLANES], plane_count[ILLUM_MAX_PLANES], n = 0;
    size_t point_first[ILLUM_MAX_PLANES], point_count[ILLUM_MAX_PLANES], np = 0;
    if (!buf || !points) {
        free(buf);
        free(points);
        free(vols.items);
        return error_set(err, "illumination_textures: out of memory for %zu vertices", nverts);
    }
    for (int pl = 0; pl < planes; pl++) {
        plane_first[pl] = n;
        point_first[pl] = np;
        for (int i = 0; i < vols.count; i++) {
            const struct volume *vol = &vols.items[i];
            vec3 q[3];
            float cd[3];
            bool valid = true;
            for (int k = 0; k < 3 && valid; k++) {
                cd[k] = vec3_dot(vol->d[k], d);
                float t = cd[k] > 1e-4f ? (pd[pl] - vec3_dot(vol->o[k], d)) / cd[k] : -1.0f;
                valid = t >= 0.0f && isfinite(t);
                if (valid)
                    q[k] = vec3_add(vol->o[k], vec3_scale(vol->d[k], t));
            }
            if (!valid)
                continue; /* a ray parallel to the plane, or the plane behind where it leaves */
            float s0 = 0.5f * vec3_length(vec3_cross(vec3_sub(q[1], q[0]), vec3_sub(q[2], q[0])));
            bool tiny = !(s0 >= texel_area);
            if (!tiny && s0 < 16.0f * texel_area) {
                /* a triangle a few texels across that no texel centre falls
                 * in would be lost by the rasterizer: a point instead */
                float t2[3][2];
                for (int k = 0; k < 3; k++) {
                    t2[k][0] = ((vec3_dot(q[k], u) - cu) / (2.0f * half) + 0.5f) * (float)size;
                    t2[k][1] = ((vec3_dot(q[k], v) - cv) / (2.0f * half) + 0.5f) * (float)size;
                }
                tiny = !covers_a_texel_centre(t2[0], t2[1], t2[2]);
            }
            if (tiny) {
                /* S_0 -> 0 (a focus on the plane), or a triangle the texels
                 * miss: three points inside it, at barycentric (2/3, 1/6,
                 * 1/6) and its turns, a third of its flux each, one texel
                 * apiece (a sliver spanning several texels spreads along) */
                vec3 dd = vec3_normalize_or(vec3_add(vec3_add(vol->d[0], vol->d[1]), vol->d[2]), d);
                vec3 in = vec3_scale(vol->flux, 1.0f / (3.0f * texel_area * fmaxf(vec3_dot(dd, d), 1e-4f)));
                for (int k = 0; k < 3; k++) {
                    float *o = points + np * ILLUM_VERTEX_FLOATS;
                    vec3 c = vec3_add(vec3_scale(q[k], 2.0f / 3.0f),
                                      vec3_scale(vec3_add(q[(k + 1) % 3], q[(k + 2) % 3]), 1.0f / 6.0f));
                    o[0] = c.x, o[1] = c.y, o[2] = c.z;
                    o[3] = in.x, o[4] = in.y, o[5] = in.z;
                    o[6] = dd.x, o[7] = dd.y, o[8] = dd.z;
                    np++;
                }
                continue;
            }
            for (int k = 0; k < 3; k++) {
                float *o = buf + (n + (size_t)k) * ILLUM_VERTEX_FLOATS;
                vec3 in = vec3_scale(vol->flux, 1.0f / (s0 * fmaxf(cd[k], 1e-4f)));
                o[0] = q[k].x, o[1] = q[k].y, o[2] = q[k].z;
                o[3] = in.x, o[4] = in.y, o[5] = in.z;
                o[6] = vol->d[k].x, o[7] = vol->d[k].y, o[8] = vol->d[k].z;
            }
            n += 3;
        }
        plane_count[pl] = n - plane_first[pl];
        point_count[pl] = np - point_first[pl];
    }
    free(vols.items);
    /* the points after the triangles in one buffer */
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
        gl.NamedBufferSubData(s->vbo, 0, (GLsizeiptr)tri_bytes, buf);
    if (point_bytes)
        gl.NamedBufferSubData(s->vbo, (GLintptr)tri_bytes, (GLsizeiptr)point_bytes, points);
    free(buf);
    free(points);
    pass_stage_end(p, "volumes");


    /* each plane's illumination texture: its intersection triangles, added */
    gl.Viewport(0, 0, size, size);
    gl.UseProgram(illum->id);
    gl.BindVertexArray(s->vao);
    gl_program_bind_texture(illum, "u_target", s->target.id);
    gl.Enable(GL_BLEND);
    gl.BlendFunc(GL_ONE, GL_ONE);
    for (int pl = 0; pl < planes; pl++) {
        const struct gl_texture *layer[1] = {&s->textures};
        int layer_index[1] = {pl};
        if (!gl_framebuffer_attach(&s->texture_fb, layer, layer_index, 1, NULL, -1, err))
            return false;
        gl.BindFramebuffer(GL_FRAMEBUFFER, s->texture_fb.id);
        if (plane_count[pl] > 0)
            gl.DrawArrays(GL_TRIANGLES, (GLint)plane_first[pl], (GLsizei)plane_count[pl]);
        if (point_count[pl] > 0)
            gl.DrawArrays(GL_POINTS, (GLint)(n + point_first[pl]), (GLsizei)point_count[pl]);
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
    if (!gl_program_get(&r->programs, "illumination_textures/map.vert", "illumination_textures/map.frag", NULL, &map,
                        err))
        return false;
    GLuint id = map->id;
    virtual_camera_set(map, &s->vc);
    gl.ProgramUniform1i(id, gl_program_uniform(map, "u_planes"), s->planes);
    for (int i = 0; i < s->planes; i++) {
        char name[32];
        snprintf(name, sizeof name, "u_plane_depth[%d]", i);
        gl.ProgramUniform1f(id, gl_program_uniform(map, name), s->plane_depth[i]);
    }
    /* the shadow test's tolerance: a few texels of depth along a surface at 60 degrees */
    gl.ProgramUniform1f(id, gl_program_uniform(map, "u_bias"),
                        4.0f * 2.0f * s->vc.half / (float)s->size + 1e-3f * (s->vc.far - s->vc.near));
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
    pass_stage_end(p, s->reused ? "mapping (textures reused)" : "mapping");
    return gl_check("illumination_textures", err);
}

/* Iwasaki et al. build the light transport table per vertex of a closed
 * glass object (§4.2): a water surface or a mirror has none. */
static const char *illumination_textures_leaves_out(const struct pass *p, const struct scene *scene,
                                                    const struct object *o)
{
    (void)scene;
    (void)p;
    if (object_is(o, OBJECT_ROLE_WATER))
        return "the light transport tables are made for closed glass objects (Iwasaki et al. 4.2), not a water "
               "surface: no caustics through it (photon_caustics, caustic_volumes or layered_caustics make them)";
    if (object_is(o, OBJECT_ROLE_MIRROR))
        return "only glass refracts light into the illumination textures: no caustics off a mirror "
               "(photon_caustics makes them)";
    return NULL;
}

const struct pass_desc illumination_textures_pass = {
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
