/* The Lua host: one state per scene script, its parameters, assets, memory
 * and time limits, its errors with file and line (the sandbox is
 * lua_sandbox.c). */
#define _GNU_SOURCE
#include "lua/lua_host.h"
#include "lua/lua_pattern.h"
#include "lua/lua_host_state.h"

#include <errno.h>
#include <limits.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <lauxlib.h>
#include <lualib.h>

#include "core/fileio.h"
#include "core/log.h"
#include "core/suggest.h"
#include "io/image.h"



/* The Lua heap, counted by the allocator so that a table bomb becomes a
 * clean "used more than N MB" instead of the machine's OOM killer. */
struct host_memory {
    size_t used, limit;
};

static void *host_alloc(void *ud, void *ptr, size_t osize, size_t nsize)
{
    struct host_memory *m = ud;
    size_t old = ptr ? osize : 0;
    if (nsize == 0) {
        free(ptr);
        m->used -= old;
        return NULL;
    }
    if (m->limit && nsize > old && m->used - old + nsize > m->limit)
        return NULL;
    void *p = realloc(ptr, nsize);
    if (p)
        m->used = m->used - old + nsize;
    return p;
}

/* The host's memory account of a state it made (NULL for any other). */
static struct host_memory *memory_of(lua_State *L)
{
    void *ud = NULL;
    return lua_getallocf(L, &ud) == host_alloc ? ud : NULL;
}

bool lua_host_charge(lua_State *L, size_t bytes, const char *what, struct error *err)
{
    struct host_memory *m = memory_of(L);
    if (!m)
        return true;
    if (m->limit && (bytes > m->limit || m->used > m->limit - bytes))
        return error_set(err, "%s needs %.0f MB, which would take the script past --script-memory %.0f MB (%.0f MB "
                              "in use; raise it, 0 = no limit)", what, (double)bytes / 1048576.0,
                         (double)m->limit / 1048576.0, (double)m->used / 1048576.0);
    m->used += bytes;
    return true;
}

unsigned long long lua_host_memory_left(lua_State *L)
{
    struct host_memory *m = memory_of(L);
    if (!m || !m->limit)
        return 0;
    return m->used < m->limit ? (unsigned long long)(m->limit - m->used) : 1ull;
}

void lua_host_uncharge(lua_State *L, size_t bytes)
{
    struct host_memory *m = memory_of(L);
    if (m)
        m->used = m->used > bytes ? m->used - bytes : 0;
}

/* The deadline of the call into a script now in progress, for the
 * watchdog (lua_host_watched_deadline): the count hook cannot stop work
 * inside a C function (a backtracking string pattern, a long image
 * operation) nor a message handler or finalizer, which run without hooks. */
static _Atomic double watched_deadline;

double lua_host_watched_deadline(void) { return atomic_load(&watched_deadline); }

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

struct host_state *lua_host_state_of(lua_State *L)
{
    lua_getfield(L, LUA_REGISTRYINDEX, HOST_KEY);
    struct host_state *h = lua_touserdata(L, -1);
    lua_pop(L, 1);
    return h;
}

bool lua_params_add(struct lua_params *params, const char *assignment, struct error *err)
{
    const char *eq = strchr(assignment, '=');
    if (!eq || eq == assignment)
        return error_set(err, "--set needs name=value, got '%s'", assignment);
    size_t klen = (size_t)(eq - assignment);
    if (klen >= sizeof params->keys[0] || strlen(eq + 1) >= sizeof params->values[0])
        return error_set(err, "--set '%s' is too long", assignment);
    int at = params->count;
    for (int i = 0; i < params->count; i++)
        if (strlen(params->keys[i]) == klen && strncmp(params->keys[i], assignment, klen) == 0)
            at = i; /* a later --set of the same name wins */
    if (at >= LUA_PARAMS_MAX)
        return error_set(err, "at most %d --set values", LUA_PARAMS_MAX);
    memcpy(params->keys[at], assignment, klen);
    params->keys[at][klen] = '\0';
    snprintf(params->values[at], sizeof params->values[at], "%s", eq + 1);
    if (at == params->count)
        params->count++;
    return true;
}

