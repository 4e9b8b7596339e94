/* Textures: their texels, the reference's sampling (the GPU's filter at
 * level 0) and the texture references materials hold (material.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fileio.h"
#include "io/image_decode.h"
#include "scene/scene.h"

static uint64_t texture_next_serial(void)
{
    static uint64_t next = 1;
    return next++;
}

/* A texture around `texels` (taken: freed here on failure). */
static struct texture *wrap_texels(const char *name, int width, int height, uint8_t *texels, struct error *err)
{
    struct texture *t = texels ? calloc(1, sizeof *t) : NULL;
    if (!t) {
        free(texels);
        error_set(err, "%s: out of memory for %dx%d texels", name, width, height);
        return NULL;
    }
    t->references = 1;
    t->serial = texture_next_serial();
    snprintf(t->name, sizeof t->name, "%s", name);
    t->width = width;
    t->height = height;
    t->texels = texels;
    t->mipmaps = true;
    return t;
}

struct texture *texture_create(const char *name, int width, int height, struct error *err)
{
    if (width < 1 || height < 1 || width > IMAGE_DECODE_MAX_SIDE || height > IMAGE_DECODE_MAX_SIDE) {
        error_set(err, "%s: a texture of %dx%d texels", name, width, height);
        return NULL;
    }
    return wrap_texels(name, width, height, calloc((size_t)width * (size_t)height, 4), err);
}

static uint8_t to_byte_srgb(float linear)
{
    float c = linear <= 0.0f ? 0.0f : linear >= 1.0f ? 1.0f : linear;
    float e = c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
    return (uint8_t)lrintf(e * 255.0f);
}

struct texture *texture_create_checker(int squares, vec3 a, vec3 b, struct error *err)
{
    if (squares < 1 || squares > 4096) {
        error_set(err, "checker: size must be a whole number of squares in 1..4096 (got %d)", squares);
        return NULL;
    }
    struct texture *t = texture_create("checker", squares, squares, err);
    if (!t)
        return NULL;
    /* One texel a square, sampled nearest: the GPU and the reference see
     * the same sharp edges at any distance (no mipmaps: a far checker
     * aliases on both rather than greying on one). The colours are stored
     * sRGB-encoded like any colour texture. */
    t->nearest = true;
    t->mipmaps = false;
    for (int y = 0; y < squares; y++)
        for (int x = 0; x < squares; x++) {
            vec3 c = (x + y) % 2 == 0 ? a : b;
            uint8_t *p = t->texels + ((size_t)y * (size_t)squares + (size_t)x) * 4;
            p[0] = to_byte_srgb(c.x);
            p[1] = to_byte_srgb(c.y);
            p[2] = to_byte_srgb(c.z);
            p[3] = 255;
        }
    return t;
}

struct texture *texture_decode(const char *name, const uint8_t *bytes, size_t size, unsigned long long max_bytes,
                               struct error *err)
{
    uint8_t *rgba;
    int w, h;
    if (!image_decode_rgba8(name, bytes, size, max_bytes, &rgba, &w, &h, err))
        return NULL;
    return wrap_texels(name, w, h, rgba, err);
}

struct texture *texture_load(const char *path, unsigned long long max_bytes, struct error *err)
{
    char *data;
    size_t size;
    if (!file_read_all(path, &data, &size, err))
        return NULL;
    struct texture *t = texture_decode(path, (const uint8_t *)data, size, max_bytes, err);
    free(data);
    return t;
}

size_t texture_bytes(const struct texture *t)
{
    return t ? (size_t)t->width * (size_t)t->height * 4 : 0;
}

void texture_retain(struct texture *t)
{
    if (t)
        t->references++;
}

void texture_destroy(struct texture *t)
{
    if (!t || --t->references > 0)
        return;
    free(t->texels);
    free(t->mip_chain[0]);
    free(t->mip_chain[1]);
    free(t);
}

