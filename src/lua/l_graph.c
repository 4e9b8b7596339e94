#define _POSIX_C_SOURCE 200809L
/* caustica.graph: the render graph and the pass constructors. Every
 * descriptor in the registry becomes `c.pass.<name>`, checked here against
 * its parameter list, with no per-pass binding code. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lauxlib.h>
#include <lua.h>

#include "core/suggest.h"
#include "graph/graph.h"
#include "lua/l_scene.h"
#include "lua/l_util.h"
#include "lua/lua_host.h"

#define GRAPH_MT "caustica.Graph"
#define PASS_MT "caustica.Pass"

struct l_pass { struct pass *pass; };
struct l_graph { struct graph graph; };


static const char *type_name(enum pass_param_type t)
{
    switch (t) {
    case PASS_PARAM_NUMBER: return "number";
    case PASS_PARAM_INTEGER: return "integer";
    case PASS_PARAM_BOOLEAN: return "boolean";
    case PASS_PARAM_STRING: return "string";
    case PASS_PARAM_ENUM: return "string";
    case PASS_PARAM_LIGHT: return "light";
    case PASS_PARAM_OBJECT: return "object";
    case PASS_PARAM_OBJECT_LIST: return "list of objects";
    case PASS_PARAM_INPUT: return "string 'pass.output'";
    case PASS_PARAM_INPUT_LIST: return "string 'pass.output' or a list of them";
    case PASS_PARAM_INPUT_MAP: return "table {name = 'pass.output'}";
    case PASS_PARAM_OUTPUT_MAP: return "table {name = 'format'}";
    case PASS_PARAM_UNIFORM_MAP: return "table {name = number or vector}";
    case PASS_PARAM_COLOR: return "color {r, g, b[, a]}";
    case PASS_PARAM_TABLE: return "table";
    case PASS_PARAM_FUNCTION: return "function";
    }
    return "?";
}

/* Scratch memory that Lua owns (freed by the collector, so an error
 * raised while reading leaks nothing). */
static void *scratch(lua_State *L, size_t size)
{
    void *m = lua_newuserdatauv(L, size > 0 ? size : 1, 0);
    memset(m, 0, size > 0 ? size : 1);
    return m;
}

/* Reads a map table into keys, values (strings) and vectors: the array part
 * first ({"color", "mask"}: an output map's names, format rgba32f), then
 * the string keys sorted so the declaration order does not depend on
 * hashing; pass_set_map validates and stores them. The strings stay alive
 * in the table at idx while they are read. */
