/* The context a custom pass's run(ctx) receives: frame facts, and the two
 * draw calls such a pass needs (clear an output, run a fullscreen shader
 * into outputs with inputs bound). Translation only: drawing is done by
 * the renderer. */
#include <stdio.h>
#include <string.h>

#include <lauxlib.h>

#include "graph/pass.h"
#include "graph/renderer.h"
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
    gl.ClearTexImage(r->texture.id, 0, GL_RGBA, GL_FLOAT, color);
    return 0;
}

/* ctx:fullscreen{shader = "x.frag", output = "color" | {...}, inputs = {name = "slot"}, uniforms = {...}} */
static int context_fullscreen(lua_State *L)
{
    struct pass_context *c = check_context(L);
    luaL_checktype(L, 2, LUA_TTABLE);
    struct renderer *r = c->frame->renderer;
    lua_getfield(L, 2, "shader");
    if (!lua_isstring(L, -1))
        return luaL_error(L, "bad argument 'shader' to 'fullscreen' (string expected, got %s)", luaL_typename(L, -1));
    char path[4096];
    lua_host_resolve_path(L, lua_tostring(L, -1), path, sizeof path);
    lua_pop(L, 1);
    struct gl_program *prog;
    struct error err;
    if (!gl_program_get(&r->programs, "common/fullscreen.vert", path, NULL, &prog, &err))
        return luaL_error(L, "%s", err.message);
    const struct gl_texture *targets[PASS_MAX_OUTPUTS];
    int ntargets = 0;
    lua_getfield(L, 2, "output");
    if (lua_isstring(L, -1)) {
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
    struct gl_framebuffer fb;
    if (!gl_framebuffer_create(&fb, &err) || !gl_framebuffer_attach(&fb, targets, NULL, ntargets, NULL, -1, &err)) {
        gl_framebuffer_destroy(&fb);
        return luaL_error(L, "%s", err.message);
    }
    renderer_reset_state(r);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fb.id);
    gl.Viewport(0, 0, targets[0]->width, targets[0]->height);
    gl.UseProgram(prog->id);
    int unit = 0;
    if (lua_getfield(L, 2, "inputs") == LUA_TTABLE) {
        lua_pushnil(L);
        while (lua_next(L, -2)) {
            const char *sampler = lua_tostring(L, -2);
            struct graph_resource *in = find_texture(L, c, luaL_checkstring(L, -1), false);
            gl.BindTextureUnit((GLuint)unit, in->texture.id);
            gl.ProgramUniform1i(prog->id, gl_program_uniform(prog, sampler), unit);
            unit++;
            lua_pop(L, 1);
        }
    }
    lua_pop(L, 1);
    if (lua_getfield(L, 2, "uniforms") == LUA_TTABLE) {
        lua_pushnil(L);
        while (lua_next(L, -2)) {
            GLint loc = gl_program_uniform(prog, lua_tostring(L, -2));
            if (lua_isnumber(L, -1)) {
                gl.ProgramUniform1f(prog->id, loc, (float)lua_tonumber(L, -1));
            } else if (lua_istable(L, -1)) {
                float v[4] = {0, 0, 0, 0};
                int n = (int)lua_rawlen(L, -1);
                for (int i = 0; i < n && i < 4; i++) {
                    lua_rawgeti(L, -1, i + 1);
                    v[i] = (float)luaL_checknumber(L, -1);
                    lua_pop(L, 1);
                }
                if (n == 2)
                    gl.ProgramUniform2f(prog->id, loc, v[0], v[1]);
                else if (n == 3)
                    gl.ProgramUniform3f(prog->id, loc, v[0], v[1], v[2]);
                else
                    gl.ProgramUniform4f(prog->id, loc, v[0], v[1], v[2], v[3]);
            }
            lua_pop(L, 1);
        }
    }
    lua_pop(L, 1);
    gl.ProgramUniform1f(prog->id, gl_program_uniform(prog, "u_time"), (float)c->frame->time);
    renderer_draw_fullscreen(r);
    renderer_reset_state(r);
    gl_framebuffer_destroy(&fb);
    return 0;
}

static int context_index(lua_State *L)
{
    struct pass_context *c = check_context(L);
    const char *k = luaL_checkstring(L, 2);
    if (strcmp(k, "frame") == 0)
        lua_pushinteger(L, c->frame->frame);
    else if (strcmp(k, "time") == 0)
        lua_pushnumber(L, c->frame->time);
    else if (strcmp(k, "width") == 0)
        lua_pushinteger(L, c->frame->width);
    else if (strcmp(k, "height") == 0)
        lua_pushinteger(L, c->frame->height);
    else if (strcmp(k, "clear") == 0)
        lua_pushcfunction(L, context_clear);
    else if (strcmp(k, "fullscreen") == 0)
        lua_pushcfunction(L, context_fullscreen);
    else
        lua_pushnil(L);
    return 1;
}

bool lua_host_run_custom_pass(struct pass *p, struct pass_frame *f, struct error *err)
{
    lua_State *L = p->lua;
    const struct pass_value *run = pass_value(p, "run");
    if (!L || !run || run->lua_ref < 0)
        return error_set(err, "custom pass has no run function");
    if (luaL_newmetatable(L, CONTEXT_MT)) {
        lua_pushcfunction(L, context_index);
        lua_setfield(L, -2, "__index");
        lua_pushstring(L, CONTEXT_MT);
        lua_setfield(L, -2, "__metatable");
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
