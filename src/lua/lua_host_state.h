/* The Lua host's own state (lua_host.c), shared with the sandbox
 * (lua_sandbox.c); private to src/lua. */
#ifndef CAUSTICA_LUA_HOST_STATE_H
#define CAUSTICA_LUA_HOST_STATE_H

#include <limits.h>
#include <stdbool.h>

#include <lua.h>

#include "lua/lua_host.h"

#define HOST_KEY "caustica.host"

struct host_state {
    struct lua_host_options options;
    struct lua_params params;
    bool used[LUA_PARAMS_MAX];
    char root[4096];
    char script[4096];
    char script_dir[4096];
    char write_dir[4096];
    char filter[256];
    /* Real paths of the folders a sandboxed script may read. */
    char read_roots[24][PATH_MAX];
    int read_root_count;
    /* Real paths of the folders c.asset searches, the project's last. */
    char asset_dirs[LUA_HOST_ASSET_DIRS_MAX + 1][PATH_MAX];
    int asset_dir_count;
    /* The time limit: the call in progress must end by `deadline`. */
    double deadline;
    int call_depth;
    /* The time limit's first error in the call, "file:line: script ran
     * longer than …": once a pcall (a test harness's xpcall too) has
     * caught it, it is raised again wherever the script goes on, so the
     * call's error reports the line where the limit was met. */
    char limit_message[512];
    /* lua_host_run_file: the line of the main chunk's return statement
     * (where the table read_result checks is written), 0 when unknown */
    bool watch_return;
    int return_line;
};

/* The state of the host that made L (NULL outside one). */
struct host_state *lua_host_state_of(lua_State *L);
/* Cuts a sandboxed script's os, io, load and require down (lua_sandbox.c). */
void lua_sandbox_apply(lua_State *L);

#endif
