#include "graph/graph.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/suggest.h"
#include "graph/renderer.h"

void graph_init(struct graph *g) { memset(g, 0, sizeof *g); }

static void release_resources(struct graph *g)
{
    for (int i = 0; i < g->resource_count; i++)
        gl_texture_destroy(&g->resources[i].texture);
    free(g->resources);
    g->resources = NULL;
    g->resource_count = 0;
}

void graph_release(struct graph *g)
{
    release_resources(g);
    for (int i = 0; i < g->count; i++) {
        if (g->entries[i].queries[0] && gl_api_ready())
            gl.DeleteQueries(2, g->entries[i].queries);
        pass_destroy(g->entries[i].pass);
    }
    free(g->entries);
    g->entries = NULL;
    g->count = g->capacity = 0;
    g->compiled = false;
}

bool graph_add(struct graph *g, const char *name, struct pass *pass, struct error *err)
{
    if (g->executing)
        return error_set(err, "the graph is rendering a frame: add passes before rendering, not from a pass's run");
    if (!name[0] || strchr(name, '.') || strlen(name) >= PASS_NAME_MAX)
        return error_set(err, "pass name '%s' must be non-empty, shorter than %d characters and without '.'", name,
                         PASS_NAME_MAX);
    for (int i = 0; i < g->count; i++) {
        if (!g->entries[i].pass->implicit && strcmp(g->entries[i].pass->name, name) == 0)
            return error_set(err, "a pass named '%s' is already in the graph", name);
        if (g->entries[i].pass == pass)
            return error_set(err, "this %s pass is already in the graph as '%s'", pass->desc->name,
                             g->entries[i].pass->name);
    }
    if (g->count == g->capacity) {
        int cap = g->capacity ? g->capacity * 2 : 8;
        struct graph_entry *e = realloc(g->entries, (size_t)cap * sizeof *e);
        if (!e)
            return error_set(err, "out of memory");
        g->entries = e;
        g->capacity = cap;
    }
    struct graph_entry *e = &g->entries[g->count++];
    memset(e, 0, sizeof *e);
    e->pass = pass;
    pass_retain(pass);
    snprintf(pass->name, sizeof pass->name, "%s", name);
    g->compiled = false;
    return true;
}

bool graph_set_output(struct graph *g, const char *name, struct error *err)
{
    if (g->executing)
        return error_set(err, "the graph is rendering a frame: set its output before rendering, not from a pass's run");
    if (!strchr(name, '.'))
        return error_set(err, "graph output '%s' must name a pass output as 'pass.output'", name);
    snprintf(g->output, sizeof g->output, "%s", name);
    g->compiled = false;
    return true;
}

static int find_output_of(const struct graph *g, int upto, const char *resource, int *which)
{
    for (int i = 0; i < upto; i++) {
        const struct pass *p = g->entries[i].pass;
        size_t n = strlen(p->name);
        if (strncmp(resource, p->name, n) != 0 || resource[n] != '.')
            continue;
        for (int o = 0; o < p->output_count; o++)
            if (strcmp(resource + n + 1, p->outputs[o].name) == 0) {
                *which = o;
                return i;
            }
    }
    return -1;
}

/* Pass i's number as the script counts its passes (from 1): the blocks
 * the graph added before it do not count (a block's own: the number of the
 * script's pass it was added before). */
static int script_number(const struct graph *g, int i)
{
    int n = 0;
    for (int j = 0; j < i; j++)
        n += !g->entries[j].pass->implicit;
    return n + 1;
}

/* "shade.color" is produced by ...: lists the passes that do produce an
 * output of that name, so an order mistake is easy to see. */
static void list_producers(const struct graph *g, const char *resource, char *out, size_t outlen)
{
    const char *dot = strrchr(resource, '.');
    const char *outname = dot ? dot + 1 : resource;
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; i < g->count; i++) {
        const struct pass *p = g->entries[i].pass;
        for (int o = 0; o < p->output_count; o++)
            if (strcmp(p->outputs[o].name, outname) == 0 && used < outlen) {
                int w = snprintf(out + used, outlen - used, "%s'%s.%s' (pass %d)", used ? ", " : "", p->name,
                                 p->outputs[o].name, script_number(g, i));
                if (w > 0)
                    used += (size_t)w;
            }
    }
}

