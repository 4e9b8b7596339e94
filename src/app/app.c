#include "app/app.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fileio.h"

#ifndef CAUSTICA_SOURCE_DIR
#define CAUSTICA_SOURCE_DIR "."
#endif

void app_init(struct app *app)
{
    memset(app, 0, sizeof *app);
    const char *env = getenv("CAUSTICA_ROOT");
    snprintf(app->root, sizeof app->root, "%s", env && env[0] ? env : CAUSTICA_SOURCE_DIR);
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
