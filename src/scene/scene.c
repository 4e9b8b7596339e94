/* Objects, lights and the scene that borrows them (materials: material.c). */
#define _POSIX_C_SOURCE 200809L
#include "scene/scene.h"
#include "scene/water.h"

#include <math.h>
#include <stdlib.h>

#include "core/array.h"
#include <string.h>

unsigned object_role(const struct object *obj) { return obj->visible ? material_role(&obj->material) : 0u; }

bool object_is(const struct object *obj, unsigned roles) { return (object_role(obj) & roles) != 0; }

bool object_is_rough_refractor(const struct object *obj)
{
    return object_is(obj, OBJECT_ROLE_REFRACTOR) && obj->material.roughness > 0.0f;
}

bool object_is_tinted_refractor(const struct object *obj)
{
    vec3 t = obj->material.tint;
    return object_is(obj, OBJECT_ROLE_REFRACTOR) &&
           (t.x != 1.0f || t.y != 1.0f || t.z != 1.0f || obj->material.base_color.texture);
}

bool object_is_partly_diffuse_refractor(const struct object *obj)
{
    return object_is(obj, OBJECT_ROLE_REFRACTOR) &&
           (obj->material.transmission < 1.0f || obj->material.transmission_map.texture);
}

struct object *object_create(struct mesh *mesh)
{
    struct object *obj = calloc(1, sizeof *obj);
    if (!obj)
        return NULL;
    static uint64_t next_serial = 1;
    obj->references = 1;
    obj->serial = next_serial++;
    obj->mesh = mesh;
    mesh_retain(mesh);
    material_init(&obj->material, MATERIAL_DIFFUSE);
    if (mesh && mesh->has_material)
        material_assign(&obj->material, &mesh->material);
    obj->scale = vec3_make(1, 1, 1);
    obj->rotation = quat_identity();
    obj->visible = true;
    obj->cast_shadows = true;
    obj->deform.direction = vec3_make(1, 0, 0);
    for (int t = 0; t < SCENE_MAX_MORPH_TARGETS && mesh; t++)
        obj->morph_weights[t] = mesh->default_weights[t];
    obj->version = 1;
    if (mesh && mesh->part_count > 0) {
        obj->parts = calloc((size_t)mesh->part_count, sizeof *obj->parts);
        for (int p = 0; obj->parts && p < mesh->part_count; p++) {
            struct object *part = object_create(mesh->parts[p]);
            if (!part)
                break;
            part->group = obj;
            obj->parts[obj->part_count++] = part;
        }
        if (obj->part_count < mesh->part_count) {
            object_destroy(obj);
            return NULL;
        }
    }
    return obj;
}

bool object_sync_parts(struct object *g)
{
    for (int p = 0; p < g->part_count; p++) {
        struct object *part = g->parts[p];
        part->position = g->position;
        part->rotation = g->rotation;
        part->scale = g->scale;
        part->visible = g->visible;
        part->cast_shadows = g->cast_shadows;
        memcpy(part->morph_weights, g->morph_weights, sizeof part->morph_weights);
        /* the deformer's source is copied only when it changed (a script
         * moving the group every frame copies no strings) */
        char *glsl = part->deform.glsl;
        bool same = glsl && g->deform.glsl ? strcmp(glsl, g->deform.glsl) == 0 : glsl == g->deform.glsl;
        if (!same) {
            char *copy = g->deform.glsl ? strdup(g->deform.glsl) : NULL;
            if (g->deform.glsl && !copy)
                return false;
            free(part->deform.glsl);
            glsl = copy;
        }
        part->deform = g->deform;
        part->deform.glsl = glsl;
        if (!object_set_joint_matrices(part, g->joint_matrices, g->joint_matrix_count))
            return false;
        part->version = g->version;
    }
    return true;
}

