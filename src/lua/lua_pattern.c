/* Lua patterns with a step budget (see lua_pattern.h). The matcher is the
 * backtracking one the Lua 5.4 manual's §6.4.1 specifies: single-character
 * classes, sets, the four repetitions (* greedy, - lazy, + and ?),
 * anchors, captures (with position captures and back-references), %b and
 * %f. What is added is a step count: every call of match(), every
 * character a repetition, a balance or a back-reference scans, so that the
 * clock is asked in proportion to the work done however the pattern spends
 * it. tests/unit/test_lua_pattern.c checks it against the stock string
 * library on a few thousand random and hand-written cases. */
#define _GNU_SOURCE /* memmem */
#include "lua/lua_pattern.h"

#include <ctype.h>
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include <lauxlib.h>

#define PATTERN_ESC '%'
#define PATTERN_SPECIALS "^$*+?.([%-"
#define PATTERN_MAX_CAPTURES 32   /* LUA_MAXCAPTURES */
#define PATTERN_MAX_DEPTH 200     /* MAXCCALLS: recursion depth of match() */
#define PATTERN_CLOCK_EVERY (1u << 20)

enum { CAPTURE_UNFINISHED = -1, CAPTURE_POSITION = -2 };

struct pattern_config {
    lua_pattern_deadline_fn check_deadline;
};

struct match_state {
    const char *src_init, *src_end; /* the subject */
    const char *p_end;              /* the pattern's end */
    lua_State *L;
    const struct pattern_config *config;
    int depth_left;
    unsigned long steps; /* since the clock was last asked */
    int level;           /* captures open or closed */
    struct {
        const char *init;
        ptrdiff_t len;
    } capture[PATTERN_MAX_CAPTURES];
};

static void count_steps(struct match_state *ms, size_t n)
{
    ms->steps += n + 1;
    if (ms->steps >= PATTERN_CLOCK_EVERY) {
        ms->steps = 0;
        if (ms->config && ms->config->check_deadline)
            ms->config->check_deadline(ms->L);
    }
}

static const char *match(struct match_state *ms, const char *s, const char *p);

static int check_capture(struct match_state *ms, int l)
{
    l -= '1';
    if (l < 0 || l >= ms->level || ms->capture[l].len == CAPTURE_UNFINISHED)
        return luaL_error(ms->L, "invalid capture index %%%d", l + 1);
    return l;
}

static int capture_to_close(struct match_state *ms)
{
    for (int level = ms->level - 1; level >= 0; level--)
        if (ms->capture[level].len == CAPTURE_UNFINISHED)
            return level;
    return luaL_error(ms->L, "invalid pattern capture");
}

static const char *class_end_scan(struct match_state *ms, const char *p);

/* The end of the single-character class at p (a set's scan counted as
 * steps: it is work however often the same set is met). */
static const char *class_end(struct match_state *ms, const char *p)
{
    const char *end = class_end_scan(ms, p);
    count_steps(ms, (size_t)(end - p));
    return end;
}

static const char *class_end_scan(struct match_state *ms, const char *p)
{
    char c = *p++;
    if (c == PATTERN_ESC) {
        if (p == ms->p_end)
            luaL_error(ms->L, "malformed pattern (ends with '%%')");
        return p + 1;
    }
    if (c == '[') {
        if (*p == '^')
            p++;
        do { /* the first character is in the set even when it is ']' */
            if (p == ms->p_end)
                luaL_error(ms->L, "malformed pattern (missing ']')");
            if (*(p++) == PATTERN_ESC && p < ms->p_end)
                p++; /* an escape such as %] */
        } while (*p != ']');
        return p + 1;
    }
    return p;
}

static bool match_class(int c, int cl)
{
    bool res;
    switch (tolower(cl)) {
    case 'a': res = isalpha(c); break;
    case 'c': res = iscntrl(c); break;
    case 'd': res = isdigit(c); break;
    case 'g': res = isgraph(c); break;
    case 'l': res = islower(c); break;
    case 'p': res = ispunct(c); break;
    case 's': res = isspace(c); break;
    case 'u': res = isupper(c); break;
    case 'w': res = isalnum(c); break;
    case 'x': res = isxdigit(c); break;
    case 'z': res = c == 0; break; /* deprecated in 5.2, still accepted */
    default: return cl == c; /* %. %% %] ...: the character itself */
    }
    return isupper(cl) ? !res : res; /* %A is the complement of %a */
}

