/* An OpenGL 4.5 core context from one of three backends. Rendering always
 * goes into framebuffer objects, so every backend produces the same pixels;
 * the window backend only adds presenting to the screen. */
#ifndef CAUSTICA_GL_CONTEXT_H
#define CAUSTICA_GL_CONTEXT_H

#include <stdbool.h>

#include "core/error.h"

enum gl_backend { GL_BACKEND_OSMESA, GL_BACKEND_EGL, GL_BACKEND_GLFW };

struct gl_context;

/* Per-backend operations (gl_context_osmesa.c, gl_context_egl.c, gl_context_glfw.c). */
struct gl_context_ops {
    const char *name;
    bool (*create)(struct gl_context *ctx, int width, int height, const char *title, struct error *err);
    void (*destroy)(struct gl_context *ctx);
};

struct gl_context {
    enum gl_backend backend;
    const struct gl_context_ops *ops;
    void *native;      /* backend state (owned, released by ops->destroy) */
    void *window;      /* GLFWwindow* for the window backend (borrowed from native) */
    char renderer[256];
    char version[256];
};

bool gl_backend_parse(const char *name, enum gl_backend *out);
const char *gl_backend_name(enum gl_backend backend);

/* Creates the context, makes it current and loads the GL function table. */
bool gl_context_create(enum gl_backend backend, int width, int height, const char *title,
                       struct gl_context **out, struct error *err);
void gl_context_destroy(struct gl_context *ctx);

extern const struct gl_context_ops gl_context_osmesa_ops;
extern const struct gl_context_ops gl_context_egl_ops;
extern const struct gl_context_ops gl_context_glfw_ops;

#endif
