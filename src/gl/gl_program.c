#include "gl/gl_program.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fileio.h"

/* A growing string. */
struct text {
    char *data;
    size_t len, cap;
};

static bool text_append(struct text *t, const char *s, size_t n)
{
    if (t->len + n + 1 > t->cap) {
        size_t cap = t->cap ? t->cap : 4096;
        while (cap < t->len + n + 1)
            cap *= 2;
        char *d = realloc(t->data, cap);
        if (!d)
            return false;
        t->data = d;
        t->cap = cap;
    }
    memcpy(t->data + t->len, s, n);
    t->len += n;
    t->data[t->len] = '\0';
    return true;
}

/* "#line" for line `line` of file `file`. The file number is folded into
 * the line number (file * LINE_STRIDE + line) rather than given as GLSL's
 * source-string number, which drivers do not report reliably (Mesa prints
 * 0 for some errors). */
#define LINE_STRIDE 100000
static bool text_line_directive(struct text *t, int line, int file)
{
    char buf[64];
    int n = snprintf(buf, sizeof buf, "#line %d\n", file * LINE_STRIDE + line);
    return n > 0 && text_append(t, buf, (size_t)n);
}

/* Files that make up one program's source, numbered for #line; the
 * defines block gets number DEFINES_SOURCE. */
#define DEFINES_SOURCE GL_PROGRAM_MAX_FILES
struct source_files {
    int count;
    char paths[GL_PROGRAM_MAX_FILES][1024];
    char defines_origin[600];
};

static void resolve(const char *root, const char *path, char *out, size_t outlen)
{
    if (path[0] == '/')
        snprintf(out, outlen, "%s", path);
    else
        path_join(root, path, out, outlen);
}

static bool assemble(const char *root, const char *path, const char *defines, struct source_files *files,
                     struct text *out, int depth, struct error *err)
{
    if (depth > 8)
        return error_set(err, "%s: #include nested too deeply (more than 8 levels)", path);
    for (int i = 0; i < files->count; i++)
        if (strcmp(files->paths[i], path) == 0 && depth > 0)
            return true; /* each file once, like #pragma once */
    if (files->count >= GL_PROGRAM_MAX_FILES)
        return error_set(err, "%s: too many included files (at most %d)", path, GL_PROGRAM_MAX_FILES);
    int id = files->count++;
    snprintf(files->paths[id], sizeof files->paths[id], "%s", path);
    char *data;
    if (!file_read_all(path, &data, NULL, err))
        return false;
    bool ok = true;
    int lineno = 0;
    if (depth > 0)
        ok = text_line_directive(out, 1, id);
    char *line = data;
    while (ok && line && *line) {
        char *next = strchr(line, '\n');
        size_t n = next ? (size_t)(next - line) : strlen(line);
        lineno++;
        const char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (strncmp(p, "#include", 8) == 0) {
            const char *q1 = strchr(p, '"');
            const char *q2 = q1 ? strchr(q1 + 1, '"') : NULL;
            if (!q1 || !q2 || q2 > line + n) {
                ok = error_set(err, "%s:%d: #include needs a quoted path", path, lineno);
                break;
            }
            char rel[512], inc[1024];
            snprintf(rel, sizeof rel, "%.*s", (int)(q2 - q1 - 1), q1 + 1);
            resolve(root, rel, inc, sizeof inc);
            if (!file_exists(inc)) {
                char dir[1024];
                path_dirname(path, dir, sizeof dir);
                path_join(dir, rel, inc, sizeof inc);
            }
            if (!file_exists(inc)) {
                ok = error_set(err, "%s:%d: #include \"%s\": no such file in %s", path, lineno, rel, root);
                break;
            }
            ok = assemble(root, inc, NULL, files, out, depth + 1, err) &&
                 text_line_directive(out, lineno + 1, id);
        } else {
            ok = text_append(out, line, n) && text_append(out, "\n", 1);
            if (ok && depth == 0 && strncmp(p, "#version", 8) == 0) {
                if (defines && defines[0])
                    ok = text_line_directive(out, 1, DEFINES_SOURCE) &&
                         text_append(out, defines, strlen(defines)) && text_append(out, "\n", 1);
                ok = ok && text_line_directive(out, lineno + 1, id);
            }
        }
        line = next ? next + 1 : NULL;
    }
    free(data);
    if (!ok && err && !err->message[0])
        error_set(err, "%s: out of memory assembling shader", path);
    return ok;
}

