/* The context a custom pass's run(ctx) receives: frame facts, and the two
 * draw calls such a pass needs (clear an output, run a fullscreen shader
 * into outputs with inputs bound). Translation only: the drawing is
 * renderer_run_fullscreen, the same as c.pass.fullscreen's. */
#include <stdio.h>
#include <string.h>

#include <lauxlib.h>

#include "graph/pass.h"
#include "graph/renderer.h"
#include "lua/l_util.h"
#include "lua/lua_host.h"

#define CONTEXT_MT "caustica.PassContext"

struct pass_context {
    struct pass *pass;
    struct pass_frame *frame;
    bool valid; /* only during run(ctx) */
};

static struct pass_context *check_context(lua_State *L)
{
    struct pass_context *c = luaL_checkudata(L, 1, CONTEXT_MT);
    if (!c->valid)
        luaL_error(L, "a pass context is valid only while its run(ctx) is running");
    return c;
}

static struct graph_resource *find_texture(lua_State *L, struct pass_context *c, const char *name, bool output)
{
    struct graph_resource *r = output ? pass_frame_output(c->pass, c->frame, name) : pass_frame_input(c->pass, c->frame, name);
    if (!r)
        luaL_error(L, "custom pass '%s' has no %s named '%s'", c->pass->name, output ? "output" : "input", name);
    return r;
}

static int context_clear(lua_State *L)
{
    struct pass_context *c = check_context(L);
    struct graph_resource *r = find_texture(L, c, luaL_checkstring(L, 2), true);
    float color[4] = {0, 0, 0, 0};
    if (!lua_isnoneornil(L, 3)) {
        luaL_checktype(L, 3, LUA_TTABLE);
        for (int i = 0; i < 4; i++) {
            lua_rawgeti(L, 3, i + 1);
            color[i] = (float)luaL_optnumber(L, -1, i == 3 ? 1.0 : 0.0);
            lua_pop(L, 1);
        }
    }
    gl_texture_clear(&r->texture, color);
    return 0;
}

/* ctx:fullscreen{shader = "x.frag", output = "color" | {...}, inputs = {name = "slot"}, uniforms = {...}}
 * Every argument is read and checked before the framebuffer exists, so a
 * Lua error (which unwinds past this C frame) cannot leak it. */
#define CONTEXT_MAX_INPUTS 16
#define CONTEXT_MAX_UNIFORMS 32