/* c.param(name, default): the --set value converted to the default's type. */
static int host_param(lua_State *L)
{
    struct host_state *h = lua_host_state_of(L);
    const char *name = luaL_checkstring(L, 1);
    if (lua_isnone(L, 2))
        return luaL_argerror(L, 2, "a default value expected");
    for (int i = 0; i < h->params.count; i++) {
        if (strcmp(h->params.keys[i], name) != 0)
            continue;
        h->used[i] = true;
        const char *v = h->params.values[i];
        switch (lua_type(L, 2)) {
        case LUA_TNUMBER: {
            char *end;
            double d = strtod(v, &end);
            if (end == v || *end)
                return luaL_error(L, "--set %s=%s: a number expected (the default is %s)", name, v, lua_tostring(L, 2));
            if (lua_isinteger(L, 2) && d == (double)(lua_Integer)d)
                lua_pushinteger(L, (lua_Integer)d);
            else
                lua_pushnumber(L, d);
            return 1;
        }
        case LUA_TBOOLEAN:
            if (strcmp(v, "true") == 0 || strcmp(v, "1") == 0 || strcmp(v, "yes") == 0)
                lua_pushboolean(L, 1);
            else if (strcmp(v, "false") == 0 || strcmp(v, "0") == 0 || strcmp(v, "no") == 0)
                lua_pushboolean(L, 0);
            else
                return luaL_error(L, "--set %s=%s: true or false expected", name, v);
            return 1;
        default:
            lua_pushstring(L, v);
            return 1;
        }
    }
    lua_pushvalue(L, 2);
    return 1;
}

void lua_host_unused_params(lua_State *L, char *out, size_t outlen)
{
    struct host_state *h = lua_host_state_of(L);
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; h && i < h->params.count; i++)
        if (!h->used[i]) {
            int w = snprintf(out + used, outlen - used, "%s%s", used ? ", " : "", h->params.keys[i]);
            if (w > 0 && used + (size_t)w < outlen)
                used += (size_t)w;
        }
}

/* The scene's own file: the script, or the glTF file a built-in script
 * stands for (session.c: `caustica render model.glb`). */
static int host_script(lua_State *L)
{
    lua_pushstring(L, lua_host_state_of(L)->script);
    return 1;
}

static int host_script_dir(lua_State *L)
{
    lua_pushstring(L, lua_host_state_of(L)->script_dir);
    return 1;
}

/* For the test harness: {update_refs = bool, filter = string|nil}. */
static int host_test_options(lua_State *L)
{
    struct host_state *h = lua_host_state_of(L);
    lua_createtable(L, 0, 2);
    lua_pushboolean(L, h->options.update_refs);
    lua_setfield(L, -2, "update_refs");
    lua_pushboolean(L, h->options.report);
    lua_setfield(L, -2, "report");
    if (h->options.filter) {
        lua_pushstring(L, h->options.filter);
        lua_setfield(L, -2, "filter");
    }
    /* --script-memory in MB (0: none), for the harness's message when a
     * case runs out of it and catches Lua's bare "not enough memory" */
    lua_pushnumber(L, h->options.memory_limit / (1024.0 * 1024.0));
    lua_setfield(L, -2, "script_memory");
    return 1;
}

/* host.mkdir(path): makes a folder (its parent must exist); trusted scripts only
 * (the test harness writes its failure images). */
static int host_mkdir(lua_State *L)
{
    const char *path = luaL_checkstring(L, 1);
    if (!lua_host_state_of(L)->options.trusted)
        return luaL_error(L, "host.mkdir: only trusted scripts (tests) may make folders");
    struct error err;
    if (!dir_ensure(path, &err))
        return luaL_error(L, "%s", err.message);
    return 0;
}

static int host_root(lua_State *L)
{
    lua_pushstring(L, lua_host_state_of(L)->root);
    return 1;
}

bool lua_host_find_asset(lua_State *L, const char *name, char *out, size_t outlen, struct error *err)
{
    struct host_state *h = lua_host_state_of(L);
    if (!name || !name[0] || name[0] == '/')
        return error_set(err, "c.asset needs a path inside an asset folder (e.g. \"env/room\"), got '%s'",
                         name ? name : "");
    for (const char *p = name; *p; p++)
        if (p[0] == '.' && p[1] == '.' && (p == name || p[-1] == '/') && (p[2] == '/' || !p[2]))
            return error_set(err, "c.asset '%s': '..' may not leave the asset folders", name);
    char searched[1024] = "";
    for (int i = 0; h && i < h->asset_dir_count; i++) {
        char path[PATH_MAX + 512];
        path_join(h->asset_dirs[i], name, path, sizeof path);
        /* an EXR layer ("x.exr:layer") or a cube map's folder both count */
        char file[sizeof path];
        snprintf(file, sizeof file, "%s", path);
        char *layer = strstr(file, ".exr:");
        if (layer)
            layer[4] = '\0';
        if (access(file, R_OK) == 0) {
            if (strlen(path) >= outlen)
                return error_set(err, "c.asset '%s': the path is too long", name);
            snprintf(out, outlen, "%s", path);
            return true;
        }
        size_t n = strlen(searched);
        snprintf(searched + n, sizeof searched - n, "%s%s", n ? ", " : "", h->asset_dirs[i]);
    }
    return error_set(err, "c.asset '%s': not found in the asset folders (%s; add one with --asset-path DIR or "
                     "CAUSTICA_ASSET_PATH)", name, searched);
}