/* Building blocks (issue 26). An input parameter with `.block` that the
 * script leaves unset is read from a block pass the graph adds before the
 * first pass that needs it, one per distinct configuration: beam_caustics
 * and layered_caustics for one light read one depth-layer set, and every
 * caustics pass the one receiver G-buffer. The blocks of the last check are
 * reused when their configuration is unchanged, so a recompile (a new size)
 * keeps their state. */
static bool name_taken(const struct graph_entry *entries, int count, const struct pass *self, const char *name)
{
    for (int i = 0; i < count; i++)
        if (entries[i].pass != self && strcmp(entries[i].pass->name, name) == 0)
            return true;
    return false;
}

static void block_name(const struct graph *g, const struct graph_entry *added, int added_count, struct pass *block)
{
    for (int n = 1;; n++) {
        char name[PASS_NAME_MAX];
        if (n == 1)
            snprintf(name, sizeof name, "%s", block->desc->name);
        else
            snprintf(name, sizeof name, "%s_%d", block->desc->name, n);
        bool taken = false;
        for (int i = 0; i < g->count; i++)
            if (!g->entries[i].pass->implicit && strcmp(g->entries[i].pass->name, name) == 0)
                taken = true;
        if (!taken && !name_taken(added, added_count, block, name)) {
            snprintf(block->name, sizeof block->name, "%s", name);
            return;
        }
    }
}

/* The blocks the graph holds from its last check: taken out of the list. */
struct old_blocks {
    struct graph_entry *entries;
    int count;
};

static void release_entry(struct graph_entry *e)
{
    if (e->queries[0] && gl_api_ready())
        gl.DeleteQueries(2, e->queries);
    pass_destroy(e->pass);
}

static bool add_block(struct graph *g, struct graph_entry *list, int *count, int consumer_index, struct old_blocks *old,
                      const struct pass_param_desc *pd, int param, struct pass **used, struct error *err)
{
    struct pass *consumer = list[consumer_index].pass;
    const struct pass_desc *desc = pass_registry_find(pd->block);
    if (!desc)
        return error_set(err, "pass '%s' (%s): input '%s' names the building block '%s', which is not a pass", consumer->name,
                         consumer->desc->name, pd->name, pd->block);
    struct pass *want = pass_create(desc);
    if (!want)
        return error_set(err, "out of memory");
    want->implicit = true;
    if (consumer->desc->configure_block && !consumer->desc->configure_block(consumer, param, want, err)) {
        pass_destroy(want);
        return error_prefix(err, "pass '%s' (%s)", consumer->name, consumer->desc->name);
    }
    /* A block already added for an earlier reader, or one the script
     * itself added before this reader with the same values, serves this one
     * too, with the merged flags this reader needs turned on (issue 54: the
     * script's depth_layers and the graph's for the same light were both
     * built, and nothing said so). */
    struct pass *block = NULL;
    for (int i = 0; i < *count && !block; i++)
        if ((list[i].pass->implicit || (i < consumer_index && list[i].pass->desc == desc)) &&
            pass_values_equal(list[i].pass, want, true))
            block = list[i].pass;
    if (block) {
        for (int k = 0; k < desc->param_count; k++)
            if (desc->params[k].merge_or && want->values[k].number != 0.0)
                pass_set_boolean(block, desc->params[k].name, true, NULL);
        pass_destroy(want);
        *used = block;
        return true;
    }
    /* Else one of the last check's (its state kept), or the new one, goes
     * in just before this reader. */
    struct graph_entry entry;
    memset(&entry, 0, sizeof entry);
    for (int i = 0; i < old->count && !block; i++)
        if (old->entries[i].pass && pass_values_equal(old->entries[i].pass, want, true)) {
            entry = old->entries[i];
            old->entries[i].pass = NULL;
            block = entry.pass;
            for (int k = 0; k < desc->param_count; k++) /* merged flags start again from this reader's */
                if (desc->params[k].merge_or)
                    pass_set_boolean(block, desc->params[k].name, want->values[k].number != 0.0, NULL);
            pass_destroy(want);
        }
    if (!block) {
        entry.pass = block = want;
        snprintf(block->origin, sizeof block->origin, "added by the graph for '%s'", consumer->name);
    }
    memmove(&list[consumer_index + 1], &list[consumer_index], (size_t)(*count - consumer_index) * sizeof *list);
    list[consumer_index] = entry;
    (*count)++;
    block_name(g, list, *count, block);
    *used = block;
    return true;
}

