/* Environment cube maps: six faces in a folder (px, nx, py, ny, pz, nz, the
 * OpenGL cube map layout) as linear float .pfm or .hdr, or 8-bit sRGB .png
 * decoded to linear; or one equirectangular .hdr / .pfm resampled into
 * faces. The same data feeds the GPU texture (RGBA16F) and the CPU lookup
 * the reference uses. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fileio.h"
#include "io/image.h"
#include "scene/scene.h"

static const char *face_names[6] = {"px", "nx", "py", "ny", "pz", "nz"};

static struct environment *environment_new(const char *path, struct error *err)
{
    static uint64_t next_serial = 1;
    struct environment *env = calloc(1, sizeof *env);
    if (!env) {
        error_set(err, "out of memory");
        return NULL;
    }
    env->references = 1;
    env->serial = next_serial++;
    snprintf(env->path, sizeof env->path, "%s", path);
    return env;
}

/* The direction through texel centre (x, y) of cube face f (the inverse of
 * the face selection in environment_lookup, OpenGL spec 8.13). */
static vec3 face_direction(int f, int x, int y, int size)
{
    float s = 2.0f * ((float)x + 0.5f) / (float)size - 1.0f, t = 2.0f * ((float)y + 0.5f) / (float)size - 1.0f;
    switch (f) {
    case 0: return vec3_normalize_or(vec3_make(1.0f, -t, -s), vec3_make(0, 0, -1));
    case 1: return vec3_normalize_or(vec3_make(-1.0f, -t, s), vec3_make(0, 0, -1));
    case 2: return vec3_normalize_or(vec3_make(s, 1.0f, t), vec3_make(0, 0, -1));
    case 3: return vec3_normalize_or(vec3_make(s, -1.0f, -t), vec3_make(0, 0, -1));
    case 4: return vec3_normalize_or(vec3_make(s, -t, 1.0f), vec3_make(0, 0, -1));
    default: return vec3_normalize_or(vec3_make(-s, -t, -1.0f), vec3_make(0, 0, -1));
    }
}

/* Bilinear lookup of a latitude-longitude image: u = 0.5 + atan2(x, -z) /
 * 2 pi (the image's centre looks along -z, caustica's default view), v =
 * acos(y) / pi (the top row looks up); wraps in u, clamps in v. */
static vec3 latlong_lookup(const struct image *img, vec3 d)
{
    float u = 0.5f + atan2f(d.x, -d.z) / (2.0f * (float)MATH_PI);
    float v = acosf(fminf(fmaxf(d.y, -1.0f), 1.0f)) / (float)MATH_PI;
    float fx = u * (float)img->width - 0.5f, fy = v * (float)img->height - 0.5f;
    float x0f = floorf(fx), y0f = floorf(fy), bx = fx - x0f, by = fy - y0f;
    vec3 out = {0, 0, 0};
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int x = ((int)x0f + i) % img->width;
            if (x < 0)
                x += img->width;
            int y = (int)fminf(fmaxf(y0f + (float)j, 0.0f), (float)(img->height - 1));
            const float *p = img->rgba + ((size_t)y * (size_t)img->width + (size_t)x) * 4;
            float w = (i ? bx : 1.0f - bx) * (j ? by : 1.0f - by);
            out = vec3_add(out, vec3_make(p[0] * w, p[1] * w, p[2] * w));
        }
    return out;
}

/* An equirectangular (latitude-longitude) .hdr, .pfm or .exr, resampled once into
 * cube faces of a quarter of its width, so that the GPU and the reference
 * read the same texels. */
static struct environment *environment_load_latlong(const char *path, struct error *err)
{
    struct image img;
    if (!image_read(path, &img, err))
        return NULL;
    if (img.width < 8 || img.width != 2 * img.height) {
        error_set(err, "%s: an equirectangular environment must be twice as wide as it is high (%dx%d)", path,
                  img.width, img.height);
        image_destroy(&img);
        return NULL;
    }
    struct environment *env = environment_new(path, err);
    if (!env) {
        image_destroy(&img);
        return NULL;
    }
    env->size = img.width / 4;
    for (int f = 0; f < 6; f++) {
        env->faces[f] = malloc((size_t)env->size * (size_t)env->size * 3 * sizeof(float));
        if (!env->faces[f]) {
            image_destroy(&img);
            environment_destroy(env);
            error_set(err, "out of memory");
            return NULL;
        }
        for (int y = 0; y < env->size; y++)
            for (int x = 0; x < env->size; x++) {
                vec3 c = latlong_lookup(&img, face_direction(f, x, y, env->size));
                float *q = env->faces[f] + ((size_t)y * (size_t)env->size + (size_t)x) * 3;
                q[0] = c.x;
                q[1] = c.y;
                q[2] = c.z;
            }
    }
    image_destroy(&img);
    return env;
}