static int context_fullscreen(lua_State *L)
{
    struct pass_context *c = check_context(L);
    luaL_checktype(L, 2, LUA_TTABLE);
    struct renderer *r = c->frame->renderer;
    lua_getfield(L, 2, "shader");
    if (lua_type(L, -1) != LUA_TSTRING)
        return luaL_error(L, "bad argument 'shader' to 'fullscreen' (string expected, got %s)", luaL_typename(L, -1));
    char path[4096];
    lua_host_resolve_path(L, lua_tostring(L, -1), path, sizeof path);
    lua_pop(L, 1);
    struct error err;
    if (!lua_host_check_read(L, path, &err))
        return luaL_error(L, "%s", err.message);
    struct gl_program *prog;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", path, NULL, &prog, &err))
        return luaL_error(L, "%s", err.message);
    const struct gl_texture *targets[PASS_MAX_OUTPUTS];
    int ntargets = 0;
    lua_getfield(L, 2, "output");
    if (lua_type(L, -1) == LUA_TSTRING) {
        targets[ntargets++] = &find_texture(L, c, lua_tostring(L, -1), true)->texture;
    } else if (lua_istable(L, -1)) {
        int n = (int)lua_rawlen(L, -1);
        for (int i = 0; i < n && ntargets < PASS_MAX_OUTPUTS; i++) {
            lua_rawgeti(L, -1, i + 1);
            targets[ntargets++] = &find_texture(L, c, luaL_checkstring(L, -1), true)->texture;
            lua_pop(L, 1);
        }
    } else {
        return luaL_error(L, "bad argument 'output' to 'fullscreen' (output name or list expected, got %s)",
                          luaL_typename(L, -1));
    }
    lua_pop(L, 1);
    if (ntargets == 0)
        return luaL_error(L, "bad argument 'output' to 'fullscreen' (at least one output expected)");
    struct renderer_shader_input inputs[CONTEXT_MAX_INPUTS];
    int ninputs = 0;
    if (lua_getfield(L, 2, "inputs") == LUA_TTABLE) {
        lua_pushnil(L);
        while (lua_next(L, -2)) {
            if (lua_type(L, -2) != LUA_TSTRING)
                return luaL_error(L, "bad argument 'inputs' to 'fullscreen' ({sampler = \"input\"} expected)");
            if (ninputs >= CONTEXT_MAX_INPUTS)
                return luaL_error(L, "bad argument 'inputs' to 'fullscreen' (at most %d inputs)", CONTEXT_MAX_INPUTS);
            inputs[ninputs].sampler = lua_tostring(L, -2); /* the table keeps the string alive */
            inputs[ninputs].texture = find_texture(L, c, luaL_checkstring(L, -1), false)->texture.id;
            ninputs++;
            lua_pop(L, 1);
        }
    }
    lua_pop(L, 1);
    struct renderer_shader_uniform uniforms[CONTEXT_MAX_UNIFORMS];
    int nuniforms = 0;
    if (lua_getfield(L, 2, "uniforms") == LUA_TTABLE) {
        lua_pushnil(L);
        while (lua_next(L, -2)) {
            if (lua_type(L, -2) != LUA_TSTRING)
                return luaL_error(L, "bad argument 'uniforms' to 'fullscreen' ({name = number or vector} expected)");
            if (nuniforms >= CONTEXT_MAX_UNIFORMS)
                return luaL_error(L, "bad argument 'uniforms' to 'fullscreen' (at most %d uniforms)",
                                  CONTEXT_MAX_UNIFORMS);
            const char *name = lua_tostring(L, -2);
            uniforms[nuniforms].name = name; /* the table keeps the string alive */
            memset(uniforms[nuniforms].value, 0, sizeof uniforms[nuniforms].value);
            if (lua_type(L, -1) == LUA_TNUMBER) {
                uniforms[nuniforms].size = 1;
                uniforms[nuniforms].value[0] = lutil_check_number(L, -1, "fullscreen", name);
            } else if (lua_istable(L, -1)) {
                int n = (int)lua_rawlen(L, -1);
                if (n < 1 || n > 4)
                    return luaL_error(L, "bad argument 'uniforms' to 'fullscreen' ('%s': 1 to 4 numbers expected)", name);
                for (int i = 0; i < n; i++) {
                    lua_rawgeti(L, -1, i + 1);
                    uniforms[nuniforms].value[i] = lutil_check_number(L, -1, "fullscreen", name);
                    lua_pop(L, 1);
                }
                uniforms[nuniforms].size = n;
            } else {
                return luaL_error(L, "bad argument 'uniforms' to 'fullscreen' ('%s': number or vector expected, got %s)",
                                  name, luaL_typename(L, -1));
            }
            nuniforms++;
            lua_pop(L, 1);
        }
    }
    lua_pop(L, 1);

    /* From here on nothing raises a Lua error. */
    struct gl_framebuffer fb;
    if (!gl_framebuffer_create(&fb, &err) || !gl_framebuffer_attach(&fb, targets, NULL, ntargets, NULL, -1, &err)) {
        gl_framebuffer_destroy(&fb);
        return luaL_error(L, "%s", err.message);
    }
    renderer_reset_state(r);
    renderer_run_fullscreen(r, prog, fb.id, targets[0]->width, targets[0]->height, inputs, ninputs, uniforms, nuniforms,
                            c->frame->time);
    renderer_reset_state(r);
    gl_framebuffer_destroy(&fb);
    return 0;
}

static int context_get_frame(lua_State *L)
{
    lua_pushinteger(L, check_context(L)->frame->frame);
    return 1;
}

static int context_get_time(lua_State *L)
{
    lua_pushnumber(L, check_context(L)->frame->time);
    return 1;
}

static int context_get_width(lua_State *L)
{
    lua_pushinteger(L, check_context(L)->frame->width);
    return 1;
}

static int context_get_height(lua_State *L)
{
    lua_pushinteger(L, check_context(L)->frame->height);
    return 1;
}

bool lua_host_run_custom_pass(struct pass *p, struct pass_frame *f, struct error *err)
{
    lua_State *L = p->script_state;
    const struct pass_value *run = pass_value(p, "run");
    if (!L || !run || run->lua_ref < 0)
        return error_set(err, "custom pass has no run function");
    if (luaL_getmetatable(L, CONTEXT_MT) == LUA_TNIL) {
        static const luaL_Reg methods[] = {{"clear", context_clear}, {"fullscreen", context_fullscreen}, {NULL, NULL}};
        static const luaL_Reg getters[] = {{"frame", context_get_frame}, {"time", context_get_time},
                                           {"width", context_get_width}, {"height", context_get_height},
                                           {NULL, NULL}};
        lutil_class(L, CONTEXT_MT, "pass context", NULL, methods, getters, NULL);
    }
    lua_pop(L, 1);
    lua_rawgeti(L, LUA_REGISTRYINDEX, run->lua_ref);
    struct pass_context *c = lua_newuserdatauv(L, sizeof *c, 0);
    c->pass = p;
    c->frame = f;
    c->valid = true;
    luaL_setmetatable(L, CONTEXT_MT);
    lua_pushvalue(L, -1);
    int ctx_ref = luaL_ref(L, LUA_REGISTRYINDEX);
    char context[128];
    snprintf(context, sizeof context, "(in run of custom pass '%s')", p->name);
    bool ok = lua_host_call(L, 1, 0, context, err);
    lua_rawgeti(L, LUA_REGISTRYINDEX, ctx_ref);
    ((struct pass_context *)lua_touserdata(L, -1))->valid = false;
    lua_pop(L, 1);
    luaL_unref(L, LUA_REGISTRYINDEX, ctx_ref);
    return ok;
}