/* c against the set [...] from p (at '[') to ec (at its ']'). */
static bool match_set(int c, const char *p, const char *ec)
{
    bool in = true;
    if (*(p + 1) == '^') {
        in = false;
        p++;
    }
    while (++p < ec) {
        if (*p == PATTERN_ESC) {
            p++;
            if (match_class(c, (unsigned char)*p))
                return in;
        } else if (*(p + 1) == '-' && p + 2 < ec) {
            p += 2;
            if ((unsigned char)*(p - 2) <= c && c <= (unsigned char)*p)
                return in;
        } else if ((unsigned char)*p == c) {
            return in;
        }
    }
    return !in;
}

static bool single_match(struct match_state *ms, const char *s, const char *p, const char *ep)
{
    if (s >= ms->src_end)
        return false;
    int c = (unsigned char)*s;
    switch (*p) {
    case '.': return true;
    case PATTERN_ESC: return match_class(c, (unsigned char)*(p + 1));
    case '[':
        count_steps(ms, (size_t)(ep - p)); /* a set is scanned character by character: a 1 MB set costs 1 MB */
        return match_set(c, p, ep - 1);
    default: return (unsigned char)*p == c;
    }
}

static const char *match_balance(struct match_state *ms, const char *s, const char *p)
{
    if (p >= ms->p_end - 1)
        luaL_error(ms->L, "malformed pattern (missing arguments to '%%b')");
    if (s >= ms->src_end || *s != *p)
        return NULL;
    int open = *p, close = *(p + 1), depth = 1;
    const char *start = s;
    while (++s < ms->src_end) {
        if (*s == close) {
            if (--depth == 0) {
                count_steps(ms, (size_t)(s - start));
                return s + 1;
            }
        } else if (*s == open) {
            depth++;
        }
    }
    count_steps(ms, (size_t)(s - start));
    return NULL;
}

/* x* and x+: as many as match, then fewer until the rest matches. */
static const char *max_expand(struct match_state *ms, const char *s, const char *p, const char *ep)
{
    ptrdiff_t i = 0;
    while (single_match(ms, s + i, p, ep))
        i++;
    count_steps(ms, (size_t)i);
    for (; i >= 0; i--) {
        const char *res = match(ms, s + i, ep + 1);
        if (res)
            return res;
    }
    return NULL;
}

/* x-: as few as let the rest match. */
static const char *min_expand(struct match_state *ms, const char *s, const char *p, const char *ep)
{
    for (;;) {
        const char *res = match(ms, s, ep + 1);
        if (res)
            return res;
        if (!single_match(ms, s, p, ep))
            return NULL;
        s++;
    }
}

static const char *start_capture(struct match_state *ms, const char *s, const char *p, int what)
{
    int level = ms->level;
    if (level >= PATTERN_MAX_CAPTURES)
        luaL_error(ms->L, "too many captures");
    ms->capture[level].init = s;
    ms->capture[level].len = what;
    ms->level = level + 1;
    const char *res = match(ms, s, p);
    if (!res)
        ms->level--; /* undo the capture */
    return res;
}

static const char *end_capture(struct match_state *ms, const char *s, const char *p)
{
    int l = capture_to_close(ms);
    ms->capture[l].len = s - ms->capture[l].init;
    const char *res = match(ms, s, p);
    if (!res)
        ms->capture[l].len = CAPTURE_UNFINISHED;
    return res;
}

static const char *match_capture(struct match_state *ms, const char *s, int l)
{
    l = check_capture(ms, l);
    size_t len = (size_t)ms->capture[l].len;
    count_steps(ms, len);
    if ((size_t)(ms->src_end - s) >= len && memcmp(ms->capture[l].init, s, len) == 0)
        return s + len;
    return NULL;
}

/* The end of the match of pattern p at s, or NULL. Tail positions loop
 * (goto next) rather than recurse, as the depth limit counts recursion. */
