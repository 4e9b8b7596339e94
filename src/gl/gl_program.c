#include "gl/gl_program.h"

#include <ctype.h>
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
static bool program_build(const char *root, struct gl_program *p, struct error *err)
{
    static const GLenum types[3] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER};
    GLuint shaders[3];
    int nshaders = 0;
    int nfiles = 0;
    char files[GL_PROGRAM_MAX_FILES][1024];
    bool ok = true;
    for (int s = 0; s < 3 && ok; s++) {
        if (!p->stages[s][0])
            continue;
        struct source_files sf = {0};
        snprintf(sf.defines_origin, sizeof sf.defines_origin, "%s", p->defines_origin);
        struct text src = {0};
        ok = assemble(root, p->stages[s], p->defines, &sf, &src, 0, err);
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
    if (!ok)
        return false;
    if (p->id)
        gl.DeleteProgram(p->id);
    p->id = prog;
    return true;
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
        free(cache->items[i]);
    }
    free(cache->items);
    cache->items = NULL;
    cache->count = cache->capacity = 0;
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
    if (!program_build(cache->root, p, err)) {
        free(p);
        return false;
    }
    if (cache->count == cache->capacity) {
        int cap = cache->capacity ? cache->capacity * 2 : 16;
        struct gl_program **items = realloc(cache->items, (size_t)cap * sizeof *items);
        if (!items) {
            gl.DeleteProgram(p->id);
            free(p);
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
        if (program_build(cache->root, p, &local)) {
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

GLint gl_program_uniform(const struct gl_program *p, const char *name)
{
    return gl.GetUniformLocation(p->id, name);
}
