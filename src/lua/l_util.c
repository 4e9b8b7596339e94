#include "lua/l_util.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "core/suggest.h"

/* "file:line: " of the innermost Lua code on the stack: a setter runs
 * under __newindex (and a constructor's lutil_assign_fields), so the level
 * luaL_where(L, 1) sees is C; the script line is further out. */
static void push_where(lua_State *L)
{
    lua_Debug ar;
    for (int level = 1; lua_getstack(L, level, &ar); level++) {
        lua_getinfo(L, "Sl", &ar);
        if (ar.currentline > 0) {
            lua_pushfstring(L, "%s:%d: ", ar.short_src, ar.currentline);
            return;
        }
    }
    lua_pushliteral(L, "");
}

int lutil_error(lua_State *L, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    push_where(L);
    lua_pushstring(L, msg);
    lua_concat(L, 2);
    return lua_error(L);
}

int lutil_field_error(lua_State *L, const char *fn, const char *field, const char *expected, int idx)
{
    return lutil_error(L, "bad argument '%s' to '%s' (%s expected, got %s)", field, fn, expected,
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
            size_t n = 0;
            while (allowed[n])
                n++;
            const char *near = lua_type(L, -2) == LUA_TSTRING ? suggest_nearest(key, allowed, n) : NULL;
            if (near)
                luaL_error(L, "unknown field '%s' in '%s' (did you mean '%s'?) (expected one of: %s)", key, fn, near,
                           lua_tostring(L, -1));
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
        if (lua_type(L, -1) != LUA_TNUMBER) {
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
    /* A colour may be one number (a grey); a position, direction or scale
     * given as one number is a mistake ({x, y, z} was meant), not a
     * broadcast. */
    if (!nonnegative && lua_type(L, idx) == LUA_TNUMBER)
        lutil_error(L, "bad argument '%s' to '%s' ({x, y, z} expected, got a single number %g)", field, fn,
                    lua_tonumber(L, idx));
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
    if (lua_type(L, idx) != LUA_TNUMBER)
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
        if (lua_type(L, -1) != LUA_TNUMBER)
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

void lutil_push_box(lua_State *L, vec3 lo, vec3 hi)
{
    lua_createtable(L, 2, 0);
    lutil_push_vec3(L, lo);
    lua_rawseti(L, -2, 1);
    lutil_push_vec3(L, hi);
    lua_rawseti(L, -2, 2);
}

void lutil_opt_number(lua_State *L, int t, const char *fn, const char *field, float *out)
{
    if (lua_getfield(L, t, field) != LUA_TNIL)
        *out = lutil_check_number(L, -1, fn, field);
    lua_pop(L, 1);
}

void lutil_opt_boolean(lua_State *L, int t, const char *fn, const char *field, bool *out)
{
    if (lua_getfield(L, t, field) != LUA_TNIL) {
        if (!lua_isboolean(L, -1))
            lutil_field_error(L, fn, field, "boolean", -1);
        *out = lua_toboolean(L, -1);
    }
    lua_pop(L, 1);
}

void lutil_opt_integer(lua_State *L, int t, const char *fn, const char *field, int *out)
{
    if (lua_getfield(L, t, field) != LUA_TNIL) {
        if (!lua_isinteger(L, -1)) {
            if (lua_type(L, -1) == LUA_TNUMBER)
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

int lutil_opt_option(lua_State *L, int t, const char *fn, const char *field, const char *const *options,
                     int default_index)
{
    int index = default_index;
    if (lua_getfield(L, t, field) != LUA_TNIL) {
        const char *s = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : NULL;
        index = -1;
        for (int i = 0; s && options[i]; i++)
            if (strcmp(options[i], s) == 0)
                index = i;
        if (index < 0) {
            char expected[256] = "";
            size_t used = 0;
            for (int i = 0; options[i] && used < sizeof expected; i++) {
                int w = snprintf(expected + used, sizeof expected - used, "%s\"%s\"", i ? " or " : "", options[i]);
                if (w > 0)
                    used += (size_t)w;
            }
            lutil_field_error(L, fn, field, expected, -1);
        }
    }
    lua_pop(L, 1);
    return index;
}

void lutil_opt_extent(lua_State *L, int t, const char *fn, const char *field, float *x, float *z)
{
    static const char expected[] = "number or {x, z} (two numbers)";
    int type = lua_getfield(L, t, field);
    if (type == LUA_TNUMBER) {
        *x = *z = lutil_check_number(L, -1, fn, field);
    } else if (type == LUA_TTABLE) {
        if (luaL_len(L, -1) != 2)
            lutil_field_error(L, fn, field, expected, -1);
        float *sides[2] = {x, z};
        for (int i = 0; i < 2; i++) {
            lua_geti(L, -1, i + 1);
            if (lua_type(L, -1) != LUA_TNUMBER)
                lutil_field_error(L, fn, field, expected, -2);
            *sides[i] = lutil_check_number(L, -1, fn, field);
            lua_pop(L, 1);
        }
    } else if (type != LUA_TNIL) {
        lutil_field_error(L, fn, field, expected, -1);
    }
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

static int class_index(lua_State *L)
{
    /* upvalues: 1 methods, 2 getters */
    lua_pushvalue(L, 2);
    if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL)
        return 1;
    lua_pop(L, 1);
    lua_pushvalue(L, 2);
    if (lua_rawget(L, lua_upvalueindex(2)) == LUA_TFUNCTION) {
        lua_pushvalue(L, 1);
        lua_call(L, 1, 1);
        return 1;
    }
    lua_pushnil(L);
    return 1;
}

static int class_newindex(lua_State *L)
{
    /* upvalues: 1 setters, 2 the class's name, 3 the settable fields, in order, for messages */
    lua_pushvalue(L, 2);
    if (lua_rawget(L, lua_upvalueindex(1)) == LUA_TFUNCTION) {
        lua_pushvalue(L, 1);
        lua_pushvalue(L, 2);
        lua_pushvalue(L, 3);
        lua_call(L, 3, 0);
        return 0;
    }
    return lutil_error(L, "%s has no field '%s' (fields: %s)", lua_tostring(L, lua_upvalueindex(2)),
                       luaL_tolstring(L, 2, NULL), lua_tostring(L, lua_upvalueindex(3)));
}

static void new_table_of(lua_State *L, const luaL_Reg *funcs)
{
    lua_newtable(L);
    if (funcs)
        luaL_setfuncs(L, funcs, 0);
}

void lutil_class(lua_State *L, const char *name, const char *what, const luaL_Reg *meta, const luaL_Reg *methods,
                 const luaL_Reg *getters, const luaL_Reg *setters)
{
    luaL_newmetatable(L, name);
    if (meta)
        luaL_setfuncs(L, meta, 0);
    new_table_of(L, methods);
    new_table_of(L, getters);
    lua_pushcclosure(L, class_index, 2);
    lua_setfield(L, -2, "__index");
    new_table_of(L, setters);
    lua_pushstring(L, what);
    char fields[512] = "";
    size_t used = 0;
    for (int i = 0; setters && setters[i].name && used < sizeof fields; i++) {
        int w = snprintf(fields + used, sizeof fields - used, "%s%s", i ? ", " : "", setters[i].name);
        if (w > 0)
            used += (size_t)w;
    }
    lua_pushstring(L, fields);
    lua_pushcclosure(L, class_newindex, 3);
    lua_setfield(L, -2, "__newindex");
    lua_pushstring(L, name);
    lua_setfield(L, -2, "__metatable");
    lua_pop(L, 1);
}

void lutil_assign_fields(lua_State *L, int object, int options, const char *const *fields)
{
    object = lua_absindex(L, object);
    options = lua_absindex(L, options);
    for (int i = 0; fields[i]; i++) {
        if (lua_getfield(L, options, fields[i]) == LUA_TNIL) {
            lua_pop(L, 1);
            continue;
        }
        lua_setfield(L, object, fields[i]);
    }
}
