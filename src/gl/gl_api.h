/* The GL function table. Code calls `gl.Clear(...)` etc.; gl_api_load fills
 * the table from the backend's get-proc-address. No GL library is linked
 * for its symbols, so the same binary runs on OSMesa, EGL and GLX. */
#ifndef CAUSTICA_GL_API_H
#define CAUSTICA_GL_API_H

#include <stdbool.h>

#include <GL/glcorearb.h>

#include "core/error.h"
#include "gl/gl_funcs.h"

struct gl_api {
#define GL_API_FIELD(type, name) type name;
    GL_FUNCTION_LIST(GL_API_FIELD)
#undef GL_API_FIELD
};

extern struct gl_api gl;

typedef void (*gl_proc)(void);
typedef gl_proc (*gl_get_proc_fn)(const char *name);

/* Fills `gl`; on failure the error lists every missing entry point. */
bool gl_api_load(gl_get_proc_fn get_proc, struct error *err);
/* True between a successful gl_api_load and gl_api_unload: destructors of
 * GL objects owned by Lua userdata check it, since Lua may collect them
 * after the context is gone. */
bool gl_api_ready(void);
void gl_api_unload(void);
/* Checks glGetError and names the operation when something failed. */
bool gl_check(const char *what, struct error *err);

#endif