static void read_map(lua_State *L, int idx, struct pass *p, int param, const char *fn)
{
    const struct pass_param_desc *d = &p->desc->params[param];
    int n = 0;
    lua_pushnil(L);
    while (lua_next(L, idx)) {
        n++;
        lua_pop(L, 1);
    }
    const char **keys = scratch(L, (size_t)n * sizeof *keys);
    const char **values = scratch(L, (size_t)n * sizeof *values);
    float(*vectors)[4] = scratch(L, (size_t)n * sizeof *vectors);
    int *sizes = scratch(L, (size_t)n * sizeof *sizes);
    int count = 0;
    int len = (int)lua_rawlen(L, idx);
    for (int i = 1; i <= len; i++) {
        lua_rawgeti(L, idx, i);
        if (d->type != PASS_PARAM_OUTPUT_MAP || !lua_isstring(L, -1))
            luaL_error(L, "bad argument '%s' to '%s' (%s expected)", d->name, fn, type_name(d->type));
        keys[count] = lua_tostring(L, -1);
        values[count++] = "rgba32f";
        lua_pop(L, 1); /* the string stays in the table */
    }
    lua_pushnil(L);
    while (lua_next(L, idx)) {
        if (lua_type(L, -2) != LUA_TSTRING) {
            lua_pop(L, 1);
            continue;
        }
        const char *key = lua_tostring(L, -2);
        int at = count;
        while (at > 0 && strcmp(keys[at - 1], key) > 0 && at > len) {
            keys[at] = keys[at - 1];
            values[at] = values[at - 1];
            memcpy(vectors[at], vectors[at - 1], sizeof vectors[0]);
            sizes[at] = sizes[at - 1];
            at--;
        }
        keys[at] = key;
        values[at] = NULL;
        sizes[at] = 0;
        memset(vectors[at], 0, sizeof vectors[0]);
        if (d->type == PASS_PARAM_UNIFORM_MAP) {
            if (lua_type(L, -1) == LUA_TNUMBER) {
                vectors[at][0] = lutil_check_number(L, -1, fn, d->name);
                sizes[at] = 1;
            } else if (lua_istable(L, -1)) {
                int m = (int)lua_rawlen(L, -1);
                if (m < 1 || m > 4)
                    luaL_error(L, "bad argument '%s' to '%s' (uniform '%s': 1 to 4 numbers expected)", d->name, fn, key);
                for (int i = 0; i < m; i++) {
                    lua_rawgeti(L, -1, i + 1);
                    vectors[at][i] = lutil_check_number(L, -1, fn, d->name);
                    lua_pop(L, 1);
                }
                sizes[at] = m;
            } else {
                luaL_error(L, "bad argument '%s' to '%s' (uniform '%s': number or vector expected, got %s)", d->name,
                           fn, key, luaL_typename(L, -1));
            }
        } else {
            if (!lua_isstring(L, -1))
                luaL_error(L, "bad argument '%s' to '%s' ('%s': string expected, got %s)", d->name, fn, key,
                           luaL_typename(L, -1));
            values[at] = lua_tostring(L, -1); /* a string value: alive in the table */
        }
        count++;
        lua_pop(L, 1);
    }
    struct error err;
    if (!pass_set_map(p, param, keys, values, (const float(*)[4])vectors, sizes, count, &err))
        luaL_error(L, "%s", err.message);
    lua_pop(L, 4); /* the scratch arrays */
}

/* An object list parameter: a group (a file of several materials) stands
 * for its parts, which are what the scene holds. */
static void read_object_list(lua_State *L, struct pass *p, int i, int idx)
{
    const struct pass_param_desc *d = &p->desc->params[i];
    const char *fn = p->desc->name;
    int t = lua_type(L, idx);
    if (t != LUA_TTABLE)
        lutil_field_error(L, fn, d->name, "list of objects", idx);
    int listed = (int)lua_rawlen(L, idx), n = 0;
    struct object *objects[256];
    for (int k = 0; k < listed; k++) {
        lua_rawgeti(L, idx, k + 1);
        struct object *o = lobject_test(L, -1);
        if (!o)
            lutil_field_error(L, fn, d->name, "list of objects", -1);
        int parts = o->part_count > 0 ? o->part_count : 1;
        if (n + parts > 256)
            lutil_error(L, "bad argument '%s' to '%s' (at most 256 objects, a file's parts counted one each)",
                        d->name, fn);
        for (int part = 0; part < parts; part++)
            objects[n++] = o->part_count > 0 ? o->parts[part] : o;
        lua_pop(L, 1);
    }
    if (!pass_set_objects(p, i, objects, n))
        luaL_error(L, "out of memory");
}

/* An input list parameter: one "pass.output" or a list of them. */
static void read_input_list(lua_State *L, struct pass *p, int i, int idx)
{
    const struct pass_param_desc *d = &p->desc->params[i];
    const char *fn = p->desc->name;
    int t = lua_type(L, idx);
    int n = t == LUA_TSTRING ? 1 : t == LUA_TTABLE ? (int)lua_rawlen(L, idx) : -1;
    if (n < 0)
        lutil_field_error(L, fn, d->name, type_name(d->type), idx);
    const char **items = scratch(L, (size_t)(n > 0 ? n : 0) * sizeof *items);
    if (t == LUA_TSTRING)
        items[0] = lua_tostring(L, idx);
    for (int k = 0; t == LUA_TTABLE && k < n; k++) {
        lua_rawgeti(L, idx, k + 1);
        if (lua_type(L, -1) != LUA_TSTRING)
            lutil_field_error(L, fn, d->name, type_name(d->type), -1);
        items[k] = lua_tostring(L, -1); /* alive in the table */
        lua_pop(L, 1);
    }
    struct error err;
    if (!pass_set_list(p, i, items, n, &err))
        luaL_error(L, "%s", err.message);
    lua_pop(L, 1);
}