/* The reader's inputs from `block`: the parameter's own (`default_output`)
 * and those read beside it. */
static bool read_block(struct pass *consumer, int param, const struct pass *block, struct error *err)
{
    const struct pass_desc *d = consumer->desc;
    char source[RESOURCE_NAME_MAX];
    snprintf(source, sizeof source, "%s.%s", block->name, d->params[param].default_output);
    if (!pass_declare_input(consumer, d->params[param].name, source, err))
        return false;
    for (int k = 0; k < d->param_count; k++) {
        const struct pass_param_desc *pk = &d->params[k];
        if (pk->type == PASS_PARAM_INPUT && !consumer->values[k].string && pk->default_beside &&
            strcmp(pk->default_beside, d->params[param].name) == 0) {
            snprintf(source, sizeof source, "%s.%s", block->name, pk->default_output);
            if (!pass_declare_input(consumer, pk->name, source, err))
                return false;
        }
    }
    return true;
}

static bool add_blocks(struct graph *g, struct error *err)
{
    struct old_blocks old = {calloc((size_t)(g->count > 0 ? g->count : 1), sizeof *old.entries), 0};
    /* room for a block before every input of every pass */
    size_t room = (size_t)g->count * (PASS_MAX_INPUTS + 1) + 1;
    struct graph_entry *list = calloc(room, sizeof *list);
    if (!old.entries || !list) {
        free(old.entries);
        free(list);
        return error_set(err, "out of memory");
    }
    int count = 0;
    for (int i = 0; i < g->count; i++) {
        if (g->entries[i].pass->implicit)
            old.entries[old.count++] = g->entries[i];
        else {
            list[count++] = g->entries[i];
            g->entries[i].pass->input_count = g->entries[i].pass->declared_inputs;
        }
    }
    bool ok = true;
    for (int i = 0; i < count && ok; i++) {
        struct pass *p = list[i].pass;
        if (p->implicit)
            continue;
        for (int k = 0; k < p->desc->param_count && ok; k++) {
            const struct pass_param_desc *pd = &p->desc->params[k];
            if (pd->type != PASS_PARAM_INPUT || !pd->block || p->values[k].string ||
                (p->desc->reads_block && !p->desc->reads_block(p, k)))
                continue;
            struct pass *block = NULL;
            int before = count;
            ok = add_block(g, list, &count, i, &old, pd, k, &block, err) && read_block(p, k, block, err);
            i += count - before; /* the reader moved down past the new block */
        }
    }
    /* every block's outputs follow its (merged) values */
    for (int i = 0; i < count && ok; i++)
        if (list[i].pass->implicit)
            ok = pass_declare(list[i].pass, err);
    for (int i = 0; i < old.count; i++)
        if (old.entries[i].pass)
            release_entry(&old.entries[i]);
    free(old.entries);
    if (!ok) {
        /* keep the script's passes; the blocks made so far go */
        int kept = 0;
        for (int i = 0; i < count; i++) {
            if (list[i].pass->implicit)
                release_entry(&list[i]);
            else
                list[kept++] = list[i];
        }
        count = kept;
    }
    free(g->entries);
    g->entries = list;
    g->count = count;
    g->capacity = (int)room;
    return ok;
}

/* The descriptor parameter behind input slot `slot`: its name, or an input
 * list's name with the item's index after it ("shadow1"). */
static int input_param(const struct pass_desc *d, const char *slot)
{
    int i = pass_param_index(d, slot);
    if (i >= 0)
        return i;
    size_t n = strlen(slot);
    while (n > 0 && slot[n - 1] >= '0' && slot[n - 1] <= '9')
        n--;
    for (int k = 0; k < d->param_count; k++)
        if (d->params[k].type == PASS_PARAM_INPUT_LIST && strlen(d->params[k].name) == n &&
            strncmp(d->params[k].name, slot, n) == 0)
            return k;
    return -1;
}

/* Input k of pass i, made by output `which` of pass `producer`: a texture
 * where a texture is read, a record of the right type where one is. */
