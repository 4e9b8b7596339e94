#define _POSIX_C_SOURCE 200809L
#include "graph/pass.h"
#include "core/hash.h"
#include "graph/frame.h"
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int choice_index(const char *choices, const char *choice);

struct pass *pass_create(const struct pass_desc *desc)
{
    struct pass *p = calloc(1, sizeof *p);
    if (!p)
        return NULL;
    p->references = 1;
    p->desc = desc;
    p->values = calloc((size_t)(desc->param_count > 0 ? desc->param_count : 1), sizeof *p->values);
    if (!p->values) {
        free(p);
        return NULL;
    }
    for (int i = 0; i < desc->param_count; i++) {
        p->values[i].lua_ref = -1;
        p->values[i].number = desc->params[i].default_number;
        if (desc->params[i].type == PASS_PARAM_ENUM && desc->params[i].default_string)
            p->values[i].number = choice_index(desc->params[i].choices, desc->params[i].default_string);
    }
    snprintf(p->name, sizeof p->name, "%s", desc->name);
    return p;
}

void pass_retain(struct pass *p)
{
    if (p)
        p->references++;
}

void pass_set_light(struct pass *p, int param, struct light *light)
{
    light_retain(light);
    light_destroy(p->values[param].light);
    p->values[param].light = light;
}

void pass_set_object(struct pass *p, int param, struct object *object)
{
    object_retain(object);
    object_destroy(p->values[param].object);
    p->values[param].object = object;
}

static void release_objects(struct pass_value *v)
{
    for (int k = 0; k < v->object_count; k++)
        object_destroy(v->objects[k]);
    free(v->objects);
    v->objects = NULL;
    v->object_count = 0;
}

bool pass_set_objects(struct pass *p, int param, struct object *const *objects, int count)
{
    struct object **copy = count > 0 ? malloc((size_t)count * sizeof *copy) : NULL;
    if (count > 0 && !copy)
        return false;
    for (int k = 0; k < count; k++) {
        copy[k] = objects[k];
        object_retain(copy[k]);
    }
    release_objects(&p->values[param]);
    p->values[param].objects = copy;
    p->values[param].object_count = count;
    p->values[param].set = true;
    return true;
}

static void release_list(struct pass_value *v)
{
    for (int k = 0; k < v->list_count; k++) {
        if (v->list)
            free(v->list[k]);
        if (v->keys)
            free(v->keys[k]);
    }
    free(v->list);
    free(v->keys);
    free(v->vectors);
    free(v->vector_sizes);
    v->list = v->keys = NULL;
    v->vectors = NULL;
    v->vector_sizes = NULL;
    v->list_count = 0;
}

static char *copy_string(const char *s)
{
    size_t n = strlen(s) + 1;
    char *c = malloc(n);
    if (c)
        memcpy(c, s, n);
    return c;
}

static const char *type_word(enum pass_param_type t);

/* The parameter `param` of the expected type, or an error naming it. */
static bool check_param(const struct pass *p, int param, unsigned types, struct error *err)
{
    if (param < 0 || param >= p->desc->param_count)
        return error_set(err, "%s: no parameter %d", p->desc->name, param);
    if (!(types & (1u << p->desc->params[param].type)))
        return error_set(err, "bad argument '%s' to '%s' (%s expected)", p->desc->params[param].name, p->desc->name,
                         type_word(p->desc->params[param].type));
    return true;
}

bool pass_set_list(struct pass *p, int param, const char *const *items, int count, struct error *err)
{
    if (!check_param(p, param, 1u << PASS_PARAM_INPUT_LIST, err))
        return false;
    const struct pass_param_desc *d = &p->desc->params[param];
    if (d->max > 0 && count > (int)d->max)
        return error_set(err, "bad argument '%s' to '%s' (at most %d inputs, got %d)", d->name, p->desc->name,
                         (int)d->max, count);
    for (int k = 0; k < count; k++)
        if (!items[k] || !strchr(items[k], '.'))
            return error_set(err, "bad argument '%s' to '%s' (item %d: \"pass.output\" expected, got '%s')", d->name,
                             p->desc->name, k + 1, items[k] ? items[k] : "nil");
    struct pass_value *v = &p->values[param];
    release_list(v);
    v->list = calloc((size_t)count + 1, sizeof *v->list);
    if (!v->list)
        return error_set(err, "out of memory");
    for (int k = 0; k < count; k++) {
        v->list[k] = copy_string(items[k]);
        if (!v->list[k])
            return error_set(err, "out of memory");
        v->list_count = k + 1;
    }
    v->set = true;
    return true;
}