static void read_param(lua_State *L, struct pass *p, int i, int idx)
{
    const struct pass_param_desc *d = &p->desc->params[i];
    struct pass_value *v = &p->values[i];
    const char *fn = p->desc->name;
    int t = lua_type(L, idx);
    v->set = true;
    switch (d->type) {
    case PASS_PARAM_NUMBER:
    case PASS_PARAM_INTEGER: {
        if (t != LUA_TNUMBER)
            lutil_field_error(L, fn, d->name, "number", idx);
        /* An integer-valued float (2.0) is an integer; 2^53 and up cannot be
         * told from its neighbours, so a Lua integer is what counts. */
        if (d->type == PASS_PARAM_INTEGER && !lua_isinteger(L, idx) && isfinite(lua_tonumber(L, idx)))
            lutil_error(L, "bad argument '%s' to '%s' (integer expected, got %g)", d->name, fn, lua_tonumber(L, idx));
        struct error err;
        if (!pass_set_number(p, d->name, lua_tonumber(L, idx), &err))
            lutil_error(L, "%s", err.message);
        break;
    }
    case PASS_PARAM_BOOLEAN: {
        if (t != LUA_TBOOLEAN)
            lutil_field_error(L, fn, d->name, "boolean", idx);
        struct error err;
        if (!pass_set_boolean(p, d->name, lua_toboolean(L, idx), &err))
            lutil_error(L, "%s", err.message);
        break;
    }
    case PASS_PARAM_STRING:
    case PASS_PARAM_ENUM:
    case PASS_PARAM_INPUT: {
        if (t != LUA_TSTRING)
            lutil_field_error(L, fn, d->name, type_name(d->type), idx);
        char path[4096];
        const char *value = lua_tostring(L, idx);
        struct error err;
        if (d->is_path) {
            lua_host_resolve_path(L, value, path, sizeof path);
            if (!lua_host_check_read(L, path, &err))
                luaL_error(L, "bad argument '%s' to '%s' (%s)", d->name, fn, err.message);
            value = path;
        }
        if (!pass_set_string(p, d->name, value, &err))
            lutil_error(L, "%s", err.message);
        break;
    }
    case PASS_PARAM_LIGHT:
        if (!llight_test(L, idx))
            lutil_field_error(L, fn, d->name, "light", idx);
        pass_set_light(p, i, llight_test(L, idx));
        break;
    case PASS_PARAM_OBJECT:
        if (!lobject_test(L, idx))
            lutil_field_error(L, fn, d->name, "object", idx);
        pass_set_object(p, i, lobject_test(L, idx));
        break;
    case PASS_PARAM_OBJECT_LIST:
        read_object_list(L, p, i, idx);
        break;
    case PASS_PARAM_INPUT_LIST:
        read_input_list(L, p, i, idx);
        break;
    case PASS_PARAM_INPUT_MAP:
    case PASS_PARAM_OUTPUT_MAP:
    case PASS_PARAM_UNIFORM_MAP:
        if (t != LUA_TTABLE)
            lutil_field_error(L, fn, d->name, type_name(d->type), idx);
        read_map(L, idx, p, i, fn);
        break;
    case PASS_PARAM_COLOR: {
        struct error err;
        if (!pass_set_color(p, i, lutil_check_color(L, idx, fn, d->name), &err))
            luaL_error(L, "%s", err.message);
        break;
    }
    case PASS_PARAM_TABLE:
    case PASS_PARAM_FUNCTION:
        if (t != (d->type == PASS_PARAM_TABLE ? LUA_TTABLE : LUA_TFUNCTION))
            lutil_field_error(L, fn, d->name, type_name(d->type), idx);
        lua_pushvalue(L, idx);
        v->lua_ref = luaL_ref(L, LUA_REGISTRYINDEX);
        break;
    }
}