static bool check_input_kind(const struct graph *g, int i, int k, int producer, int which, struct error *err)
{
    const struct pass *p = g->entries[i].pass;
    int param = input_param(p->desc, p->inputs[k].name);
    const struct pass_output_decl *made = &g->entries[producer].pass->outputs[which];
    const struct record_type *want = param >= 0 ? p->desc->params[param].bundle : NULL;
    const struct record_type *have = made->kind == RESOURCE_RECORD ? made->record : NULL;
    if (want != have)
        return error_set(err, "%s%spass '%s' (%s) reads %s = '%s', which is %s%s, where %s%s is expected",
                         p->origin[0] ? p->origin : "", p->origin[0] ? ": " : "", p->name, p->desc->name,
                         p->inputs[k].name, p->inputs[k].source, have ? "a " : "a texture",
                         have ? have->name : "", want ? "a " : "a texture", want ? want->name : "");
    /* a texture that must carry a typed record (a shadow map's
     * light matrix): another texture there rendered unshadowed,
     * exit 0 and no word (issue 54) */
    const struct record_type *want_record = param >= 0 ? p->desc->params[param].record : NULL;
    if (want_record && made->record != want_record) {
        /* an input list's item as the script wrote it: shadow[2] */
        char shown[PASS_NAME_MAX + 16];
        const char *pname = p->desc->params[param].name;
        if (p->desc->params[param].type == PASS_PARAM_INPUT_LIST)
            snprintf(shown, sizeof shown, "%s[%d]", pname, atoi(p->inputs[k].name + strlen(pname)) + 1);
        else
            snprintf(shown, sizeof shown, "%s", pname);
        return error_set(err, "%s%spass '%s' (%s) reads %s = '%s', a texture that is not a %s's (a %s "
                              "pass's `depth` is expected, e.g. \"shadow.depth\")",
                         p->origin[0] ? p->origin : "", p->origin[0] ? ": " : "", p->name, p->desc->name,
                         shown, p->inputs[k].source, want_record->name, want_record->name);
    }
    return true;
}

/* Input k of pass i, which no earlier pass makes: which pass makes it
 * later, or what the named pass does make ("shade.colour": shade makes
 * color, ...). Always false. */
static bool explain_missing_input(const struct graph *g, int i, int k, struct error *err)
{
    const struct pass *p = g->entries[i].pass;
    int which = 0;
    char producers[512];
    list_producers(g, p->inputs[k].source, producers, sizeof producers);
    int later = find_output_of(g, g->count, p->inputs[k].source, &which);
    if (later >= 0)
        return error_set(err, "pass '%s' (%s, pass %d) reads %s = '%s', which pass '%s' (pass %d) "
                              "makes only later: move '%s' before '%s'",
                         p->name, p->desc->name, script_number(g, i), p->inputs[k].name, p->inputs[k].source,
                         g->entries[later].pass->name, script_number(g, later), g->entries[later].pass->name,
                         p->name);
    /* what the named pass does make */
    char made[512] = "";
    const char *dot = strchr(p->inputs[k].source, '.');
    for (int j = 0; dot && j < g->count; j++) {
        const struct pass *q = g->entries[j].pass;
        if (strlen(q->name) != (size_t)(dot - p->inputs[k].source) ||
            strncmp(q->name, p->inputs[k].source, (size_t)(dot - p->inputs[k].source)) != 0)
            continue;
        size_t used = (size_t)snprintf(made, sizeof made, "; pass '%s' makes ", q->name);
        for (int o = 0; o < q->output_count && used < sizeof made; o++) {
            int w = snprintf(made + used, sizeof made - used, "%s'%s.%s'", o ? ", " : "", q->name,
                             q->outputs[o].name);
            if (w > 0)
                used += (size_t)w;
        }
    }
    return error_set(err, "%s%spass '%s' (%s, pass %d) reads %s = '%s', which no earlier pass makes%s%s%s",
                     p->origin[0] ? p->origin : "", p->origin[0] ? ": " : "", p->name, p->desc->name,
                     script_number(g, i), p->inputs[k].name, p->inputs[k].source,
                     producers[0] ? "; outputs of that name: " : "", producers, made);
}

/* The graph's output, which no pass makes: the nearest name it makes (a
 * typo: "env.colr"). Always false. */