void texture_ref_init(struct texture_ref *ref)
{
    memset(ref, 0, sizeof *ref);
    ref->transform[0] = 1.0f;
    ref->transform[3] = 1.0f;
    ref->scale = 1.0f;
}

void texture_ref_apply(const struct texture_ref *ref, const float uv[2], float out[2])
{
    const float *m = ref->transform;
    out[0] = m[0] * uv[0] + m[2] * uv[1] + m[4];
    out[1] = m[1] * uv[0] + m[3] * uv[1] + m[5];
}

/* The texel index of i under a wrap mode (GL's REPEAT, CLAMP_TO_EDGE,
 * MIRRORED_REPEAT). */
static int wrap_index(long i, int n, enum texture_wrap wrap)
{
    switch (wrap) {
    case TEXTURE_CLAMP: return i < 0 ? 0 : i >= n ? n - 1 : (int)i;
    case TEXTURE_MIRROR: {
        long period = 2L * n, k = ((i % period) + period) % period;
        return (int)(k < n ? k : period - 1 - k);
    }
    case TEXTURE_REPEAT:
    default: return (int)(((i % n) + n) % n);
    }
}

static float srgb_decode_byte(uint8_t b)
{
    static float table[256];
    static int ready;
    if (!ready) {
        for (int i = 0; i < 256; i++) {
            double e = i / 255.0;
            table[i] = (float)(e <= 0.04045 ? e / 12.92 : pow((e + 0.055) / 1.055, 2.4));
        }
        ready = 1;
    }
    return table[b];
}

static vec3 texel(const struct texture *t, int x, int y, bool srgb)
{
    const uint8_t *p = t->texels + ((size_t)y * (size_t)t->width + (size_t)x) * 4;
    if (srgb)
        return vec3_make(srgb_decode_byte(p[0]), srgb_decode_byte(p[1]), srgb_decode_byte(p[2]));
    return vec3_make(p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f);
}

/* The texels GL's filter reads at uv (transformed) on a level of w x h:
 * x[0..1] by y[0..1] with weights ax, ay along them (nearest: one texel,
 * both weights 0). */
static void texture_footprint(const struct texture *t, int w, int h, bool nearest, const float uv[2], int x[2],
                              int y[2], float *ax, float *ay)
{
    /* A coordinate that is not finite (a degenerate mapping) samples texel 0. */
    double u = isfinite(uv[0]) ? uv[0] : 0.0, v = isfinite(uv[1]) ? uv[1] : 0.0;
    /* Far-away coordinates lose nothing to the wrap but would overflow a long. */
    u = fmod(u, 65536.0);
    v = fmod(v, 65536.0);
    if (nearest) {
        x[0] = x[1] = wrap_index((long)floor(u * w), w, t->wrap_s);
        y[0] = y[1] = wrap_index((long)floor(v * h), h, t->wrap_t);
        *ax = *ay = 0.0f;
        return;
    }
    /* GL's bilinear filter: texel centres at (i + 0.5) / n. */
    double fx = floor(u * w - 0.5), fy = floor(v * h - 0.5);
    *ax = (float)(u * w - 0.5 - fx);
    *ay = (float)(v * h - 0.5 - fy);
    x[0] = wrap_index((long)fx, w, t->wrap_s);
    x[1] = wrap_index((long)fx + 1, w, t->wrap_s);
    y[0] = wrap_index((long)fy, h, t->wrap_t);
    y[1] = wrap_index((long)fy + 1, h, t->wrap_t);
}

vec3 texture_sample(const struct texture_ref *ref, const float uv_in[2], bool srgb)
{
    const struct texture *t = ref->texture;
    if (!t)
        return vec3_make(1, 1, 1);
    int x[2], y[2];
    float ax, ay, uv[2];
    texture_ref_apply(ref, uv_in, uv);
    texture_footprint(t, t->width, t->height, t->nearest, uv, x, y, &ax, &ay);
    vec3 a = vec3_lerp(texel(t, x[0], y[0], srgb), texel(t, x[1], y[0], srgb), ax);
    vec3 b = vec3_lerp(texel(t, x[0], y[1], srgb), texel(t, x[1], y[1], srgb), ax);
    return vec3_lerp(a, b, ay);
}