bool object_set_joint_matrices(struct object *obj, const float *matrices, int count)
{
    if (count != obj->joint_matrix_count) {
        float *m = count > 0 ? malloc((size_t)count * 16 * sizeof *m) : NULL;
        if (count > 0 && !m)
            return false;
        free(obj->joint_matrices);
        obj->joint_matrices = m;
        obj->joint_matrix_count = count;
    }
    if (count > 0)
        memcpy(obj->joint_matrices, matrices, (size_t)count * 16 * sizeof *matrices);
    /* the box of the skinned base shape (deform.comp's blend, on the CPU):
     * what bounds the object's shadow frusta and a camera framing it */
    const struct mesh *m = obj->mesh;
    obj->skin_min = m->bounds_min;
    obj->skin_max = m->bounds_max;
    if (count > 0 && m->joints) {
        vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t v = 0; v < m->vertex_count; v++) {
            vec3 p = vec3_make(m->positions[v * 3], m->positions[v * 3 + 1], m->positions[v * 3 + 2]), q = {0, 0, 0};
            float total = 0.0f;
            for (int k = 0; k < 4; k++) {
                float w = m->joint_weights[v * 4 + (size_t)k];
                int j = (int)m->joints[v * 4 + (size_t)k];
                if (!(w > 0.0f) || j < 0 || j >= count)
                    continue;
                mat4 jm;
                memcpy(jm.m, obj->joint_matrices + (size_t)j * 16, sizeof jm.m);
                q = vec3_add(q, vec3_scale(mat4_transform_point(jm, p), w));
                total += w;
            }
            if (total > 0.0f)
                p = q;
            lo = vec3_min(lo, p);
            hi = vec3_max(hi, p);
        }
        if (m->vertex_count > 0)
            obj->skin_min = lo, obj->skin_max = hi;
    }
    return true;
}

void object_set_material(struct object *obj, const struct material *m)
{
    material_assign(&obj->material, m);
    for (int p = 0; p < obj->part_count; p++) {
        material_assign(&obj->parts[p]->material, m);
        obj->parts[p]->version++;
    }
    obj->version++;
}

void object_retain(struct object *obj)
{
    if (obj)
        obj->references++;
}

void object_destroy(struct object *obj)
{
    if (!obj || --obj->references > 0)
        return;
    free(obj->deform.glsl);
    free(obj->joint_matrices);
    material_release(&obj->material);
    for (int p = 0; p < obj->part_count; p++) {
        obj->parts[p]->group = NULL;
        object_destroy(obj->parts[p]);
    }
    free(obj->parts);
    if (obj->water) {
        water_release(obj->water);
        free(obj->water);
    }
    mesh_destroy(obj->mesh);
    free(obj);
}

bool object_is_animated_geometry(const struct object *obj)
{
    if (obj->water || obj->deform.kind != DEFORM_NONE || (obj->joint_matrix_count > 0 && obj->mesh->joints))
        return true;
    for (int t = 0; t < obj->mesh->target_count; t++)
        if (obj->morph_weights[t] != 0.0f)
            return true;
    return false;
}

mat4 object_model_matrix(const struct object *obj)
{
    return mat4_trs(obj->position, obj->rotation, obj->scale);
}

void object_world_bounds(const struct object *obj, vec3 *lo, vec3 *hi)
{
    bool skinned = obj->joint_matrix_count > 0 && obj->mesh->joints;
    vec3 a = skinned ? obj->skin_min : obj->mesh->bounds_min, b = skinned ? obj->skin_max : obj->mesh->bounds_max;
    /* Morphs and deformers move vertices: grow the box by the largest
     * possible displacement so shadow frusta never clip the object. */
    float grow = 0.0f;
    for (int t = 0; t < obj->mesh->target_count; t++)
        grow += fabsf(obj->morph_weights[t]) * obj->mesh->morph_extent;
    if (obj->deform.kind == DEFORM_WAVE)
        grow += fabsf(obj->deform.amplitude);
    if (obj->water) {
        grow += (float)water_max_height(obj->water);
    }
    else if (obj->deform.kind == DEFORM_GLSL)
        grow += 0.5f * vec3_length(vec3_sub(b, a)); /* unknown function: be generous */
    a = vec3_sub(a, vec3_make(grow, grow, grow));
    b = vec3_add(b, vec3_make(grow, grow, grow));
    mat4 m = object_model_matrix(obj);
    vec3 l = {INFINITY, INFINITY, INFINITY}, h = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < 8; i++) {
        vec3 c = {(i & 1) ? b.x : a.x, (i & 2) ? b.y : a.y, (i & 4) ? b.z : a.z};
        vec3 w = mat4_transform_point(m, c);
        l = vec3_min(l, w);
        h = vec3_max(h, w);
    }
    *lo = l;
    *hi = h;
}

