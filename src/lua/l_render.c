/* c.image.render(script, opts): renders another scene script in its own
 * Lua state (same GL context) and returns the linear image; what the
 * scripted regression tests are built on. The rendering itself is the
 * application's (lua_host_options.render): this file only translates. */
#include <stdio.h>
#include <string.h>

#include <lauxlib.h>

#include "core/fileio.h"
#include "lua/l_image.h"
#include "lua/lua_host.h"
#include "reference/reference.h"


/* A scene path as a test writes it: relative to the working folder, the
 * project root, or the test script's folder, in that order. */
static void find_script(lua_State *L, const char *rel, char *out, size_t outlen)
{
    if (rel[0] == '/' || file_exists(rel)) {
        snprintf(out, outlen, "%s", rel);
        return;
    }
    path_join(lua_host_root(L), rel, out, outlen);
    if (file_exists(out))
        return;
    lua_host_resolve_path(L, rel, out, outlen);
}

/* Reads {set = {...}, size = {w, h}, frame = n} into the request. */
static void read_options(lua_State *L, char *path, size_t pathlen, struct lua_render_request *o)
{
    find_script(L, luaL_checkstring(L, 1), path, pathlen);
    memset(o, 0, sizeof *o);
    o->script = path;
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
            lua_Integer w = luaL_checkinteger(L, -2), h = luaL_checkinteger(L, -1);
            if (w < 1 || h < 1 || w > 16384 || h > 16384)
                luaL_error(L, "render: size must be {width, height} in 1..16384");
            o->width = (int)w;
            o->height = (int)h;
            lua_pop(L, 2);
        }
        lua_pop(L, 1);
        if (lua_getfield(L, 2, "frame") != LUA_TNIL) {
            lua_Integer f = luaL_checkinteger(L, -1);
            if (f < 0 || f > 100000000)
                luaL_error(L, "render: frame must be >= 0");
            o->frame = (int)f;
        }
        lua_pop(L, 1);
    }
}

/* Rendering other scripts is the test harness's tool: a sandboxed scene
 * script may not start renders (or a reference, a long C computation no
 * script time limit can interrupt). */
static const struct lua_host_options *check_render_allowed(lua_State *L, const char *fn)
{
    const struct lua_host_options *o = lua_host_options_of(L);
    if (!o || !o->render)
        luaL_error(L, "%s: not available here", fn);
    if (!o->trusted)
        luaL_error(L, "c.image.%s is not available to a sandboxed scene script (it is for tests; run with --trusted "
                      "to allow it)", fn);
    return o;
}

int limage_render(lua_State *L)
{
    const struct lua_host_options *host = check_render_allowed(L, "render");
    char path[4096];
    struct lua_render_request request;
    read_options(L, path, sizeof path, &request);
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return luaL_error(L, "render: %s", err.message);
    struct image *img = limage_push(L);
    struct lua_render_reply reply;
    double left = lua_host_suspend_deadline(L);
    bool rendered = host->render(host->render_context, &request, img, &reply, &err);
    lua_host_resume_deadline(L, left);
    if (!rendered)
        return luaL_error(L, "%s", err.message);
    limage_charge(L, img, img->width, img->height);
    /* second result: per-pass milliseconds */
    lua_newtable(L);
    for (int i = 0; i < reply.pass_count; i++) {
        lua_pushnumber(L, reply.pass_ms[i]);
        lua_setfield(L, -2, reply.pass_names[i]);
    }
    return 2;
}

/* reference(script, {set, size, frame, photons, spp, seed, radius, time_budget, aov = "tir" | "exit",
 *                     caustics = false (the image less its caustic part),
 *                     antialias = true (each pixel's mean, not its centre),
 *                     tessellated = true (the spheres' triangles, not the spheres)})
 * -> the ground-truth image and {iterations, photons, caustic_photons, seconds}. */
int limage_reference(lua_State *L)
{
    const struct lua_host_options *host = check_render_allowed(L, "reference");
    char path[4096];
    struct lua_render_request request;
    read_options(L, path, sizeof path, &request);
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
        if (lua_getfield(L, 2, "aov") != LUA_TNIL) {
            static const char *const aovs[] = {"none", "tir", "exit", NULL};
            ro.aov = (enum ref_aov)luaL_checkoption(L, -1, NULL, aovs);
        }
        if (lua_getfield(L, 2, "antialias") != LUA_TNIL) {
            luaL_argexpected(L, lua_isboolean(L, -1), 2, "antialias = true or false");
            ro.antialias = lua_toboolean(L, -1);
        }
        lua_pop(L, 1);
        if (lua_getfield(L, 2, "caustics") != LUA_TNIL) {
            luaL_argexpected(L, lua_isboolean(L, -1), 2, "caustics = true or false");
            request.without_caustics = !lua_toboolean(L, -1);
        }
        lua_pop(L, 8);
        if (lua_getfield(L, 2, "tessellated") != LUA_TNIL) {
            luaL_argexpected(L, lua_isboolean(L, -1), 2, "tessellated = true or false");
            ro.tessellated = lua_toboolean(L, -1);
        }
        lua_pop(L, 1);
    }
    if (ro.photons < 0 || ro.iterations < 1)
        return luaL_error(L, "reference: photons must be >= 0 and spp >= 1");
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return luaL_error(L, "reference: %s", err.message);
    request.reference = &ro;
    struct image *img = limage_push(L);
    struct lua_render_reply st;
    double left = lua_host_suspend_deadline(L);
    bool rendered = host->render(host->render_context, &request, img, &st, &err);
    lua_host_resume_deadline(L, left);
    if (!rendered)
        return luaL_error(L, "%s", err.message);
    limage_charge(L, img, img->width, img->height);
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
