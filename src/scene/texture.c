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

/* The texels GL's filter reads at uv (after the reference's transform):
 * x[0..1] by y[0..1] with weights ax, ay along them (nearest: one texel,
 * both weights 0). */
static void texture_footprint(const struct texture_ref *ref, const float uv_in[2], int x[2], int y[2], float *ax,
                              float *ay)
{
    const struct texture *t = ref->texture;
    float uv[2];
    texture_ref_apply(ref, uv_in, uv);
    /* A coordinate that is not finite (a degenerate mapping) samples texel 0. */
    double u = isfinite(uv[0]) ? uv[0] : 0.0, v = isfinite(uv[1]) ? uv[1] : 0.0;
    /* Far-away coordinates lose nothing to the wrap but would overflow a long. */
    u = fmod(u, 65536.0);
    v = fmod(v, 65536.0);
    if (t->nearest) {
        x[0] = x[1] = wrap_index((long)floor(u * t->width), t->width, t->wrap_s);
        y[0] = y[1] = wrap_index((long)floor(v * t->height), t->height, t->wrap_t);
        *ax = *ay = 0.0f;
        return;
    }
    /* GL's bilinear filter: texel centres at (i + 0.5) / n. */
    double fx = floor(u * t->width - 0.5), fy = floor(v * t->height - 0.5);
    *ax = (float)(u * t->width - 0.5 - fx);
    *ay = (float)(v * t->height - 0.5 - fy);
    x[0] = wrap_index((long)fx, t->width, t->wrap_s);
    x[1] = wrap_index((long)fx + 1, t->width, t->wrap_s);
    y[0] = wrap_index((long)fy, t->height, t->wrap_t);
    y[1] = wrap_index((long)fy + 1, t->height, t->wrap_t);
}

vec3 texture_sample(const struct texture_ref *ref, const float uv_in[2], bool srgb)
{
    const struct texture *t = ref->texture;
    if (!t)
        return vec3_make(1, 1, 1);
    int x[2], y[2];
    float ax, ay;
    texture_footprint(ref, uv_in, x, y, &ax, &ay);
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
    float ax, ay;
    texture_footprint(ref, uv_in, x, y, &ax, &ay);
    float at[2][2];
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++)
            at[j][i] = t->texels[((size_t)y[j] * (size_t)t->width + (size_t)x[i]) * 4 + 3] / 255.0f;
    float a = at[0][0] + (at[0][1] - at[0][0]) * ax, b = at[1][0] + (at[1][1] - at[1][0]) * ax;
    return a + (b - a) * ay;
}