/* host.suggest(word, {names}): the name nearest a misspelt word, or nil. */
static int host_suggest(lua_State *L)
{
    const char *word = luaL_checkstring(L, 1);
    luaL_checktype(L, 2, LUA_TTABLE);
    const char *names[256];
    size_t n = 0;
    lua_Integer len = luaL_len(L, 2);
    for (lua_Integer i = 1; i <= len && n < 256; i++) {
        lua_rawgeti(L, 2, i);
        if (lua_type(L, -1) == LUA_TSTRING)
            names[n++] = lua_tostring(L, -1); /* kept alive by the table */
        lua_pop(L, 1);
    }
    const char *near = suggest_nearest(word, names, n);
    if (near)
        lua_pushstring(L, near);
    else
        lua_pushnil(L);
    return 1;
}

static int host_asset(lua_State *L)
{
    const char *name = luaL_checkstring(L, 1);
    char path[PATH_MAX + 512];
    struct error err;
    if (!lua_host_find_asset(L, name, path, sizeof path, &err))
        return luaL_error(L, "%s", err.message);
    lua_pushstring(L, path);
    return 1;
}

int luaopen_caustica_host(lua_State *L)
{
    static const luaL_Reg funcs[] = {{"param", host_param}, {"script", host_script}, {"script_dir", host_script_dir}, {"root", host_root},
                                     {"asset", host_asset}, {"suggest", host_suggest}, {"test_options", host_test_options}, {"mkdir", host_mkdir}, {NULL, NULL}};
    luaL_newlib(L, funcs);
    return 1;
}

static void timeout_hook(lua_State *L, lua_Debug *ar);

void lua_host_check_deadline(lua_State *L, const char *where)
{
    struct host_state *h = lua_host_state_of(L);
    if (!h || h->deadline <= 0 || now_seconds() < h->deadline)
        return;
    lua_sethook(L, timeout_hook, LUA_MASKCOUNT, 1); /* a pcall around it cannot keep the script going */
    char msg[200];
    snprintf(msg, sizeof msg, "script ran longer than %g s (in %s; raise --script-timeout, 0 = no limit)",
             h->options.timeout, where);
    luaL_where(L, 1);
    lua_pushstring(L, msg);
    lua_concat(L, 2);
    if (!h->limit_message[0])
        snprintf(h->limit_message, sizeof h->limit_message, "%s", lua_tostring(L, -1));
    lua_error(L);
}

double lua_host_suspend_deadline(lua_State *L)
{
    struct host_state *h = lua_host_state_of(L);
    if (!h || h->deadline <= 0)
        return 0.0;
    double left = h->deadline - now_seconds();
    atomic_store(&watched_deadline, 0.0);
    return left > 0.0 ? left : 1e-9; /* an overdue call stays overdue */
}

void lua_host_resume_deadline(lua_State *L, double left)
{
    struct host_state *h = lua_host_state_of(L);
    if (!h || left <= 0.0 || h->deadline <= 0)
        return;
    h->deadline = now_seconds() + left;
    atomic_store(&watched_deadline, h->deadline);
}

/* The same limit inside the pattern matcher (lua_pattern.c), which asks
 * every 2^20 steps; the error names the script's line that called it. */
static void pattern_deadline(lua_State *L) { lua_host_check_deadline(L, "a string pattern"); }

/* The time limit: a count hook looks at the clock every 10,000 VM
 * instructions. The error it raises can be caught by a pcall in the script
 * (`while true do pcall(loop) end`), so once the deadline has passed it
 * fires on every instruction: the first one run after a pcall caught the
 * error raises it again, one level further out, until it reaches the top. */
