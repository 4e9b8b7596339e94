#include "app/techniques.h"

#include <stdio.h>
#include <string.h>

#include <lauxlib.h>

/* A scalar of the declaration as text: numbers as Lua writes them, true/false, strings. */
static bool scalar_text(lua_State *L, int index, char *out, size_t size)
{
    int type = lua_type(L, index);
    if (type != LUA_TNUMBER && type != LUA_TSTRING && type != LUA_TBOOLEAN)
        return false;
    size_t n;
    const char *text = luaL_tolstring(L, index, &n); /* pushes */
    bool fits = n < size && n > 0 && !strchr(text, ',') && !strchr(text, ' ');
    if (fits)
        snprintf(out, size, "%s", text);
    lua_pop(L, 1);
    return fits;
}

/* Sorts a point's assignments by key (pairs() order is not stable). */
static void point_sort(struct technique_point *p)
{
    for (int i = 1; i < p->count; i++)
        for (int j = i; j > 0 && strcmp(p->keys[j - 1], p->keys[j]) > 0; j--) {
            char tk[64], tv[64];
            memcpy(tk, p->keys[j], 64);
            memcpy(tv, p->values[j], 64);
            memcpy(p->keys[j], p->keys[j - 1], 64);
            memcpy(p->values[j], p->values[j - 1], 64);
            memcpy(p->keys[j - 1], tk, 64);
            memcpy(p->values[j - 1], tv, 64);
        }
}

/* Appends key=value to a point (a later value of the same key wins). */
static bool point_set(struct technique_point *p, const char *key, const char *value)
{
    int at = p->count;
    for (int i = 0; i < p->count; i++)
        if (strcmp(p->keys[i], key) == 0)
            at = i;
    if (at >= TECHNIQUE_ASSIGNMENTS_MAX)
        return false;
    snprintf(p->keys[at], sizeof p->keys[at], "%s", key);
    snprintf(p->values[at], sizeof p->values[at], "%s", value);
    if (at == p->count)
        p->count++;
    return true;
}

#define FAIL(...) do { error_set(err, __VA_ARGS__); lua_settop(L, top); return false; } while (0)

/* points = { {key = value, ...}, ... } */
static bool read_points(lua_State *L, int t, const char *script, struct technique *tech, struct error *err)
{
    int top = lua_gettop(L);
    if (lua_getfield(L, t, "points") == LUA_TNIL) {
        lua_settop(L, top);
        return true;
    }
    if (!lua_istable(L, -1))
        FAIL("%s: techniques: %s.points must be a list of settings {[\"pass.param\"] = value, ...}", script, tech->name);
    lua_Integer n = luaL_len(L, -1);
    for (lua_Integer i = 1; i <= n; i++) {
        if (tech->point_count >= TECHNIQUE_POINTS_MAX)
            FAIL("%s: techniques: %s has more than %d settings", script, tech->name, TECHNIQUE_POINTS_MAX);
        if (lua_rawgeti(L, -1, i) != LUA_TTABLE)
            FAIL("%s: techniques: %s.points[%lld] must be a table {[\"pass.param\"] = value, ...}", script, tech->name,
                 (long long)i);
        struct technique_point *p = &tech->points[tech->point_count++];
        memset(p, 0, sizeof *p);
        lua_pushnil(L);
        while (lua_next(L, -2)) {
            char value[64];
            if (lua_type(L, -2) != LUA_TSTRING || !scalar_text(L, -1, value, sizeof value) ||
                !point_set(p, lua_tostring(L, -2), value))
                FAIL("%s: techniques: %s.points[%lld]: keys are \"pass.param\" or scene parameters, values numbers, "
                     "booleans or words (at most %d)", script, tech->name, (long long)i, TECHNIQUE_ASSIGNMENTS_MAX);
            lua_pop(L, 1);
        }
        point_sort(p);
        lua_pop(L, 1);
    }
    lua_settop(L, top);
    return true;
}