static const char *match(struct match_state *ms, const char *s, const char *p)
{
    if (ms->depth_left-- == 0)
        luaL_error(ms->L, "pattern too complex");
next:
    count_steps(ms, 0);
    if (p != ms->p_end) {
        switch (*p) {
        case '(':
            if (p + 1 < ms->p_end && *(p + 1) == ')')
                s = start_capture(ms, s, p + 2, CAPTURE_POSITION);
            else
                s = start_capture(ms, s, p + 1, CAPTURE_UNFINISHED);
            break;
        case ')':
            s = end_capture(ms, s, p + 1);
            break;
        case '$':
            if (p + 1 != ms->p_end)
                goto single;
            s = s == ms->src_end ? s : NULL;
            break;
        case PATTERN_ESC:
            switch (*(p + 1)) {
            case 'b':
                s = match_balance(ms, s, p + 2);
                if (s) {
                    p += 4;
                    goto next;
                }
                break;
            case 'f': { /* the frontier %f[set]: the previous character not in it, this one in it */
                p += 2;
                if (*p != '[')
                    luaL_error(ms->L, "missing '[' after '%%f' in pattern");
                const char *ep = class_end(ms, p);
                int previous = s == ms->src_init ? '\0' : (unsigned char)*(s - 1);
                int current = s < ms->src_end ? (unsigned char)*s : '\0';
                if (!match_set(previous, p, ep - 1) && match_set(current, p, ep - 1)) {
                    p = ep;
                    goto next;
                }
                s = NULL;
                break;
            }
            case '0': case '1': case '2': case '3': case '4':
            case '5': case '6': case '7': case '8': case '9':
                s = match_capture(ms, s, (unsigned char)*(p + 1));
                if (s) {
                    p += 2;
                    goto next;
                }
                break;
            default:
                goto single;
            }
            break;
        default:
        single: {
            const char *ep = class_end(ms, p);
            char repeat = ep < ms->p_end ? *ep : '\0';
            if (!single_match(ms, s, p, ep)) {
                if (repeat == '*' || repeat == '?' || repeat == '-') { /* zero repetitions are a match */
                    p = ep + 1;
                    goto next;
                }
                s = NULL;
            } else {
                switch (repeat) {
                case '?': {
                    const char *res = match(ms, s + 1, ep + 1);
                    if (res) {
                        s = res;
                    } else {
                        p = ep + 1;
                        goto next;
                    }
                    break;
                }
                case '+': s = max_expand(ms, s + 1, p, ep); break;
                case '*': s = max_expand(ms, s, p, ep); break;
                case '-': s = min_expand(ms, s, p, ep); break;
                default:
                    s++;
                    p = ep;
                    goto next;
                }
            }
            break;
        }
        }
    }
    ms->depth_left++;
    return s;
}

/* ---- captures -------------------------------------------------------- */

/* Capture i as a string (its length returned, *cap set) or, for a
 * position capture, pushed as an integer (CAPTURE_POSITION returned). */
static ptrdiff_t get_capture(struct match_state *ms, int i, const char *s, const char *e, const char **cap)
{
    if (i >= ms->level) {
        if (i != 0)
            luaL_error(ms->L, "invalid capture index %%%d", i + 1);
        *cap = s; /* no captures: the whole match */
        return e - s;
    }
    ptrdiff_t len = ms->capture[i].len;
    *cap = ms->capture[i].init;
    if (len == CAPTURE_UNFINISHED)
        luaL_error(ms->L, "unfinished capture");
    else if (len == CAPTURE_POSITION)
        lua_pushinteger(ms->L, (ms->capture[i].init - ms->src_init) + 1);
    return len;
}

static void push_capture(struct match_state *ms, int i, const char *s, const char *e)
{
    const char *cap;
    ptrdiff_t len = get_capture(ms, i, s, e, &cap);
    if (len != CAPTURE_POSITION)
        lua_pushlstring(ms->L, cap, (size_t)len);
}

static int push_captures(struct match_state *ms, const char *s, const char *e)
{
    int n = (ms->level == 0 && s) ? 1 : ms->level;
    luaL_checkstack(ms->L, n, "too many captures");
    for (int i = 0; i < n; i++)
        push_capture(ms, i, s, e);
    return n;
}

/* ---- the library functions --------------------------------------------- */

static void state_init(struct match_state *ms, lua_State *L, const struct pattern_config *config, const char *s,
                       size_t ls, const char *p, size_t lp)
{
    ms->L = L;
    ms->config = config;
    ms->steps = 0;
    ms->src_init = s;
    ms->src_end = s + ls;
    ms->p_end = p + lp;
}

