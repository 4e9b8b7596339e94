#include "gl/gl_api.h"

#include <stdio.h>
#include <string.h>

struct gl_api gl;
static bool loaded;

bool gl_api_load(gl_get_proc_fn get_proc, struct error *err)
{
    char missing[ERROR_MESSAGE_MAX] = "";
    size_t used = 0;
    int count = 0;
#define GL_API_LOAD(type, name)                                                 \
    gl.name = (type)get_proc("gl" #name);                                       \
    if (!gl.name) {                                                             \
        int w = snprintf(missing + used, sizeof missing - used, "%sgl%s",       \
                         count ? ", " : "", #name);                             \
        if (w > 0 && used + (size_t)w < sizeof missing)                         \
            used += (size_t)w;                                                  \
        count++;                                                                \
    }
    GL_FUNCTION_LIST(GL_API_LOAD)
#undef GL_API_LOAD
    if (count > 0)
        return error_set(err, "the OpenGL driver lacks %d entry point%s caustica needs: %s",
                         count, count == 1 ? "" : "s", missing);
    loaded = true;
    return true;
}

bool gl_api_ready(void) { return loaded; }

void gl_api_unload(void)
{
    loaded = false;
    memset(&gl, 0, sizeof gl);
}

bool gl_check(const char *what, struct error *err)
{
    GLenum e = gl.GetError();
    if (e == GL_NO_ERROR)
        return true;
    while (gl.GetError() != GL_NO_ERROR) {
    }
    return error_set(err, "OpenGL error 0x%04x during %s", (unsigned)e, what);
}
