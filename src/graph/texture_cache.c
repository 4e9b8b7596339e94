#include "graph/texture_cache.h"

#include <stdlib.h>
#include <string.h>

#include "core/array.h"

void texture_cache_init(struct texture_cache *c) { memset(c, 0, sizeof *c); }

static void release_entry(struct gpu_texture *e)
{
    if (e->id && gl_api_ready())
        gl.DeleteTextures(1, &e->id);
    e->id = 0;
}

void texture_cache_release(struct texture_cache *c)
{
    for (int i = 0; i < c->count; i++)
        release_entry(&c->entries[i]);
    free(c->entries);
    texture_cache_init(c);
}

static void mark(struct texture_cache *c, const struct texture *t)
{
    for (int i = 0; t && i < c->count; i++)
        if (c->entries[i].serial == t->serial)
            c->entries[i].used = true;
}

void texture_cache_begin_frame(struct texture_cache *c, const struct scene *scene)
{
    for (int i = 0; i < c->count; i++)
        c->entries[i].used = false;
    for (int i = 0; i < scene->object_count; i++) {
        /* every slot: one left out was released and uploaded again, with
         * its mipmaps, every frame (the specular and clearcoat textures) */
        const struct texture_ref *slots[MATERIAL_TEXTURE_SLOTS];
        bool srgb[MATERIAL_TEXTURE_SLOTS];
        material_texture_slots(&scene->objects[i]->material, slots, srgb);
        for (int k = 0; k < MATERIAL_TEXTURE_SLOTS; k++)
            mark(c, slots[k]->texture);
    }
    int kept = 0;
    for (int i = 0; i < c->count; i++) {
        if (c->entries[i].used)
            c->entries[kept++] = c->entries[i];
        else
            release_entry(&c->entries[i]);
    }
    c->count = kept;
}

static GLint gl_wrap(enum texture_wrap w)
{
    return w == TEXTURE_CLAMP ? GL_CLAMP_TO_EDGE : w == TEXTURE_MIRROR ? GL_MIRRORED_REPEAT : GL_REPEAT;
}

bool texture_cache_get(struct texture_cache *c, const struct texture *t, bool srgb, GLuint *id, struct error *err)
{
    for (int i = 0; i < c->count; i++)
        if (c->entries[i].serial == t->serial && c->entries[i].srgb == srgb) {
            *id = c->entries[i].id;
            return true;
        }
    if (!array_grow((void **)&c->entries, &c->capacity, c->count, sizeof *c->entries, err))
        return false;
    int levels = 1;
    if (t->mipmaps)
        for (int s = t->width > t->height ? t->width : t->height; s > 1; s /= 2)
            levels++;
    GLuint tex = 0;
    gl.CreateTextures(GL_TEXTURE_2D, 1, &tex);
    gl.TextureStorage2D(tex, levels, srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, t->width, t->height);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TextureSubImage2D(tex, 0, 0, 0, t->width, t->height, GL_RGBA, GL_UNSIGNED_BYTE, t->texels);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (levels > 1)
        gl.GenerateTextureMipmap(tex);
    gl.TextureParameteri(tex, GL_TEXTURE_WRAP_S, gl_wrap(t->wrap_s));
    gl.TextureParameteri(tex, GL_TEXTURE_WRAP_T, gl_wrap(t->wrap_t));
    gl.TextureParameteri(tex, GL_TEXTURE_MAG_FILTER, t->nearest ? GL_NEAREST : GL_LINEAR);
    gl.TextureParameteri(tex, GL_TEXTURE_MIN_FILTER,
                         levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : t->nearest ? GL_NEAREST : GL_LINEAR);
    if (!gl_check("texture upload", err)) {
        gl.DeleteTextures(1, &tex);
        return error_prefix(err, "%s", t->name);
    }
    struct gpu_texture *e = &c->entries[c->count++];
    e->serial = t->serial;
    e->srgb = srgb;
    e->id = tex;
    e->used = true;
    *id = tex;
    return true;
}