bool pass_set_map(struct pass *p, int param, const char *const *keys, const char *const *values,
                  const float (*vectors)[4], const int *sizes, int count, struct error *err)
{
    unsigned maps = 1u << PASS_PARAM_INPUT_MAP | 1u << PASS_PARAM_OUTPUT_MAP | 1u << PASS_PARAM_UNIFORM_MAP;
    if (!check_param(p, param, maps, err))
        return false;
    const struct pass_param_desc *d = &p->desc->params[param];
    bool uniforms = d->type == PASS_PARAM_UNIFORM_MAP;
    for (int k = 0; k < count; k++) {
        if (!keys[k] || !keys[k][0])
            return error_set(err, "bad argument '%s' to '%s' (entry %d has no name)", d->name, p->desc->name, k + 1);
        if (uniforms) {
            if (!vectors || !sizes || sizes[k] < 1 || sizes[k] > 4)
                return error_set(err, "bad argument '%s' to '%s' (uniform '%s': 1 to 4 numbers expected)", d->name,
                                 p->desc->name, keys[k]);
            for (int c = 0; c < sizes[k]; c++)
                if (!isfinite(vectors[k][c]))
                    return error_set(err, "bad argument '%s' to '%s' (uniform '%s': not a finite number)", d->name,
                                     p->desc->name, keys[k]);
        } else if (!values || !values[k]) {
            return error_set(err, "bad argument '%s' to '%s' ('%s': string expected)", d->name, p->desc->name,
                             keys[k]);
        }
    }
    struct pass_value *v = &p->values[param];
    release_list(v);
    v->keys = calloc((size_t)count + 1, sizeof *v->keys);
    v->list = calloc((size_t)count + 1, sizeof *v->list);
    v->vectors = calloc((size_t)count + 1, sizeof *v->vectors);
    v->vector_sizes = calloc((size_t)count + 1, sizeof *v->vector_sizes);
    if (!v->keys || !v->list || !v->vectors || !v->vector_sizes)
        return error_set(err, "out of memory");
    for (int k = 0; k < count; k++) {
        v->keys[k] = copy_string(keys[k]);
        v->list[k] = copy_string(uniforms ? "" : values[k]);
        if (!v->keys[k] || !v->list[k])
            return error_set(err, "out of memory");
        if (uniforms) {
            memcpy(v->vectors[k], vectors[k], sizeof v->vectors[k]);
            v->vector_sizes[k] = sizes[k];
        }
        v->list_count = k + 1;
    }
    v->set = true;
    return true;
}

bool pass_set_color(struct pass *p, int param, vec3 color, struct error *err)
{
    if (!check_param(p, param, 1u << PASS_PARAM_COLOR, err))
        return false;
    if (!isfinite(color.x) || !isfinite(color.y) || !isfinite(color.z))
        return error_set(err, "bad argument '%s' to '%s' (a colour of finite numbers expected)",
                         p->desc->params[param].name, p->desc->name);
    struct pass_value *v = &p->values[param];
    v->color[0] = color.x;
    v->color[1] = color.y;
    v->color[2] = color.z;
    v->color[3] = 1.0f;
    v->set = true;
    return true;
}

void pass_stage_begin(struct pass *p)
{
    if (!p->stages.queries[0])
        gl.GenQueries(PASS_MAX_STAGES + 1, p->stages.queries);
    p->stages.count = 0;
    gl.QueryCounter(p->stages.queries[0], GL_TIMESTAMP);
}

void pass_stage_end(struct pass *p, const char *name)
{
    struct pass_stages *s = &p->stages;
    if (!s->queries[0] || s->count >= PASS_MAX_STAGES)
        return;
    snprintf(s->names[s->count], sizeof s->names[s->count], "%s", name);
    gl.QueryCounter(s->queries[s->count + 1], GL_TIMESTAMP);
    s->count++;
}

void pass_stages_collect(struct pass *p)
{
    struct pass_stages *s = &p->stages;
    GLuint64 prev = 0;
    if (s->count > 0)
        gl.GetQueryObjectui64v(s->queries[0], GL_QUERY_RESULT, &prev);
    for (int i = 0; i < s->count; i++) {
        GLuint64 t = 0;
        gl.GetQueryObjectui64v(s->queries[i + 1], GL_QUERY_RESULT, &t);
        s->ms[i] = t > prev ? (double)(t - prev) * 1e-6 : 0.0;
        prev = t;
    }
}

