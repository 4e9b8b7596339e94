#include "gl/gl_context.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_api.h"

bool gl_backend_parse(const char *name, enum gl_backend *out)
{
    if (strcmp(name, "osmesa") == 0)
        *out = GL_BACKEND_OSMESA;
    else if (strcmp(name, "egl") == 0)
        *out = GL_BACKEND_EGL;
    else if (strcmp(name, "glfw") == 0 || strcmp(name, "window") == 0)
        *out = GL_BACKEND_GLFW;
    else
        return false;
    return true;
}

const char *gl_backend_name(enum gl_backend backend)
{
    switch (backend) {
    case GL_BACKEND_OSMESA: return "osmesa";
    case GL_BACKEND_EGL: return "egl";
    case GL_BACKEND_GLFW: return "glfw";
    }
    return "?";
}

bool gl_context_create(enum gl_backend backend, int width, int height, const char *title,
                       struct gl_context **out, struct error *err)
{
    struct gl_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx)
        return error_set(err, "out of memory creating the GL context");
    ctx->backend = backend;
    ctx->ops = backend == GL_BACKEND_OSMESA ? &gl_context_osmesa_ops
             : backend == GL_BACKEND_EGL    ? &gl_context_egl_ops
                                            : &gl_context_glfw_ops;
    if (!ctx->ops->create(ctx, width, height, title, err)) {
        error_prefix(err, "%s backend", ctx->ops->name);
        free(ctx);
        return false;
    }
    /* ops->create loaded the function table; check the version we got. */
    GLint major = 0, minor = 0;
    gl.GetIntegerv(GL_MAJOR_VERSION, &major);
    gl.GetIntegerv(GL_MINOR_VERSION, &minor);
    const char *renderer = (const char *)gl.GetString(GL_RENDERER);
    const char *version = (const char *)gl.GetString(GL_VERSION);
    snprintf(ctx->renderer, sizeof ctx->renderer, "%s", renderer ? renderer : "?");
    snprintf(ctx->version, sizeof ctx->version, "%s", version ? version : "?");
    if (major * 10 + minor < 45) {
        error_set(err, "%s backend: OpenGL 4.5 core is needed, the driver gives %d.%d (%s)",
                  ctx->ops->name, major, minor, ctx->renderer);
        gl_context_destroy(ctx);
        return false;
    }
    *out = ctx;
    return true;
}

void gl_context_destroy(struct gl_context *ctx)
{
    if (!ctx)
        return;
    gl_api_unload();
    ctx->ops->destroy(ctx);
    free(ctx);
}
