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
/* Reads {x, y, z} (or a single number, repeated) at `idx`. */
bool lutil_to_vec3(lua_State *L, int idx, vec3 *out);
/* {x, y, z} of finite numbers: positions, directions, scales. */
vec3 lutil_check_vec3(lua_State *L, int idx, const char *fn, const char *field);
/* {r, g, b} of finite numbers >= 0: colours, intensities, coefficients. */
vec3 lutil_check_color(lua_State *L, int idx, const char *fn, const char *field);
quat lutil_check_quat(lua_State *L, int idx, const char *fn, const char *field);
void lutil_push_vec3(lua_State *L, vec3 v);
void lutil_push_quat(lua_State *L, quat q);
/* Optional fields of the option table at `t`: leave *out unchanged when
 * absent. Numbers must be finite; integers must fit an int. */
void lutil_opt_number(lua_State *L, int t, const char *fn, const char *field, float *out);
void lutil_opt_integer(lua_State *L, int t, const char *fn, const char *field, int *out);
void lutil_opt_vec3(lua_State *L, int t, const char *fn, const char *field, vec3 *out);
void lutil_opt_color(lua_State *L, int t, const char *fn, const char *field, vec3 *out);
/* A finite number (every number a script gives is checked with isfinite). */
float lutil_check_number(lua_State *L, int idx, const char *fn, const char *field);
/* "script.lua:12" of the Lua code that called the running C function. */
void lutil_where(lua_State *L, char *out, size_t outlen);

#endif
