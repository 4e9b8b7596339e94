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

int limage_render(lua_State *L)
{
    struct app *app = lua_host_app(L);
    if (!app)
        return luaL_error(L, "render: not available here");
    char path[4096];
    find_script(L, luaL_checkstring(L, 1), path, sizeof path);
    struct session_options o = {.script = path};
    int frame = 0;
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
                if (!lua_params_add(&o.params, assignment, &err))
                    return luaL_error(L, "render: %s", err.message);
            }
        }
        lua_pop(L, 1);
        if (lua_getfield(L, 2, "size") == LUA_TTABLE) {
            lua_rawgeti(L, -1, 1);
            lua_rawgeti(L, -2, 2);
            o.width = (int)luaL_checkinteger(L, -2);
            o.height = (int)luaL_checkinteger(L, -1);
            lua_pop(L, 2);
        }
        lua_pop(L, 1);
        if (lua_getfield(L, 2, "frame") != LUA_TNIL)
            frame = (int)luaL_checkinteger(L, -1);
        lua_pop(L, 1);
    }
    struct session *s;
    struct error err;
    if (!session_open(app, &o, &s, &err))
        return luaL_error(L, "%s", err.message);
    struct image *img = limage_push(L);
    bool ok = session_render(s, frame, &err) && session_read_linear(s, img, &err);
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