/* Rewrites the driver's "0:12(5): error" (Mesa) or "0(12) : error" (NVIDIA)
 * into "file:12: error", so the message points into the right file. */
static void rewrite_log(const char *log, const struct source_files *files, struct error *err)
{
    struct text t = {0};
    const char *line = log;
    while (line && *line) {
        const char *next = strchr(line, '\n');
        size_t n = next ? (size_t)(next - line) : strlen(line);
        int file = -1, lno = -1, consumed = 0;
        if (sscanf(line, "%d:%d(%*d)%n", &file, &lno, &consumed) == 2 ||
            sscanf(line, "%d(%d)%n", &file, &lno, &consumed) == 2) {
            file = lno / LINE_STRIDE;
            lno = lno % LINE_STRIDE;
            const char *rest = line + consumed;
            while (*rest == ' ' || *rest == ':')
                rest++;
            const char *name = file >= 0 && file < files->count ? files->paths[file]
                             : file == DEFINES_SOURCE && files->defines_origin[0] ? files->defines_origin : "?";
            char head[1200];
            int hn = snprintf(head, sizeof head, "%s:%d: ", name, lno);
            text_append(&t, head, (size_t)hn);
            text_append(&t, rest, n - (size_t)(rest - line));
        } else if (n > 0) {
            text_append(&t, line, n);
        }
        if (n > 0)
            text_append(&t, "\n", 1);
        line = next ? next + 1 : NULL;
    }
    /* Drop the trailing newline: messages are one line where possible. */
    while (t.len > 0 && (t.data[t.len - 1] == '\n' || t.data[t.len - 1] == ' '))
        t.data[--t.len] = '\0';
    error_set(err, "%s", t.data ? t.data : log);
    free(t.data);
}

static bool compile_stage(GLenum type, const char *source, const struct source_files *files, GLuint *out,
                          struct error *err)
{
    GLuint sh = gl.CreateShader(type);
    const GLchar *src = source;
    gl.ShaderSource(sh, 1, &src, NULL);
    gl.CompileShader(sh);
    GLint ok = 0;
    gl.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = "";
        gl.GetShaderInfoLog(sh, sizeof log, NULL, log);
        gl.DeleteShader(sh);
        rewrite_log(log, files, err);
        return false;
    }
    *out = sh;
    return true;
}

static bool link_program(GLuint *shaders, int n, const char *what, GLuint *out, struct error *err)
{
    GLuint prog = gl.CreateProgram();
    for (int i = 0; i < n; i++)
        gl.AttachShader(prog, shaders[i]);
    gl.LinkProgram(prog);
    for (int i = 0; i < n; i++) {
        gl.DetachShader(prog, shaders[i]);
        gl.DeleteShader(shaders[i]);
    }
    GLint ok = 0;
    gl.GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = "";
        gl.GetProgramInfoLog(prog, sizeof log, NULL, log);
        gl.DeleteProgram(prog);
        return error_set(err, "%s: link failed: %s", what, log);
    }
    *out = prog;
    return true;
}

/* Builds `p->id` from its stage files; on failure leaves p->id untouched. */
static bool program_assign_slots(struct gl_program_cache *cache, struct gl_program *p, GLuint prog,
                                 struct error *err);