static void state_reset(struct match_state *ms)
{
    ms->level = 0;
    ms->depth_left = PATTERN_MAX_DEPTH;
}

static const struct pattern_config *config_of(lua_State *L)
{
    return lua_touserdata(L, lua_upvalueindex(1));
}

/* A relative start position (negative: from the end) as 1..len+1. */
static size_t start_position(lua_Integer pos, size_t len)
{
    if (pos > 0)
        return (size_t)pos;
    if (pos == 0)
        return 1;
    if (pos < -(lua_Integer)len)
        return 1;
    return len + (size_t)pos + 1;
}

static bool has_specials(const char *p, size_t lp)
{
    size_t upto = 0;
    do { /* a pattern may hold zeros: look past each */
        if (strpbrk(p + upto, PATTERN_SPECIALS))
            return true;
        upto += strlen(p + upto) + 1;
    } while (upto <= lp);
    return false;
}

static int find_or_match(lua_State *L, bool find)
{
    size_t ls, lp;
    const char *s = luaL_checklstring(L, 1, &ls);
    const char *p = luaL_checklstring(L, 2, &lp);
    size_t init = start_position(luaL_optinteger(L, 3, 1), ls) - 1;
    if (init > ls) {
        luaL_pushfail(L);
        return 1;
    }
    if (find && (lua_toboolean(L, 4) || !has_specials(p, lp))) {
        /* memmem: linear (two-way), where a naive search is quadratic */
        const char *at = lp == 0 ? s + init : memmem(s + init, ls - init, p, lp);
        if (at) {
            lua_pushinteger(L, (at - s) + 1);
            lua_pushinteger(L, (lua_Integer)((size_t)(at - s) + lp));
            return 2;
        }
    } else {
        struct match_state ms;
        const char *s1 = s + init;
        bool anchor = *p == '^';
        if (anchor) {
            p++;
            lp--;
        }
        state_init(&ms, L, config_of(L), s, ls, p, lp);
        do {
            state_reset(&ms);
            const char *e = match(&ms, s1, p);
            if (e) {
                if (find) {
                    lua_pushinteger(L, (s1 - s) + 1);
                    lua_pushinteger(L, e - s);
                    return push_captures(&ms, NULL, 0) + 2;
                }
                return push_captures(&ms, s1, e);
            }
        } while (s1++ < ms.src_end && !anchor);
    }
    luaL_pushfail(L);
    return 1;
}

static int pattern_find(lua_State *L) { return find_or_match(L, true); }

static int pattern_match(lua_State *L) { return find_or_match(L, false); }

struct gmatch_state {
    const char *src, *p, *last_match;
    struct match_state ms;
};

static int gmatch_next(lua_State *L)
{
    struct gmatch_state *gm = lua_touserdata(L, lua_upvalueindex(3));
    gm->ms.L = L; /* the iterator may be called from another coroutine */
    for (const char *src = gm->src; src <= gm->ms.src_end; src++) {
        state_reset(&gm->ms);
        const char *e = match(&gm->ms, src, gm->p);
        if (e && e != gm->last_match) {
            gm->src = gm->last_match = e;
            return push_captures(&gm->ms, src, e);
        }
    }
    return 0;
}

static int pattern_gmatch(lua_State *L)
{
    size_t ls, lp;
    const char *s = luaL_checklstring(L, 1, &ls);
    const char *p = luaL_checklstring(L, 2, &lp);
    size_t init = start_position(luaL_optinteger(L, 3, 1), ls) - 1;
    const struct pattern_config *config = config_of(L);
    lua_settop(L, 2); /* the subject and the pattern stay alive as upvalues */
    struct gmatch_state *gm = lua_newuserdatauv(L, sizeof *gm, 0);
    if (init > ls)
        init = ls + 1; /* past the end: no match */
    state_init(&gm->ms, L, config, s, ls, p, lp);
    gm->src = s + init;
    gm->p = p;
    gm->last_match = NULL;
    lua_pushvalue(L, lua_upvalueindex(1)); /* the config, kept alive too */
    lua_pushcclosure(L, gmatch_next, 4);
    return 1;
}

