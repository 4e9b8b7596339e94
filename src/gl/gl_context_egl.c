/* EGL without a window: the EGL device platform on a GPU server
 * (EGL_EXT_platform_device), else Mesa's surfaceless platform, else the
 * default display. Rendering goes into FBOs, so no surface is created
 * (EGL_KHR_surfaceless_context). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "gl/gl_api.h"
#include "gl/gl_context.h"

struct egl_state {
    EGLDisplay display;
    EGLContext context;
};

static gl_proc egl_get_proc(const char *name) { return (gl_proc)eglGetProcAddress(name); }

static bool egl_try_display(EGLDisplay dpy, struct egl_state *s)
{
    if (dpy == EGL_NO_DISPLAY)
        return false;
    EGLint major, minor;
    if (!eglInitialize(dpy, &major, &minor))
        return false;
    if (!eglBindAPI(EGL_OPENGL_API)) {
        eglTerminate(dpy);
        return false;
    }
    const EGLint surface_types[] = {EGL_PBUFFER_BIT, 0};
    EGLConfig config = NULL;
    EGLint count = 0;
    for (int i = 0; i < 2 && count == 0; i++) {
        const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                         EGL_SURFACE_TYPE, surface_types[i], EGL_NONE};
        eglChooseConfig(dpy, config_attribs, &config, 1, &count);
    }
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    EGLContext context = eglCreateContext(dpy, count > 0 ? config : (EGLConfig)0, EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) {
        eglTerminate(dpy);
        return false;
    }
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        eglDestroyContext(dpy, context);
        eglTerminate(dpy);
        return false;
    }
    s->display = dpy;
    s->context = context;
    return true;
}

static bool egl_create(struct gl_context *ctx, int width, int height, const char *title, struct error *err)
{
    (void)width;
    (void)height;
    (void)title;
    struct egl_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    PFNEGLQUERYDEVICESEXTPROC query_devices = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    bool ok = false;
    const char *how = "";
    if (get_platform_display && query_devices) {
        EGLDeviceEXT devices[16];
        EGLint ndevices = 0;
        if (query_devices(16, devices, &ndevices)) {
            for (EGLint i = 0; i < ndevices && !ok; i++) {
                ok = egl_try_display(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL), s);
                how = "device platform";
            }
        }
    }
    if (!ok && get_platform_display) {
        ok = egl_try_display(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL), s);
        how = "surfaceless platform";
    }
    if (!ok) {
        ok = egl_try_display(eglGetDisplay(EGL_DEFAULT_DISPLAY), s);
        how = "default display";
    }
    if (!ok) {
        free(s);
        return error_set(err, "no EGL display gave an OpenGL 4.5 core context (tried the device, "
                              "surfaceless and default platforms; last EGL error 0x%04x)",
                         (unsigned)eglGetError());
    }
    (void)how;
    ctx->native = s;
    if (!gl_api_load(egl_get_proc, err)) {
        eglMakeCurrent(s->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(s->display, s->context);
        eglTerminate(s->display);
        free(s);
        ctx->native = NULL;
        return false;
    }
    return true;
}

static void egl_destroy(struct gl_context *ctx)
{
    struct egl_state *s = ctx->native;
    if (!s)
        return;
    eglMakeCurrent(s->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(s->display, s->context);
    eglTerminate(s->display);
    free(s);
    ctx->native = NULL;
}

const struct gl_context_ops gl_context_egl_ops = {"egl", egl_create, egl_destroy};