static bool program_build(struct gl_program_cache *cache, struct gl_program *p, struct error *err)
{
    const char *root = cache->root;
    static const GLenum types[3] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER};
    GLuint shaders[3];
    int nshaders = 0;
    int nfiles = 0;
    char files[GL_PROGRAM_MAX_FILES][1024];
    bool ok = true;
    struct text all = {0}; /* every stage's source, kept in p->source */
    for (int s = 0; s < 3 && ok; s++) {
        if (!p->stages[s][0])
            continue;
        struct source_files sf = {0};
        snprintf(sf.defines_origin, sizeof sf.defines_origin, "%s", p->defines_origin);
        struct text src = {0};
        ok = assemble(root, p->stages[s], p->defines, &sf, &src, 0, err);
        if (ok && !text_append(&all, src.data, src.len))
            ok = error_set(err, "out of memory for the source of %s", p->stages[s]);
        if (ok) {
            ok = compile_stage(types[s], src.data, &sf, &shaders[nshaders], err);
            if (ok)
                nshaders++;
        }
        for (int i = 0; i < sf.count && nfiles < GL_PROGRAM_MAX_FILES; i++)
            memcpy(files[nfiles++], sf.paths[i], sizeof files[0]);
        free(src.data);
    }
    GLuint prog = 0;
    if (ok)
        ok = link_program(shaders, nshaders, p->stages[0][0] ? p->stages[0] : p->stages[2], &prog, err);
    else
        for (int i = 0; i < nshaders; i++)
            gl.DeleteShader(shaders[i]);
    /* Remember the files even on failure, so an edit that fixes them is seen. */
    p->nfiles = nfiles;
    for (int i = 0; i < nfiles; i++) {
        memcpy(p->files[i], files[i], sizeof files[0]);
        p->mtimes[i] = file_mtime_ns(files[i]);
    }
    if (!ok) {
        free(all.data);
        return false;
    }
    if (!program_assign_slots(cache, p, prog, err)) {
        gl.DeleteProgram(prog);
        free(all.data);
        return false;
    }
    if (p->id)
        gl.DeleteProgram(p->id);
    p->id = prog;
    p->local_size[0] = p->local_size[1] = p->local_size[2] = 0;
    if (p->stages[2][0]) /* a compute program: its work group, as the shader's layout declares it */
        gl.GetProgramiv(prog, GL_COMPUTE_WORK_GROUP_SIZE, p->local_size);
    free(p->attached); /* (its locations were the old link's) */
    p->attached = NULL;
    p->attached_size = 0;
    free(p->source);
    p->source = all.data;
    p->cache = cache;
    if (!p->checked)
        p->checked = calloc(1, sizeof *p->checked); /* NULL (out of memory): misses are not remembered */
    if (p->checked)
        p->checked->count = 0; /* a rebuilt source: look again */
    return true;
}

static void program_free(struct gl_program *p)
{
    free(p->attached);
    free(p->slots);
    free(p->locations);
    free(p->source);
    if (p->checked)
        free(p->checked->names);
    free(p->checked);
    free(p);
}

void gl_program_cache_init(struct gl_program_cache *cache, const char *shader_root)
{
    memset(cache, 0, sizeof *cache);
    snprintf(cache->root, sizeof cache->root, "%s", shader_root);
}

void gl_program_cache_destroy(struct gl_program_cache *cache)
{
    for (int i = 0; i < cache->count; i++) {
        if (cache->items[i]->id && gl_api_ready())
            gl.DeleteProgram(cache->items[i]->id);
        program_free(cache->items[i]);
    }
    free(cache->items);
    cache->items = NULL;
    cache->count = cache->capacity = 0;
    free(cache->assigned);
    cache->assigned = NULL;
    cache->nassigned = cache->assigned_capacity = 0;
}

static bool program_get(struct gl_program_cache *cache, const char *stages[3], const char *defines,
                        const char *origin, struct gl_program **out, struct error *err)
{
    char resolved[3][1024];
    for (int s = 0; s < 3; s++) {
        resolved[s][0] = '\0';
        if (stages[s])
            resolve(cache->root, stages[s], resolved[s], sizeof resolved[s]);
    }
    const char *defs = defines ? defines : "";
    for (int i = 0; i < cache->count; i++) {
        struct gl_program *p = cache->items[i];
        if (strcmp(p->defines, defs) == 0 && strcmp(p->stages[0], resolved[0]) == 0 &&
            strcmp(p->stages[1], resolved[1]) == 0 && strcmp(p->stages[2], resolved[2]) == 0) {
            if (!p->id)
                return error_set(err, "%s: this program failed to build earlier", resolved[0]);
            *out = p;
            return true;
        }
    }
    struct gl_program *p = calloc(1, sizeof *p);
    if (!p)
        return error_set(err, "out of memory");
    for (int s = 0; s < 3; s++)
        memcpy(p->stages[s], resolved[s], sizeof resolved[s]);
    snprintf(p->defines, sizeof p->defines, "%s", defs);
    snprintf(p->defines_origin, sizeof p->defines_origin, "%s", origin ? origin : "defines");
    if (strlen(defs) >= sizeof p->defines) {
        free(p);
        return error_set(err, "%s: shader defines longer than %zu characters", origin ? origin : resolved[0],
                         sizeof p->defines - 1);
    }
    if (!program_build(cache, p, err)) {
        program_free(p);
        return false;
    }
    if (cache->count == cache->capacity) {
        int cap = cache->capacity ? cache->capacity * 2 : 16;
        struct gl_program **items = realloc(cache->items, (size_t)cap * sizeof *items);
        if (!items) {
            gl.DeleteProgram(p->id);
            program_free(p);
            return error_set(err, "out of memory");
        }
        cache->items = items;
        cache->capacity = cap;
    }
    cache->items[cache->count++] = p;
    *out = p;
    return true;
}