/* sweep = { ["pass.param"] = {v1, v2, ...}, ... }: every combination. */
static bool read_sweep(lua_State *L, int t, const char *script, struct technique *tech, struct error *err)
{
    int top = lua_gettop(L);
    if (lua_getfield(L, t, "sweep") == LUA_TNIL) {
        lua_settop(L, top);
        return true;
    }
    if (!lua_istable(L, -1))
        FAIL("%s: techniques: %s.sweep must be a table {[\"pass.param\"] = {v1, v2, ...}}", script, tech->name);
    int sweep = lua_gettop(L);
    /* the keys in a stable (sorted) order: pairs() order is not */
    char keys[TECHNIQUE_ASSIGNMENTS_MAX][64];
    int nkeys = 0;
    lua_pushnil(L);
    while (lua_next(L, sweep)) {
        if (lua_type(L, -2) != LUA_TSTRING || !lua_istable(L, -1) || nkeys >= TECHNIQUE_ASSIGNMENTS_MAX ||
            strlen(lua_tostring(L, -2)) >= sizeof keys[0])
            FAIL("%s: techniques: %s.sweep: each key a \"pass.param\" or scene parameter, each value a list", script,
                 tech->name);
        snprintf(keys[nkeys++], sizeof keys[0], "%s", lua_tostring(L, -2));
        lua_pop(L, 1);
    }
    for (int i = 1; i < nkeys; i++)
        for (int j = i; j > 0 && strcmp(keys[j - 1], keys[j]) > 0; j--) {
            char tmp[64];
            memcpy(tmp, keys[j], sizeof tmp);
            memcpy(keys[j], keys[j - 1], sizeof tmp);
            memcpy(keys[j - 1], tmp, sizeof tmp);
        }
    int counts[TECHNIQUE_ASSIGNMENTS_MAX], combos = 1;
    for (int k = 0; k < nkeys; k++) {
        lua_getfield(L, sweep, keys[k]);
        counts[k] = (int)luaL_len(L, -1);
        lua_pop(L, 1);
        if (counts[k] < 1)
            FAIL("%s: techniques: %s.sweep[\"%s\"] is empty", script, tech->name, keys[k]);
        combos *= counts[k];
        if (tech->point_count + combos > TECHNIQUE_POINTS_MAX)
            FAIL("%s: techniques: %s has more than %d settings (the sweep's combinations count)", script, tech->name,
                 TECHNIQUE_POINTS_MAX);
    }
    for (int c = 0; nkeys > 0 && c < combos; c++) {
        struct technique_point *p = &tech->points[tech->point_count++];
        memset(p, 0, sizeof *p);
        int rest = c;
        for (int k = nkeys - 1; k >= 0; k--) {
            int v = rest % counts[k];
            rest /= counts[k];
            lua_getfield(L, sweep, keys[k]);
            lua_rawgeti(L, -1, v + 1);
            char value[64];
            if (!scalar_text(L, -1, value, sizeof value))
                FAIL("%s: techniques: %s.sweep[\"%s\"][%d] must be a number, boolean or word", script, tech->name,
                     keys[k], v + 1);
            lua_pop(L, 2);
            point_set(p, keys[k], value);
        }
        point_sort(p); /* the keys in order, as a point's are */
    }
    lua_settop(L, top);
    return true;
}

bool techniques_read(const struct session *s, struct technique_list *out, struct error *err)
{
    lua_State *L = s->L;
    const char *script = s->script;
    int top = lua_gettop(L);
    memset(out, 0, sizeof *out);
    lua_rawgeti(L, LUA_REGISTRYINDEX, s->result_ref);
    if (lua_getfield(L, -1, "techniques") != LUA_TTABLE)
        FAIL("%s: the script returns no 'techniques' table, which `--sweep technique=...` and `choose` need: return "
             "techniques = { { \"plain\" }, { \"photons\", sweep = { [\"caustics.buffer\"] = {128, 512} } }, ... } "
             "(docs/LUA_API.md)", script);
    int list = lua_gettop(L);
    const char *param = "technique";
    if (lua_getfield(L, list, "param") != LUA_TNIL && !lua_isstring(L, -1))
        FAIL("%s: techniques.param must be the name of the scene parameter that selects the technique", script);
    char param_name[64];
    snprintf(param_name, sizeof param_name, "%s", lua_isstring(L, -1) ? lua_tostring(L, -1) : param);
    lua_pop(L, 1);
    out->metric = TECHNIQUE_METRIC_CAUSTIC;
    if (lua_getfield(L, list, "metric") != LUA_TNIL) {
        const char *m = lua_isstring(L, -1) ? lua_tostring(L, -1) : "";
        if (strcmp(m, "image") == 0)
            out->metric = TECHNIQUE_METRIC_IMAGE;
        else if (strcmp(m, "caustic") != 0)
            FAIL("%s: techniques.metric must be \"caustic\" (the caustic region's error) or \"image\" (the whole "
                 "image's)", script);
    }
    lua_pop(L, 1);
    lua_Integer n = luaL_len(L, list);
    if (n < 1 || n > TECHNIQUES_MAX)
        FAIL("%s: techniques must list 1 to %d techniques, it lists %lld", script, TECHNIQUES_MAX, (long long)n);
    for (lua_Integer i = 1; i <= n; i++) {
        struct technique *tech = &out->items[out->count++];
        if (lua_rawgeti(L, list, i) != LUA_TTABLE)
            FAIL("%s: techniques[%lld] must be a table { \"name\", set = {...}, sweep = {...}, points = {...} }", script,
                 (long long)i);
        int t = lua_gettop(L);
        lua_rawgeti(L, t, 1);
        if (!scalar_text(L, -1, tech->name, sizeof tech->name) || lua_type(L, -1) != LUA_TSTRING)
            FAIL("%s: techniques[%lld] needs its name first: { \"photons\", ... }", script, (long long)i);
        lua_pop(L, 1);
        for (int j = 0; j < out->count - 1; j++)
            if (strcmp(out->items[j].name, tech->name) == 0)
                FAIL("%s: techniques: two are named '%s'", script, tech->name);
        if (lua_getfield(L, t, "set") == LUA_TNIL) {
            tech->set_count = 1;
            snprintf(tech->set_keys[0], sizeof tech->set_keys[0], "%s", param_name);
            memcpy(tech->set_values[0], tech->name, sizeof tech->set_values[0]); /* same size */
        } else {
            if (!lua_istable(L, -1))
                FAIL("%s: techniques: %s.set must be a table of scene parameters {technique = ..., ...}", script,
                     tech->name);
            lua_pushnil(L);
            while (lua_next(L, -2)) {
                if (lua_type(L, -2) != LUA_TSTRING || tech->set_count >= 4 ||
                    !scalar_text(L, -1, tech->set_values[tech->set_count], sizeof tech->set_values[0]) ||
                    strlen(lua_tostring(L, -2)) >= sizeof tech->set_keys[0])
                    FAIL("%s: techniques: %s.set: at most 4 scene parameters, name = value", script, tech->name);
                snprintf(tech->set_keys[tech->set_count++], sizeof tech->set_keys[0], "%s", lua_tostring(L, -2));
                lua_pop(L, 1);
            }
        }
        lua_pop(L, 1);
        tech->point_count = 1; /* point 0: the defaults */
        memset(&tech->points[0], 0, sizeof tech->points[0]);
        if (!read_sweep(L, t, script, tech, err) || !read_points(L, t, script, tech, err)) {
            lua_settop(L, top);
            return false;
        }
        lua_settop(L, list);
    }
    lua_settop(L, top);
    return true;
}