void pass_destroy(struct pass *p)
{
    if (!p || --p->references > 0)
        return;
    if (p->stages.queries[0] && gl_api_ready())
        gl.DeleteQueries(PASS_MAX_STAGES + 1, p->stages.queries);
    if (p->created && p->desc->destroy)
        p->desc->destroy(p);
    for (int i = 0; i < p->desc->param_count; i++) {
        free(p->values[i].string);
        release_list(&p->values[i]);
        light_destroy(p->values[i].light);
        object_destroy(p->values[i].object);
        release_objects(&p->values[i]);
    }
    free(p->values);
    free(p);
}

int pass_param_index(const struct pass_desc *desc, const char *name)
{
    for (int i = 0; i < desc->param_count; i++)
        if (strcmp(desc->params[i].name, name) == 0)
            return i;
    return -1;
}

const struct pass_value *pass_value(const struct pass *p, const char *name)
{
    int i = pass_param_index(p->desc, name);
    return i >= 0 ? &p->values[i] : NULL;
}

static const char *type_word(enum pass_param_type t)
{
    switch (t) {
    case PASS_PARAM_NUMBER: return "number";
    case PASS_PARAM_INTEGER: return "integer";
    case PASS_PARAM_BOOLEAN: return "boolean";
    case PASS_PARAM_ENUM: return "enum";
    case PASS_PARAM_STRING: return "string";
    case PASS_PARAM_INPUT: return "input";
    case PASS_PARAM_INPUT_LIST: return "input list";
    case PASS_PARAM_LIGHT: return "light";
    case PASS_PARAM_OBJECT: return "object";
    case PASS_PARAM_OBJECT_LIST: return "object list";
    default: return "table";
    }
}

static int find_param(struct pass *p, const char *name, struct error *err)
{
    int i = pass_param_index(p->desc, name);
    if (i < 0)
        error_set(err, "pass '%s' (%s) has no parameter '%s'", p->name, p->desc->name, name);
    return i;
}

bool pass_set_number(struct pass *p, const char *name, double value, struct error *err)
{
    int i = find_param(p, name, err);
    if (i < 0)
        return false;
    const struct pass_param_desc *d = &p->desc->params[i];
    const char *fn = p->desc->name;
    if (d->type == PASS_PARAM_BOOLEAN && (value == 0.0 || value == 1.0))
        return pass_set_boolean(p, name, value != 0.0, err);
    if (d->type != PASS_PARAM_NUMBER && d->type != PASS_PARAM_INTEGER)
        return error_set(err, "bad argument '%s' to '%s' (%s parameter: not a number parameter)", name, fn,
                         type_word(d->type));
    if (!isfinite(value))
        return error_set(err, "bad argument '%s' to '%s' (a finite number expected, got %g)", name, fn,
                         isnan(value) ? NAN : value);
    if (d->type == PASS_PARAM_INTEGER && value != floor(value))
        return error_set(err, "bad argument '%s' to '%s' (integer expected, got %g)", name, fn, value);
    if (d->min < d->max && (value < d->min || value > d->max))
        return error_set(err, "bad argument '%s' to '%s' (%g is out of range %g..%g)", name, fn, value, d->min, d->max);
    if (d->type == PASS_PARAM_INTEGER && d->multiple > 0 && fmod(value, (double)d->multiple) != 0.0)
        return error_set(err, "bad argument '%s' to '%s' (a multiple of %d expected, got %g)", name, fn, d->multiple,
                         value);
    p->values[i].number = value;
    p->values[i].set = true;
    return true;
}

bool pass_set_boolean(struct pass *p, const char *name, bool value, struct error *err)
{
    int i = find_param(p, name, err);
    if (i < 0)
        return false;
    if (p->desc->params[i].type != PASS_PARAM_BOOLEAN)
        return error_set(err, "bad argument '%s' to '%s' (%s expected, got boolean)", name, p->desc->name,
                         type_word(p->desc->params[i].type));
    p->values[i].number = value ? 1.0 : 0.0;
    p->values[i].set = true;
    return true;
}

