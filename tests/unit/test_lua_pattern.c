/* The bounded pattern functions (src/lua/lua_pattern.c) against Lua's own
 * string library: the same results and the same error messages for
 * hand-written cases (every feature of the manual's §6.4.1 and its error
 * paths) and for 6,000 random patterns over the special characters; then
 * what they add: the clock is asked while a backtracking pattern runs, and
 * a plain find is linear. */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include <lauxlib.h>
#include <lualib.h>

#include "check.h"
#include "lua/lua_pattern.h"

static int deadline_calls;

/* A deadline that has passed at the first look. */
static void deadline_passed(lua_State *L)
{
    deadline_calls++;
    luaL_error(L, "deadline passed");
}

static void deadline_counting(lua_State *L)
{
    (void)L;
    deadline_calls++;
}

static const char *const differential =
    "local B = ...\n"
    "local function pack(ok, ...) return { ok = ok, n = select('#', ...), ... } end\n"
    "local function show(r) local t = {} for i = 1, r.n do t[i] = tostring(r[i]) end\n"
    "  return (r.ok and 'ok ' or 'error ') .. table.concat(t, ',') end\n"
    "local function same(a, b)\n"
    "  if a.ok ~= b.ok or a.n ~= b.n then return false end\n"
    "  for i = 1, a.n do if a[i] ~= b[i] then return false end end\n"
    "  return true end\n"
    "local function all(iter) local out = {} for i = 1, 200 do\n"
    "  local r = table.pack(iter()) if r[1] == nil then break end\n"
    "  out[#out + 1] = table.concat((function() local t = {} for k = 1, r.n do t[k] = tostring(r[k]) end return t end)(), '|') end\n"
    "  return table.concat(out, ';') end\n"
    "local failures, cases = {}, 0\n"
    "local function compare(what, f, g, ...)\n"
    "  cases = cases + 1\n"
    "  local a, b = pack(pcall(f, ...)), pack(pcall(g, ...))\n"
    "  if not same(a, b) and #failures < 10 then\n"
    "    local args = table.pack(...) for i = 1, args.n do args[i] = string.format('%q', tostring(args[i])) end\n"
    "    failures[#failures + 1] = what .. '(' .. table.concat(args, ', ') .. '): lua ' .. show(a) .. ' / bounded ' .. show(b) end end\n"
    "local function gm(lib) return function(s, p, i) return all(lib.gmatch(s, p, i)) end end\n"
    "local repls = { '<%0>', '%1-%%', '%2', '%', 'x%9', {a = 'A', ['()'] = false, b = 1.5},\n"
    "  function(c, d) if c == 'a' then return false end return (c or '') .. '!' end, 7, function() return {} end }\n"
    "local function check(s, p, init)\n"
    "  compare('find', string.find, B.find, s, p, init)\n"
    "  compare('find plain', string.find, B.find, s, p, init, true)\n"
    "  compare('match', string.match, B.match, s, p, init)\n"
    "  compare('gmatch', gm(string), gm(B), s, p, init)\n"
    "  for _, r in ipairs(repls) do compare('gsub', string.gsub, B.gsub, s, p, r) end\n"
    "  compare('gsub n', string.gsub, B.gsub, s, p, '[%0]', 2)\n"
    "end\n"
    "local hand = {\n"
    "  {'hello world', 'o w'}, {'hello world', 'l+'}, {'hello world', 'l-o'}, {'hello', '^h'}, {'hello', 'o$'},\n"
    "  {'hello', '^$'}, {'', '^$'}, {'', ''}, {'abc', ''}, {'a.b', '%.'}, {'x=1, y=22', '(%w+)=(%w+)'},\n"
    "  {'THE (quick) fox', '%f[%a]%a+'}, {'THE (quick) fox', '%b()'}, {'f(a(b)c)d', '%b()'}, {'aaa', 'a-b'},\n"
    "  {'hello hello', '(h)(e)(l)(l)(o) %1%2'}, {'abab', '(ab)%1'}, {'abc', '()b()'}, {'  x  ', '^%s*(.-)%s*$'},\n"
    "  {'a]b', '[]]'}, {'a]b', '[^]]+'}, {'a-b', '[a-]+'}, {'a%b', '[%%]'}, {'a^b', '[b^]'}, {'a$b', '$b'},\n"
    "  {'abc', '%'}, {'abc', '[a'}, {'abc', '[%'}, {'abc', '%b'}, {'abc', '%ba'}, {'abc', '%f'}, {'abc', '%fa'},\n"
    "  {'abc', '(a'}, {'abc', 'a)'}, {'abc', '%1'}, {'abc', '(a%1)'}, {'abc', '%0'}, {'abc', '(()'},\n"
    "  {'0x1F ff', '%x+'}, {'A1_b', '[%w_]+'}, {'A1_b', '%W'}, {'a\\0b', '%z'}, {'a\\0b', '\\0'}, {'a\\0b', '[\\0]'},\n"
    "  {'a\\0b', 'a.b'}, {'caf\\xc3\\xa9', '[\\x80-\\xff]+'}, {'key = value', '(%w+)%s*=%s*(%w+)'},\n"
    "  {'aaab', 'a*b'}, {'aaab', 'a?a?b'}, {'b', 'a*'}, {'ab', '.-$'}, {'x', 'x?x?x?x'}, {'one two', '%a+', -3},\n"
    "  {'one two', '%a+', 100}, {'one two', '%a+', -100}, {'one two', '%a+', 0}, {'^x', '^^x'}, {'x^', 'x^'},\n"
    "  {string.rep('(', 40) .. string.rep(')', 40), '%b()'}, {string.rep('a', 300), string.rep('(a)', 33)},\n"
    "  {'abc', string.rep('(', 250) .. string.rep(')', 250)}, {string.rep('a', 20), string.rep('a?', 20) .. string.rep('a', 20)},\n"
    "}\n"
    "for _, c in ipairs(hand) do check(c[1], c[2], c[3]) end\n"
    "local tokens = { 'a', 'b', '.', '%a', '%d', '%s', '%A', '[ab]', '[^a]', '[a-c]', '(', ')', '()', '*', '+', '-',\n"
    "  '?', '^', '$', '%b()', '%f[%a]', '%f[%A]', '%1', '%2', '%', '[', ']', '%%', 'x', '%.', '1', ' ' }\n"
    "local letters = { 'a', 'a', 'b', '(', ')', 'x', '1', ' ', '.', '%' }\n"
    "math.randomseed(31)\n"
    "for _ = 1, 6000 do\n"
    "  local p = {} for i = 1, math.random(1, 7) do p[i] = tokens[math.random(#tokens)] end\n"
    "  local s = {} for i = 1, math.random(0, 12) do s[i] = letters[math.random(#letters)] end\n"
    "  check(table.concat(s), table.concat(p), math.random(-4, 14))\n"
    "end\n"
    "return cases, table.concat(failures, '\\n')\n";