bool techniques_select(struct technique_list *list, const char *names, struct error *err)
{
    if (strcmp(names, "all") == 0)
        return true;
    struct technique_list kept = *list;
    kept.count = 0;
    for (const char *p = names; *p;) {
        const char *comma = strchr(p, ',');
        size_t n = comma ? (size_t)(comma - p) : strlen(p);
        int found = -1;
        for (int i = 0; i < list->count; i++)
            if (strlen(list->items[i].name) == n && strncmp(list->items[i].name, p, n) == 0)
                found = i;
        if (found < 0) {
            char known[600] = "";
            for (int i = 0; i < list->count; i++)
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", i ? ", " : "",
                         list->items[i].name);
            return error_set(err, "--sweep technique: the scene declares no technique '%.*s' (it has: %s, or all)",
                             (int)n, p, known);
        }
        kept.items[kept.count++] = list->items[found];
        p = comma ? comma + 1 : p + n;
    }
    *list = kept;
    return true;
}

void technique_point_label(const struct technique_point *p, char *out, size_t size)
{
    if (p->count == 0) {
        snprintf(out, size, "defaults");
        return;
    }
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; i < p->count && used < size; i++) {
        int w = snprintf(out + used, size - used, "%s%s=%s", i ? " " : "", p->keys[i], p->values[i]);
        if (w < 0)
            break;
        used += (size_t)w;
    }
}

bool technique_point_parse(const char *label, struct technique_point *out)
{
    memset(out, 0, sizeof *out);
    if (strcmp(label, "defaults") == 0)
        return true;
    for (const char *p = label; *p;) {
        size_t n = strcspn(p, " ");
        const char *eq = memchr(p, '=', n);
        if (!eq || eq == p || out->count >= TECHNIQUE_ASSIGNMENTS_MAX || (size_t)(eq - p) >= sizeof out->keys[0] ||
            n - (size_t)(eq - p) - 1 >= sizeof out->values[0])
            return false;
        snprintf(out->keys[out->count], sizeof out->keys[0], "%.*s", (int)(eq - p), p);
        snprintf(out->values[out->count++], sizeof out->values[0], "%.*s", (int)(n - (size_t)(eq - p) - 1), eq + 1);
        p += n;
        p += strspn(p, " ");
    }
    return true;
}

bool technique_key_is_pass(const char *key)
{
    return strchr(key, '.') != NULL;
}

bool techniques_is_selector(const struct technique_list *list, const char *key)
{
    for (int i = 0; i < list->count; i++)
        for (int j = 0; j < list->items[i].set_count; j++)
            if (strcmp(list->items[i].set_keys[j], key) == 0)
                return true;
    return false;
}
