/* The Lua host: a state per scene script with the caustica modules, the
 * script's parameters (--set), a sandbox unless --trusted, and errors that
 * carry "file:line: message" plus a short traceback. */
#ifndef CAUSTICA_LUA_HOST_H
#define CAUSTICA_LUA_HOST_H

#include <stdbool.h>
#include <stddef.h>

#include <lua.h>

#include "core/error.h"

struct pass;
struct pass_frame;
struct scene;
struct graph;
struct image;
struct ref_options;

#define LUA_PARAMS_MAX 64

struct lua_params {
    int count;
    char keys[LUA_PARAMS_MAX][64];
    char values[LUA_PARAMS_MAX][256];
};

/* Adds "k=v"; false with a message when malformed or too many. */
bool lua_params_add(struct lua_params *params, const char *assignment, struct error *err);

/* What c.image.render and c.image.reference ask of the application (the
 * Lua layer cannot open sessions itself: they live above it). */
#define LUA_RENDER_MAX_PASSES 64
struct lua_render_request {
    const char *script; /* resolved path */
    struct lua_params params;
    int width, height;  /* 0: the script's size */
    int frame;
    const struct ref_options *reference; /* NULL: render the graph on the GPU */
    bool without_caustics;  /* reference: the image less its caustic part (what refraction alone should match) */
};

struct lua_render_reply {
    int pass_count; /* kept passes and their milliseconds (GPU renders) */
    char pass_names[LUA_RENDER_MAX_PASSES][64];
    double pass_ms[LUA_RENDER_MAX_PASSES];
    int iterations; /* reference renders */
    long long photons, caustic_photons;
    double caustic_power[3];
    double seconds;
};

/* Renders `request` into `out` (created by the service); false with a message. */
typedef bool (*lua_render_service)(void *context, const struct lua_render_request *request, struct image *out,
                                   struct lua_render_reply *reply, struct error *err);

#define LUA_HOST_ASSET_DIRS_MAX 16

struct lua_host_options {
    const char *root;        /* project folder: lua/ and shaders/ */
    const char *script_path; /* the scene or test script */
    const struct lua_params *params;
    bool trusted;            /* no sandbox */
    const char *write_dir;   /* where a sandboxed script may write (NULL: nowhere) */
    lua_render_service render; /* for c.image.render/reference (tests); NULL: not available */
    void *render_context;
    bool update_refs;        /* caustica test --update-refs */
    const char *filter;      /* caustica test --filter */
    bool report;             /* caustica test --report: keep a thumbnail of every image case, passing too */
    double timeout;          /* seconds one call into the script may run (0: no limit) */
    double memory_limit;     /* bytes of Lua heap (0: no limit) */
    const char *const *read_dirs; /* more folders a sandboxed script may read (--allow-read) */
    int read_dir_count;
    /* Folders c.asset searches, in order, before <root>/scenes/assets
     * (--asset-path, then $CAUSTICA_ASSET_PATH); a sandboxed script may read them. */
    const char *const *asset_dirs;
    int asset_dir_count;
};

/* When the call into a script now in progress must end (monotonic
 * seconds, as log_now), 0 when none is: what the app's watchdog
 * (app/watchdog.c) enforces where the count hook cannot. */
double lua_host_watched_deadline(void);
/* For long loops in C functions a script calls: raises the time limit's
 * Lua error ("script ran longer than S s (in WHERE; …)", at the calling
 * line) once the call's deadline has passed; returns otherwise. Callers
 * hold nothing that the error would leak (results are userdata). */
void lua_host_check_deadline(lua_State *L, const char *where);
/* Around work done for the script that is not the script's own (a nested
 * c.image.render or c.image.reference: its own host holds its calls to
 * the limits, the rendering itself is not script time): the call's
 * deadline stops counting and the watchdog leaves it alone. Returns the
 * seconds that were left (0: no deadline), which resume gives back. */
double lua_host_suspend_deadline(lua_State *L);
void lua_host_resume_deadline(lua_State *L, double left);
lua_State *lua_host_create(const struct lua_host_options *options, struct error *err);
void lua_host_destroy(lua_State *L);
/* Runs a file, leaving `nresults` values on the stack. */
bool lua_host_run_file(lua_State *L, const char *path, int nresults, struct error *err);
/* The line of the return statement the last file run by lua_host_run_file
 * ended with (where its returned table is written), 0 when unknown. */
int lua_host_return_line(lua_State *L);
/* Calls the function at the top of the stack with `nargs` arguments below it. */
bool lua_host_call(lua_State *L, int nargs, int nresults, const char *context, struct error *err);
/* The sandbox's file rules (docs/SECURITY.md). Reading: the script's own
 * folder and below, the project folder (lua/, shaders/, scenes/ assets), the
 * output folder and --allow-read folders. Writing: only inside the output
 * folder the verb allows (none for `render`, the frames folder for `record`)
 * or --allow-write, never through a symbolic link. Both always succeed with
 * --trusted. False with a message naming the path and what to do. */
bool lua_host_check_read(lua_State *L, const char *path, struct error *err);
bool lua_host_check_write(lua_State *L, const char *path, struct error *err);
/* `rel` against the running script's folder (absolute paths unchanged). */
void lua_host_resolve_path(lua_State *L, const char *rel, char *out, size_t outlen);
/* c.asset: `name` found in the asset folders (see lua_host_options), the
 * first that holds it, as an absolute path in `out`; false with a message
 * naming the folders searched. */
bool lua_host_find_asset(lua_State *L, const char *name, char *out, size_t outlen, struct error *err);
/* Memory a script causes outside the Lua heap (its images' pixels) counted
 * against --script-memory with the heap: charge before (or right after)
 * allocating, false with a message when it would pass the limit. */
bool lua_host_charge(lua_State *L, size_t bytes, const char *what, struct error *err);
void lua_host_uncharge(lua_State *L, size_t bytes);
/* What --script-memory leaves the script, for a reader to check a header
 * against before it allocates: 0 when there is no limit (at least 1 when
 * there is one, so that 0 never reads as "none"). */
unsigned long long lua_host_memory_left(lua_State *L);
/* The project folder the host was made with. */
const char *lua_host_root(lua_State *L);
/* The scene or graph userdata at `idx`, or NULL when it is something else. */
struct scene *lua_host_to_scene(lua_State *L, int idx);
struct graph *lua_host_to_graph(lua_State *L, int idx);
const struct lua_host_options *lua_host_options_of(lua_State *L);
/* Parameters given with --set that the script never asked for. */
void lua_host_unused_params(lua_State *L, char *out, size_t outlen);
/* The custom pass: calls its run(ctx) (l_pass_context.c). */
bool lua_host_run_custom_pass(struct pass *p, struct pass_frame *f, struct error *err);

int luaopen_caustica_scene(lua_State *L);
int luaopen_caustica_graph(lua_State *L);
int luaopen_caustica_image(lua_State *L);
int luaopen_caustica_host(lua_State *L);

#endif
