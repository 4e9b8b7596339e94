/* Helpers the bindings share: reading vectors and typed fields from option
 * tables with errors in the Lua manual's style, naming the field and the
 * function: "bad argument 'size' to 'shadow_map' (number expected, got string)". */
#ifndef CAUSTICA_L_UTIL_H
#define CAUSTICA_L_UTIL_H

#include <stdbool.h>

#include <lauxlib.h>
#include <lua.h>

#include "core/vecmath.h"

/* luaL_error with the whole of printf's formats (luaL_error has no %g). */
int lutil_error(lua_State *L, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Raises the error above for value at `idx`. */
int lutil_field_error(lua_State *L, const char *fn, const char *field, const char *expected, int idx);
/* Checks that every key of the table at `idx` is in `allowed` (NULL-terminated). */
void lutil_check_fields(lua_State *L, int idx, const char *fn, const char *const *allowed);
/* Reads {x, y, z} (or a single number, repeated: colours) at `idx`. */
bool lutil_to_vec3(lua_State *L, int idx, vec3 *out);
/* {x, y, z} of finite numbers: positions, directions, scales (one number is refused). */
vec3 lutil_check_vec3(lua_State *L, int idx, const char *fn, const char *field);
/* {r, g, b} of finite numbers >= 0: colours, intensities, coefficients. */
vec3 lutil_check_color(lua_State *L, int idx, const char *fn, const char *field);
quat lutil_check_quat(lua_State *L, int idx, const char *fn, const char *field);
void lutil_push_vec3(lua_State *L, vec3 v);
void lutil_push_quat(lua_State *L, quat q);
/* A box as { {min}, {max} } (mesh.bounds, object.bounds). */
void lutil_push_box(lua_State *L, vec3 lo, vec3 hi);
/* Optional fields of the option table at `t`: leave *out unchanged when
 * absent. Numbers must be finite; integers must fit an int. */
void lutil_opt_number(lua_State *L, int t, const char *fn, const char *field, float *out);
void lutil_opt_integer(lua_State *L, int t, const char *fn, const char *field, int *out);
void lutil_opt_boolean(lua_State *L, int t, const char *fn, const char *field, bool *out);
void lutil_opt_vec3(lua_State *L, int t, const char *fn, const char *field, vec3 *out);
void lutil_opt_color(lua_State *L, int t, const char *fn, const char *field, vec3 *out);
/* A square or rectangular extent: one number s (both sides) or {x, z}. */
void lutil_opt_extent(lua_State *L, int t, const char *fn, const char *field, float *x, float *z);
/* An enum field: the index of its string in `options` (NULL-terminated),
 * `default_index` when absent; luaL_checkoption's rule with the field's name. */
int lutil_opt_option(lua_State *L, int t, const char *fn, const char *field, const char *const *options,
                     int default_index);
/* A finite number (every number a script gives is checked with isfinite). */
float lutil_check_number(lua_State *L, int idx, const char *fn, const char *field);
/* A userdata class as Lua's own libraries make them: the metatable `name`
 * with the metamethods `meta` (__gc, __tostring, ...), an __index that
 * finds `methods` first and then calls the getter of `getters` for the key
 * (getter(self) -> value), an __newindex that calls the setter of `setters`
 * (setter(self, key, value)) or says which fields there are, and a
 * __metatable field so that a script cannot reach __gc. Any table may be
 * NULL. `what` names the class in messages ("object has no field 'x'"). */
void lutil_class(lua_State *L, const char *name, const char *what, const luaL_Reg *meta, const luaL_Reg *methods,
                 const luaL_Reg *getters, const luaL_Reg *setters);
/* Assigns each field of the option table at `options` that `fields` names
 * (in that order) to the userdata at `object`, through its setters. */
void lutil_assign_fields(lua_State *L, int object, int options, const char *const *fields);
/* "script.lua:12" of the Lua code that called the running C function. */
void lutil_where(lua_State *L, char *out, size_t outlen);

#endif