static int lpass_new(lua_State *L)
{
    const struct pass_desc *desc = lua_touserdata(L, lua_upvalueindex(1));
    if (lua_isnoneornil(L, 1)) {
        lua_settop(L, 0);
        lua_newtable(L);
    }
    if (!lua_istable(L, 1))
        return luaL_typeerror(L, 1, "table of parameters");
    const char *allowed[PASS_MAX_INPUTS * 2 + 1];
    int na = 0;
    for (int i = 0; i < desc->param_count && na < PASS_MAX_INPUTS * 2; i++)
        allowed[na++] = desc->params[i].name;
    allowed[na] = NULL;
    lutil_check_fields(L, 1, desc->name, allowed);

    struct l_pass *u = lua_newuserdatauv(L, sizeof *u, 1);
    u->pass = pass_create(desc);
    luaL_setmetatable(L, PASS_MT);
    if (!u->pass)
        return luaL_error(L, "out of memory");
    int idx = lua_gettop(L);
    lua_pushvalue(L, 1);
    lua_setiuservalue(L, idx, 1); /* keeps lights and functions alive */
    struct pass *p = u->pass;
    p->script_run = lua_host_run_custom_pass;
    p->script_state = L;
    lutil_where(L, p->origin, sizeof p->origin);
    for (int i = 0; i < desc->param_count; i++) {
        const struct pass_param_desc *d = &desc->params[i];
        if (lua_getfield(L, 1, d->name) == LUA_TNIL) {
            if (d->required)
                luaL_error(L, "bad argument '%s' to '%s' (%s expected, got no value)", d->name, desc->name,
                           type_name(d->type));
        } else {
            read_param(L, p, i, lua_gettop(L));
        }
        lua_pop(L, 1);
    }
    struct error err;
    if (!pass_declare(p, &err))
        return luaL_error(L, "%s", err.message);
    lua_settop(L, idx);
    return 1;
}

static int pass_gc(lua_State *L)
{
    struct l_pass *u = luaL_checkudata(L, 1, PASS_MT);
    if (u->pass) {
        /* The functions stay with a pass that a graph still holds. */
        for (int i = 0; u->pass->references == 1 && i < u->pass->desc->param_count; i++)
            if (u->pass->values[i].lua_ref >= 0)
                luaL_unref(L, LUA_REGISTRYINDEX, u->pass->values[i].lua_ref);
        pass_destroy(u->pass);
    }
    u->pass = NULL;
    return 0;
}

static struct l_pass *check_pass(lua_State *L, int idx)
{
    struct l_pass *u = luaL_checkudata(L, idx, PASS_MT);
    if (!u->pass)
        luaL_argerror(L, idx, "this pass was already released");
    return u;
}

static int pass_get_kind(lua_State *L)
{
    lua_pushstring(L, check_pass(L, 1)->pass->desc->name);
    return 1;
}

static int pass_get_name(lua_State *L)
{
    lua_pushstring(L, check_pass(L, 1)->pass->name);
    return 1;
}