/* Index of `choice` in "a|b|c", or -1. */
static int choice_index(const char *choices, const char *choice)
{
    size_t n = strlen(choice);
    int index = 0;
    for (const char *c = choices; c && *c; index++) {
        const char *bar = strchr(c, '|');
        size_t len = bar ? (size_t)(bar - c) : strlen(c);
        if (len == n && strncmp(c, choice, n) == 0)
            return index;
        c = bar ? bar + 1 : NULL;
    }
    return -1;
}

static bool store_string(struct pass_value *v, const char *value, struct error *err)
{
    char *copy = strdup(value);
    if (!copy)
        return error_set(err, "out of memory");
    free(v->string);
    v->string = copy;
    v->set = true;
    return true;
}

bool pass_set_enum(struct pass *p, const char *name, const char *choice, struct error *err)
{
    int i = find_param(p, name, err);
    if (i < 0)
        return false;
    const struct pass_param_desc *d = &p->desc->params[i];
    if (d->type != PASS_PARAM_ENUM)
        return error_set(err, "bad argument '%s' to '%s' (%s expected, got string)", name, p->desc->name,
                         type_word(d->type));
    int k = choice_index(d->choices, choice);
    if (k < 0)
        return error_set(err, "bad argument '%s' to '%s' (one of %s expected, got '%s')", name, p->desc->name,
                         d->choices, choice);
    p->values[i].number = k;
    return store_string(&p->values[i], choice, err);
}

bool pass_set_string(struct pass *p, const char *name, const char *value, struct error *err)
{
    int i = find_param(p, name, err);
    if (i < 0)
        return false;
    const struct pass_param_desc *d = &p->desc->params[i];
    if (d->type == PASS_PARAM_ENUM)
        return pass_set_enum(p, name, value, err);
    if (d->type != PASS_PARAM_STRING && d->type != PASS_PARAM_INPUT)
        return error_set(err, "bad argument '%s' to '%s' (%s expected, got string)", name, p->desc->name,
                         type_word(d->type));
    return store_string(&p->values[i], value, err);
}

double pass_real(const struct pass *p, int param) { return p->values[param].number; }
int pass_int(const struct pass *p, int param) { return (int)p->values[param].number; }
bool pass_flag(const struct pass *p, int param) { return p->values[param].number != 0.0; }
int pass_choice(const struct pass *p, int param) { return (int)p->values[param].number; }

const char *pass_text(const struct pass *p, int param)
{
    return p->values[param].string ? p->values[param].string : p->desc->params[param].default_string;
}

struct light *pass_light_at(const struct pass *p, int param) { return p->values[param].light; }
struct object *pass_object_at(const struct pass *p, int param) { return p->values[param].object; }

bool pass_declare(struct pass *p, struct error *err)
{
    p->input_count = 0;
    p->output_count = 0;
    const struct pass_desc *d = p->desc;
    for (int i = 0; i < d->param_count; i++) {
        const struct pass_param_desc *pd = &d->params[i];
        if (pd->type == PASS_PARAM_INPUT_LIST) {
            /* one slot per item: "<name>0", "<name>1", ... */
            const struct pass_value *v = &p->values[i];
            if (pd->max > 0 && v->list_count > (int)pd->max)
                return error_set(err, "bad argument '%s' to '%s' (at most %d inputs, got %d)", pd->name, d->name,
                                 (int)pd->max, v->list_count);
            for (int k = 0; k < v->list_count; k++) {
                char slot[PASS_NAME_MAX];
                snprintf(slot, sizeof slot, "%.40s%d", pd->name, k);
                if (!pass_declare_input(p, slot, v->list[k], err))
                    return false;
            }
            continue;
        }
        if (pd->type != PASS_PARAM_INPUT)
            continue;
        const char *source = p->values[i].string;
        char derived[RESOURCE_NAME_MAX];
        if (!source && pd->default_beside) {
            int b = pass_param_index(d, pd->default_beside);
            const char *beside = b >= 0 ? p->values[b].string : NULL;
            const char *dot = beside ? strchr(beside, '.') : NULL;
            if (dot) {
                snprintf(derived, sizeof derived, "%.*s.%s", (int)(dot - beside), beside, pd->default_output);
                source = derived;
            }
        }
        if (!source) {
            if (pd->required)
                return error_set(err, "bad argument '%s' to '%s' (input \"pass.output\" expected, got no value)",
                                 pd->name, d->name);
            continue;
        }
        if (!pass_declare_input(p, pd->name, source, err))
            return false;
    }
    if (d->declare && !d->declare(p, err))
        return false;
    p->declared_inputs = p->input_count;
    return true;
}

