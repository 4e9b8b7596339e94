/* Process-wide state of the command line: the project folder, the GL
 * context (made on first need) and the renderer every session shares. */
#ifndef CAUSTICA_APP_H
#define CAUSTICA_APP_H

#include <stdbool.h>

#include "core/error.h"
#include "gl/gl_context.h"
#include "graph/renderer.h"

struct app {
    char root[4096];
    enum gl_backend backend;
    bool trusted;
    struct gl_context *gl;
    bool renderer_ready;
    struct renderer renderer;
    int window_width, window_height; /* for the window backend */
    /* The sandbox's limits (docs/SECURITY.md): wall time of one script call
     * (seconds, 0 = none) and the Lua heap (bytes, 0 = none). */
    double script_timeout;
    double script_memory;
    const char *allow_read[8]; /* --allow-read DIR: more folders a sandboxed script may read */
    int allow_read_count;
    const char *allow_write;   /* --allow-write DIR: a folder a sandboxed script may write */
    /* Folders c.asset searches before the project's scenes/assets: the
     * --asset-path ones first, then $CAUSTICA_ASSET_PATH's (split at ':'). */
    const char *asset_path[8];
    int asset_path_count;      /* --asset-path folders */
    char asset_env[4096];      /* $CAUSTICA_ASSET_PATH, its ':' made NULs */
    const char *asset_env_dirs[8];
    int asset_env_count;
    int threads;               /* --threads N: the reference's workers (0: the CPUs this process may use) */
    int render_depth;          /* c.image.render nesting (a script that renders itself) */
};

/* Finds the project folder: $CAUSTICA_ROOT; else the folder the binary was
 * installed with (<prefix>/share/caustica beside <prefix>/bin/caustica);
 * else the source tree it was built from. Reads $CAUSTICA_ASSET_PATH. */
void app_init(struct app *app);
bool app_ensure_gl(struct app *app, struct error *err);
void app_shutdown(struct app *app);
/* The asset folders in search order (--asset-path, then $CAUSTICA_ASSET_PATH); returns the count. */
int app_asset_dirs(const struct app *app, const char **dirs, int max);

#endif