int main(void)
{
    lua_State *L = luaL_newstate();
    luaL_openlibs(L);

    /* Differential: the stock functions against the bounded ones, side by
     * side in one state (deadline_counting: the clock never says stop). */
    lua_newtable(L);
    lua_pattern_register(L, -1, deadline_counting);
    int bounded = lua_gettop(L);
    CHECK(luaL_loadstring(L, differential) == LUA_OK);
    lua_pushvalue(L, bounded);
    if (lua_pcall(L, 1, 2, 0) != LUA_OK) {
        fprintf(stderr, "differential script: %s\n", lua_tostring(L, -1));
        CHECK(false);
    } else {
        long long cases = lua_tointeger(L, -2);
        const char *failures = lua_tostring(L, -1);
        printf("%lld calls compared\n", cases);
        CHECK(cases > 60000);
        if (failures[0])
            fprintf(stderr, "differences:\n%s\n", failures);
        CHECK(failures[0] == '\0');
        lua_pop(L, 2);
    }

    /* The clock is asked while a backtracking pattern runs (the stock
     * matcher would take ~2^40 steps here): at the first look, the
     * deadline's error comes out of find, gsub and a gmatch iterator. */
    lua_newtable(L);
    lua_pattern_register(L, -1, deadline_passed);
    lua_setglobal(L, "B");
    const char *catastrophic =
        "local s, p = ('a'):rep(40), ('a?'):rep(40) .. ('a'):rep(40) .. 'b'\n"
        "local r = {}\n"
        "r[1] = select(2, pcall(B.find, s, p))\n"
        "r[2] = select(2, pcall(B.gsub, ('x'):rep(100000), '(.-)(.-)(.-)c', ''))\n"
        "r[3] = select(2, pcall(function() for _ in B.gmatch(s, p) do end end))\n"
        "r[4] = select(2, pcall(B.find, ('('):rep(3000) .. (')'):rep(2999), '%b()%b()'))\n"
        "return (table.concat(r, '|'):gsub('%[string [^]]*%]:%d+: ', ''))\n";
    deadline_calls = 0;
    CHECK(luaL_dostring(L, catastrophic) == LUA_OK);
    const char *stopped = lua_tostring(L, -1);
    printf("stopped: %s\n", stopped ? stopped : "(nil)");
    CHECK(stopped && strcmp(stopped, "deadline passed|deadline passed|deadline passed|deadline passed") == 0);
    CHECK(deadline_calls == 4);
    lua_pop(L, 1);

    /* Work that matches nothing backtracking still asks the clock, in
     * proportion to the bytes it scans (issue 55): a 1 MB set tried at 64
     * positions, and a gsub whose 1 MB replacement is copied 64 times.
     * Before, each cost one step: the clock was never asked. */
    lua_newtable(L);
    lua_pattern_register(L, -1, deadline_counting);
    lua_setglobal(L, "C");
    deadline_calls = 0;
    CHECK(luaL_dostring(L, "return C.find(('b'):rep(64), '[' .. ('a'):rep(1 << 20) .. ']')") == LUA_OK);
    CHECK(lua_isnil(L, -1));
    lua_pop(L, 1);
    printf("a 1 MB set at 64 positions: the clock asked %d times\n", deadline_calls);
    CHECK(deadline_calls >= 64);
    deadline_calls = 0;
    CHECK(luaL_dostring(L, "local r, n = C.gsub(('a'):rep(64), 'a', ('x'):rep(1 << 20)) return #r, n") == LUA_OK);
    CHECK(lua_tointeger(L, -2) == 64 << 20 && lua_tointeger(L, -1) == 64);
    lua_pop(L, 2);
    printf("a 1 MB replacement 64 times: the clock asked %d times\n", deadline_calls);
    CHECK(deadline_calls >= 64);
    deadline_calls = 0;
    CHECK(luaL_dostring(L, "local r = C.gsub(('ab'):rep(32), '(a)b', '%1' .. ('y'):rep(1 << 20) .. '%0') return #r") ==
          LUA_OK);
    CHECK(lua_tointeger(L, -1) == 32 * ((1 << 20) + 3));
    lua_pop(L, 1);
    CHECK(deadline_calls >= 32);

    /* A plain find is linear: half a million a's and a 'b' against a
     * million a's (the naive search's n*m is 2.5e11) */
    CHECK(luaL_dostring(L, "return B.find(('a'):rep(1000000), ('a'):rep(500000) .. 'b', 1, true)") == LUA_OK);
    CHECK(lua_isnil(L, -1));
    lua_pop(L, 1);
    CHECK(luaL_dostring(L, "return B.find(('a'):rep(1000000) .. 'b', ('a'):rep(500000) .. 'b', 1, true)") == LUA_OK);
    CHECK(lua_tointeger(L, -1) == 1000001 && lua_tointeger(L, -2) == 500001);
    lua_pop(L, 2);

    lua_close(L);
    return check_finish("test_lua_pattern");
}