struct environment *environment_load(const char *path, struct error *err)
{
    if (image_path_is_hdr(path) || image_path_is_pfm(path) || image_path_is_exr(path))
        return environment_load_latlong(path, err);
    struct environment *env = environment_new(path, err);
    if (!env)
        return NULL;
    for (int f = 0; f < 6; f++) {
        /* each face as linear float (.pfm, .hdr) or 8-bit sRGB (.png) */
        static const char *const extensions[] = {"pfm", "hdr", "png"};
        char face[1024] = "";
        for (int e = 0; e < 3; e++) {
            snprintf(face, sizeof face, "%s/%s.%s", path, face_names[f], extensions[e]);
            if (file_exists(face))
                break;
        }
        struct image img;
        if (!image_read(face, &img, err)) {
            environment_destroy(env);
            error_prefix(err, "cube map '%s' needs px/nx/py/ny/pz/nz faces (.pfm, .hdr or .png)", path);
            return NULL;
        }
        if (img.width != img.height || (f > 0 && img.width != env->size)) {
            error_set(err, "%s: cube map faces must be square and of one size (%dx%d)", face, img.width, img.height);
            image_destroy(&img);
            environment_destroy(env);
            return NULL;
        }
        env->size = img.width;
        env->faces[f] = malloc((size_t)img.width * (size_t)img.height * 3 * sizeof(float));
        if (!env->faces[f]) {
            image_destroy(&img);
            environment_destroy(env);
            error_set(err, "out of memory");
            return NULL;
        }
        for (size_t i = 0; i < (size_t)img.width * (size_t)img.height; i++)
            for (int c = 0; c < 3; c++)
                env->faces[f][i * 3 + (size_t)c] = img.rgba[i * 4 + (size_t)c];
        image_destroy(&img);
    }
    return env;
}

vec3 environment_lookup(const struct environment *env, vec3 d)
{
    /* The OpenGL cube map face selection and (s, t) (spec §8.13). */
    float ax = fabsf(d.x), ay = fabsf(d.y), az = fabsf(d.z);
    int face;
    float ma, sc, tc;
    if (ax >= ay && ax >= az) {
        face = d.x >= 0 ? 0 : 1;
        ma = ax;
        sc = d.x >= 0 ? -d.z : d.z;
        tc = -d.y;
    } else if (ay >= az) {
        face = d.y >= 0 ? 2 : 3;
        ma = ay;
        sc = d.x;
        tc = d.y >= 0 ? d.z : -d.z;
    } else {
        face = d.z >= 0 ? 4 : 5;
        ma = az;
        sc = d.z >= 0 ? d.x : -d.x;
        tc = -d.y;
    }
    float s = 0.5f * (math_safe_div(sc, ma, 0.0f) + 1.0f), t = 0.5f * (math_safe_div(tc, ma, 0.0f) + 1.0f);
    /* Bilinear within the face, clamped at its edges: what the GPU's
     * GL_LINEAR cube map lookup (not seamless) returns, so that the
     * reference and the passes see the same environment. */
    float fx = s * (float)env->size - 0.5f, fy = t * (float)env->size - 0.5f;
    float x0f = floorf(fx), y0f = floorf(fy);
    float bx = fx - x0f, by = fy - y0f;
    int last = env->size - 1;
    int x0 = (int)fminf(fmaxf(x0f, 0.0f), (float)last), x1 = (int)fminf(fmaxf(x0f + 1.0f, 0.0f), (float)last);
    int y0 = (int)fminf(fmaxf(y0f, 0.0f), (float)last), y1 = (int)fminf(fmaxf(y0f + 1.0f, 0.0f), (float)last);
    const float *f = env->faces[face];
    vec3 out = {0, 0, 0};
    const int xs[2] = {x0, x1}, ys[2] = {y0, y1};
    const float wx[2] = {1.0f - bx, bx}, wy[2] = {1.0f - by, by};
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            const float *px = f + ((size_t)ys[j] * (size_t)env->size + (size_t)xs[i]) * 3;
            float w = wx[i] * wy[j];
            out = vec3_add(out, vec3_make(px[0] * w, px[1] * w, px[2] * w));
        }
    return out;
}

void environment_retain(struct environment *env)
{
    if (env)
        env->references++;
}

void environment_destroy(struct environment *env)
{
    if (env && --env->references > 0)
        return;
    if (!env)
        return;
    for (int f = 0; f < 6; f++)
        free(env->faces[f]);
    free(env);
}