struct light *light_create(enum light_kind kind)
{
    struct light *l = calloc(1, sizeof *l);
    if (!l)
        return NULL;
    l->kind = kind;
    l->position = vec3_make(0, 5, 0);
    l->end = vec3_make(1, 5, 0);
    l->direction = vec3_make(0, -1, 0);
    l->intensity = vec3_make(1, 1, 1);
    l->angle = 30.0f;
    l->softness = 0.2f;
    l->samples = 8;
    l->cast_shadows = true;
    l->version = 1;
    l->references = 1;
    return l;
}

vec3 light_center(const struct light *l)
{
    return l->kind == LIGHT_LINEAR ? vec3_scale(vec3_add(l->position, l->end), 0.5f) : l->position;
}

double light_view_flux_bound(float intensity, const mat4 *proj)
{
    double sx = fabs((double)proj->m[0]), sy = fabs((double)proj->m[5]);
    if (sx <= 0.0 || sy <= 0.0)
        return intensity * 4.0 * MATH_PI;
    double tx = 1.0 / sx, ty = 1.0 / sy; /* half extents: tangents, or lengths when orthographic */
    if (proj->m[11] == 0.0f)
        return intensity * 4.0 * tx * ty;
    /* a rectangular pyramid of half-angle tangents tx, ty */
    return intensity * 4.0 * atan(tx * ty / sqrt(1.0 + tx * tx + ty * ty));
}

void light_retain(struct light *light)
{
    if (light)
        light->references++;
}

void light_destroy(struct light *light)
{
    if (light && --light->references <= 0)
        free(light);
}

const char *light_kind_name(enum light_kind kind)
{
    switch (kind) {
    case LIGHT_POINT: return "point";
    case LIGHT_DIRECTIONAL: return "directional";
    case LIGHT_SPOT: return "spot";
    case LIGHT_LINEAR: return "linear";
    }
    return "?";
}

void scene_init(struct scene *scene)
{
    memset(scene, 0, sizeof *scene);
    scene->camera.eye = vec3_make(0, 2, 6);
    scene->camera.target = vec3_make(0, 0.5f, 0);
    scene->camera.up = vec3_make(0, 1, 0);
    scene->camera.fov = 45.0f;
    scene->camera.znear = 0.05f;
    scene->camera.zfar = 100.0f;
    scene->camera.version = 1;
    scene->background = vec3_make(0.05f, 0.05f, 0.06f);
    scene->version = 1;
}

void scene_release(struct scene *scene)
{
    for (int i = 0; i < scene->object_count; i++)
        object_destroy(scene->objects[i]);
    for (int i = 0; i < scene->light_count; i++)
        light_destroy(scene->lights[i]);
    scene_set_environment(scene, NULL);
    scene_set_medium(scene, NULL);
    scene->object_capacity = scene->light_capacity = 0;
    free(scene->objects);
    free(scene->lights);
    scene->objects = NULL;
    scene->lights = NULL;
    scene->object_count = scene->light_count = 0;
}


bool scene_object_add(struct scene *scene, struct object *obj, struct error *err)
{
    if (obj->part_count > 0) {
        /* the scene holds a group's parts, each an object of one material */
        for (int p = 0; p < obj->part_count; p++)
            if (!scene_object_add(scene, obj->parts[p], err))
                return false;
        return true;
    }
    for (int i = 0; i < scene->object_count; i++)
        if (scene->objects[i] == obj)
            return true;
    if (!array_grow((void **)&scene->objects, &scene->object_capacity, scene->object_count, sizeof(struct object *), err))
        return false;
    obj->id = scene->next_object_id++;
    object_retain(obj);
    scene->objects[scene->object_count++] = obj;
    scene->version++;
    return true;
}

bool scene_light_add(struct scene *scene, struct light *light, struct error *err)
{
    for (int i = 0; i < scene->light_count; i++)
        if (scene->lights[i] == light)
            return true;
    if (!array_grow((void **)&scene->lights, &scene->light_capacity, scene->light_count, sizeof(struct light *), err))
        return false;
    light_retain(light);
    scene->lights[scene->light_count++] = light;
    scene->version++;
    return true;
}