bool pass_declare_input(struct pass *p, const char *slot, const char *source, struct error *err)
{
    if (p->input_count >= PASS_MAX_INPUTS)
        return error_set(err, "pass '%s': more than %d inputs", p->name, PASS_MAX_INPUTS);
    if (!strchr(source, '.'))
        return error_set(err, "pass '%s': input %s = '%s' must name a pass output as 'pass.output'", p->name,
                         slot, source);
    struct pass_input_decl *in = &p->inputs[p->input_count++];
    snprintf(in->name, sizeof in->name, "%s", slot);
    snprintf(in->source, sizeof in->source, "%s", source);
    return true;
}

bool pass_declare_output(struct pass *p, const char *name, GLenum format, GLenum target, int width, int height,
                         struct error *err)
{
    if (p->output_count >= PASS_MAX_OUTPUTS)
        return error_set(err, "pass '%s': more than %d outputs", p->name, PASS_MAX_OUTPUTS);
    struct pass_output_decl *out = &p->outputs[p->output_count++];
    snprintf(out->name, sizeof out->name, "%s", name);
    out->kind = RESOURCE_TEXTURE;
    out->record = NULL;
    out->format = format;
    out->target = target;
    out->width = width;
    out->height = height;
    return true;
}

bool pass_declare_output_record(struct pass *p, const char *name, const struct record_type *record, GLenum format,
                                GLenum target, int width, int height, struct error *err)
{
    if (!pass_declare_output(p, name, format, target, width, height, err))
        return false;
    p->outputs[p->output_count - 1].record = record;
    return true;
}

bool pass_declare_bundle(struct pass *p, const char *name, const struct record_type *record, struct error *err)
{
    if (!pass_declare_output(p, name, GL_NONE, GL_NONE, 0, 0, err))
        return false;
    p->outputs[p->output_count - 1].kind = RESOURCE_RECORD;
    p->outputs[p->output_count - 1].record = record;
    return true;
}

static bool strings_equal(const char *a, const char *b)
{
    return a == b || (a && b && strcmp(a, b) == 0);
}

bool pass_values_equal(const struct pass *a, const struct pass *b, bool ignore_merged)
{
    if (a->desc != b->desc)
        return false;
    for (int i = 0; i < a->desc->param_count; i++) {
        const struct pass_param_desc *pd = &a->desc->params[i];
        const struct pass_value *x = &a->values[i], *y = &b->values[i];
        if (ignore_merged && pd->merge_or)
            continue;
        if (x->number != y->number || x->light != y->light || x->object != y->object ||
            !strings_equal(x->string, y->string) || x->object_count != y->object_count ||
            x->list_count != y->list_count || memcmp(x->color, y->color, sizeof x->color) != 0)
            return false;
        for (int k = 0; k < x->object_count; k++)
            if (x->objects[k] != y->objects[k])
                return false;
        for (int k = 0; k < x->list_count; k++)
            if (!strings_equal(x->list[k], y->list[k]) || !strings_equal(x->keys ? x->keys[k] : NULL, y->keys ? y->keys[k] : NULL))
                return false;
        if (x->lua_ref != y->lua_ref || pd->type == PASS_PARAM_UNIFORM_MAP)
            return false; /* tables, functions and uniform maps: never shared */
    }
    return true;
}

struct graph_resource *pass_frame_input(const struct pass *p, struct pass_frame *f, const char *slot)
{
    for (int i = 0; i < p->input_count; i++)
        if (strcmp(p->inputs[i].name, slot) == 0)
            return f->inputs[i];
    return NULL;
}

struct graph_resource *pass_frame_output(const struct pass *p, struct pass_frame *f, const char *name)
{
    for (int i = 0; i < p->output_count; i++)
        if (strcmp(p->outputs[i].name, name) == 0)
            return f->outputs[i];
    return NULL;
}

void *pass_frame_record(const struct pass *p, struct pass_frame *f, const char *slot, const struct record_type *type)
{
    struct graph_resource *res = pass_frame_input(p, f, slot);
    return res && res->decl.record == type ? res->record : NULL;
}

uint64_t pass_key_mix(uint64_t key, const void *data, size_t size) { return hash_fnv1a(key, data, size); }

static uint64_t key_mix_u64(uint64_t key, uint64_t v) { return hash_fnv1a(key, &v, sizeof v); }