float texture_sample_alpha(const struct texture_ref *ref, const float uv_in[2])
{
    const struct texture *t = ref->texture;
    if (!t)
        return 1.0f;
    int x[2], y[2];
    float ax, ay, uv[2];
    texture_ref_apply(ref, uv_in, uv);
    texture_footprint(t, t->width, t->height, t->nearest, uv, x, y, &ax, &ay);
    float at[2][2];
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++)
            at[j][i] = t->texels[((size_t)y[j] * (size_t)t->width + (size_t)x[i]) * 4 + 3] / 255.0f;
    float a = at[0][0] + (at[0][1] - at[0][0]) * ax, b = at[1][0] + (at[1][1] - at[1][0]) * ax;
    return a + (b - a) * ay;
}

/* ---- mipmaps: the chain the GPU filters through, for the reference ---- */

static int level_side(int side, int level)
{
    int s = side >> level;
    return s > 0 ? s : 1;
}

/* Level `level`'s texels: level 0 is the texture's own, the others lie
 * one after the other in the chain. */
static const uint8_t *level_texels(const struct texture *t, int chain, int level)
{
    if (level == 0)
        return t->texels;
    size_t offset = 0;
    for (int k = 1; k < level; k++)
        offset += (size_t)level_side(t->width, k) * (size_t)level_side(t->height, k) * 4;
    return t->mip_chain[chain] + offset;
}

/* RGBA of texel (x, y) of a level w texels wide, RGB decoded from sRGB
 * when `srgb` (alpha is always linear). */
static void level_texel(const uint8_t *texels, int w, int x, int y, bool srgb, float out[4])
{
    const uint8_t *p = texels + ((size_t)y * (size_t)w + (size_t)x) * 4;
    for (int k = 0; k < 3; k++)
        out[k] = srgb ? srgb_decode_byte(p[k]) : p[k] / 255.0f;
    out[3] = p[3] / 255.0f;
}

/* GL's filter in one level: bilinear, or nearest (level 0 magnified). */
static void level_filter(const struct texture *t, int chain, int level, bool nearest, const float uv[2], bool srgb,
                         float out[4])
{
    int w = level_side(t->width, level), h = level_side(t->height, level);
    const uint8_t *texels = level_texels(t, chain, level);
    int x[2], y[2];
    float ax, ay, c[2][2][4];
    texture_footprint(t, w, h, nearest, uv, x, y, &ax, &ay);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++)
            level_texel(texels, w, x[i], y[j], srgb, c[j][i]);
    for (int k = 0; k < 4; k++) {
        float a = c[0][0][k] + (c[0][1][k] - c[0][0][k]) * ax, b = c[1][0][k] + (c[1][1][k] - c[1][0][k]) * ax;
        out[k] = a + (b - a) * ay;
    }
}

/* Level k from level k - 1 as Mesa's glGenerateMipmap does it (a linear
 * blit: each new texel the bilinear value at its centre in the level
 * above, edges clamped; a 2 x 2 box where the side halves exactly), in
 * linear values (sRGB colours decoded, averaged, encoded again). */