/* The replacement string with %0..%9 and %%. */
static void add_replacement_string(struct match_state *ms, luaL_Buffer *b, const char *s, const char *e)
{
    lua_State *L = ms->L;
    size_t l;
    const char *news = lua_tolstring(L, 3, &l);
    count_steps(ms, l); /* every byte of the replacement is copied for every match */
    const char *p;
    while ((p = memchr(news, PATTERN_ESC, l)) != NULL) {
        luaL_addlstring(b, news, (size_t)(p - news));
        p++;
        if (*p == PATTERN_ESC) {
            luaL_addchar(b, *p);
        } else if (*p == '0') {
            count_steps(ms, (size_t)(e - s));
            luaL_addlstring(b, s, (size_t)(e - s));
        } else if (isdigit((unsigned char)*p)) {
            const char *cap;
            ptrdiff_t len = get_capture(ms, *p - '1', s, e, &cap);
            if (len == CAPTURE_POSITION) {
                luaL_addvalue(b);
            } else {
                count_steps(ms, (size_t)len);
                luaL_addlstring(b, cap, (size_t)len);
            }
        } else {
            luaL_error(L, "invalid use of '%c' in replacement string", PATTERN_ESC);
        }
        l -= (size_t)(p + 1 - news);
        news = p + 1;
    }
    luaL_addlstring(b, news, l);
}

/* Adds the replacement of the match s..e; false when it kept the match
 * (a function or table gave false or nil). */
static bool add_replacement(struct match_state *ms, luaL_Buffer *b, const char *s, const char *e, int type)
{
    lua_State *L = ms->L;
    switch (type) {
    case LUA_TFUNCTION: {
        lua_pushvalue(L, 3);
        int n = push_captures(ms, s, e);
        lua_call(L, n, 1);
        break;
    }
    case LUA_TTABLE:
        push_capture(ms, 0, s, e);
        lua_gettable(L, 3);
        break;
    default:
        add_replacement_string(ms, b, s, e);
        return true;
    }
    if (!lua_toboolean(L, -1)) {
        lua_pop(L, 1);
        luaL_addlstring(b, s, (size_t)(e - s));
        return false;
    }
    if (!lua_isstring(L, -1))
        luaL_error(L, "invalid replacement value (a %s)", luaL_typename(L, -1));
    luaL_addvalue(b);
    return true;
}

static int pattern_gsub(lua_State *L)
{
    size_t srcl, lp;
    const char *src = luaL_checklstring(L, 1, &srcl);
    const char *p = luaL_checklstring(L, 2, &lp);
    const char *last_match = NULL;
    int type = lua_type(L, 3);
    lua_Integer max_n = luaL_optinteger(L, 4, (lua_Integer)srcl + 1);
    bool anchor = *p == '^';
    lua_Integer n = 0;
    bool changed = false;
    luaL_argexpected(L, type == LUA_TNUMBER || type == LUA_TSTRING || type == LUA_TFUNCTION || type == LUA_TTABLE, 3,
                     "string/function/table");
    luaL_Buffer b;
    luaL_buffinit(L, &b);
    if (anchor) {
        p++;
        lp--;
    }
    struct match_state ms;
    state_init(&ms, L, config_of(L), src, srcl, p, lp);
    while (n < max_n) {
        state_reset(&ms);
        const char *e = match(&ms, src, p);
        if (e && e != last_match) {
            n++;
            changed = add_replacement(&ms, &b, src, e, type) || changed;
            src = last_match = e;
        } else if (src < ms.src_end) {
            luaL_addchar(&b, *src++);
        } else {
            break;
        }
        if (anchor)
            break;
    }
    if (!changed) {
        lua_pushvalue(L, 1); /* the subject itself */
    } else {
        luaL_addlstring(&b, src, (size_t)(ms.src_end - src));
        luaL_pushresult(&b);
    }
    lua_pushinteger(L, n);
    return 2;
}

void lua_pattern_register(lua_State *L, int table, lua_pattern_deadline_fn check_deadline)
{
    table = lua_absindex(L, table);
    static const luaL_Reg functions[] = {{"find", pattern_find},
                                         {"match", pattern_match},
                                         {"gmatch", pattern_gmatch},
                                         {"gsub", pattern_gsub},
                                         {NULL, NULL}};
    for (const luaL_Reg *f = functions; f->name; f++) {
        struct pattern_config *config = lua_newuserdatauv(L, sizeof *config, 0);
        config->check_deadline = check_deadline;
        lua_pushcclosure(L, f->func, 1);
        lua_setfield(L, table, f->name);
    }
}
