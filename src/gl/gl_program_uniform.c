/* Uniform look-ups by name (the table gl_program.c reads after link), and
 * the check that makes a name C asks for but no stage of the program
 * declares an error: the program's assembled source tells a misspelt name
 * from one the compiler dropped as unused (gl_program.h). */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl/gl_program.h"

/* Whether `name` occurs in `text` as a whole identifier. */
static bool identifier_in(const char *text, const char *name)
{
    size_t n = strlen(name);
    for (const char *s = text; n > 0 && (s = strstr(s, name)) != NULL; s += n) {
        bool start = s == text || !(isalnum((unsigned char)s[-1]) || s[-1] == '_');
        bool end = !(isalnum((unsigned char)s[n]) || s[n] == '_');
        if (start && end)
            return true;
    }
    return false;
}

/* A name the program lacks: reported once to the cache when no stage's
 * source declares it ("u_a[3]" and "Block.member" by their base name).
 * Checked once per name and build, so a variant's dropped uniform costs a
 * list lookup a frame. */
static void note_missing(const struct gl_program *p, const char *name)
{
    if (!p->cache || !p->source)
        return;
    char base[GL_PROGRAM_NAME_MAX];
    size_t n = strcspn(name, "[.");
    if (n == 0 || n >= sizeof base)
        return;
    memcpy(base, name, n);
    base[n] = '\0';
    struct gl_program_names *c = p->checked;
    if (c)
        for (int i = 0; i < c->count; i++)
            if (strcmp(c->names[i], base) == 0)
                return;
    if (!identifier_in(p->source, base)) {
        struct gl_program_cache *cache = p->cache;
        const char *stage = p->stages[1][0] ? p->stages[1] : p->stages[0][0] ? p->stages[0] : p->stages[2];
        size_t root = strlen(cache->root);
        const char *rel = stage;
        if (strncmp(stage, cache->root, root) == 0 && stage[root] == '/')
            rel = stage + root + 1; /* "shade/shade.frag" under shaders/ */
        size_t used = strlen(cache->undeclared);
        if (!strstr(cache->undeclared, base) && used + strlen(base) + strlen(rel) + 8 < sizeof cache->undeclared)
            snprintf(cache->undeclared + used, sizeof cache->undeclared - used, "%s'%s' (%s)", used ? ", " : "", base,
                     rel);
        cache->undeclared_count++;
    }
    /* remember it, declared or not (the list the build made) */
    if (c && c->count == c->capacity) {
        int cap = c->capacity ? c->capacity * 2 : 8;
        void *names = realloc(c->names, (size_t)cap * sizeof *c->names);
        if (!names)
            return;
        c->names = names;
        c->capacity = cap;
    }
    if (c)
        memcpy(c->names[c->count++], base, sizeof base);
}

int gl_program_cache_take_undeclared(struct gl_program_cache *cache, char *out, size_t outlen)
{
    int n = cache->undeclared_count;
    snprintf(out, outlen, "%s", cache->undeclared);
    cache->undeclared[0] = '\0';
    cache->undeclared_count = 0;
    return n;
}

/* (shared with gl_program.c's slot look-ups) */
struct gl_program_lookups gl_program_lookup_counts;

struct gl_program_lookups gl_program_lookups_so_far(void) { return gl_program_lookup_counts; }

GLint gl_program_uniform_optional(const struct gl_program *p, const char *name)
{
    gl_program_lookup_counts.uniforms++;
    for (int i = 0; i < p->nlocations; i++)
        if (strcmp(p->locations[i].name, name) == 0)
            return p->locations[i].location;
    return -1;
}

GLint gl_program_uniform(const struct gl_program *p, const char *name)
{
    GLint loc = gl_program_uniform_optional(p, name);
    if (loc < 0)
        note_missing(p, name);
    return loc;
}