static void timeout_hook(lua_State *L, lua_Debug *ar)
{
    struct host_state *h = lua_host_state_of(L);
    if (!h || h->deadline <= 0 || now_seconds() < h->deadline)
        return;
    lua_sethook(L, timeout_hook, LUA_MASKCOUNT, 1);
    lua_getinfo(L, "Sl", ar);
    if (ar->currentline > 0)
        lua_pushfstring(L, "%s:%d: ", ar->short_src, ar->currentline);
    else
        lua_pushstring(L, "");
    char msg[160];
    snprintf(msg, sizeof msg, "script ran longer than %g s (raise --script-timeout, 0 = no limit)",
             h->options.timeout);
    lua_pushstring(L, msg);
    lua_concat(L, 2);
    if (!h->limit_message[0])
        snprintf(h->limit_message, sizeof h->limit_message, "%s", lua_tostring(L, -1));
    lua_error(L);
}

/* The hook while a file's main chunk runs: the time limit's count, and the
 * line the chunk returns from (its returned table's errors name it). Only
 * the outermost function's return is looked at. */
static void run_file_hook(lua_State *L, lua_Debug *ar)
{
    if (ar->event != LUA_HOOKRET) {
        timeout_hook(L, ar);
        return;
    }
    lua_Debug caller;
    if (lua_getstack(L, 1, &caller))
        return; /* a function the chunk called */
    struct host_state *h = lua_host_state_of(L);
    if (h && lua_getinfo(L, "l", ar) && ar->currentline > 0)
        h->return_line = ar->currentline;
}

int lua_host_return_line(lua_State *L)
{
    struct host_state *h = lua_host_state_of(L);
    return h ? h->return_line : 0;
}

/* ---- state ----------------------------------------------------------- */

static void add_read_root(struct host_state *h, const char *dir)
{
    if (!dir || !dir[0] || h->read_root_count >= (int)(sizeof h->read_roots / sizeof h->read_roots[0]))
        return;
    if (realpath(dir, h->read_roots[h->read_root_count]))
        h->read_root_count++;
}

lua_State *lua_host_create(const struct lua_host_options *options, struct error *err)
{
    struct host_memory *mem = calloc(1, sizeof *mem);
    if (!mem) {
        error_set(err, "cannot create a Lua state (out of memory)");
        return NULL;
    }
    mem->limit = options->memory_limit > 0 ? (size_t)options->memory_limit : 0;
    lua_State *L = lua_newstate(host_alloc, mem);
    if (!L) {
        free(mem);
        error_set(err, "cannot create a Lua state (out of memory)");
        return NULL;
    }
    luaL_openlibs(L);
    struct host_state *h = lua_newuserdatauv(L, sizeof *h, 0);
    memset(h, 0, sizeof *h);
    h->options = *options;
    if (options->params)
        h->params = *options->params;
    snprintf(h->root, sizeof h->root, "%s", options->root);
    snprintf(h->script, sizeof h->script, "%s", options->script_path ? options->script_path : "");
    /* Absolute, so that paths made from it mean the same to every module
     * (shader paths that are not absolute are read from shaders/). */
    char dir[4096];
    path_dirname(h->script, dir, sizeof dir);
    if (!realpath(dir, h->script_dir))
        snprintf(h->script_dir, sizeof h->script_dir, "%s", dir);
    snprintf(h->write_dir, sizeof h->write_dir, "%s", options->write_dir ? options->write_dir : "");
    snprintf(h->filter, sizeof h->filter, "%s", options->filter ? options->filter : "");
    h->options.filter = options->filter ? h->filter : NULL;
    h->options.params = &h->params;
    h->options.write_dir = options->write_dir ? h->write_dir : NULL;
    h->options.read_dirs = NULL;
    h->options.read_dir_count = 0;
    add_read_root(h, h->script_dir);
    add_read_root(h, h->root);
    add_read_root(h, h->write_dir);
    for (int i = 0; i < options->read_dir_count; i++)
        add_read_root(h, options->read_dirs[i]);
    h->options.asset_dirs = NULL;
    h->options.asset_dir_count = 0;
    char project_assets[sizeof h->root + 32];
    snprintf(project_assets, sizeof project_assets, "%s/scenes/assets", h->root);
    for (int i = 0; i <= options->asset_dir_count && h->asset_dir_count <= LUA_HOST_ASSET_DIRS_MAX; i++) {
        const char *folder = i < options->asset_dir_count ? options->asset_dirs[i] : project_assets;
        if (folder && folder[0] && realpath(folder, h->asset_dirs[h->asset_dir_count])) {
            add_read_root(h, h->asset_dirs[h->asset_dir_count]);
            h->asset_dir_count++;
        } else if (folder && folder[0] && i < options->asset_dir_count) {
            log_warn("asset folder %s: %s (left out of the search)", folder, strerror(errno));
        }
    }
    lua_setfield(L, LUA_REGISTRYINDEX, HOST_KEY);
    if (options->timeout > 0)
        lua_sethook(L, timeout_hook, LUA_MASKCOUNT, 10000);
    /* string.find, match, gmatch and gsub with a matcher that looks at the
     * clock as it works: a backtracking pattern ends with the time limit's
     * error in the script, not by the watchdog ending the process */
    lua_getglobal(L, "string");
    lua_pattern_register(L, -1, pattern_deadline);
    lua_pop(L, 1);

    /* Modules: the C ones preloaded, the Lua ones from <root>/lua. */
    lua_getglobal(L, "package");
    lua_pushfstring(L, "%s/lua/?.lua;%s/lua/?/init.lua;%s/?.lua", h->root, h->root, h->script_dir);
    lua_setfield(L, -2, "path");
    lua_getfield(L, -1, "preload");
    lua_pushcfunction(L, luaopen_caustica_scene);
    lua_setfield(L, -2, "caustica.scene");
    lua_pushcfunction(L, luaopen_caustica_graph);
    lua_setfield(L, -2, "caustica.graph");
    lua_pushcfunction(L, luaopen_caustica_image);
    lua_setfield(L, -2, "caustica.image");
    lua_pushcfunction(L, luaopen_caustica_host);
    lua_setfield(L, -2, "caustica.host");
    lua_pop(L, 2);
    if (!options->trusted)
        lua_sandbox_apply(L);
    return L;
}