uint64_t pass_frame_key(const struct pass *p, const struct pass_frame *f, unsigned depends)
{
    uint64_t h = HASH_FNV1A_BASIS;
    h = key_mix_u64(h, (uint64_t)f->width);
    h = key_mix_u64(h, (uint64_t)f->height);
    for (int k = 0; k < p->desc->param_count; k++) {
        const struct pass_value *v = &p->values[k];
        h = pass_key_mix(h, &v->number, sizeof v->number);
        h = key_mix_u64(h, (uint64_t)(uintptr_t)v->light);
        h = key_mix_u64(h, v->light ? v->light->version : 0u);
        h = key_mix_u64(h, (uint64_t)(uintptr_t)v->object);
        h = key_mix_u64(h, v->object ? v->object->version : 0u);
        for (int i = 0; i < v->object_count; i++) {
            h = key_mix_u64(h, (uint64_t)(uintptr_t)v->objects[i]);
            h = key_mix_u64(h, v->objects[i]->version);
        }
        if (v->string)
            h = pass_key_mix(h, v->string, strlen(v->string));
        h = pass_key_mix(h, v->color, sizeof v->color);
        for (int i = 0; i < v->list_count; i++) {
            if (v->list && v->list[i])
                h = pass_key_mix(h, v->list[i], strlen(v->list[i]) + 1);
            if (v->keys && v->keys[i])
                h = pass_key_mix(h, v->keys[i], strlen(v->keys[i]) + 1);
            if (v->vectors)
                h = pass_key_mix(h, v->vectors[i], sizeof v->vectors[i]);
        }
    }
    if (depends & PASS_DEPENDS_INPUTS)
        for (int k = 0; k < p->input_count; k++)
            h = key_mix_u64(h, f->inputs[k] ? f->inputs[k]->version : 0u);
    if (depends & PASS_DEPENDS_CAMERA)
        h = key_mix_u64(h, f->scene->camera.version);
    if (depends & PASS_DEPENDS_GEOMETRY)
        h = key_mix_u64(h, scene_geometry_version(f->scene));
    if (depends & PASS_DEPENDS_LIGHTS)
        h = key_mix_u64(h, scene_lights_version(f->scene));
    return h;
}

bool pass_frame_reusable(const struct pass_frame *f, bool made, uint64_t made_key, uint64_t key)
{
    return made && made_key == key && !f->snapshot->geometry_animated;
}

const char *pass_refractor_left_out(const struct object *o, bool caustics)
{
    /* one sentence for what of roughness, partial transmission, tint and a
     * normal map the object has (graph_lint copies it before the next call) */
    static char sentence[400];
    bool mapped = o->material.normal.texture != NULL && !o->material.thin;
    const char *alpha = o->material.alpha_blend          ? "its alphaMode BLEND"
                        : o->material.alpha_cutoff > 0.0f ? "its alphaMode MASK's holes"
                                                          : NULL;
    const char *parts[5];
    int n = 0;
    bool mirror = object_is(o, OBJECT_ROLE_MIRROR);
    bool rough = mirror ? o->material.roughness > 0.0f : object_is_rough_refractor(o);
    if (rough)
        parts[n++] = "its roughness";
    if (!mirror && object_is_partly_diffuse_refractor(o))
        parts[n++] = "its transmission below 1";
    if (!mirror && object_is_tinted_refractor(o))
        parts[n++] = "its tint";
    if (mapped && object_is(o, OBJECT_ROLE_SPECULAR))
        parts[n++] = "its normal map";
    if (alpha && object_is(o, OBJECT_ROLE_SPECULAR))
        parts[n++] = alpha;
    if (n == 0)
        return NULL;
    char list[200] = "";
    for (int k = 0; k < n; k++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k == 0 ? "" : k == n - 1 ? " and " : ", ",
                 parts[k]);
    /* what the pass draws instead: a mirror or glass without those */
    char as[80] = "";
    const char *adjectives[4] = {rough ? "smooth" : NULL,
                                 !mirror && (object_is_partly_diffuse_refractor(o) || object_is_tinted_refractor(o))
                                     ? "clear"
                                     : NULL,
                                 mapped ? "flat" : NULL, alpha ? "whole" : NULL};
    for (int k = 0, m = 0; k < 4; k++)
        if (adjectives[k])
            snprintf(as + strlen(as), sizeof as - strlen(as), "%s%s", m++ ? ", " : "", adjectives[k]);
    if (mirror)
        snprintf(sentence, sizeof sentence, "%s: %s%s%s", list,
                 caustics ? "the light it reflects is reflected as by a " : "drawn as a ", as,
                 caustics ? " mirror, so its caustic is sharp or whole (the reference draws the mirror as it is)"
                          : " mirror (refraction draws it as it is, a rough one by its scene lookup)");
    else
        snprintf(sentence, sizeof sentence, "%s: %s%s%s", list,
                 caustics ? "all the light that meets it is refracted as by " : "the view through it is drawn as through ",
                 as,
                 caustics ? " glass, so the caustic it focuses is sharp, too bright or uncoloured (the reference draws "
                            "the glass as it is)"
                          : " glass (refraction draws it as it is, rough glass by its scene lookup)");
    return sentence;
}

