/* The reference's mip levels against the GPU's (issue 50): textures made
 * of random texels (power-of-two and odd sides, sRGB and linear, each
 * wrap mode) are uploaded as the renderer uploads them (texture_cache_get:
 * glGenerateMipmap, LINEAR_MIPMAP_LINEAR) and read by textureGrad in a
 * compute shader at random coordinates and derivatives, from magnified to
 * past the last level, and texture_sample_grad must read the same values.
 * Before it, the reference read level 0 alone: a texture minified ten
 * times showed its texels' contrast where the GPU showed their mean. */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "gl/gl_context.h"
#include "gl/gl_program.h"
#include "graph/texture_cache.h"
#include "scene/scene.h"

static const char sample_comp[] =
    "#version 450 core\n"
    "layout(local_size_x = 1) in;\n"
    "layout(std430) buffer Cases { vec4 cases[]; };\n"
    "layout(std430) buffer Results { vec4 results[]; };\n"
    "uniform sampler2D u_texture;\n"
    "void main() {\n"
    "    uint i = gl_GlobalInvocationID.x;\n"
    "    vec4 a = cases[2u * i], b = cases[2u * i + 1u];\n"
    "    results[i] = textureGrad(u_texture, a.xy, a.zw, b.xy);\n"
    "}\n";

enum { CASES = 600 };

static uint32_t rng_state = 12345u;
static double uniform01(void)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (rng_state >> 8) / 16777216.0;
}

struct trial {
    int width, height;
    bool srgb, nearest;
    enum texture_wrap wrap;
    const char *what;
};

/* Largest difference over the cases, per channel, between GL and C. */
static double compare(struct gl_program *prog, const struct trial *tr)
{
    struct error err;
    struct texture *t = texture_create(tr->what, tr->width, tr->height, &err);
    CHECK(t != NULL);
    if (!t)
        return INFINITY;
    for (int i = 0; i < tr->width * tr->height * 4; i++)
        t->texels[i] = (uint8_t)(uniform01() * 256.0);
    t->wrap_s = t->wrap_t = tr->wrap;
    t->nearest = tr->nearest;
    struct texture_cache cache;
    texture_cache_init(&cache);
    GLuint id = 0;
    CHECK(texture_cache_get(&cache, t, tr->srgb, &id, &err));
    CHECK(texture_build_mips(t, tr->srgb, &err));
    struct texture_ref ref;
    texture_ref_init(&ref);
    ref.texture = t;
    static float cases[CASES * 8], got[CASES * 4];
    int longer = tr->width > tr->height ? tr->width : tr->height;
    for (int i = 0; i < CASES; i++) {
        float *c = cases + i * 8;
        c[0] = (float)(uniform01() * 3.0 - 1.0);
        c[1] = (float)(uniform01() * 3.0 - 1.0);
        /* level of detail from -2 to two past the last level, isotropic
         * or up to 4:1, at any angle */
        double lod = -2.0 + uniform01() * (log2(longer) + 4.0), rho = exp2(lod) / longer;
        double angle = uniform01() * 6.283185307, squash = 0.25 + 0.75 * uniform01();
        c[2] = (float)(rho * cos(angle));
        c[3] = (float)(rho * sin(angle));
        c[4] = (float)(-rho * squash * sin(angle));
        c[5] = (float)(rho * squash * cos(angle));
        c[6] = c[7] = 0.0f;
    }
    GLuint in, out;
    gl.CreateBuffers(1, &in);
    gl.CreateBuffers(1, &out);
    gl.NamedBufferStorage(in, sizeof cases, cases, 0);
    gl.NamedBufferStorage(out, sizeof got, NULL, GL_DYNAMIC_STORAGE_BIT);
    gl.UseProgram(prog->id);
    CHECK(gl_program_bind_storage(prog, "Cases", in) && gl_program_bind_storage(prog, "Results", out));
    CHECK(gl_program_bind_texture(prog, "u_texture", id));
    gl.DispatchCompute(CASES, 1, 1);
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl.GetNamedBufferSubData(out, 0, sizeof got, got);
    gl.DeleteBuffers(1, &in);
    gl.DeleteBuffers(1, &out);
    double worst = 0.0, worst_level0 = 0.0;
    for (int i = 0; i < CASES; i++) {
        const float *c = cases + i * 8;
        float rgba[4];
        texture_sample_grad(&ref, c, c + 2, tr->srgb, rgba);
        vec3 level0 = texture_sample(&ref, c, tr->srgb);
        for (int k = 0; k < 4; k++)
            worst = fmax(worst, fabs(rgba[k] - got[i * 4 + k]));
        worst_level0 = fmax(worst_level0, fabs(level0.x - got[i * 4]));
    }
    printf("%-32s largest difference %.4f (level 0 alone: %.4f)\n", tr->what, worst, worst_level0);
    /* level 0 alone must be far off: the comparison can fail */
    CHECK(worst_level0 > 0.2);
    texture_cache_release(&cache);
    texture_destroy(t);
    return worst;
}

int main(void)
{
    struct error err;
    struct gl_context *ctx;
    if (!gl_context_create(GL_BACKEND_OSMESA, 16, 16, "test", &ctx, &err)) {
        fprintf(stderr, "test_texture_lod: no GL context: %s\n", err.message);
        return 1;
    }
    char root[] = "/tmp/caustica-test-lod.XXXXXX", path[256];
    CHECK(mkdtemp(root) != NULL);
    snprintf(path, sizeof path, "%s/sample.comp", root);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    fputs(sample_comp, f);
    fclose(f);
    struct gl_program_cache programs;
    gl_program_cache_init(&programs, root);
    struct gl_program *prog = NULL;
    if (!gl_program_get_compute(&programs, "sample.comp", NULL, NULL, &prog, &err)) {
        fprintf(stderr, "test_texture_lod: %s\n", err.message);
        return 1;
    }
    const struct trial trials[] = {
        {64, 64, false, false, TEXTURE_REPEAT, "64x64 linear, repeat"},
        {64, 32, true, false, TEXTURE_MIRROR, "64x32 sRGB, mirrored repeat"},
        {37, 20, false, false, TEXTURE_CLAMP, "37x20 linear, clamp"},
        {45, 45, true, true, TEXTURE_REPEAT, "45x45 sRGB, nearest when magnified"},
    };
    for (size_t i = 0; i < sizeof trials / sizeof trials[0]; i++) {
        double worst = compare(prog, &trials[i]);
        /* llvmpipe filters in 8-bit fixed point and stores each level in
         * the texture's 8 bits, as the chain here does */
        CHECK(worst < 0.03);
    }
    gl_program_cache_destroy(&programs);
    snprintf(path, sizeof path, "%s/sample.comp", root);
    unlink(path);
    rmdir(root);
    gl_context_destroy(ctx);
    return check_finish("test_texture_lod");
}