void lua_host_destroy(lua_State *L)
{
    if (!L)
        return;
    void *mem;
    lua_getallocf(L, &mem);
    /* finalizers (__gc) run here without hooks: the watchdog holds them to
     * the script's time limit (at most 5 s) */
    struct host_state *h = lua_host_state_of(L);
    /* a nested host (c.image.render from a test) is destroyed inside its
     * caller's call: the caller's deadline is watched again afterwards */
    double outer = atomic_load(&watched_deadline);
    if (h && h->options.timeout > 0)
        atomic_store(&watched_deadline, now_seconds() + (h->options.timeout < 5.0 ? h->options.timeout : 5.0));
    lua_close(L);
    atomic_store(&watched_deadline, outer);
    free(mem);
}

const struct lua_host_options *lua_host_options_of(lua_State *L)
{
    struct host_state *h = lua_host_state_of(L);
    return h ? &h->options : NULL;
}

const char *lua_host_root(lua_State *L)
{
    struct host_state *h = lua_host_state_of(L);
    return h ? h->root : ".";
}

void lua_host_resolve_path(lua_State *L, const char *rel, char *out, size_t outlen)
{
    struct host_state *h = lua_host_state_of(L);
    path_join(h ? h->script_dir : ".", rel, out, outlen);
}

/* Message handler: the error plus the script frames of the traceback. */
static int message_handler(lua_State *L)
{
    const char *msg = lua_tostring(L, 1);
    if (!msg) {
        if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING)
            msg = lua_tostring(L, -1);
        else
            msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
    }
    luaL_traceback(L, L, msg, 1);
    return 1;
}

/* Keeps the first line (the message) and the traceback lines that point
 * into Lua files, dropping C frames; no traceback when it adds nothing. */
