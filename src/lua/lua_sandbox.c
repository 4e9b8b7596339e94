/* The sandbox a scene script runs in unless --trusted (docs/SECURITY.md):
 * os, io, load and require cut down to reading the script's own folder,
 * the project's lua/, shaders/ and scenes/, the --allow-read folders and
 * the output folder, and writing only where the verb writes. */
#define _GNU_SOURCE
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <lauxlib.h>
#include <lualib.h>

#include "core/fileio.h"
#include "io/image.h"
#include "lua/lua_host.h"
#include "lua/lua_host_state.h"
static int sandbox_denied(lua_State *L)
{
    return luaL_error(L, "%s is not available to a sandboxed scene script (run with --trusted to allow it)",
                      lua_tostring(L, lua_upvalueindex(1)));
}

static void deny(lua_State *L, const char *lib, const char *name)
{
    if (lua_getglobal(L, lib) != LUA_TTABLE) {
        lua_pop(L, 1);
        return;
    }
    lua_pushfstring(L, "%s.%s", lib, name);
    lua_pushcclosure(L, sandbox_denied, 1);
    lua_setfield(L, -2, name);
    lua_pop(L, 1);
}

static bool inside(const char *real, const char *root)
{
    size_t n = strlen(root);
    if (n == 1 && root[0] == '/')
        return true;
    return strncmp(real, root, n) == 0 && (real[n] == '\0' || real[n] == '/');
}

/* The real path of `path`, or of its folder (plus the last component) when
 * the file does not exist yet. */
static bool real_path_of(const char *path, char *out, bool *exists)
{
    if (realpath(path, out)) {
        *exists = true;
        return true;
    }
    *exists = false;
    char dir[4096], real_dir[PATH_MAX];
    path_dirname(path, dir, sizeof dir);
    if (!realpath(dir, real_dir))
        return false;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    return snprintf(out, PATH_MAX, "%s/%s", real_dir, base) < PATH_MAX;
}

bool lua_host_check_read(lua_State *L, const char *path, struct error *err)
{
    struct host_state *h = lua_host_state_of(L);
    if (!h || h->options.trusted)
        return true;
    /* the file that will be opened: "x.exr:layer/name" opens x.exr, so x.exr is what is checked */
    char file[PATH_MAX];
    if (!image_path_file(path, file, sizeof file))
        return error_set(err, "%.200s...: the path is too long", path);
    char real[PATH_MAX];
    bool exists;
    if (!real_path_of(file, real, &exists))
        return error_set(err, "%s: no such file (its folder does not exist)", file);
    for (int i = 0; i < h->read_root_count; i++)
        if (inside(real, h->read_roots[i]))
            return true;
    return error_set(err, "%s: a sandboxed scene script may read only its own folder, the project's lua/, shaders/ "
                          "and scenes/, and the output folder (add --allow-read DIR, or run with --trusted)", path);
}

bool lua_host_check_write(lua_State *L, const char *path, struct error *err)
{
    struct host_state *h = lua_host_state_of(L);
    if (!h || h->options.trusted)
        return true;
    if (!h->write_dir[0])
        return error_set(err, "%s: a sandboxed scene script may not write files here (render writes only its -o "
                              "image; give --allow-write DIR, or run with --trusted)", path);
    char dir[4096], real_dir[PATH_MAX], real_allowed[PATH_MAX];
    path_dirname(path, dir, sizeof dir);
    if (!realpath(dir, real_dir) || !realpath(h->write_dir, real_allowed) || !inside(real_dir, real_allowed))
        return error_set(err, "%s: a sandboxed scene script may write only inside %s (run with --trusted to allow "
                              "it)", path, h->write_dir);
    /* The last component must not be a link out of the folder (or into it:
     * the link may be changed between the check and the write). */
    struct stat st;
    if (lstat(path, &st) == 0 && S_ISLNK(st.st_mode))
        return error_set(err, "%s: is a symbolic link; a sandboxed scene script does not write through links", path);
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    if (!base[0] || strcmp(base, ".") == 0 || strcmp(base, "..") == 0)
        return error_set(err, "%s: not a file name", path);
    return true;
}

static int raise_error(lua_State *L, const struct error *err)
{
    luaL_where(L, 1);
    lua_pushstring(L, err->message);
    lua_concat(L, 2);
    return lua_error(L);
}

/* io.open with the sandbox's read and write rules. */
static int sandbox_io_open(lua_State *L)
{
    const char *path = luaL_checkstring(L, 1);
    const char *mode = luaL_optstring(L, 2, "r");
    struct error err;
    bool writes = strpbrk(mode, "wa+") != NULL;
    if (writes ? !lua_host_check_write(L, path, &err) : !lua_host_check_read(L, path, &err))
        return raise_error(L, &err);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
}

/* io.lines(file) and io.input(file) read: the read rule. */
static int sandbox_io_read_file(lua_State *L)
{
    if (lua_type(L, 1) == LUA_TSTRING) {
        struct error err;
        if (!lua_host_check_read(L, lua_tostring(L, 1), &err))
            return raise_error(L, &err);
    }
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
    return lua_gettop(L);
}

/* load/loadfile accept text only: a crafted binary chunk can crash Lua.
 * The mode is forced to "t"; the environment argument is passed on only
 * when the caller gave one (Lua's load tells "no env" from an explicit
 * nil by the argument count: padding it would give every chunk a nil
 * _ENV, so that any global it touched failed). */