static bool explain_missing_output(const struct graph *g, struct error *err)
{
    char producers[512], nearest[RESOURCE_NAME_MAX + 32] = "";
    list_producers(g, g->output, producers, sizeof producers);
    char names[256][RESOURCE_NAME_MAX];
    const char *candidates[256];
    size_t count = 0;
    for (int i = 0; i < g->count; i++)
        for (int o = 0; o < g->entries[i].pass->output_count && count < 256; o++) {
            snprintf(names[count], sizeof names[count], "%s.%s", g->entries[i].pass->name,
                     g->entries[i].pass->outputs[o].name);
            candidates[count] = names[count];
            count++;
        }
    const char *near = count ? suggest_nearest(g->output, candidates, count) : NULL;
    if (near)
        snprintf(nearest, sizeof nearest, " (did you mean '%s'?)", near);
    return error_set(err, "%sgraph output '%s' is made by no pass%s%s%s", g->output_where, g->output, nearest,
                     producers[0] ? "; outputs of that name: " : "", producers);
}

/* Keeps what the output depends on, walking backwards. */
static void keep_needed(struct graph *g, int out_pass)
{
    int which = 0;
    for (int i = 0; i < g->count; i++) {
        g->entries[i].state = GRAPH_PASS_PRUNED;
        snprintf(g->entries[i].reason, sizeof g->entries[i].reason,
                 "contributes nothing to the output '%s'", g->output);
    }
    g->entries[out_pass].state = GRAPH_PASS_KEPT;
    g->entries[out_pass].reason[0] = '\0';
    for (int i = out_pass; i >= 0; i--) {
        struct graph_entry *e = &g->entries[i];
        if (e->state != GRAPH_PASS_KEPT)
            continue;
        for (int k = 0; k < e->pass->input_count; k++) {
            int producer = find_output_of(g, i, e->pass->inputs[k].source, &which);
            if (producer >= 0 && g->entries[producer].state != GRAPH_PASS_KEPT) {
                g->entries[producer].state = GRAPH_PASS_KEPT;
                g->entries[producer].reason[0] = '\0';
            }
        }
    }
}

bool graph_check(struct graph *g, struct error *err)
{
    if (g->count == 0)
        return error_set(err, "the graph has no passes: add one with g:add(name, c.pass.<kind>{...})");
    if (!add_blocks(g, err))
        return false;
    if (!g->output[0])
        return error_set(err, "the graph has no output: call g:output(\"pass.output\")");
    /* Every input must be produced by an earlier pass: the script's passes
     * first, then the blocks the graph added, whose inputs come from their
     * readers' values (a reader's shadow maps lighting its distance map):
     * the message names the pass the script wrote. */
    for (int n = 0; n < 2 * g->count; n++) {
        int i = n % g->count;
        struct pass *p = g->entries[i].pass;
        if (p->implicit != (n >= g->count))
            continue;
        for (int k = 0; k < p->input_count; k++) {
            int which = 0;
            int producer = find_output_of(g, i, p->inputs[k].source, &which);
            if (producer < 0)
                return explain_missing_input(g, i, k, err);
            if (!check_input_kind(g, i, k, producer, which, err))
                return false;
        }
    }
    int which = 0;
    int out_pass = find_output_of(g, g->count, g->output, &which);
    if (out_pass < 0)
        return explain_missing_output(g, err);
    if (g->entries[out_pass].pass->outputs[which].kind == RESOURCE_RECORD)
        return error_set(err, "graph output '%s' is a %s, not an image: output one of the textures made from it",
                         g->output, g->entries[out_pass].pass->outputs[which].record->name);
    keep_needed(g, out_pass);
    return true;
}