static void format_error(const char *raw, const char *context, struct error *err)
{
    char out[ERROR_MESSAGE_MAX];
    const char *nl = strchr(raw, '\n');
    size_t first = nl ? (size_t)(nl - raw) : strlen(raw);
    int used = snprintf(out, sizeof out, "%.*s%s%s", (int)first, raw, context ? " " : "", context ? context : "");
    if (log_verbose() && nl && used > 0 && (size_t)used < sizeof out) {
        /* --verbose: Lua's whole traceback, C frames included. */
        snprintf(out + used, sizeof out - (size_t)used, "%s", nl);
        error_set(err, "%s", out);
        return;
    }
    int frames = 0;
    char trace[ERROR_MESSAGE_MAX] = "";
    size_t tused = 0;
    const char *line = nl ? nl + 1 : NULL;
    while (line && *line) {
        const char *next = strchr(line, '\n');
        size_t n = next ? (size_t)(next - line) : strlen(line);
        const char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        bool keep = strncmp(p, "[C]", 3) != 0 && strncmp(p, "stack traceback", 15) != 0 && strstr(p, ".lua:") &&
                    strstr(p, "[C]: in ?") == NULL;
        if (keep && tused + n + 8 < sizeof trace) {
            tused += (size_t)snprintf(trace + tused, sizeof trace - tused, "\n  %.*s", (int)(n - (size_t)(p - line)), p);
            frames++;
        }
        line = next ? next + 1 : NULL;
    }
    if (frames > 1 && used > 0 && (size_t)used < sizeof out)
        snprintf(out + used, sizeof out - (size_t)used, "\nstack traceback:%.*s",
                 (int)(sizeof out - (size_t)used - 18), trace);
    error_set(err, "%s", out);
}

bool lua_host_call(lua_State *L, int nargs, int nresults, const char *context, struct error *err)
{
    struct host_state *h = lua_host_state_of(L);
    /* The time limit counts from the outermost call into the script. A
     * host made inside another's call (c.image.render of a test) watches
     * its own deadline while it runs and gives the caller's back when its
     * call ends: the watchdog is never left disarmed. */
    double outer = atomic_load(&watched_deadline);
    if (h && h->call_depth == 0)
        h->limit_message[0] = '\0';
    bool watch_return = h && h->call_depth == 0 && h->watch_return;
    if (h && h->call_depth++ == 0 && h->options.timeout > 0) {
        h->deadline = now_seconds() + h->options.timeout;
        atomic_store(&watched_deadline, h->deadline);
        lua_sethook(L, timeout_hook, LUA_MASKCOUNT, 10000);
    }
    if (watch_return) /* the count only where there is a time limit (its hook reads the clock) */
        lua_sethook(L, run_file_hook, LUA_MASKRET | (h->options.timeout > 0 ? LUA_MASKCOUNT : 0), 10000);
    int base = lua_gettop(L) - nargs;
    lua_pushcfunction(L, message_handler);
    lua_insert(L, base);
    int rc = lua_pcall(L, nargs, nresults, base);
    lua_remove(L, base);
    if (h && --h->call_depth == 0) {
        h->deadline = 0;
        atomic_store(&watched_deadline, outer);
        if (watch_return) {
            h->watch_return = false;
            if (h->options.timeout > 0)
                lua_sethook(L, timeout_hook, LUA_MASKCOUNT, 10000);
            else
                lua_sethook(L, NULL, 0, 0);
        }
    }
    if (rc == LUA_ERRMEM) {
        void *ud;
        lua_getallocf(L, &ud);
        const struct host_memory *mem = ud;
        lua_pop(L, 1);
        lua_gc(L, LUA_GCCOLLECT);
        if (!mem->limit)
            return error_set(err, "%s: out of memory%s%s", h ? h->script : "script", context ? " " : "",
                             context ? context : "");
        return error_set(err, "%s: the script used more than %.0f MB of memory (raise --script-memory MB, 0 = no "
                              "limit)%s%s", h ? h->script : "script", (double)mem->limit / (1024.0 * 1024.0),
                         context ? " " : "", context ? context : "");
    }
    if (rc != LUA_OK) {
        /* a time limit met inside a pcall: the line where it was met */
        const char *raised = lua_tostring(L, -1) ? lua_tostring(L, -1) : "(error)";
        if (h && h->call_depth == 0 && h->limit_message[0] && strstr(raised, "script ran longer than"))
            raised = h->limit_message;
        format_error(raised, context, err);
        lua_pop(L, 1);
        return false;
    }
    return true;
}

bool lua_host_run_file(lua_State *L, const char *path, int nresults, struct error *err)
{
    if (!file_exists(path))
        return error_set(err, "%s: no such file", path);
    int rc = luaL_loadfilex(L, path, "t");
    if (rc != LUA_OK) {
        /* Syntax errors already read "file:line: message". */
        format_error(lua_tostring(L, -1), NULL, err);
        lua_pop(L, 1);
        return false;
    }
    struct host_state *h = lua_host_state_of(L);
    if (h && h->call_depth == 0) {
        h->watch_return = true;
        h->return_line = 0;
    }
    return lua_host_call(L, 0, nresults, NULL, err);
}
