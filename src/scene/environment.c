/* Environment cube maps: six PNG faces in a folder (px, nx, py, ny, pz, nz
 * .png, the OpenGL cube map layout), decoded to linear radiance. The same
 * data feeds the GPU texture and the CPU lookup the reference uses. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fileio.h"
#include "io/image.h"
#include "scene/scene.h"

static const char *face_names[6] = {"px", "nx", "py", "ny", "pz", "nz"};

struct environment *environment_load(const char *folder, struct error *err)
{
    static uint64_t next_serial = 1;
    struct environment *env = calloc(1, sizeof *env);
    if (env) {
        env->references = 1;
        env->serial = next_serial++;
    }
    if (!env) {
        error_set(err, "out of memory");
        return NULL;
    }
    snprintf(env->path, sizeof env->path, "%s", folder);
    for (int f = 0; f < 6; f++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s.png", folder, face_names[f]);
        struct image img;
        if (!image_read_png(path, &img, err)) {
            environment_destroy(env);
            error_prefix(err, "cube map '%s' needs px/nx/py/ny/pz/nz.png", folder);
            return NULL;
        }
        if (img.width != img.height || (f > 0 && img.width != env->size)) {
            error_set(err, "%s: cube map faces must be square and of one size (%dx%d)", path, img.width, img.height);
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