static int pass_get_outputs(lua_State *L)
{
    struct pass *p = check_pass(L, 1)->pass;
    lua_createtable(L, p->output_count, 0);
    for (int i = 0; i < p->output_count; i++) {
        lua_pushstring(L, p->outputs[i].name);
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

static int pass_tostring(lua_State *L)
{
    struct l_pass *u = check_pass(L, 1);
    lua_pushfstring(L, "Pass(%s '%s')", u->pass->desc->name, u->pass->name);
    return 1;
}

/* ---- graph ----------------------------------------------------------- */

static struct graph *check_graph(lua_State *L, int idx)
{
    return &((struct l_graph *)luaL_checkudata(L, idx, GRAPH_MT))->graph;
}

struct graph *lua_host_to_graph(lua_State *L, int idx)
{
    struct l_graph *u = luaL_testudata(L, idx, GRAPH_MT);
    return u ? &u->graph : NULL;
}

static int lgraph_new(lua_State *L)
{
    struct l_graph *u = lua_newuserdatauv(L, sizeof *u, 1);
    graph_init(&u->graph);
    luaL_setmetatable(L, GRAPH_MT);
    lua_newtable(L);
    lua_setiuservalue(L, -2, 1);
    return 1;
}

static int graph_gc(lua_State *L)
{
    struct graph *g = check_graph(L, 1);
    if (g->executing)
        return luaL_error(L, "the graph is rendering a frame and cannot be released");
    graph_release(g);
    return 0;
}

static int graph_add_l(lua_State *L)
{
    struct graph *g = check_graph(L, 1);
    const char *name = luaL_checkstring(L, 2);
    struct l_pass *p = luaL_testudata(L, 3, PASS_MT);
    if (!p || !p->pass)
        return luaL_argerror(L, 3, lua_pushfstring(L, "pass (c.pass.<kind>{...}) expected, got %s", luaL_typename(L, 3)));
    struct error err;
    if (!graph_add(g, name, p->pass, &err))
        return luaL_error(L, "%s", err.message);
    lua_getiuservalue(L, 1, 1);
    lua_pushvalue(L, 3);
    lua_rawseti(L, -2, (lua_Integer)lua_rawlen(L, -2) + 1);
    lua_pushvalue(L, 3);
    return 1;
}

static int graph_output_l(lua_State *L)
{
    struct graph *g = check_graph(L, 1);
    struct error err;
    if (!graph_set_output(g, luaL_checkstring(L, 2), &err))
        return luaL_error(L, "%s", err.message);
    /* the line that named it, for the error when no pass makes it (known
     * only once the graph is checked, after the script has returned) */
    luaL_where(L, 1);
    snprintf(g->output_where, sizeof g->output_where, "%s", lua_tostring(L, -1));
    lua_pop(L, 1);
    return 0;
}

static int graph_timings_l(lua_State *L)
{
    struct graph *g = check_graph(L, 1);
    lua_newtable(L);
    for (int i = 0; i < g->count; i++) {
        if (g->entries[i].state != GRAPH_PASS_KEPT)
            continue;
        lua_pushnumber(L, g->entries[i].last_ms);
        lua_setfield(L, -2, g->entries[i].pass->name);
    }
    return 1;
}

static int graph_passes_l(lua_State *L)
{
    struct graph *g = check_graph(L, 1);
    struct error err;
    bool checked = graph_check(g, &err);
    lua_createtable(L, g->count, 0);
    for (int i = 0; i < g->count; i++) {
        const struct graph_entry *e = &g->entries[i];
        lua_createtable(L, 0, 4);
        lua_pushstring(L, e->pass->name);
        lua_setfield(L, -2, "name");
        lua_pushstring(L, e->pass->desc->name);
        lua_setfield(L, -2, "kind");
        lua_pushboolean(L, checked && e->state == GRAPH_PASS_KEPT);
        lua_setfield(L, -2, "kept");
        lua_pushstring(L, checked ? e->reason : err.message);
        lua_setfield(L, -2, "reason");
        lua_rawseti(L, -2, i + 1);
    }
    return 1;
}

static int graph_tostring(lua_State *L)
{
    struct graph *g = check_graph(L, 1);
    lua_pushfstring(L, "Graph(%d passes, output '%s')", g->count, g->output);
    return 1;
}

/* c.pass.<unknown>: say which passes exist instead of "attempt to call nil". */
static int pass_table_index(lua_State *L)
{
    const char *name = lua_tostring(L, 2);
    luaL_Buffer b;
    luaL_buffinit(L, &b);
    for (int i = 0; i < pass_registry_count(); i++) {
        if (i)
            luaL_addstring(&b, ", ");
        luaL_addstring(&b, pass_registry_get(i)->name);
    }
    luaL_pushresult(&b);
    const char *names[64];
    size_t n = 0;
    for (int i = 0; i < pass_registry_count() && n < 64; i++)
        names[n++] = pass_registry_get(i)->name;
    const char *near = name ? suggest_nearest(name, names, n) : NULL;
    if (near)
        return luaL_error(L, "unknown pass '%s' (did you mean '%s'?) (known passes: %s)", name, near,
                          lua_tostring(L, -1));
    return luaL_error(L, "unknown pass '%s' (known passes: %s)", name ? name : "?", lua_tostring(L, -1));
}

/* Is `name` among the strings of the list at index `list` (0: no list)? */
static bool listed(lua_State *L, int list, const char *name)
{
    if (!list)
        return false;
    lua_Integer n = luaL_len(L, list);
    for (lua_Integer k = 1; k <= n; k++) {
        bool same = lua_geti(L, list, k) == LUA_TSTRING && strcmp(lua_tostring(L, -1), name) == 0;
        lua_pop(L, 1);
        if (same)
            return true;
    }
    return false;
}

/* c.techniques(FAMILY [, EXCEPT]): the names of the registered techniques
 * of a family ("caustics", "water_caustics", "view", "water_view"), in the
 * registry's order, but those in the list EXCEPT: what the comparison
 * scenes and the optics matrix enumerate, so that a technique added to the
 * registry joins them (issue 54); EXCEPT names the ones a scene already
 * holds, or left out with a reason. */
static int techniques_l(lua_State *L)
{
    const char *family = luaL_checkstring(L, 1);
    int except = lua_isnoneornil(L, 2) ? 0 : 2;
    if (except)
        luaL_checktype(L, 2, LUA_TTABLE);
    bool known = false;
    for (int t = PASS_TECHNIQUE_CAUSTICS; t <= PASS_TECHNIQUE_WATER_VIEW; t++)
        known = known || strcmp(family, pass_technique_name((enum pass_technique)t)) == 0;
    if (!known)
        return luaL_argerror(L, 1, "a technique family expected: caustics, water_caustics, view or water_view");
    lua_newtable(L);
    int n = 0;
    for (int i = 0; i < pass_registry_count(); i++) {
        const char *f = pass_technique_name(pass_registry_get(i)->technique);
        if (f && strcmp(f, family) == 0 && !listed(L, except, pass_registry_get(i)->name)) {
            lua_pushstring(L, pass_registry_get(i)->name);
            lua_rawseti(L, -2, ++n);
        }
    }
    return 1;
}

int luaopen_caustica_graph(lua_State *L)
{
    static const luaL_Reg pass_meta[] = {{"__gc", pass_gc}, {"__tostring", pass_tostring}, {NULL, NULL}};
    static const luaL_Reg pass_getters[] = {{"kind", pass_get_kind}, {"name", pass_get_name},
                                            {"outputs", pass_get_outputs}, {NULL, NULL}};
    lutil_class(L, PASS_MT, "pass", pass_meta, NULL, pass_getters, NULL);
    static const luaL_Reg graph_meta[] = {{"__gc", graph_gc}, {"__tostring", graph_tostring}, {NULL, NULL}};
    static const luaL_Reg graph_methods[] = {{"add", graph_add_l}, {"output", graph_output_l},
                                             {"timings", graph_timings_l}, {"passes", graph_passes_l}, {NULL, NULL}};
    lutil_class(L, GRAPH_MT, "graph", graph_meta, graph_methods, NULL, NULL);
    lua_newtable(L);
    lua_pushcfunction(L, lgraph_new);
    lua_setfield(L, -2, "graph");
    lua_pushcfunction(L, techniques_l);
    lua_setfield(L, -2, "techniques");
    lua_newtable(L);
    for (int i = 0; i < pass_registry_count(); i++) {
        const struct pass_desc *d = pass_registry_get(i);
        lua_pushlightuserdata(L, (void *)d);
        lua_pushcclosure(L, lpass_new, 1);
        lua_setfield(L, -2, d->name);
    }
    lua_newtable(L);
    lua_pushcfunction(L, pass_table_index);
    lua_setfield(L, -2, "__index");
    lua_setmetatable(L, -2);
    lua_setfield(L, -2, "pass");
    return 1;
}