bool gl_program_get(struct gl_program_cache *cache, const char *vert, const char *frag, const char *defines,
                    struct gl_program **out, struct error *err)
{
    const char *stages[3] = {vert, frag, NULL};
    return program_get(cache, stages, defines, NULL, out, err);
}

bool gl_program_get_compute(struct gl_program_cache *cache, const char *comp, const char *defines,
                            const char *defines_origin, struct gl_program **out, struct error *err)
{
    const char *stages[3] = {NULL, NULL, comp};
    return program_get(cache, stages, defines, defines_origin, out, err);
}

bool gl_program_cache_reload_changed(struct gl_program_cache *cache, bool *any_reloaded, struct error *err)
{
    bool ok = true;
    if (any_reloaded)
        *any_reloaded = false;
    for (int i = 0; i < cache->count; i++) {
        struct gl_program *p = cache->items[i];
        bool changed = false;
        for (int f = 0; f < p->nfiles; f++)
            if (file_mtime_ns(p->files[f]) != p->mtimes[f])
                changed = true;
        if (!changed)
            continue;
        struct error local;
        if (program_build(cache, p, &local)) {
            if (any_reloaded)
                *any_reloaded = true;
        } else if (ok) {
            ok = false;
            if (err)
                *err = local;
        }
    }
    return ok;
}

/* ---- Binding by name ---- */

static const char *const slot_kind_names[GL_SLOT_KINDS] = {"texture unit", "image unit", "storage block binding",
                                                           "uniform block binding"};

static bool type_is_sampler(GLenum type)
{
    switch (type) {
    case GL_SAMPLER_1D: case GL_SAMPLER_2D: case GL_SAMPLER_3D: case GL_SAMPLER_CUBE:
    case GL_SAMPLER_1D_SHADOW: case GL_SAMPLER_2D_SHADOW: case GL_SAMPLER_1D_ARRAY: case GL_SAMPLER_2D_ARRAY:
    case GL_SAMPLER_1D_ARRAY_SHADOW: case GL_SAMPLER_2D_ARRAY_SHADOW: case GL_SAMPLER_2D_MULTISAMPLE:
    case GL_SAMPLER_2D_MULTISAMPLE_ARRAY: case GL_SAMPLER_CUBE_SHADOW: case GL_SAMPLER_BUFFER:
    case GL_SAMPLER_2D_RECT: case GL_SAMPLER_2D_RECT_SHADOW: case GL_SAMPLER_CUBE_MAP_ARRAY:
    case GL_SAMPLER_CUBE_MAP_ARRAY_SHADOW:
    case GL_INT_SAMPLER_1D: case GL_INT_SAMPLER_2D: case GL_INT_SAMPLER_3D: case GL_INT_SAMPLER_CUBE:
    case GL_INT_SAMPLER_1D_ARRAY: case GL_INT_SAMPLER_2D_ARRAY: case GL_INT_SAMPLER_2D_MULTISAMPLE:
    case GL_INT_SAMPLER_2D_MULTISAMPLE_ARRAY: case GL_INT_SAMPLER_BUFFER: case GL_INT_SAMPLER_2D_RECT:
    case GL_INT_SAMPLER_CUBE_MAP_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_1D: case GL_UNSIGNED_INT_SAMPLER_2D: case GL_UNSIGNED_INT_SAMPLER_3D:
    case GL_UNSIGNED_INT_SAMPLER_CUBE: case GL_UNSIGNED_INT_SAMPLER_1D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY: case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE:
    case GL_UNSIGNED_INT_SAMPLER_2D_MULTISAMPLE_ARRAY: case GL_UNSIGNED_INT_SAMPLER_BUFFER:
    case GL_UNSIGNED_INT_SAMPLER_2D_RECT: case GL_UNSIGNED_INT_SAMPLER_CUBE_MAP_ARRAY:
        return true;
    default:
        return false;
    }
}