static int sandbox_load(lua_State *L)
{
    int n = lua_gettop(L);
    if (n < 1)
        return luaL_argerror(L, 1, "value expected");
    int nargs = n >= 4 ? 4 : 3;
    lua_settop(L, nargs);
    lua_pushstring(L, "t");
    lua_replace(L, 3);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, nargs, LUA_MULTRET);
    return lua_gettop(L);
}

static int sandbox_loadfile(lua_State *L)
{
    if (lua_type(L, 1) != LUA_TSTRING)
        return luaL_error(L, "loadfile needs a file name in a sandboxed scene script (no standard input)");
    struct error err;
    if (!lua_host_check_read(L, lua_tostring(L, 1), &err))
        return raise_error(L, &err);
    int nargs = lua_gettop(L) >= 3 ? 3 : 2; /* an environment only when given, as for load */
    lua_settop(L, nargs);
    lua_pushstring(L, "t");
    lua_replace(L, 2);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, nargs, LUA_MULTRET);
    return lua_gettop(L);
}

/* require's searcher for Lua files, text chunks only and under the read rule
 * (the standard one loads binary chunks: string.dump output written to a
 * file and required ran, and a patched one crashed the process). */
static int sandbox_lua_searcher(lua_State *L)
{
    const char *name = luaL_checkstring(L, 1);
    lua_getglobal(L, "package");
    lua_getfield(L, -1, "path");
    const char *path = lua_tostring(L, -1);
    if (!path)
        return luaL_error(L, "'package.path' must be a string");
    const char *file = luaL_gsub(L, name, ".", "/");
    luaL_Buffer tried;
    luaL_buffinit(L, &tried);
    char candidate[4096];
    for (const char *p = path; *p;) {
        const char *semi = strchr(p, ';');
        size_t n = semi ? (size_t)(semi - p) : strlen(p);
        if (n > 0 && n < 1024) {
            char tmpl[1024];
            memcpy(tmpl, p, n);
            tmpl[n] = '\0';
            size_t used = 0;
            candidate[0] = '\0';
            for (const char *t = tmpl; *t && used + strlen(file) + 1 < sizeof candidate; t++) {
                if (*t == '?')
                    used += (size_t)snprintf(candidate + used, sizeof candidate - used, "%s", file);
                else
                    candidate[used++] = *t, candidate[used] = '\0';
            }
            FILE *f = fopen(candidate, "r");
            if (f) {
                fclose(f);
                struct error err;
                if (!lua_host_check_read(L, candidate, &err))
                    return raise_error(L, &err);
                if (luaL_loadfilex(L, candidate, "t") != LUA_OK)
                    return luaL_error(L, "error loading module '%s' from file '%s': %s", name, candidate,
                                      lua_tostring(L, -1));
                lua_pushstring(L, candidate);
                return 2;
            }
            luaL_addstring(&tried, "\n\tno file '");
            luaL_addstring(&tried, candidate);
            luaL_addstring(&tried, "'");
        }
        p += n;
        if (*p == ';')
            p++;
    }
    luaL_pushresult(&tried);
    return 1;
}

static void wrap_global(lua_State *L, const char *lib, const char *name, lua_CFunction wrapper)
{
    if (lib) {
        lua_getglobal(L, lib);
        lua_getfield(L, -1, name);
        lua_pushcclosure(L, wrapper, 1);
        lua_setfield(L, -2, name);
        lua_pop(L, 1);
    } else {
        lua_getglobal(L, name);
        lua_pushcclosure(L, wrapper, 1);
        lua_setglobal(L, name);
    }
}

void lua_sandbox_apply(lua_State *L)
{
    deny(L, "os", "execute");
    deny(L, "os", "exit");
    deny(L, "os", "remove");
    deny(L, "os", "rename");
    deny(L, "os", "tmpname");
    deny(L, "os", "getenv");
    deny(L, "os", "setlocale");
    deny(L, "io", "popen");
    deny(L, "io", "output");
    deny(L, "io", "tmpfile");
    deny(L, "package", "loadlib");
    wrap_global(L, "io", "open", sandbox_io_open);
    wrap_global(L, "io", "lines", sandbox_io_read_file);
    wrap_global(L, "io", "input", sandbox_io_read_file);
    wrap_global(L, NULL, "load", sandbox_load);
    wrap_global(L, NULL, "loadfile", sandbox_loadfile);
    /* dofile through the wrapped loadfile. */
    luaL_dostring(L, "local loadfile = loadfile; dofile = function(f) local fn = assert(loadfile(f)); return fn() end");
    /* No C modules, Lua modules as text only, and no debug library (it
     * reaches past every wrapper and every protected metatable). */
    lua_getglobal(L, "package");
    lua_pushstring(L, "");
    lua_setfield(L, -2, "cpath");
    lua_getfield(L, -1, "searchers");
    lua_pushcfunction(L, sandbox_lua_searcher);
    lua_rawseti(L, -2, 2);
    lua_pushnil(L);
    lua_rawseti(L, -2, 4);
    lua_pushnil(L);
    lua_rawseti(L, -2, 3);
    lua_pop(L, 2);
    luaL_dostring(L, "local tb = debug.traceback; debug = { traceback = tb }; package.loaded.debug = debug");
}
