/* GLFW: a window for `caustica run`. The scene is still rendered into FBOs;
 * the window only shows the tone-mapped result. */
#include <stdio.h>
#include <stdlib.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "gl/gl_api.h"
#include "gl/gl_context.h"

static gl_proc glfw_get_proc(const char *name) { return (gl_proc)glfwGetProcAddress(name); }

static char glfw_last_error[512];

static void glfw_error_callback(int code, const char *description)
{
    (void)code;
    snprintf(glfw_last_error, sizeof glfw_last_error, "%s", description);
}

static bool glfw_create(struct gl_context *ctx, int width, int height, const char *title, struct error *err)
{
    glfwSetErrorCallback(glfw_error_callback);
    if (!glfwInit())
        return error_set(err, "cannot open a window: %s (is DISPLAY set? try xvfb-run -a)",
                         glfw_last_error[0] ? glfw_last_error : "glfwInit failed");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    GLFWwindow *window = glfwCreateWindow(width, height, title ? title : "caustica", NULL, NULL);
    if (!window) {
        glfwTerminate();
        return error_set(err, "cannot create a window with an OpenGL 4.5 core context: %s", glfw_last_error);
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(1);
    ctx->native = window;
    ctx->window = window;
    if (!gl_api_load(glfw_get_proc, err)) {
        glfwDestroyWindow(window);
        glfwTerminate();
        ctx->native = ctx->window = NULL;
        return false;
    }
    return true;
}

static void glfw_destroy(struct gl_context *ctx)
{
    if (ctx->native) {
        glfwDestroyWindow(ctx->native);
        glfwTerminate();
    }
    ctx->native = ctx->window = NULL;
}

const struct gl_context_ops gl_context_glfw_ops = {"glfw", glfw_create, glfw_destroy};