bool graph_compile(struct graph *g, struct renderer *r, int width, int height, struct error *err)
{
    if (g->compiled && g->width == width && g->height == height)
        return true;
    if (!graph_check(g, err))
        return false;
    release_resources(g);
    int total = 0;
    for (int i = 0; i < g->count; i++)
        total += g->entries[i].pass->output_count;
    g->resources = calloc((size_t)(total > 0 ? total : 1), sizeof *g->resources);
    if (!g->resources)
        return error_set(err, "out of memory");
    g->width = width;
    g->height = height;
    for (int i = 0; i < g->count; i++) {
        struct graph_entry *e = &g->entries[i];
        struct pass *p = e->pass;
        for (int o = 0; o < PASS_MAX_OUTPUTS; o++)
            e->output_resources[o] = -1;
        for (int k = 0; k < PASS_MAX_INPUTS; k++)
            e->input_resources[k] = -1;
        for (int k = 0; k < p->input_count; k++) {
            int which = 0, producer = find_output_of(g, i, p->inputs[k].source, &which);
            e->input_resources[k] = g->entries[producer].output_resources[which];
        }
        if (e->state != GRAPH_PASS_KEPT)
            continue;
        for (int o = 0; o < p->output_count; o++) {
            struct graph_resource *res = &g->resources[g->resource_count];
            const struct pass_output_decl *d = &p->outputs[o];
            snprintf(res->name, sizeof res->name, "%s.%s", p->name, d->name);
            res->decl = *d;
            res->producer = i;
            if (d->kind == RESOURCE_RECORD) { /* the producer's record: no texture */
                e->output_resources[o] = g->resource_count++;
                continue;
            }
            int w = d->width > 0 ? d->width : width, h = d->height > 0 ? d->height : height;
            if (!gl_texture_create(&res->texture, d->target, d->format, w, h, 1, err)) {
                release_resources(g);
                return error_prefix(err, "pass '%s' output '%s'", p->name, d->name);
            }
            e->output_resources[o] = g->resource_count++;
        }
        if (!p->created) {
            if (p->desc->create && !p->desc->create(p, r, err))
                return error_prefix(err, "pass '%s' (%s%s%s)", p->name, p->desc->name, p->origin[0] ? ", made at " : "",
                                    p->origin);
            p->created = true;
        }
        if (!e->queries[0])
            gl.GenQueries(2, e->queries);
        e->reuse_valid = false; /* new textures: nothing in them yet */
    }
    int which = 0;
    int out_pass = find_output_of(g, g->count, g->output, &which);
    g->output_resource = g->entries[out_pass].output_resources[which];
    g->compiled = true;
    return gl_check("graph compile", err);
}

static bool execute_passes(struct graph *g, struct renderer *r, struct scene *scene, int frame, double time,
                           struct error *err);

/* A pass whose light is not among the frame's lights makes nothing this
 * frame, whatever the pass (issue 26: three passes refused such a light and
 * three rendered zero without a word); graph_lint says so. */
static bool lights_present(const struct pass *p, const struct renderer *r, const struct scene *scene, char *why,
                           size_t whylen)
{
    for (int k = 0; k < p->desc->param_count; k++) {
        const struct light *light = p->values[k].light;
        if (p->desc->params[k].type == PASS_PARAM_LIGHT && light && renderer_light_slot(r, scene, light) < 0) {
            snprintf(why, whylen, "left out: its %s is not among the scene's lights (scene:add(light))",
                     p->desc->params[k].name);
            return false;
        }
    }
    return true;
}

/* The graph is frozen while it executes: a custom pass's run may not add
 * passes or release the graph under the loop (graph_add refuses). */
bool graph_execute(struct graph *g, struct renderer *r, struct scene *scene, int frame, double time,
                   struct error *err)
{
    if (g->executing)
        return error_set(err, "the graph is already rendering a frame");
    g->executing = true;
    bool ok = execute_passes(g, r, scene, frame, time, err);
    g->executing = false;
    return ok;
}

