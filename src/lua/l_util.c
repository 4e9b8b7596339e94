#include "lua/l_util.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int lutil_error(lua_State *L, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return luaL_error(L, "%s", msg);
}

int lutil_field_error(lua_State *L, const char *fn, const char *field, const char *expected, int idx)
{
    return luaL_error(L, "bad argument '%s' to '%s' (%s expected, got %s)", field, fn, expected,
                      luaL_typename(L, idx));
}

void lutil_check_fields(lua_State *L, int idx, const char *fn, const char *const *allowed)
{
    idx = lua_absindex(L, idx);
    lua_pushnil(L);
    while (lua_next(L, idx)) {
        lua_pop(L, 1);
        bool ok = false;
        if (lua_type(L, -1) == LUA_TSTRING) {
            const char *key = lua_tostring(L, -1);
            for (int i = 0; allowed[i]; i++)
                if (strcmp(allowed[i], key) == 0)
                    ok = true;
        }
        if (!ok) {
            luaL_Buffer b;
            luaL_buffinit(L, &b);
            for (int i = 0; allowed[i]; i++) {
                if (i)
                    luaL_addstring(&b, ", ");
                luaL_addstring(&b, allowed[i]);
            }
            luaL_pushresult(&b);
            const char *key = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : luaL_typename(L, -2);
            luaL_error(L, "unknown field '%s' in '%s' (expected one of: %s)", key, fn, lua_tostring(L, -1));
        }
    }
}

bool lutil_to_vec3(lua_State *L, int idx, vec3 *out)
{
    idx = lua_absindex(L, idx);
    if (lua_type(L, idx) == LUA_TNUMBER) {
        float v = (float)lua_tonumber(L, idx);
        *out = vec3_make(v, v, v);
        return true;
    }
    if (!lua_istable(L, idx))
        return false;
    float c[3];
    for (int i = 0; i < 3; i++) {
        lua_rawgeti(L, idx, i + 1);
        if (!lua_isnumber(L, -1)) {
            lua_pop(L, 1);
            return false;
        }
        c[i] = (float)lua_tonumber(L, -1);
        lua_pop(L, 1);
    }
    *out = vec3_make(c[0], c[1], c[2]);
    return true;
}

/* The first non-finite (or negative) component of a vector at idx, for the
 * message; NAN when the value is not a vector at all. */
static vec3 check_vector(lua_State *L, int idx, const char *fn, const char *field, bool nonnegative)
{
    vec3 v;
    if (!lutil_to_vec3(L, idx, &v))
        lutil_field_error(L, fn, field, nonnegative ? "{r, g, b}" : "{x, y, z}", idx);
    const float c[3] = {v.x, v.y, v.z};
    for (int i = 0; i < 3; i++)
        if (!isfinite(c[i]) || (nonnegative && c[i] < 0.0f))
            lutil_error(L, "bad argument '%s' to '%s' (finite numbers%s expected, got %g)", field, fn,
                        nonnegative ? " >= 0" : "", isnan(c[i]) ? NAN : (double)c[i]); /* "nan", not "-nan" */
    return v;
}

vec3 lutil_check_vec3(lua_State *L, int idx, const char *fn, const char *field)
{
    return check_vector(L, idx, fn, field, false);
}

vec3 lutil_check_color(lua_State *L, int idx, const char *fn, const char *field)
{
    return check_vector(L, idx, fn, field, true);
}

float lutil_check_number(lua_State *L, int idx, const char *fn, const char *field)
{
    if (!lua_isnumber(L, idx))
        lutil_field_error(L, fn, field, "number", idx);
    double d = lua_tonumber(L, idx);
    if (!isfinite(d) || fabs(d) > 3.4e38)
        lutil_error(L, "bad argument '%s' to '%s' (a finite number expected, got %g)", field, fn, isnan(d) ? NAN : d);
    return (float)d;
}

quat lutil_check_quat(lua_State *L, int idx, const char *fn, const char *field)
{
    idx = lua_absindex(L, idx);
    float c[4];
    if (!lua_istable(L, idx))
        lutil_field_error(L, fn, field, "quaternion {x, y, z, w}", idx);
    for (int i = 0; i < 4; i++) {
        lua_rawgeti(L, idx, i + 1);
        if (!lua_isnumber(L, -1))
            lutil_field_error(L, fn, field, "quaternion {x, y, z, w}", idx);
        c[i] = (float)lua_tonumber(L, -1);
        if (!isfinite(c[i]))
            lutil_error(L, "bad argument '%s' to '%s' (finite numbers expected, got %g)", field, fn,
                        isnan(c[i]) ? NAN : (double)c[i]);
        lua_pop(L, 1);
    }
    /* A zero quaternion has no rotation to normalise to. */
    if (c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3] < 1e-30f)
        lutil_error(L, "bad argument '%s' to '%s' (a non-zero quaternion expected)", field, fn);
    return quat_normalize((quat){c[0], c[1], c[2], c[3]});
}

void lutil_push_vec3(lua_State *L, vec3 v)
{
    lua_createtable(L, 3, 0);
    lua_pushnumber(L, v.x);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, v.y);
    lua_rawseti(L, -2, 2);
    lua_pushnumber(L, v.z);
    lua_rawseti(L, -2, 3);
}

void lutil_push_quat(lua_State *L, quat q)
{
    lua_createtable(L, 4, 0);
    lua_pushnumber(L, q.x);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, q.y);
    lua_rawseti(L, -2, 2);
    lua_pushnumber(L, q.z);
    lua_rawseti(L, -2, 3);
    lua_pushnumber(L, q.w);
    lua_rawseti(L, -2, 4);
}

void lutil_opt_number(lua_State *L, int t, const char *fn, const char *field, float *out)
{
    if (lua_getfield(L, t, field) != LUA_TNIL)
        *out = lutil_check_number(L, -1, fn, field);
    lua_pop(L, 1);
}

void lutil_opt_integer(lua_State *L, int t, const char *fn, const char *field, int *out)
{
    if (lua_getfield(L, t, field) != LUA_TNIL) {
        if (!lua_isinteger(L, -1)) {
            if (lua_isnumber(L, -1))
                lutil_error(L, "bad argument '%s' to '%s' (integer expected, got %g)", field, fn,
                            (double)lua_tonumber(L, -1));
            lutil_field_error(L, fn, field, "integer", -1);
        }
        lua_Integer v = lua_tointeger(L, -1);
        if (v < INT_MIN || v > INT_MAX)
            lutil_error(L, "bad argument '%s' to '%s' (integer expected, got %lld, which does not fit)", field, fn,
                        (long long)v);
        *out = (int)v;
    }
    lua_pop(L, 1);
}

void lutil_opt_vec3(lua_State *L, int t, const char *fn, const char *field, vec3 *out)
{
    if (lua_getfield(L, t, field) != LUA_TNIL)
        *out = lutil_check_vec3(L, -1, fn, field);
    lua_pop(L, 1);
}

void lutil_opt_color(lua_State *L, int t, const char *fn, const char *field, vec3 *out)
{
    if (lua_getfield(L, t, field) != LUA_TNIL)
        *out = lutil_check_color(L, -1, fn, field);
    lua_pop(L, 1);
}

void lutil_where(lua_State *L, char *out, size_t outlen)
{
    luaL_where(L, 1);
    const char *w = lua_tostring(L, -1);
    size_t n = strlen(w);
    /* luaL_where gives "file:line: " */
    snprintf(out, outlen, "%.*s", (int)(n >= 2 ? n - 2 : n), w);
    lua_pop(L, 1);
}