static bool type_is_image(GLenum type)
{
    switch (type) {
    case GL_IMAGE_1D: case GL_IMAGE_2D: case GL_IMAGE_3D: case GL_IMAGE_2D_RECT: case GL_IMAGE_CUBE:
    case GL_IMAGE_BUFFER: case GL_IMAGE_1D_ARRAY: case GL_IMAGE_2D_ARRAY: case GL_IMAGE_CUBE_MAP_ARRAY:
    case GL_IMAGE_2D_MULTISAMPLE: case GL_IMAGE_2D_MULTISAMPLE_ARRAY:
    case GL_INT_IMAGE_1D: case GL_INT_IMAGE_2D: case GL_INT_IMAGE_3D: case GL_INT_IMAGE_2D_RECT:
    case GL_INT_IMAGE_CUBE: case GL_INT_IMAGE_BUFFER: case GL_INT_IMAGE_1D_ARRAY: case GL_INT_IMAGE_2D_ARRAY:
    case GL_INT_IMAGE_CUBE_MAP_ARRAY: case GL_INT_IMAGE_2D_MULTISAMPLE: case GL_INT_IMAGE_2D_MULTISAMPLE_ARRAY:
    case GL_UNSIGNED_INT_IMAGE_1D: case GL_UNSIGNED_INT_IMAGE_2D: case GL_UNSIGNED_INT_IMAGE_3D:
    case GL_UNSIGNED_INT_IMAGE_2D_RECT: case GL_UNSIGNED_INT_IMAGE_CUBE: case GL_UNSIGNED_INT_IMAGE_BUFFER:
    case GL_UNSIGNED_INT_IMAGE_1D_ARRAY: case GL_UNSIGNED_INT_IMAGE_2D_ARRAY:
    case GL_UNSIGNED_INT_IMAGE_CUBE_MAP_ARRAY: case GL_UNSIGNED_INT_IMAGE_2D_MULTISAMPLE:
    case GL_UNSIGNED_INT_IMAGE_2D_MULTISAMPLE_ARRAY:
        return true;
    default:
        return false;
    }
}

static int slot_limit(enum gl_slot_kind kind)
{
    static const GLenum limits[GL_SLOT_KINDS] = {GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, GL_MAX_IMAGE_UNITS,
                                                 GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS,
                                                 GL_MAX_UNIFORM_BUFFER_BINDINGS};
    GLint n = 0;
    gl.GetIntegerv(limits[kind], &n);
    return n > 0 ? n : 8;
}

static bool assignment_append(struct gl_program_cache *cache, const char *space, enum gl_slot_kind kind,
                              const char *name, int unit, int count, struct error *err)
{
    if (cache->nassigned == cache->assigned_capacity) {
        int cap = cache->assigned_capacity ? cache->assigned_capacity * 2 : 64;
        struct gl_slot_assignment *a = realloc(cache->assigned, (size_t)cap * sizeof *a);
        if (!a)
            return error_set(err, "out of memory");
        cache->assigned = a;
        cache->assigned_capacity = cap;
    }
    struct gl_slot_assignment *a = &cache->assigned[cache->nassigned++];
    snprintf(a->space, sizeof a->space, "%s", space);
    snprintf(a->name, sizeof a->name, "%s", name);
    a->kind = kind;
    a->unit = unit;
    a->count = count;
    return true;
}

/* True when [unit, unit + count) overlaps a unit of `kind` that is
 * reserved or given in `space`. */
static bool units_taken(const struct gl_program_cache *cache, const char *space, enum gl_slot_kind kind, int unit,
                        int count)
{
    for (int i = 0; i < cache->nassigned; i++) {
        const struct gl_slot_assignment *a = &cache->assigned[i];
        if (a->kind != kind || (a->space[0] && strcmp(a->space, space) != 0))
            continue;
        if (unit < a->unit + a->count && a->unit < unit + count)
            return true;
    }
    return false;
}

