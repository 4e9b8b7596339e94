/* c.image.render(script, opts): renders another scene script in its own
 * Lua state (same GL context) and returns the linear image; what the
 * scripted regression tests are built on. */
#include <stdio.h>
#include <string.h>

#include <lauxlib.h>

#include "app/session.h"
#include "core/fileio.h"
#include "graph/graph.h"
#include "lua/l_image.h"
#include "lua/lua_host.h"
#include "reference/reference.h"

/* c.image.render inside a rendered script inside ...: a test renders a scene
 * (depth 1), which may render another; more is a script rendering itself. */
#define LIMAGE_RENDER_MAX_DEPTH 4

/* A scene path as a test writes it: relative to the working folder, the
 * project root, or the test script's folder, in that order. */
static void find_script(lua_State *L, const char *rel, char *out, size_t outlen)
{
    struct app *app = lua_host_app(L);
    if (rel[0] == '/' || file_exists(rel)) {
        snprintf(out, outlen, "%s", rel);
        return;
    }
    path_join(app->root, rel, out, outlen);
    if (file_exists(out))
        return;
    lua_host_resolve_path(L, rel, out, outlen);
}

/* Reads {set = {...}, size = {w, h}, frame = n} into the session options. */
static void read_options(lua_State *L, char *path, size_t pathlen, struct session_options *o, int *frame)
{
    find_script(L, luaL_checkstring(L, 1), path, pathlen);
    memset(o, 0, sizeof *o);
    o->script = path;
    *frame = 0;
    if (!lua_isnoneornil(L, 2)) {
        luaL_checktype(L, 2, LUA_TTABLE);
        if (lua_getfield(L, 2, "set") == LUA_TTABLE) {
            lua_pushnil(L);
            while (lua_next(L, -2)) {
                char assignment[400];
                lua_pushvalue(L, -2);
                const char *k = lua_tostring(L, -1);
                const char *v = luaL_tolstring(L, -2, NULL);
                snprintf(assignment, sizeof assignment, "%s=%s", k, v);
                lua_pop(L, 3);
                struct error err;
                if (!lua_params_add(&o->params, assignment, &err))
                    luaL_error(L, "render: %s", err.message);
            }
        }
        lua_pop(L, 1);
        if (lua_getfield(L, 2, "size") == LUA_TTABLE) {
            lua_rawgeti(L, -1, 1);
            lua_rawgeti(L, -2, 2);
            o->width = (int)luaL_checkinteger(L, -2);
            o->height = (int)luaL_checkinteger(L, -1);
            lua_pop(L, 2);
        }
        lua_pop(L, 1);
        if (lua_getfield(L, 2, "frame") != LUA_TNIL)
            *frame = (int)luaL_checkinteger(L, -1);
        lua_pop(L, 1);
    }
}

/* Rendering other scripts is the test harness's tool: a sandboxed scene
 * script may not start renders (or a reference, a long C computation no
 * script time limit can interrupt). */
static struct app *check_render_allowed(lua_State *L, const char *fn)
{
    struct app *app = lua_host_app(L);
    const struct lua_host_options *o = lua_host_options_of(L);
    if (!app)
        luaL_error(L, "%s: not available here", fn);
    if (o && !o->trusted)
        luaL_error(L, "c.image.%s is not available to a sandboxed scene script (it is for tests; run with --trusted "
                      "to allow it)", fn);
    return app;
}

