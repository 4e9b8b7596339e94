/* c.medium { ... }: a participating medium (scene/medium.c samples its
 * density function onto the grid; this file only translates). */
#include <math.h>

#include "lua/l_scene.h"
#include "lua/l_util.h"

static struct l_medium *check_medium(lua_State *L, int idx)
{
    struct l_medium *u = luaL_checkudata(L, idx, MEDIUM_MT);
    if (!u->medium)
        lscene_released(L, idx, "medium");
    return u;
}

/* The density function at `user` (a stack index), called for each grid corner. */
struct density_call {
    lua_State *L;
    int function;
};

static double call_density(void *user, vec3 p)
{
    struct density_call *c = user;
    lua_pushvalue(c->L, c->function);
    lua_pushnumber(c->L, p.x);
    lua_pushnumber(c->L, p.y);
    lua_pushnumber(c->L, p.z);
    lua_call(c->L, 3, 1);
    if (lua_type(c->L, -1) != LUA_TNUMBER)
        lutil_error(c->L, "medium density function must return a number, got %s", luaL_typename(c->L, -1));
    double d = lua_tonumber(c->L, -1);
    lua_pop(c->L, 1);
    return d;
}

/* c.medium { sigma_s, sigma_a, g, density = number | function(x, y, z), resolution = {nx, ny, nz}, box = {min, max} } */
static int medium_new(lua_State *L)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    static const char *const fields[] = {"sigma_s", "sigma_a", "g", "density", "resolution", "box", NULL};
    lutil_check_fields(L, 1, "medium", fields);
    struct l_medium *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->medium = medium_create();
    luaL_setmetatable(L, MEDIUM_MT);
    if (!u->medium)
        return lutil_error(L, "out of memory");
    int idx = lua_gettop(L);
    struct medium *m = u->medium;
    lutil_opt_color(L, 1, "medium", "sigma_s", &m->sigma_s);
    lutil_opt_color(L, 1, "medium", "sigma_a", &m->sigma_a);
    lutil_opt_number(L, 1, "medium", "g", &m->g);
    if (!(m->g >= -0.99f && m->g <= 0.99f))
        return lutil_error(L, "bad argument 'g' to 'medium' (a number in [-0.99, 0.99] expected, got %g)", (double)m->g);
    if (lua_getfield(L, 1, "box") != LUA_TTABLE)
        return lutil_error(L, "bad argument 'box' to 'medium' ({{x0, y0, z0}, {x1, y1, z1}} expected, got %s)",
                          luaL_typename(L, -1));
    lua_rawgeti(L, -1, 1);
    m->box_min = lutil_check_vec3(L, -1, "medium", "box");
    lua_rawgeti(L, -2, 2);
    m->box_max = lutil_check_vec3(L, -1, "medium", "box");
    lua_pop(L, 3);
    if (!(m->box_min.x < m->box_max.x && m->box_min.y < m->box_max.y && m->box_min.z < m->box_max.z))
        return lutil_error(L, "bad argument 'box' to 'medium' (min must be below max on every axis)");
    int type = lua_getfield(L, 1, "density");
    if (type == LUA_TNUMBER) {
        m->density = (float)lua_tonumber(L, -1);
        if (!(m->density >= 0) || !isfinite(m->density))
            return lutil_error(L, "bad argument 'density' to 'medium' (a non-negative number expected)");
        m->max_density = m->density;
    } else if (type == LUA_TFUNCTION) {
        /* A density function, sampled once on the corners of a grid. */
        int res[3] = {32, 32, 32};
        if (lua_getfield(L, 1, "resolution") == LUA_TTABLE)
            for (int k = 0; k < 3; k++) {
                lua_rawgeti(L, -1, k + 1);
                lua_Integer r = luaL_checkinteger(L, -1);
                res[k] = r < 0 || r > 100000 ? 0 : (int)r;
                lua_pop(L, 1);
            }
        lua_pop(L, 1);
        struct density_call call = {L, lua_gettop(L)};
        struct error err;
        if (!medium_sample_grid(m, res[0], res[1], res[2], call_density, &call, &err))
            return lutil_error(L, "%s", err.message);
    } else if (type != LUA_TNIL) {
        return lutil_field_error(L, "medium", "density", "number or function(x, y, z)", -1);
    }
    lua_settop(L, idx);
    return 1;
}

/* medium:density_at{x, y, z} */
static int medium_density_at(lua_State *L)
{
    struct l_medium *u = check_medium(L, 1);
    vec3 p = lutil_check_vec3(L, 2, "density_at", "point");
    lua_pushnumber(L, medium_density(u->medium, p));
    return 1;
}

static int medium_gc(lua_State *L)
{
    struct l_medium *u = luaL_checkudata(L, 1, MEDIUM_MT);
    medium_destroy(u->medium);
    u->medium = NULL;
    return 0;
}

static int get_sigma_s(lua_State *L)
{
    lutil_push_vec3(L, check_medium(L, 1)->medium->sigma_s);
    return 1;
}

static int get_sigma_a(lua_State *L)
{
    lutil_push_vec3(L, check_medium(L, 1)->medium->sigma_a);
    return 1;
}

static int get_g(lua_State *L)
{
    lua_pushnumber(L, check_medium(L, 1)->medium->g);
    return 1;
}

void lmedium_open(lua_State *L)
{
    static const luaL_Reg meta[] = {{"__gc", medium_gc}, {NULL, NULL}};
    static const luaL_Reg methods[] = {{"density_at", medium_density_at}, {NULL, NULL}};
    static const luaL_Reg getters[] = {{"sigma_s", get_sigma_s}, {"sigma_a", get_sigma_a}, {"g", get_g}, {NULL, NULL}};
    lutil_class(L, MEDIUM_MT, "medium", meta, methods, getters, NULL);
    lua_pushcfunction(L, medium_new);
    lua_setfield(L, -2, "medium");
}
