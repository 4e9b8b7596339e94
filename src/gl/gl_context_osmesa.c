/* OSMesa: offscreen rendering on Mesa (llvmpipe here), the default backend. */
#include <stdlib.h>

/* glcorearb.h (through gl_api.h) before osmesa.h: osmesa.h pulls in GL/gl.h,
 * which would hide the GL 1.1 function-pointer types of glcorearb.h. */
#include "gl/gl_api.h"
#include "gl/gl_context.h"

#include <GL/osmesa.h>

struct osmesa_state {
    OSMesaContext context;
    unsigned char *buffer; /* OSMesa needs a colour buffer to make current; we draw into FBOs */
};

static gl_proc osmesa_get_proc(const char *name) { return (gl_proc)OSMesaGetProcAddress(name); }

static bool osmesa_create(struct gl_context *ctx, int width, int height, const char *title, struct error *err)
{
    (void)width;
    (void)height;
    (void)title;
    struct osmesa_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    s->context = OSMesaCreateContextAttribs(attribs, NULL);
    if (!s->context) {
        free(s);
        return error_set(err, "OSMesaCreateContextAttribs could not create an OpenGL 4.5 core context");
    }
    s->buffer = calloc(16 * 16, 4);
    if (!s->buffer || !OSMesaMakeCurrent(s->context, s->buffer, GL_UNSIGNED_BYTE, 16, 16)) {
        OSMesaDestroyContext(s->context);
        free(s->buffer);
        free(s);
        return error_set(err, "OSMesaMakeCurrent failed");
    }
    ctx->native = s;
    if (!gl_api_load(osmesa_get_proc, err)) {
        OSMesaDestroyContext(s->context);
        free(s->buffer);
        free(s);
        ctx->native = NULL;
        return false;
    }
    return true;
}

static void osmesa_destroy(struct gl_context *ctx)
{
    struct osmesa_state *s = ctx->native;
    if (!s)
        return;
    OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(s->context);
    free(s->buffer);
    free(s);
    ctx->native = NULL;
}

const struct gl_context_ops gl_context_osmesa_ops = {"osmesa", osmesa_create, osmesa_destroy};
