/* Shader programs: GLSL files with `#include "common/x.glsl"`, compiled with
 * errors that name the file and line, cached by (files, defines), and
 * reloaded when a file changes (a failed reload keeps the last good one).
 *
 * Binding by name: shaders declare samplers, images and buffer blocks
 * without `binding =`; after link the cache gives each one a unit (or
 * binding point) and C binds by the name the shader uses
 * (gl_program_bind_texture(p, "u_scene", tex)). A name keeps its unit in
 * every program of one shader folder (its namespace), so a pass may bind a
 * buffer once and dispatch several of its folder's programs; names the
 * renderer keeps bound for every pass (the frame block, the environment)
 * are reserved once with gl_program_cache_reserve. No list of slot numbers
 * exists to edit when a technique is added. */
#ifndef CAUSTICA_GL_PROGRAM_H
#define CAUSTICA_GL_PROGRAM_H

#include <stdbool.h>
#include <stddef.h>

#include "core/error.h"
#include "gl/gl_api.h"

#define GL_PROGRAM_MAX_FILES 24
#define GL_PROGRAM_NAME_MAX 64

enum gl_slot_kind { GL_SLOT_TEXTURE, GL_SLOT_IMAGE, GL_SLOT_STORAGE, GL_SLOT_UNIFORM_BLOCK, GL_SLOT_KINDS };

/* One sampler, image or block of a program and the unit it was given
 * (`count` consecutive units for an array of samplers). */
struct gl_program_slot {
    char name[GL_PROGRAM_NAME_MAX];
    enum gl_slot_kind kind;
    int unit, count;
};

/* A uniform's location, looked up once after link. */
struct gl_program_location {
    char name[GL_PROGRAM_NAME_MAX];
    GLint location;
};

struct gl_program {
    GLuint id;
    char stages[3][1024];  /* resolved stage paths: vert, frag or comp, "" if unused */
    char defines[8192];
    char defines_origin[600]; /* names the defines block in error messages */
    int nfiles;            /* every file read, includes too, to notice edits */
    char files[GL_PROGRAM_MAX_FILES][1024];
    long long mtimes[GL_PROGRAM_MAX_FILES];
    char space[GL_PROGRAM_NAME_MAX]; /* the namespace of its units: its shader folder */
    struct gl_program_slot *slots;   /* owned */
    int nslots;
    struct gl_program_location *locations; /* owned */
    int nlocations;
    /* Every stage's assembled GLSL (owned), to tell a name C asks for that
     * the shaders never declare (a misspelt uniform: an error) from one the
     * compiler dropped as unused (a variant without the feature: fine). */
    char *source;
    struct gl_program_names *checked;  /* owned: the missing names already looked for in `source` */
    struct gl_program_cache *cache;    /* where an undeclared name is reported */
    void *attached;                    /* owned: gl_program_attached's block, until the next link */
    GLint local_size[3];               /* a compute program's work group (layout(local_size_x = ...)), else 0 */
    size_t attached_size;
};

/* The missing names a program was asked for (see gl_program.source). */
struct gl_program_names {
    char (*names)[GL_PROGRAM_NAME_MAX];
    int count, capacity;
};

/* A name's unit in one namespace ("" for a reserved name: every namespace). */
struct gl_slot_assignment {
    char space[GL_PROGRAM_NAME_MAX];
    char name[GL_PROGRAM_NAME_MAX];
    enum gl_slot_kind kind;
    int unit, count;
};

struct gl_program_cache {
    char root[1024];           /* the shaders/ folder */
    struct gl_program **items; /* owned */
    int count, capacity;
    struct gl_slot_assignment *assigned; /* owned: reserved names, then each folder's */
    int nassigned, assigned_capacity;
    /* Names C asked a program for that none of its stages declares, since
     * the last gl_program_cache_take_undeclared: "'u_x' (shade/shade.frag)". */
    char undeclared[512];
    int undeclared_count;
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

/* The location of a uniform (-1 when the program does not use it), from
 * the table read after link. A name that no stage of the program declares
 * at all is also reported to the cache (gl_program_cache_take_undeclared). */
GLint gl_program_uniform(const struct gl_program *p, const char *name);

/* The same, for a helper that sets what any of many programs may have
 * (the renderer's per-object material uniforms, a shared binding): a name
 * the program lacks is no error. */
GLint gl_program_uniform_optional(const struct gl_program *p, const char *name);

/* A block of `size` bytes kept with the program for one caller: the
 * renderer's look-ups of its locations and units (renderer.c), found once
 * per link instead of by name every draw. Zeroed, with *made set, the first
 * time after each link; the same block afterwards (made false). NULL when
 * out of memory or when `size` differs from the first call's. */
void *gl_program_attached(const struct gl_program *p, size_t size, bool *made);

/* Look-ups by name since the process started (issue 54's count of them a
 * frame: `render --timings` prints the timed frame's): uniforms' locations
 * (gl_program_uniform and _optional) and the units of samplers, images and
 * blocks (the gl_program_bind_* functions). The renderer is single-threaded;
 * nothing else calls these. */
struct gl_program_lookups {
    unsigned long long uniforms, units;
};
struct gl_program_lookups gl_program_lookups_so_far(void);

/* The undeclared names reported since the last call, as one line in `out`
 * ("'u_strenght' (fx/glow.frag), ..."); their count (0: none). The graph
 * makes them an error naming the pass that asked. */
int gl_program_cache_take_undeclared(struct gl_program_cache *cache, char *out, size_t outlen);

/* Gives `name` of `kind` the units [unit, unit + count) in every program:
 * for what the renderer binds once for all passes. Call before the first
 * program is built. False when the units are taken. */
bool gl_program_cache_reserve(struct gl_program_cache *cache, enum gl_slot_kind kind, const char *name, int unit,
                              int count, struct error *err);

/* The unit `name` was given in `p` (the first of an array), or -1 when the
 * program does not use it (the linker may drop what a shader never reads). */
int gl_program_unit(const struct gl_program *p, enum gl_slot_kind kind, const char *name);

/* Runs compute program `p` over nx x ny x nz invocations: as many work
 * groups of the size its shader declares as cover them (the shader's
 * layout(local_size_...) is read after link, so C does not repeat it),
 * then a memory barrier of `barriers` (0: none). */
void gl_program_dispatch(const struct gl_program *p, int nx, int ny, int nz, GLbitfield barriers);

/* Binds `texture` to a texture unit gl_program_unit gave (the renderer
 * finds a program's units once per link): -1 binds nothing. */
void gl_program_bind_texture_unit(int unit, GLuint texture);
/* The same for a uniform block's binding point (gl_param_block's). */
void gl_program_bind_uniform_block_unit(int unit, GLuint buffer);

/* Bind by the shader's name. Each returns false, binding nothing, when the
 * program does not use the name. `index` picks an element of a sampler
 * array. */
bool gl_program_bind_texture(const struct gl_program *p, const char *name, GLuint texture);
bool gl_program_bind_texture_at(const struct gl_program *p, const char *name, int index, GLuint texture);
/* Level 0, every layer when `layered` (an array image), else layer 0. */
bool gl_program_bind_image(const struct gl_program *p, const char *name, GLuint texture, GLboolean layered,
                           GLenum access, GLenum format);
bool gl_program_bind_storage(const struct gl_program *p, const char *block, GLuint buffer);
bool gl_program_bind_uniform_block(const struct gl_program *p, const char *block, GLuint buffer);

#endif