void scene_object_remove(struct scene *scene, struct object *obj)
{
    for (int p = 0; p < obj->part_count; p++)
        scene_object_remove(scene, obj->parts[p]);
    for (int i = 0; i < scene->object_count; i++)
        if (scene->objects[i] == obj) {
            memmove(scene->objects + i, scene->objects + i + 1,
                    (size_t)(scene->object_count - i - 1) * sizeof *scene->objects);
            scene->object_count--;
            scene->version++;
            object_destroy(obj);
            return;
        }
}

bool scene_role_bounds(const struct scene *scene, unsigned roles, vec3 *lo, vec3 *hi)
{
    vec3 l = {INFINITY, INFINITY, INFINITY}, h = {-INFINITY, -INFINITY, -INFINITY};
    bool any = false;
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        if (!object_is(o, roles))
            continue;
        vec3 a, b;
        object_world_bounds(o, &a, &b);
        l = vec3_min(l, a);
        h = vec3_max(h, b);
        any = true;
    }
    if (any) {
        *lo = l;
        *hi = h;
    }
    return any;
}

bool object_in_view(const struct object *o, mat4 view_proj)
{
    vec3 a, b;
    object_world_bounds(o, &a, &b);
    /* the box's corners in clip space: outside when all are beyond one plane */
    int outside[6] = {0, 0, 0, 0, 0, 0};
    for (int k = 0; k < 8; k++) {
        vec3 p = {k & 1 ? b.x : a.x, k & 2 ? b.y : a.y, k & 4 ? b.z : a.z};
        const float *m = view_proj.m;
        float c[4];
        for (int r = 0; r < 4; r++)
            c[r] = m[r] * p.x + m[4 + r] * p.y + m[8 + r] * p.z + m[12 + r];
        outside[0] += c[0] < -c[3];
        outside[1] += c[0] > c[3];
        outside[2] += c[1] < -c[3];
        outside[3] += c[1] > c[3];
        outside[4] += c[2] < -c[3];
        outside[5] += c[2] > c[3];
    }
    for (int q = 0; q < 6; q++)
        if (outside[q] == 8)
            return false;
    return true;
}

bool scene_specular_in_view(const struct scene *scene, mat4 view_proj)
{
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        if (object_is(o, OBJECT_ROLE_SPECULAR) && object_in_view(o, view_proj))
            return true;
    }
    return false;
}

bool scene_bounds(const struct scene *scene, vec3 *lo, vec3 *hi)
{
    if (scene_role_bounds(scene, OBJECT_ROLE_SPECULAR | OBJECT_ROLE_RECEIVER, lo, hi))
        return true;
    *lo = *hi = vec3_make(0, 0, 0);
    return false;
}

int scene_light_index(const struct scene *scene, const struct light *light)
{
    for (int i = 0; i < scene->light_count; i++)
        if (scene->lights[i] == light)
            return i;
    return -1;
}

uint64_t scene_lights_version(const struct scene *scene)
{
    uint64_t v = (uint64_t)scene->light_count;
    for (int i = 0; i < scene->light_count; i++)
        v = v * 31u + scene->lights[i]->version;
    return v;
}

uint64_t scene_geometry_version(const struct scene *scene)
{
    uint64_t v = scene->version * 1000003u;
    for (int i = 0; i < scene->object_count; i++)
        v = v * 31u + scene->objects[i]->version;
    return v;
}

void scene_light_remove(struct scene *scene, struct light *light)
{
    for (int i = 0; i < scene->light_count; i++)
        if (scene->lights[i] == light) {
            memmove(scene->lights + i, scene->lights + i + 1, (size_t)(scene->light_count - i - 1) * sizeof *scene->lights);
            scene->light_count--;
            scene->version++;
            light_destroy(light);
            return;
        }
}

void scene_set_environment(struct scene *scene, struct environment *env)
{
    environment_retain(env);
    environment_destroy(scene->environment);
    scene->environment = env;
}

void scene_set_medium(struct scene *scene, struct medium *medium)
{
    medium_retain(medium);
    medium_destroy(scene->medium);
    scene->medium = medium;
}
