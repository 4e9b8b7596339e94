/* c.light.point / directional / spot / linear: lights with live fields
 * (an assignment takes effect on the next frame and bumps the version). */
#include <string.h>

#include "lua/l_scene.h"
#include "lua/l_util.h"

struct light *llight_check(lua_State *L, int idx)
{
    struct light *l = ((struct l_light *)luaL_checkudata(L, idx, LIGHT_MT))->light;
    if (!l)
        lscene_released(L, idx, "light");
    return l;
}

struct light *llight_test(lua_State *L, int idx)
{
    struct l_light *u = luaL_testudata(L, idx, LIGHT_MT);
    return u ? u->light : NULL;
}

static void set_vector(struct light *l, vec3 *field, vec3 value)
{
    if (memcmp(&value, field, sizeof value) != 0)
        l->version++;
    *field = value;
}

static int set_position(lua_State *L)
{
    struct light *l = llight_check(L, 1);
    set_vector(l, &l->position, lutil_check_vec3(L, 3, light_kind_name(l->kind), lua_tostring(L, 2)));
    return 0;
}

static int set_end(lua_State *L)
{
    struct light *l = llight_check(L, 1);
    set_vector(l, &l->end, lutil_check_vec3(L, 3, light_kind_name(l->kind), "end"));
    return 0;
}

static int set_direction(lua_State *L)
{
    struct light *l = llight_check(L, 1);
    const char *fn = light_kind_name(l->kind);
    vec3 d = lutil_check_vec3(L, 3, fn, "direction");
    if (vec3_dot(d, d) < 1e-20f)
        lutil_error(L, "bad argument 'direction' to '%s' (a non-zero vector expected)", fn);
    set_vector(l, &l->direction, d);
    return 0;
}

static int set_intensity(lua_State *L)
{
    struct light *l = llight_check(L, 1);
    set_vector(l, &l->intensity, lutil_check_color(L, 3, light_kind_name(l->kind), "intensity"));
    return 0;
}

static int set_angle(lua_State *L)
{
    struct light *l = llight_check(L, 1);
    const char *fn = light_kind_name(l->kind);
    float x = lutil_check_number(L, 3, fn, "angle");
    if (!(x > 0.0f && x <= 90.0f))
        lutil_error(L, "bad argument 'angle' to '%s' (a half-angle in (0, 90] degrees expected, got %g)", fn, (double)x);
    if (l->angle != x)
        l->version++;
    l->angle = x;
    return 0;
}

static int set_softness(lua_State *L)
{
    struct light *l = llight_check(L, 1);
    const char *fn = light_kind_name(l->kind);
    float x = lutil_check_number(L, 3, fn, "softness");
    if (!(x >= 0.0f && x <= 1.0f))
        lutil_error(L, "bad argument 'softness' to '%s' (a fraction in [0, 1] expected, got %g)", fn, (double)x);
    if (l->softness != x)
        l->version++;
    l->softness = x;
    return 0;
}

static int set_samples(lua_State *L)
{
    struct light *l = llight_check(L, 1);
    if (!lua_isinteger(L, 3) || lua_tointeger(L, 3) < 1 || lua_tointeger(L, 3) > 32)
        lutil_error(L, "bad argument 'samples' to '%s' (integer 1..32 expected)", light_kind_name(l->kind));
    l->samples = (int)lua_tointeger(L, 3);
    l->version++;
    return 0;
}

static int set_cast_shadows(lua_State *L)
{
    struct light *l = llight_check(L, 1);
    if (!lua_isboolean(L, 3))
        lutil_field_error(L, light_kind_name(l->kind), "cast_shadows", "boolean", 3);
    l->cast_shadows = lua_toboolean(L, 3);
    l->version++;
    return 0;
}

static int get_position(lua_State *L)
{
    lutil_push_vec3(L, llight_check(L, 1)->position);
    return 1;
}

static int get_end(lua_State *L)
{
    lutil_push_vec3(L, llight_check(L, 1)->end);
    return 1;
}

static int get_direction(lua_State *L)
{
    lutil_push_vec3(L, llight_check(L, 1)->direction);
    return 1;
}

static int get_intensity(lua_State *L)
{
    lutil_push_vec3(L, llight_check(L, 1)->intensity);
    return 1;
}

static int get_angle(lua_State *L)
{
    lua_pushnumber(L, llight_check(L, 1)->angle);
    return 1;
}

static int get_softness(lua_State *L)
{
    lua_pushnumber(L, llight_check(L, 1)->softness);
    return 1;
}

static int get_samples(lua_State *L)
{
    lua_pushinteger(L, llight_check(L, 1)->samples);
    return 1;
}

static int get_cast_shadows(lua_State *L)
{
    lua_pushboolean(L, llight_check(L, 1)->cast_shadows);
    return 1;
}

static int get_kind(lua_State *L)
{
    lua_pushstring(L, light_kind_name(llight_check(L, 1)->kind));
    return 1;
}

static const char *const light_fields[] = {"position", "start", "end", "direction", "intensity", "angle",
                                           "softness", "samples", "cast_shadows", NULL};

static int push_light(lua_State *L, enum light_kind kind)
{
    luaL_checktype(L, 1, LUA_TTABLE);
    lutil_check_fields(L, 1, light_kind_name(kind), light_fields);
    struct l_light *u = lua_newuserdatauv(L, sizeof *u, 0);
    u->light = light_create(kind);
    luaL_setmetatable(L, LIGHT_MT);
    if (!u->light)
        return lutil_error(L, "out of memory");
    lutil_assign_fields(L, -1, 1, light_fields);
    return 1;
}

static int light_point(lua_State *L) { return push_light(L, LIGHT_POINT); }
static int light_directional(lua_State *L) { return push_light(L, LIGHT_DIRECTIONAL); }
static int light_spot(lua_State *L) { return push_light(L, LIGHT_SPOT); }
static int light_linear(lua_State *L) { return push_light(L, LIGHT_LINEAR); }

static int light_gc(lua_State *L)
{
    struct l_light *u = luaL_checkudata(L, 1, LIGHT_MT);
    light_destroy(u->light);
    u->light = NULL;
    return 0;
}

static int light_tostring(lua_State *L)
{
    lua_pushfstring(L, "Light(%s)", light_kind_name(llight_check(L, 1)->kind));
    return 1;
}

void llight_open(lua_State *L)
{
    static const luaL_Reg meta[] = {{"__gc", light_gc}, {"__tostring", light_tostring}, {NULL, NULL}};
    static const luaL_Reg getters[] = {{"position", get_position}, {"start", get_position}, {"end", get_end},
                                       {"direction", get_direction}, {"intensity", get_intensity},
                                       {"angle", get_angle}, {"softness", get_softness}, {"samples", get_samples},
                                       {"cast_shadows", get_cast_shadows}, {"kind", get_kind}, {NULL, NULL}};
    static const luaL_Reg setters[] = {{"position", set_position}, {"start", set_position}, {"end", set_end},
                                       {"direction", set_direction}, {"intensity", set_intensity},
                                       {"angle", set_angle}, {"softness", set_softness}, {"samples", set_samples},
                                       {"cast_shadows", set_cast_shadows}, {NULL, NULL}};
    lutil_class(L, LIGHT_MT, "light", meta, NULL, getters, setters);
    static const luaL_Reg lights[] = {{"point", light_point}, {"directional", light_directional},
                                      {"spot", light_spot}, {"linear", light_linear}, {NULL, NULL}};
    luaL_newlib(L, lights);
    lua_setfield(L, -2, "light");
}