bool gl_program_cache_reserve(struct gl_program_cache *cache, enum gl_slot_kind kind, const char *name, int unit,
                              int count, struct error *err)
{
    if (units_taken(cache, "", kind, unit, count))
        return error_set(err, "%s %d is reserved twice ('%s')", slot_kind_names[kind], unit, name);
    return assignment_append(cache, "", kind, name, unit, count, err);
}

/* The unit of `name` in `space`: reserved, given earlier, or the lowest
 * free run of `count` units. */
static int slot_assign(struct gl_program_cache *cache, const struct gl_program *p, enum gl_slot_kind kind,
                       const char *name, int count, struct error *err)
{
    for (int i = 0; i < cache->nassigned; i++) {
        const struct gl_slot_assignment *a = &cache->assigned[i];
        if (a->kind != kind || strcmp(a->name, name) != 0 || (a->space[0] && strcmp(a->space, p->space) != 0))
            continue;
        if (count > a->count) {
            /* An array grew (a define changed its size): move it. */
            if (!a->space[0]) {
                error_set(err, "%s: '%s' has %d elements but %d %ss are reserved for it", p->stages[1][0] ? p->stages[1] : p->stages[2],
                          name, count, a->count, slot_kind_names[kind]);
                return -1;
            }
            break;
        }
        return a->unit;
    }
    int limit = slot_limit(kind);
    for (int unit = 0; unit + count <= limit; unit++)
        if (!units_taken(cache, p->space, kind, unit, count)) {
            for (int i = 0; i < cache->nassigned; i++) /* the smaller array's entry, if it grew */
                if (cache->assigned[i].kind == kind && strcmp(cache->assigned[i].name, name) == 0 &&
                    strcmp(cache->assigned[i].space, p->space) == 0)
                    cache->assigned[i].name[0] = '\0';
            if (!assignment_append(cache, p->space, kind, name, unit, count, err))
                return -1;
            return unit;
        }
    error_set(err, "shaders/%s: its programs use more than the %d %ss this GL offers ('%s' has none left); "
              "split the folder or share names", p->space, limit, slot_kind_names[kind], name);
    return -1;
}

/* The folder of the program's main stage (compute, else fragment, else
 * vertex), below the shader root; a stage in common/ names no folder
 * unless all of them are there. */
static void program_space(const struct gl_program_cache *cache, struct gl_program *p)
{
    static const int order[3] = {2, 1, 0};
    const char *chosen = NULL;
    size_t rootlen = strlen(cache->root);
    for (int k = 0; k < 3; k++) {
        const char *path = p->stages[order[k]];
        if (!path[0])
            continue;
        const char *rel = strncmp(path, cache->root, rootlen) == 0 && path[rootlen] == '/' ? path + rootlen + 1 : path;
        if (!chosen)
            chosen = rel;
        if (strncmp(rel, "common/", 7) != 0) {
            chosen = rel;
            break;
        }
    }
    const char *slash = chosen ? strrchr(chosen, '/') : NULL;
    size_t n = slash ? (size_t)(slash - chosen) : 0;
    if (n >= sizeof p->space)
        n = sizeof p->space - 1;
    memcpy(p->space, chosen ? chosen : "", n);
    p->space[n] = '\0';
}

static bool slot_push(struct gl_program_slot **slots, int *n, int *cap, const char *name, enum gl_slot_kind kind,
                      int unit, int count, struct error *err)
{
    if (*n == *cap) {
        int c = *cap ? *cap * 2 : 16;
        struct gl_program_slot *s = realloc(*slots, (size_t)c * sizeof *s);
        if (!s)
            return error_set(err, "out of memory");
        *slots = s;
        *cap = c;
    }
    struct gl_program_slot *s = &(*slots)[(*n)++];
    snprintf(s->name, sizeof s->name, "%s", name);
    s->kind = kind;
    s->unit = unit;
    s->count = count;
    return true;
}