static void downsample(const uint8_t *src, int sw, int sh, uint8_t *dst, int dw, int dh, bool srgb)
{
    for (int j = 0; j < dh; j++) {
        double sy = (j + 0.5) * sh / dh - 0.5, fy = floor(sy);
        int y0 = (int)fy < 0 ? 0 : (int)fy, y1 = (int)fy + 1 >= sh ? sh - 1 : (int)fy + 1;
        float ay = (float)(sy - fy);
        for (int i = 0; i < dw; i++) {
            double sx = (i + 0.5) * sw / dw - 0.5, fx = floor(sx);
            int x0 = (int)fx < 0 ? 0 : (int)fx, x1 = (int)fx + 1 >= sw ? sw - 1 : (int)fx + 1;
            float ax = (float)(sx - fx), c[4][4];
            level_texel(src, sw, x0, y0, srgb, c[0]);
            level_texel(src, sw, x1, y0, srgb, c[1]);
            level_texel(src, sw, x0, y1, srgb, c[2]);
            level_texel(src, sw, x1, y1, srgb, c[3]);
            uint8_t *d = dst + ((size_t)j * (size_t)dw + (size_t)i) * 4;
            for (int k = 0; k < 4; k++) {
                float a = c[0][k] + (c[1][k] - c[0][k]) * ax, b = c[2][k] + (c[3][k] - c[2][k]) * ax;
                float v = a + (b - a) * ay;
                d[k] = srgb && k < 3 ? to_byte_srgb(v) : (uint8_t)lrintf(fminf(fmaxf(v, 0.0f), 1.0f) * 255.0f);
            }
        }
    }
}

bool texture_build_mips(struct texture *t, bool srgb, struct error *err)
{
    int chain = srgb ? 1 : 0;
    if (!t->mipmaps || t->mip_chain[chain])
        return true;
    int levels = 1;
    for (int s = t->width > t->height ? t->width : t->height; s > 1; s /= 2)
        levels++; /* as graph/texture_cache.c allocates the GPU's */
    if (levels == 1)
        return true;
    size_t bytes = 0;
    for (int k = 1; k < levels; k++)
        bytes += (size_t)level_side(t->width, k) * (size_t)level_side(t->height, k) * 4;
    uint8_t *c = malloc(bytes);
    if (!c)
        return error_set(err, "%s: out of memory for its mipmaps (%zu bytes)", t->name, bytes);
    t->mip_chain[chain] = c;
    t->levels = levels;
    for (int k = 1; k < levels; k++)
        downsample(level_texels(t, chain, k - 1), level_side(t->width, k - 1), level_side(t->height, k - 1),
                   (uint8_t *)level_texels(t, chain, k), level_side(t->width, k), level_side(t->height, k), srgb);
    return true;
}

void texture_sample_grad(const struct texture_ref *ref, const float uv_in[2], const float duv[4], bool srgb,
                         float rgba[4])
{
    const struct texture *t = ref->texture;
    int chain = srgb ? 1 : 0;
    if (!t) {
        rgba[0] = rgba[1] = rgba[2] = rgba[3] = 1.0f;
        return;
    }
    float uv[2];
    texture_ref_apply(ref, uv_in, uv);
    /* The transform's linear part carries the derivatives too. */
    const float *m = ref->transform;
    double dudx = m[0] * duv[0] + m[2] * duv[1], dvdx = m[1] * duv[0] + m[3] * duv[1];
    double dudy = m[0] * duv[2] + m[2] * duv[3], dvdy = m[1] * duv[2] + m[3] * duv[3];
    /* §8.14.1: rho, the longer of the two derivatives in texels, lambda = log2(rho) */
    double rho = fmax(hypot(dudx * t->width, dvdx * t->height), hypot(dudy * t->width, dvdy * t->height));
    double lod = rho > 0.0 ? log2(rho) : 0.0; /* (NaN: not > 0, the magnification below) */
    if (!t->mipmaps || !t->mip_chain[chain] || !(lod > 0.0)) {
        /* magnified (or no chain): level 0 through the magnification filter */
        level_filter(t, chain, 0, t->nearest, uv, srgb, rgba);
        return;
    }
    /* LINEAR_MIPMAP_LINEAR: bilinear in levels floor(lambda) and the next, linear between */
    double top = t->levels - 1;
    lod = fmin(lod, top); /* (inf: the last level) */
    int d1 = (int)floor(lod), d2 = d1 + 1 <= (int)top ? d1 + 1 : d1;
    float f = (float)(lod - d1), a[4], b[4];
    level_filter(t, chain, d1, false, uv, srgb, a);
    level_filter(t, chain, d2, false, uv, srgb, b);
    for (int k = 0; k < 4; k++)
        rgba[k] = a[k] + (b[k] - a[k]) * f;
}
