/* Lua's string pattern functions (string.find, match, gmatch, gsub) with
 * a bounded matcher: the same patterns, results and error messages as the
 * Lua 5.4 manual's §6.4.1 describes, but a matcher that counts its steps
 * and asks the host's clock every 2^20 of them, so that a backtracking
 * pattern (`("a?"):rep(40) .. ("a"):rep(40)` against 40 a's is ~2^40
 * steps) ends with the script's time-limit error, raised in the calling
 * script like any other, instead of running where the count hook cannot
 * reach it. Plain finds use a linear search (memmem) rather than the
 * quadratic one. */
#ifndef CAUSTICA_LUA_PATTERN_H
#define CAUSTICA_LUA_PATTERN_H

#include <lua.h>

/* Called every 2^20 matcher steps: raises a Lua error (and does not
 * return) when the call's time is up. */
typedef void (*lua_pattern_deadline_fn)(lua_State *L);

/* Sets find, match, gmatch and gsub in the table at `table` (the string
 * library's table, which is also the strings' __index, so ("x"):find is
 * covered too). */
void lua_pattern_register(lua_State *L, int table, lua_pattern_deadline_fn check_deadline);

#endif
