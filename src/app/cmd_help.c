#define _POSIX_C_SOURCE 200809L
/* `caustica help [passes | PASS] [--markdown]`: the pass reference, printed
 * from the descriptors themselves (src/passes/), so it cannot drift from
 * the code. The pass section of docs/LUA_API.md is this output with
 * --markdown; tests/cli/docs_test.sh fails when the two differ. */
#include <stdio.h>
#include <string.h>

#include "app/cli.h"
#include "core/suggest.h"
#include "graph/pass.h"
#include "scene/scene.h"
#include "scene/water.h"

static const char *param_type_name(const struct pass_param_desc *d)
{
    switch (d->type) {
    case PASS_PARAM_NUMBER: return "number";
    case PASS_PARAM_INTEGER: return "integer";
    case PASS_PARAM_BOOLEAN: return "boolean";
    case PASS_PARAM_STRING: return d->is_path ? "path" : "string";
    case PASS_PARAM_ENUM: return "enum";
    case PASS_PARAM_LIGHT: return "light";
    case PASS_PARAM_OBJECT: return "object";
    case PASS_PARAM_OBJECT_LIST: return "object list";
    case PASS_PARAM_INPUT:
        if (d->bundle) { /* a record, not a texture: say which */
            static char bundle[64];
            snprintf(bundle, sizeof bundle, "input \"pass.output\" (%s)", d->bundle->name);
            return bundle;
        }
        return "input \"pass.output\"";
    case PASS_PARAM_INPUT_LIST: return "input or list of inputs";
    case PASS_PARAM_COLOR: return "colour {r, g, b}";
    case PASS_PARAM_INPUT_MAP: return "{slot = \"pass.output\"}";
    case PASS_PARAM_OUTPUT_MAP: return "{name = \"format\"}";
    case PASS_PARAM_UNIFORM_MAP: return "{name = number or vector}";
    case PASS_PARAM_TABLE: return "table";
    case PASS_PARAM_FUNCTION: return "function";
    }
    return "?";
}

/* The default as a script would write it, or "" when there is none. */
static void param_default(const struct pass_param_desc *d, char *out, size_t outlen)
{
    out[0] = '\0';
    if (d->block) {
        snprintf(out, outlen, "a shared %s", d->block);
        return;
    }
    if (d->required) {
        snprintf(out, outlen, "required");
        return;
    }
    switch (d->type) {
    case PASS_PARAM_NUMBER:
    case PASS_PARAM_INTEGER:
        snprintf(out, outlen, "%g", d->default_number);
        break;
    case PASS_PARAM_BOOLEAN:
        snprintf(out, outlen, "%s", d->default_number != 0.0 ? "true" : "false");
        break;
    case PASS_PARAM_STRING:
    case PASS_PARAM_ENUM:
        if (d->default_string)
            snprintf(out, outlen, "\"%s\"", d->default_string);
        break;
    default:
        break;
    }
}

static void param_range(const struct pass_param_desc *d, char *out, size_t outlen)
{
    out[0] = '\0';
    if ((d->type == PASS_PARAM_NUMBER || d->type == PASS_PARAM_INTEGER) && d->min < d->max)
        snprintf(out, outlen, d->multiple > 0 ? "%g..%g, x%d" : "%g..%g", d->min, d->max, d->multiple);
    else if (d->type == PASS_PARAM_ENUM && d->choices)
        snprintf(out, outlen, "%s", d->choices);
}

/* The outputs a pass declares with its default parameters (a pass whose
 * outputs depend on required parameters says so). */
static void pass_outputs(const struct pass_desc *desc, char *out, size_t outlen)
{
    out[0] = '\0';
    struct pass *p = pass_create(desc);
    struct error err;
    /* Required parameters get stand-ins (a source name for an input, a
     * directional light, a water object, a shader path): the outputs listed
     * are those of the defaults. */
    struct light *light = light_create(LIGHT_DIRECTIONAL);
    struct mesh *mesh = mesh_create_sphere(1.0f, 8, &err);
    struct object *object = mesh ? object_create(mesh) : NULL;
    struct water water;
    memset(&water, 0, sizeof water);
    if (object)
        object->water = &water;
    bool decided_by_script = !light || !object;
    for (int i = 0; p && i < desc->param_count; i++) {
        const struct pass_param_desc *d = &desc->params[i];
        if (!d->required)
            continue;
        if (d->type == PASS_PARAM_INPUT) {
            pass_set_string(p, d->name, "input.source", NULL);
        } else if (d->type == PASS_PARAM_LIGHT) {
            pass_set_light(p, i, light);
        } else if (d->type == PASS_PARAM_OBJECT) {
            pass_set_object(p, i, object);
        } else if (d->type == PASS_PARAM_STRING) {
            pass_set_string(p, d->name, d->is_path ? "shader.frag" : "value", NULL);
        } else if (d->type == PASS_PARAM_FUNCTION) {
            p->values[i].set = true; /* declare() does not call it */
        } else {
            decided_by_script = true;
        }
    }
    bool declared = p && !decided_by_script && pass_declare(p, &err);
    if (declared) {
        size_t used = 0;
        for (int i = 0; i < p->output_count && used < outlen; i++) {
            int n = snprintf(out + used, outlen - used, "%s`%s`", i ? ", " : "", p->outputs[i].name);
            if (n > 0)
                used += (size_t)n;
        }
    }
    if (!declared || !p->output_count)
        snprintf(out, outlen, "(set by its parameters)");
    pass_destroy(p);
    if (object)
        object->water = NULL;
    object_destroy(object);
    mesh_destroy(mesh);
    light_destroy(light);
}