/* Whether some of object q lies inside o's solid: its bounds' centre or
 * one of up to 32 of its vertices, evenly spread, inside o's closed mesh */
/* The world box of an object's base shape (its mesh's bounds' corners) */
static void world_box(const struct object *o, vec3 *lo, vec3 *hi)
{
    mat4 model = object_model_matrix(o);
    const struct mesh *m = o->mesh;
    *lo = vec3_make(INFINITY, INFINITY, INFINITY), *hi = vec3_make(-INFINITY, -INFINITY, -INFINITY);
    for (int k = 0; k < 8; k++) {
        vec3 c = {k & 1 ? m->bounds_max.x : m->bounds_min.x, k & 2 ? m->bounds_max.y : m->bounds_min.y,
                  k & 4 ? m->bounds_max.z : m->bounds_min.z};
        vec3 w = mat4_transform_point(model, c);
        *lo = vec3_make(fminf(lo->x, w.x), fminf(lo->y, w.y), fminf(lo->z, w.z));
        *hi = vec3_make(fmaxf(hi->x, w.x), fmaxf(hi->y, w.y), fmaxf(hi->z, w.z));
    }
}

static bool object_within(const struct object *q, const struct object *o)
{
    const struct mesh *m = q->mesh;
    if (!m || m->vertex_count == 0 || !o->mesh)
        return false;
    vec3 qlo, qhi, olo, ohi; /* boxes apart: nothing to test (a refractor of many triangles is slow to ask) */
    world_box(q, &qlo, &qhi);
    world_box(o, &olo, &ohi);
    if (qlo.x > ohi.x || qlo.y > ohi.y || qlo.z > ohi.z || olo.x > qhi.x || olo.y > qhi.y || olo.z > qhi.z)
        return false;
    mat4 model = object_model_matrix(q);
    vec3 centre = mat4_transform_point(model, vec3_scale(vec3_add(m->bounds_min, m->bounds_max), 0.5f));
    if (object_encloses_point(o, centre))
        return true;
    size_t step = m->vertex_count > 32 ? m->vertex_count / 32 : 1;
    for (size_t v = 0; v < m->vertex_count; v += step) {
        const float *p = m->positions + v * 3;
        if (object_encloses_point(o, mat4_transform_point(model, vec3_make(p[0], p[1], p[2]))))
            return true;
    }
    return false;
}

const char *pass_refractor_holds(const struct scene *scene, const struct object *o, const char *other)
{
    static char sentence[400];
    if (!object_is(o, OBJECT_ROLE_REFRACTOR))
        return other;
    int first = -1, more = 0;
    for (int k = 0; k < scene->object_count; k++) {
        const struct object *q = scene->objects[k];
        if (q == o || !q->visible || object_is(q, OBJECT_ROLE_SPECULAR | OBJECT_ROLE_THIN) || !object_within(q, o))
            continue;
        if (first < 0)
            first = k;
        else
            more++;
    }
    if (first < 0)
        return other;
    char extra[64] = "";
    if (more)
        snprintf(extra, sizeof extra, " (and %d more)", more);
    snprintf(sentence, sizeof sentence,
             "object %d%s inside its %s: the pass finds what lies behind the %s's surfaces, not what lies within them, "
             "so it is not seen through it (the reference draws it)%s%s", first + 1, extra,
             o->material.kind == MATERIAL_WATER ? "water" : "glass", o->material.kind == MATERIAL_WATER ? "water" : "glass",
             other ? "; and " : "", other ? other : "");
    return sentence;
}