int limage_render(lua_State *L)
{
    struct app *app = check_render_allowed(L, "render");
    char path[4096];
    struct session_options o;
    int frame;
    read_options(L, path, sizeof path, &o, &frame);
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return luaL_error(L, "render: %s", err.message);
    /* A script that renders itself would recurse until the C stack ends. */
    if (app->render_depth >= LIMAGE_RENDER_MAX_DEPTH)
        return luaL_error(L, "render: scripts rendering scripts nest deeper than %d (does '%s' render itself?)",
                          LIMAGE_RENDER_MAX_DEPTH, path);
    struct session *s;
    app->render_depth++;
    bool opened = session_open(app, &o, &s, &err);
    if (!opened) {
        app->render_depth--;
        return luaL_error(L, "%s", err.message);
    }
    struct image *img = limage_push(L);
    bool ok = session_render(s, frame, &err) && session_read_linear(s, img, &err);
    app->render_depth--;
    if (ok) {
        /* second result: per-pass milliseconds */
        lua_newtable(L);
        for (int i = 0; i < s->graph->count; i++)
            if (s->graph->entries[i].state == GRAPH_PASS_KEPT) {
                lua_pushnumber(L, s->graph->entries[i].last_ms);
                lua_setfield(L, -2, s->graph->entries[i].pass->name);
            }
    }
    session_close(s);
    if (!ok)
        return luaL_error(L, "%s", err.message);
    return 2;
}

/* reference(script, {set, size, frame, photons, spp, seed, radius, time_budget})
 * -> the ground-truth image and {iterations, photons, caustic_photons, seconds}. */
int limage_reference(lua_State *L)
{
    struct app *app = check_render_allowed(L, "reference");
    char path[4096];
    struct session_options o;
    int frame;
    read_options(L, path, sizeof path, &o, &frame);
    struct ref_options ro;
    ref_options_default(&ro);
    if (lua_istable(L, 2)) {
        if (lua_getfield(L, 2, "photons") != LUA_TNIL)
            ro.photons = (long)luaL_checkinteger(L, -1);
        if (lua_getfield(L, 2, "spp") != LUA_TNIL)
            ro.iterations = (int)luaL_checkinteger(L, -1);
        if (lua_getfield(L, 2, "seed") != LUA_TNIL)
            ro.seed = (uint64_t)luaL_checkinteger(L, -1);
        if (lua_getfield(L, 2, "radius") != LUA_TNIL)
            ro.initial_radius = luaL_checknumber(L, -1);
        if (lua_getfield(L, 2, "time_budget") != LUA_TNIL)
            ro.time_budget = luaL_checknumber(L, -1);
        if (lua_getfield(L, 2, "threads") != LUA_TNIL)
            ro.threads = (int)luaL_checkinteger(L, -1);
        lua_pop(L, 6);
    }
    if (ro.photons < 0 || ro.iterations < 1)
        return luaL_error(L, "reference: photons must be >= 0 and spp >= 1");
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return luaL_error(L, "reference: %s", err.message);
    if (app->render_depth >= LIMAGE_RENDER_MAX_DEPTH)
        return luaL_error(L, "reference: scripts rendering scripts nest deeper than %d (does '%s' render itself?)",
                          LIMAGE_RENDER_MAX_DEPTH, path);
    struct session *s;
    app->render_depth++;
    bool opened = session_open(app, &o, &s, &err);
    if (!opened) {
        app->render_depth--;
        return luaL_error(L, "%s", err.message);
    }
    struct image *img = limage_push(L);
    struct ref_stats st;
    bool ok = session_reference(s, frame, &ro, img, &st, &err);
    app->render_depth--;
    session_close(s);
    if (!ok)
        return luaL_error(L, "%s", err.message);
    lua_createtable(L, 0, 4);
    lua_pushinteger(L, st.iterations);
    lua_setfield(L, -2, "iterations");
    lua_pushinteger(L, (lua_Integer)st.photons);
    lua_setfield(L, -2, "photons");
    lua_pushinteger(L, (lua_Integer)st.caustic_photons);
    lua_setfield(L, -2, "caustic_photons");
    lua_pushnumber(L, st.seconds);
    lua_setfield(L, -2, "seconds");
    lua_createtable(L, 3, 0);
    for (int k = 0; k < 3; k++) {
        lua_pushnumber(L, st.caustic_power[k]);
        lua_rawseti(L, -2, k + 1);
    }
    lua_setfield(L, -2, "caustic_power");
    return 2;
}