/* A Markdown table cell: '|' (enum choices) escaped. */
static void print_cell(FILE *f, const char *text)
{
    fputs(" ", f);
    for (const char *c = text; *c; c++) {
        if (*c == '|')
            fputc('\\', f);
        fputc(*c, f);
    }
    fputs(" |", f);
}

static void print_pass(FILE *f, const struct pass_desc *d, bool markdown)
{
    char outputs[512], def[128], range[256];
    pass_outputs(d, outputs, sizeof outputs);
    if (markdown) {
        fprintf(f, "### `c.pass.%s`\n\n%s.\n\nOutputs: %s.\n\n", d->name, d->summary, outputs);
        if (pass_technique_name(d->technique))
            fprintf(f, "A technique of the family `%s` (`c.techniques \"%s\"`: the optics matrix and the comparison "
                       "scenes enumerate it).\n\n",
                    pass_technique_name(d->technique), pass_technique_name(d->technique));
        fprintf(f, "| parameter | type | default | range | what it is |\n|---|---|---|---|---|\n");
        for (int i = 0; i < d->param_count; i++) {
            const struct pass_param_desc *p = &d->params[i];
            param_default(p, def, sizeof def);
            param_range(p, range, sizeof range);
            fprintf(f, "| `%s` |", p->name);
            print_cell(f, param_type_name(p));
            print_cell(f, def);
            print_cell(f, range);
            print_cell(f, p->help ? p->help : "");
            fputc('\n', f);
        }
        fputc('\n', f);
        return;
    }
    fprintf(f, "%s: %s\n  outputs: %s\n", d->name, d->summary, outputs);
    if (pass_technique_name(d->technique))
        fprintf(f, "  technique: %s (c.techniques \"%s\")\n", pass_technique_name(d->technique),
                pass_technique_name(d->technique));
    for (int i = 0; i < d->param_count; i++) {
        const struct pass_param_desc *p = &d->params[i];
        param_default(p, def, sizeof def);
        param_range(p, range, sizeof range);
        fprintf(f, "  %-14s %-24s", p->name, param_type_name(p));
        if (def[0])
            fprintf(f, p->required ? " %s" : " default %s", def);
        if (range[0])
            fprintf(f, " (%s)", range);
        if (p->help)
            fprintf(f, "\n  %14s %s", "", p->help);
        fputc('\n', f);
    }
}

int cmd_help(int argc, char **argv)
{
    bool markdown = false;
    const char *topic = NULL;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--markdown") == 0) {
            markdown = true;
        } else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            printf("usage:\n  caustica help                   every verb\n"
                   "  caustica help passes            every pass with its parameters\n"
                   "  caustica help PASS              one pass: what it reads and makes, each parameter's "
                   "meaning, default and range\n"
                   "  caustica help VERB              the same as caustica VERB --help\n"
                   "options:\n  --markdown                      the pass reference as Markdown\n");
            return 0;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            fprintf(stderr, "caustica: help: unknown option '%s'\nsee `caustica help --help`\n", argv[i]);
            return EXIT_USAGE;
        } else if (!topic)
            topic = argv[i];
        else {
            fprintf(stderr, "caustica: help takes one topic, got '%s' too\n", argv[i]);
            return EXIT_USAGE;
        }
    }
    if (!topic) {
        cli_usage(stdout);
        printf("\ncaustica help passes    every pass with its parameters\ncaustica help PASS      one pass\n");
        return 0;
    }
    if (strcmp(topic, "passes") == 0) {
        for (int i = 0; i < pass_registry_count(); i++) {
            print_pass(stdout, pass_registry_get(i), markdown);
            if (!markdown && i + 1 < pass_registry_count())
                fputc('\n', stdout);
        }
        return 0;
    }
    if (cli_is_verb(topic)) {
        cli_usage_verb(stdout, topic);
        return 0;
    }
    const struct pass_desc *d = pass_registry_find(topic);
    if (!d) {
        const char *names[64];
        size_t n = 0;
        for (int i = 0; i < pass_registry_count() && n < 64; i++)
            names[n++] = pass_registry_get(i)->name;
        const char *near = suggest_nearest(topic, names, n);
        fprintf(stderr, "caustica: help: no pass named '%s'", topic);
        if (near)
            fprintf(stderr, " (did you mean '%s'?)", near);
        fprintf(stderr, " (known passes:");
        for (int i = 0; i < pass_registry_count(); i++)
            fprintf(stderr, "%s %s", i ? "," : "", pass_registry_get(i)->name);
        fprintf(stderr, ")\n");
        return EXIT_SCENE_ERROR;
    }
    print_pass(stdout, d, markdown);
    return 0;
}
