#include "graph/pass.h"
#include "scene/scene.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

void pass_destroy(struct pass *p)
{
    if (!p || --p->references > 0)
        return;
    if (p->created && p->desc->destroy)
        p->desc->destroy(p);
    for (int i = 0; i < p->desc->param_count; i++) {
        free(p->values[i].string);
        for (int k = 0; k < p->values[i].list_count; k++) {
            free(p->values[i].list[k]);
            if (p->values[i].keys)
                free(p->values[i].keys[k]);
        }
        free(p->values[i].list);
        free(p->values[i].keys);
        free(p->values[i].vectors);
        free(p->values[i].vector_sizes);
        light_destroy(p->values[i].light);
        object_destroy(p->values[i].object);
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

double pass_number(const struct pass *p, const char *name)
{
    const struct pass_value *v = pass_value(p, name);
    return v ? v->number : 0.0;
}

const char *pass_string(const struct pass *p, const char *name)
{
    int i = pass_param_index(p->desc, name);
    if (i < 0)
        return NULL;
    if (p->values[i].string)
        return p->values[i].string;
    return p->desc->params[i].default_string;
}

struct light *pass_light(const struct pass *p, const char *name)
{
    const struct pass_value *v = pass_value(p, name);
    return v ? v->light : NULL;
}

struct object *pass_object(const struct pass *p, const char *name)
{
    const struct pass_value *v = pass_value(p, name);
    return v ? v->object : NULL;
}

const float *pass_color(const struct pass *p, const char *name)
{
    const struct pass_value *v = pass_value(p, name);
    return v && v->set ? v->color : NULL;
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
    out->format = format;
    out->target = target;
    out->width = width;
    out->height = height;
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