static bool location_push(struct gl_program_location **locs, int *n, int *cap, const char *name, GLint location,
                          struct error *err)
{
    if (*n == *cap) {
        int c = *cap ? *cap * 2 : 32;
        struct gl_program_location *l = realloc(*locs, (size_t)c * sizeof *l);
        if (!l)
            return error_set(err, "out of memory");
        *locs = l;
        *cap = c;
    }
    struct gl_program_location *l = &(*locs)[(*n)++];
    snprintf(l->name, sizeof l->name, "%s", name);
    l->location = location;
    return true;
}

/* After link: gives every sampler, image and block its unit (setting the
 * program's uniform or block binding) and reads every uniform's location. */
static bool program_assign_slots(struct gl_program_cache *cache, struct gl_program *p, GLuint prog,
                                 struct error *err)
{
    program_space(cache, p);
    struct gl_program_slot *slots = NULL;
    struct gl_program_location *locs = NULL;
    int nslots = 0, slot_cap = 0, nlocs = 0, loc_cap = 0;
    bool ok = true;

    GLint count = 0;
    gl.GetProgramInterfaceiv(prog, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    for (GLint i = 0; i < count && ok; i++) {
        static const GLenum props[4] = {GL_TYPE, GL_ARRAY_SIZE, GL_LOCATION, GL_BLOCK_INDEX};
        GLint v[4] = {0, 0, -1, -1};
        char name[256];
        gl.GetProgramResourceiv(prog, GL_UNIFORM, (GLuint)i, 4, props, 4, NULL, v);
        gl.GetProgramResourceName(prog, GL_UNIFORM, (GLuint)i, sizeof name, NULL, name);
        if (v[3] != -1 || v[2] < 0)
            continue; /* a member of a uniform block, or a built-in */
        size_t len = strlen(name);
        bool array = len >= 3 && strcmp(name + len - 3, "[0]") == 0;
        if (array)
            name[len - 3] = '\0';
        if (strlen(name) >= GL_PROGRAM_NAME_MAX) {
            ok = error_set(err, "%s: uniform name '%s' is longer than %d characters", p->stages[1][0] ? p->stages[1] : p->stages[2],
                           name, GL_PROGRAM_NAME_MAX - 1);
            break;
        }
        int size = v[1] > 0 ? v[1] : 1;
        ok = location_push(&locs, &nlocs, &loc_cap, name, v[2], err);
        char element[GL_PROGRAM_NAME_MAX + 16];
        /* each element by name too, an array whose only active element
         * is [0] (size 1: the rest optimized away) included */
        for (int e = 0; e < size && ok && array; e++) {
            snprintf(element, sizeof element, "%s[%d]", name, e);
            if (strlen(element) < GL_PROGRAM_NAME_MAX)
                ok = location_push(&locs, &nlocs, &loc_cap, element, gl.GetUniformLocation(prog, element), err);
        }
        enum gl_slot_kind kind;
        if (type_is_sampler((GLenum)v[0]))
            kind = GL_SLOT_TEXTURE;
        else if (type_is_image((GLenum)v[0]))
            kind = GL_SLOT_IMAGE;
        else
            continue;
        int unit = ok ? slot_assign(cache, p, kind, name, size, err) : -1;
        if (unit < 0) {
            ok = false;
            break;
        }
        GLint units[64];
        for (int e = 0; e < size && e < 64; e++)
            units[e] = unit + e;
        gl.ProgramUniform1iv(prog, v[2], size < 64 ? size : 64, units);
        ok = slot_push(&slots, &nslots, &slot_cap, name, kind, unit, size, err);
    }

    static const GLenum blocks[2] = {GL_SHADER_STORAGE_BLOCK, GL_UNIFORM_BLOCK};
    for (int b = 0; b < 2 && ok; b++) {
        enum gl_slot_kind kind = b == 0 ? GL_SLOT_STORAGE : GL_SLOT_UNIFORM_BLOCK;
        count = 0;
        gl.GetProgramInterfaceiv(prog, blocks[b], GL_ACTIVE_RESOURCES, &count);
        for (GLint i = 0; i < count && ok; i++) {
            char name[GL_PROGRAM_NAME_MAX];
            gl.GetProgramResourceName(prog, blocks[b], (GLuint)i, sizeof name, NULL, name);
            int unit = slot_assign(cache, p, kind, name, 1, err);
            if (unit < 0) {
                ok = false;
                break;
            }
            if (b == 0)
                gl.ShaderStorageBlockBinding(prog, (GLuint)i, (GLuint)unit);
            else
                gl.UniformBlockBinding(prog, (GLuint)i, (GLuint)unit);
            ok = slot_push(&slots, &nslots, &slot_cap, name, kind, unit, 1, err);
        }
    }
    if (!ok) {
        free(slots);
        free(locs);
        return false;
    }
    free(p->slots);
    free(p->locations);
    p->slots = slots;
    p->nslots = nslots;
    p->locations = locs;
    p->nlocations = nlocs;
    return true;
}

void *gl_program_attached(const struct gl_program *p, size_t size, bool *made)
{
    /* a cache of what the program's link decided, kept beside it: the
     * program itself (its GL name, tables and sources) stays as linked */
    struct gl_program *q = (struct gl_program *)p;
    *made = false;
    if (q->attached)
        return q->attached_size == size ? q->attached : NULL;
    q->attached = calloc(1, size);
    if (!q->attached)
        return NULL;
    q->attached_size = size;
    *made = true;
    return q->attached;
}

extern struct gl_program_lookups gl_program_lookup_counts; /* (gl_program_uniform.c) */

static const struct gl_program_slot *slot_find(const struct gl_program *p, enum gl_slot_kind kind, const char *name)
{
    gl_program_lookup_counts.units++;
    for (int i = 0; i < p->nslots; i++)
        if (p->slots[i].kind == kind && strcmp(p->slots[i].name, name) == 0)
            return &p->slots[i];
    return NULL;
}

int gl_program_unit(const struct gl_program *p, enum gl_slot_kind kind, const char *name)
{
    const struct gl_program_slot *s = slot_find(p, kind, name);
    return s ? s->unit : -1;
}

void gl_program_dispatch(const struct gl_program *p, int nx, int ny, int nz, GLbitfield barriers)
{
    GLuint groups[3];
    const int n[3] = {nx, ny, nz};
    for (int k = 0; k < 3; k++) {
        int size = p->local_size[k] > 0 ? p->local_size[k] : 1;
        groups[k] = n[k] > 0 ? (GLuint)((n[k] + size - 1) / size) : 0u;
    }
    gl.UseProgram(p->id);
    gl.DispatchCompute(groups[0], groups[1], groups[2]);
    if (barriers)
        gl.MemoryBarrier(barriers);
}

void gl_program_bind_texture_unit(int unit, GLuint texture)
{
    if (unit >= 0)
        gl.BindTextureUnit((GLuint)unit, texture);
}

void gl_program_bind_uniform_block_unit(int unit, GLuint buffer)
{
    if (unit >= 0)
        gl.BindBufferBase(GL_UNIFORM_BUFFER, (GLuint)unit, buffer);
}

bool gl_program_bind_texture(const struct gl_program *p, const char *name, GLuint texture)
{
    return gl_program_bind_texture_at(p, name, 0, texture);
}

bool gl_program_bind_texture_at(const struct gl_program *p, const char *name, int index, GLuint texture)
{
    const struct gl_program_slot *s = slot_find(p, GL_SLOT_TEXTURE, name);
    if (!s || index < 0 || index >= s->count)
        return false;
    gl.BindTextureUnit((GLuint)(s->unit + index), texture);
    return true;
}

bool gl_program_bind_image(const struct gl_program *p, const char *name, GLuint texture, GLboolean layered,
                           GLenum access, GLenum format)
{
    const struct gl_program_slot *s = slot_find(p, GL_SLOT_IMAGE, name);
    if (!s)
        return false;
    gl.BindImageTexture((GLuint)s->unit, texture, 0, layered, 0, access, format);
    return true;
}

bool gl_program_bind_storage(const struct gl_program *p, const char *block, GLuint buffer)
{
    const struct gl_program_slot *s = slot_find(p, GL_SLOT_STORAGE, block);
    if (!s)
        return false;
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)s->unit, buffer);
    return true;
}

bool gl_program_bind_uniform_block(const struct gl_program *p, const char *block, GLuint buffer)
{
    const struct gl_program_slot *s = slot_find(p, GL_SLOT_UNIFORM_BLOCK, block);
    if (!s)
        return false;
    gl.BindBufferBase(GL_UNIFORM_BUFFER, (GLuint)s->unit, buffer);
    return true;
}
