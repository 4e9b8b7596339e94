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
};

/* Finds the project folder: $CAUSTICA_ROOT, else the build's source folder. */
void app_init(struct app *app);
bool app_ensure_gl(struct app *app, struct error *err);
void app_shutdown(struct app *app);

#endif
