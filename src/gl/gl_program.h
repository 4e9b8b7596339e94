/* Shader programs: GLSL files with `#include "common/x.glsl"`, compiled with
 * errors that name the file and line, cached by (files, defines), and
 * reloaded when a file changes (a failed reload keeps the last good one). */
#ifndef CAUSTICA_GL_PROGRAM_H
#define CAUSTICA_GL_PROGRAM_H

#include <stdbool.h>

#include "core/error.h"
#include "gl/gl_api.h"

#define GL_PROGRAM_MAX_FILES 24

struct gl_program {
    GLuint id;
    char stages[3][1024];  /* resolved stage paths: vert, frag or comp, "" if unused */
    char defines[8192];
    char defines_origin[600]; /* names the defines block in error messages */
    int nfiles;            /* every file read, includes too, to notice edits */
    char files[GL_PROGRAM_MAX_FILES][1024];
    long long mtimes[GL_PROGRAM_MAX_FILES];
};

struct gl_program_cache {
    char root[1024];           /* the shaders/ folder */
    struct gl_program **items; /* owned */
    int count, capacity;
};

void gl_program_cache_init(struct gl_program_cache *cache, const char *shader_root);
void gl_program_cache_destroy(struct gl_program_cache *cache);
/* Paths are relative to the shader root unless absolute. `defines` is a
 * block of "#define ..." lines (or NULL). */
bool gl_program_get(struct gl_program_cache *cache, const char *vert, const char *frag,
                    const char *defines, struct gl_program **out, struct error *err);
/* `defines_origin` (may be NULL) names the defines block in errors: a
 * deformer written in a scene script reports "scene.lua:12 (deformer):3". */
bool gl_program_get_compute(struct gl_program_cache *cache, const char *comp, const char *defines,
                            const char *defines_origin, struct gl_program **out, struct error *err);
/* Recompiles programs whose files changed. Returns false with the first
 * compile error; failed programs keep their previous, working version. */
bool gl_program_cache_reload_changed(struct gl_program_cache *cache, bool *any_reloaded, struct error *err);

GLint gl_program_uniform(const struct gl_program *p, const char *name);

#endif
