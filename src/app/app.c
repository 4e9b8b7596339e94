#define _DEFAULT_SOURCE /* readlink */
#include "app/app.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/fileio.h"

#ifndef CAUSTICA_SOURCE_DIR
#define CAUSTICA_SOURCE_DIR "."
#endif

/* <prefix>/share/caustica when this binary is <prefix>/bin/caustica and
 * that folder holds the shaders (an installed copy). */
static bool installed_root(char *out, size_t outlen)
{
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0)
        return false;
    exe[n] = '\0';
    char *slash = strrchr(exe, '/');
    if (!slash)
        return false;
    *slash = '\0';
    char shaders[4096 + 64];
    snprintf(shaders, sizeof shaders, "%s/../share/caustica/shaders", exe);
    if (access(shaders, R_OK) != 0)
        return false;
    return (size_t)snprintf(out, outlen, "%.4000s/../share/caustica", exe) < outlen;
}

void app_init(struct app *app)
{
    memset(app, 0, sizeof *app);
    const char *env = getenv("CAUSTICA_ROOT");
    if (env && env[0])
        snprintf(app->root, sizeof app->root, "%s", env);
    else if (!installed_root(app->root, sizeof app->root))
        snprintf(app->root, sizeof app->root, "%s", CAUSTICA_SOURCE_DIR);
    const char *assets = getenv("CAUSTICA_ASSET_PATH");
    snprintf(app->asset_env, sizeof app->asset_env, "%s", assets ? assets : "");
    for (char *p = app->asset_env; *p && app->asset_env_count < 8;) {
        char *colon = strchr(p, ':');
        if (colon)
            *colon = '\0';
        if (*p)
            app->asset_env_dirs[app->asset_env_count++] = p;
        if (!colon)
            break;
        p = colon + 1;
    }
    app->backend = GL_BACKEND_OSMESA;
    app->window_width = 512;
    app->window_height = 512;
    app->script_timeout = 30.0;
    app->script_memory = 4096.0 * 1024.0 * 1024.0;
}

bool app_ensure_gl(struct app *app, struct error *err)
{
    if (app->renderer_ready)
        return true;
    if (!app->gl && !gl_context_create(app->backend, app->window_width, app->window_height, "caustica", &app->gl, err))
        return false;
    if (!renderer_create(&app->renderer, app->root, err))
        return false;
    app->renderer_ready = true;
    return true;
}

void app_shutdown(struct app *app)
{
    if (app->renderer_ready)
        renderer_destroy(&app->renderer);
    app->renderer_ready = false;
    gl_context_destroy(app->gl);
    app->gl = NULL;
}

int app_asset_dirs(const struct app *app, const char **dirs, int max)
{
    int n = 0;
    for (int i = 0; i < app->asset_path_count && n < max; i++)
        dirs[n++] = app->asset_path[i];
    for (int i = 0; i < app->asset_env_count && n < max; i++)
        dirs[n++] = app->asset_env_dirs[i];
    return n;
}
