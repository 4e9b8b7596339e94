#include "graph/frame.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void frame_init(struct frame *f) { memset(f, 0, sizeof *f); }

void frame_release(struct frame *f)
{
    free(f->objects);
    frame_init(f);
}

/* The lights as the shaders see them. A linear light becomes `samples`
 * point lights spread along its segment, each with 1/samples of the
 * intensity (the "linear = N point lights" of the design). */
static void expand_lights(struct frame *f, const struct scene *scene)
{
    int n = 0;
    for (int i = 0; i < scene->light_count && i < SCENE_MAX_GPU_LIGHTS; i++) {
        const struct light *l = scene->lights[i];
        f->light_first[i] = n;
        int count = l->kind == LIGHT_LINEAR ? (l->samples < 1 ? 1 : l->samples) : 1;
        int made = 0;
        for (int s = 0; s < count && n < SCENE_MAX_GPU_LIGHTS; s++, made++) {
            struct frame_light *g = &f->lights[n++];
            g->kind = l->kind == LIGHT_LINEAR ? LIGHT_POINT : l->kind;
            g->scene_light = i;
            g->position = l->position;
            g->intensity = l->intensity;
            if (l->kind == LIGHT_LINEAR) {
                float u = ((float)s + 0.5f) / (float)count;
                g->position = vec3_add(l->position, vec3_scale(vec3_sub(l->end, l->position), u));
                g->intensity = vec3_scale(l->intensity, 1.0f / (float)count);
            }
            g->direction = vec3_normalize_or(l->direction, vec3_make(0, -1, 0));
            float outer = fminf(fmaxf(l->angle, 0.1f), 89.9f) * (float)MATH_PI / 180.0f;
            float inner = outer * (1.0f - fminf(fmaxf(l->softness, 0.0f), 1.0f));
            g->cos_outer = cosf(outer);
            g->cos_inner = cosf(inner);
        }
        f->light_entries[i] = made;
    }
    f->light_count = n;
}

static enum frame_vertices vertices_of(const struct object *o)
{
    if (o->water)
        return FRAME_VERTICES_WATER;
    if (o->deform.kind != DEFORM_NONE)
        return FRAME_VERTICES_DEFORMED;
    return object_is_animated_geometry(o) ? FRAME_VERTICES_MORPHED : FRAME_VERTICES_MESH;
}

bool frame_build(struct frame *f, const struct scene *scene, int width, int height, int index, double time,
                 struct error *err)
{
    f->width = width;
    f->height = height;
    f->index = index;
    f->time = time;
    const struct camera *c = &scene->camera;
    f->eye = c->eye;
    f->view = mat4_look_at(c->eye, c->target, c->up);
    float znear = c->znear > 1e-4f ? c->znear : 1e-4f;
    float zfar = c->zfar > znear * 2 ? c->zfar : znear * 2;
    if (c->ortho_width > 0.0f) {
        float hw = 0.5f * c->ortho_width, hh = hw * (float)height / (float)width;
        f->proj = mat4_ortho(-hw, hw, -hh, hh, znear, zfar);
    } else {
        f->proj = mat4_perspective(c->fov, (float)width / (float)height, znear, zfar);
    }
    f->view_proj = mat4_mul(f->proj, f->view);
    mat4_inverse(f->view_proj, &f->inv_view_proj);
    expand_lights(f, scene);
    if (scene->object_count > f->object_capacity) {
        struct frame_object *grown = realloc(f->objects, (size_t)scene->object_count * sizeof *grown);
        if (!grown)
            return error_set(err, "out of memory for the frame's objects");
        f->objects = grown;
        f->object_capacity = scene->object_count;
    }
    f->object_count = scene->object_count;
    f->geometry_animated = f->casters_animated = false;
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        struct frame_object *fo = &f->objects[i];
        fo->object = o;
        fo->model = object_model_matrix(o);
        mat4 inv;
        mat4_inverse(fo->model, &inv);
        fo->normal_matrix = mat4_transpose(inv);
        fo->vertices = vertices_of(o);
        bool animated = fo->vertices != FRAME_VERTICES_MESH;
        f->geometry_animated = f->geometry_animated || (o->visible && animated);
        f->casters_animated = f->casters_animated || (o->visible && o->cast_shadows && animated);
    }
    return true;
}

const struct frame_object *frame_object_of(const struct frame *f, const struct object *object)
{
    for (int i = 0; i < f->object_count; i++)
        if (f->objects[i].object == object)
            return &f->objects[i];
    return NULL;
}