static bool execute_passes(struct graph *g, struct renderer *r, struct scene *scene, int frame, double time,
                           struct error *err)
{
    for (int i = 0; i < g->count; i++) {
        struct graph_entry *e = &g->entries[i];
        if (e->state != GRAPH_PASS_KEPT)
            continue;
        struct pass *p = e->pass;
        struct pass_frame f;
        memset(&f, 0, sizeof f);
        f.renderer = r;
        f.scene = scene;
        f.snapshot = &r->frame;
        f.width = g->width;
        f.height = g->height;
        f.frame = frame;
        f.time = time;
        for (int k = 0; k < p->input_count; k++)
            f.inputs[k] = e->input_resources[k] >= 0 ? &g->resources[e->input_resources[k]] : NULL;
        for (int o = 0; o < p->output_count; o++)
            f.outputs[o] = e->output_resources[o] >= 0 ? &g->resources[e->output_resources[o]] : NULL;
        e->last_why[0] = '\0';
        unsigned depends = p->desc->depends ? p->desc->depends(p) : 0u;
        uint64_t key = depends ? pass_frame_key(p, &f, depends | PASS_DEPENDS_INPUTS) : 0u;
        if (!lights_present(p, r, scene, e->last_why, sizeof e->last_why))
            e->last_need = PASS_SKIP;
        else if (depends && e->reuse_valid && e->reuse_key == key && !r->frame.geometry_animated) {
            e->last_need = PASS_REUSE;
            snprintf(e->last_why, sizeof e->last_why, "reuses its outputs: its parameters, inputs%s%s%s did not change",
                     depends & PASS_DEPENDS_CAMERA ? ", the camera" : "",
                     depends & PASS_DEPENDS_GEOMETRY ? ", the geometry" : "",
                     depends & PASS_DEPENDS_LIGHTS ? ", the lights" : "");
        } else
            e->last_need = p->desc->needed ? p->desc->needed(p, &f, e->last_why, sizeof e->last_why) : PASS_RUN;
        e->reuse_valid = false; /* until it runs to the end below */
        if (e->last_need == PASS_SKIP) {
            /* Nothing to do this frame: the outputs read as empty (no light,
             * far depth) rather than as last frame's. */
            const float zero[4] = {0, 0, 0, 0}, far_depth = 1.0f;
            for (int o = 0; o < p->output_count; o++) {
                if (f.outputs[o]) {
                    f.outputs[o]->record = NULL; /* its readers find nothing made this frame (a shadow map of no light) */
                    f.outputs[o]->version++;     /* emptied: its readers' keys change */
                }
                if (f.outputs[o] && f.outputs[o]->texture.id) {
                    bool depth = gl_format_is_depth(f.outputs[o]->texture.format);
                    gl.ClearTexImage(f.outputs[o]->texture.id, 0, depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT,
                                     depth ? (const void *)&far_depth : (const void *)zero);
                }
            }
        }
        if (e->last_need != PASS_RUN) {
            e->last_ms = 0.0;
            e->reuse_valid = e->last_need == PASS_REUSE;
            continue;
        }
        renderer_reset_state(r);
        /* Timestamps rather than GL_TIME_ELAPSED: Mesa's llvmpipe under EGL
         * loses the start of an elapsed-time query that follows a compute
         * dispatch (seen with the deformers), while timestamps hold. */
        p->stages.count = 0;
        long draws = r->draw_calls, triangles = r->draw_triangles;
        char undeclared[512];
        if (gl_program_cache_take_undeclared(&r->programs, undeclared, sizeof undeclared) > 0)
            return error_set(err, "the renderer asked its shaders for %s, which they do not declare", undeclared);
        gl.QueryCounter(e->queries[0], GL_TIMESTAMP);
        bool ok = p->desc->execute(p, &f, err);
        gl.QueryCounter(e->queries[1], GL_TIMESTAMP);
        e->last_draws = r->draw_calls - draws;
        e->last_triangles = r->draw_triangles - triangles;
        if (!ok)
            return error_prefix(err, "pass '%s' (%s)", p->name, p->desc->name);
        /* a name C sets or binds that no stage of the program declares (a
         * misspelt uniform would otherwise be location -1, in silence) */
        if (gl_program_cache_take_undeclared(&r->programs, undeclared, sizeof undeclared) > 0)
            return error_set(err, "pass '%s' (%s): its shaders do not declare %s (a misspelt name, or one the "
                                  "shader lost)", p->name, p->desc->name, undeclared);
        if (!gl_check("executing the pass", err))
            return error_prefix(err, "pass '%s' (%s)", p->name, p->desc->name);
        for (int o = 0; o < p->output_count; o++)
            if (f.outputs[o])
                f.outputs[o]->version++;
        e->reuse_key = key;
        e->reuse_valid = depends != 0;
    }
    /* Timings: waiting for the queries costs a pipeline drain, which the
     * frame needs anyway before its image is read back. */
    for (int i = 0; i < g->count; i++) {
        struct graph_entry *e = &g->entries[i];
        if (e->state != GRAPH_PASS_KEPT || e->last_need != PASS_RUN)
            continue;
        GLuint64 t0 = 0, t1 = 0;
        gl.GetQueryObjectui64v(e->queries[0], GL_QUERY_RESULT, &t0);
        gl.GetQueryObjectui64v(e->queries[1], GL_QUERY_RESULT, &t1);
        e->last_ms = t1 > t0 ? (double)(t1 - t0) * 1e-6 : 0.0;
        pass_stages_collect(e->pass);
    }
    return true;
}

struct graph_resource *graph_output(struct graph *g)
{
    return g->compiled && g->output_resource >= 0 ? &g->resources[g->output_resource] : NULL;
}

struct graph_resource *graph_find_resource(struct graph *g, const char *name)
{
    for (int i = 0; i < g->resource_count; i++)
        if (strcmp(g->resources[i].name, name) == 0)
            return &g->resources[i];
    return NULL;
}
