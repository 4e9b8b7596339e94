/* Binding by name (gl/gl_program.c): after link every sampler, image and
 * buffer block gets a unit; one name keeps its unit in every program of a
 * shader folder; reserved names keep theirs everywhere; binding by the
 * shader's name reaches the data (a compute shader reads two textures and
 * writes what it read into a buffer); uniform locations come from the
 * table read after link. */
#define _DEFAULT_SOURCE /* mkdtemp, usleep */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "core/fileio.h"
#include "gl/gl_context.h"
#include "gl/gl_param_block.h"
#include "gl/gl_program.h"
#include "gl/gl_texture.h"

static void write_shader(const char *root, const char *rel, const char *text)
{
    char path[1200], dir[1200];
    snprintf(path, sizeof path, "%s/%s", root, rel);
    snprintf(dir, sizeof dir, "%s", path);
    *strrchr(dir, '/') = '\0';
    char cmd[1300];
    snprintf(cmd, sizeof cmd, "mkdir -p '%s'", dir);
    if (system(cmd) != 0)
        return;
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static GLint sampler_value(const struct gl_program *p, const char *name)
{
    GLint v = -1;
    gl.GetUniformiv(p->id, gl_program_uniform(p, name), &v);
    return v;
}

static GLuint texel_texture(float r, float g, float b)
{
    struct gl_texture t;
    struct error err;
    if (!gl_texture_create(&t, GL_TEXTURE_2D, GL_RGBA32F, 1, 1, 1, &err))
        return 0;
    const float c[4] = {r, g, b, 1.0f};
    gl.ClearTexImage(t.id, 0, GL_RGBA, GL_FLOAT, c);
    return t.id;
}

int main(void)
{
    struct error err;
    struct gl_context *ctx;
    if (!gl_context_create(GL_BACKEND_OSMESA, 16, 16, "test", &ctx, &err)) {
        fprintf(stderr, "test_program: no GL context: %s\n", err.message);
        return 1;
    }
    char root[] = "/tmp/caustica-test-program.XXXXXX";
    CHECK(mkdtemp(root) != NULL);
    const char *head = "#version 450 core\nlayout(local_size_x = 1) in;\n"
                       "uniform sampler2D u_env;\nlayout(std430) buffer Out { vec4 values[]; };\n";
    char a[2048], b[2048], c[2048];
    snprintf(a, sizeof a, "%s%s", head,
             "uniform sampler2D u_x;\nuniform sampler2D u_y;\nuniform float u_gain;\n"
             "void main() { values[0] = texelFetch(u_x, ivec2(0), 0) * u_gain;\n"
             "  values[1] = texelFetch(u_y, ivec2(0), 0); values[2] = texelFetch(u_env, ivec2(0), 0); }\n");
    snprintf(b, sizeof b, "%s%s", head,
             "uniform sampler2D u_z[2];\nuniform sampler2D u_y;\nlayout(rgba32f) uniform image2D u_img;\n"
             "void main() { values[3] = texelFetch(u_z[0], ivec2(0), 0) + texelFetch(u_z[1], ivec2(0), 0)\n"
             "  + texelFetch(u_y, ivec2(0), 0); imageStore(u_img, ivec2(0), vec4(1)); }\n");
    snprintf(c, sizeof c, "%s%s", head,
             "uniform sampler2D u_w;\nvoid main() { values[4] = texelFetch(u_w, ivec2(0), 0); }\n");
    write_shader(root, "first/a.comp", a);
    write_shader(root, "first/b.comp", b);
    write_shader(root, "second/c.comp", c);
    /* a pass's parameters as one block (gl_program_check_block) */
    write_shader(root, "second/grid.comp",
                 "#version 450 core\nlayout(local_size_x = 8, local_size_y = 4) in;\n"
                 "layout(std430) buffer Count { uint invocations; };\n"
                 "void main() { atomicAdd(invocations, 1u); }\n");
    write_shader(root, "second/params.comp",
                 "#version 450 core\nlayout(local_size_x = 1) in;\nlayout(std430) buffer Out { vec4 values[]; };\n"
                 "layout(std140) uniform Params { int u_count; float u_gain; float u_bias; };\n"
                 "void main() { values[5] = vec4(float(u_count) * u_gain + u_bias); }\n");

    struct gl_program_cache cache;
    gl_program_cache_init(&cache, root);
    CHECK(gl_program_cache_reserve(&cache, GL_SLOT_TEXTURE, "u_env", 0, 1, &err));
    CHECK(!gl_program_cache_reserve(&cache, GL_SLOT_TEXTURE, "u_other", 0, 1, &err));
    CHECK_CONTAINS(err.message, "reserved twice");
    struct gl_program *pa, *pb, *pc;
    CHECK(gl_program_get_compute(&cache, "first/a.comp", NULL, NULL, &pa, &err));
    CHECK(gl_program_get_compute(&cache, "first/b.comp", NULL, NULL, &pb, &err));
    CHECK(gl_program_get_compute(&cache, "second/c.comp", NULL, NULL, &pc, &err));
    CHECK(strcmp(pa->space, "first") == 0 && strcmp(pc->space, "second") == 0);

    /* the units, and the values the programs' samplers were given */
    int x = gl_program_unit(pa, GL_SLOT_TEXTURE, "u_x"), y = gl_program_unit(pa, GL_SLOT_TEXTURE, "u_y");
    int z = gl_program_unit(pb, GL_SLOT_TEXTURE, "u_z");
    CHECK(gl_program_unit(pa, GL_SLOT_TEXTURE, "u_env") == 0);
    CHECK(gl_program_unit(pc, GL_SLOT_TEXTURE, "u_env") == -1); /* declared, unread: the linker dropped it */
    CHECK(x > 0 && y > 0 && x != y);
    CHECK(gl_program_unit(pb, GL_SLOT_TEXTURE, "u_y") == y); /* one name, one unit in a folder */
    CHECK(z > 0 && z != x && z != y && z + 1 != x && z + 1 != y); /* an array: two units of its own */
    CHECK(sampler_value(pa, "u_x") == x && sampler_value(pa, "u_y") == y && sampler_value(pa, "u_env") == 0);

    /* a uniform no stage declares is reported (a misspelt name); one the
     * linker dropped (declared, unread) and an optional look-up are not */
    char undeclared[512];
    CHECK(gl_program_cache_take_undeclared(&cache, undeclared, sizeof undeclared) == 0);
    CHECK(gl_program_uniform(pa, "u_gian") == -1);
    CHECK(gl_program_uniform(pc, "u_env") == -1);          /* declared in c.comp, unread */
    CHECK(gl_program_uniform_optional(pc, "u_other") == -1); /* a shared helper's guess */
    CHECK(gl_program_uniform(pa, "u_gian[2]") == -1);     /* the same base name: reported once */
    CHECK(gl_program_cache_take_undeclared(&cache, undeclared, sizeof undeclared) == 1);
    CHECK(strcmp(undeclared, "'u_gian' (first/a.comp)") == 0);
    CHECK(gl_program_uniform(pa, "u_gian") == -1); /* asked again: known missing, no new report */
    CHECK(gl_program_cache_take_undeclared(&cache, undeclared, sizeof undeclared) == 0);
    CHECK(sampler_value(pb, "u_z[1]") == z + 1);
    CHECK(gl_program_unit(pb, GL_SLOT_IMAGE, "u_img") >= 0);
    CHECK(gl_program_unit(pa, GL_SLOT_STORAGE, "Out") == gl_program_unit(pb, GL_SLOT_STORAGE, "Out"));
    CHECK(gl_program_unit(pc, GL_SLOT_TEXTURE, "u_w") > 0); /* another folder: its own units, never 0 */
    CHECK(gl_program_unit(pa, GL_SLOT_TEXTURE, "u_missing") == -1);
    CHECK(!gl_program_bind_texture(pa, "u_missing", 0));
    CHECK(!gl_program_bind_texture_at(pb, "u_z", 2, 0)); /* past the array's end */

    /* locations from the table equal the GL's */
    CHECK(gl_program_uniform(pa, "u_gain") == gl.GetUniformLocation(pa->id, "u_gain"));
    CHECK(gl_program_uniform(pa, "u_gain") >= 0);
    CHECK(gl_program_uniform(pa, "u_nothing") == -1);

    /* bound by name, read by the shaders */
    GLuint red = texel_texture(1, 0, 0), green = texel_texture(0, 1, 0), blue = texel_texture(0, 0, 1);
    GLuint grey = texel_texture(0.5f, 0.5f, 0.5f), image = texel_texture(0, 0, 0);
    GLuint out;
    gl.CreateBuffers(1, &out);
    gl.NamedBufferStorage(out, 5 * 4 * sizeof(float), NULL, GL_DYNAMIC_STORAGE_BIT);
    const float zero = 0.0f;
    gl.ClearNamedBufferData(out, GL_R32F, GL_RED, GL_FLOAT, &zero);
    gl.BindTextureUnit(0, grey); /* the reserved unit: bound once, as the renderer does */
    gl.UseProgram(pa->id);
    gl.ProgramUniform1f(pa->id, gl_program_uniform(pa, "u_gain"), 2.0f);
    CHECK(gl_program_bind_texture(pa, "u_x", red));
    CHECK(gl_program_bind_texture(pa, "u_y", green));
    CHECK(gl_program_bind_storage(pa, "Out", out));
    gl.DispatchCompute(1, 1, 1);
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl.UseProgram(pb->id); /* u_y and Out still bound: the folder's units */
    CHECK(gl_program_bind_texture_at(pb, "u_z", 0, red));
    CHECK(gl_program_bind_texture_at(pb, "u_z", 1, blue));
    CHECK(gl_program_bind_image(pb, "u_img", image, GL_FALSE, GL_WRITE_ONLY, GL_RGBA32F));
    gl.DispatchCompute(1, 1, 1);
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl.UseProgram(pc->id);
    CHECK(gl_program_bind_texture(pc, "u_w", blue));
    CHECK(gl_program_bind_storage(pc, "Out", out));
    gl.DispatchCompute(1, 1, 1);
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    float v[20];
    gl.GetNamedBufferSubData(out, 0, sizeof v, v);
    CHECK_NEAR(v[0], 2.0, 1e-6); /* red * gain */
    CHECK_NEAR(v[1], 0.0, 1e-6);
    CHECK_NEAR(v[5], 1.0, 1e-6); /* green */
    CHECK_NEAR(v[8], 0.5, 1e-6); /* the reserved unit's grey */
    CHECK_NEAR(v[12], 1.0, 1e-6); /* red + blue + green */
    CHECK_NEAR(v[13], 1.0, 1e-6);
    CHECK_NEAR(v[14], 1.0, 1e-6);
    CHECK_NEAR(v[18], 1.0, 1e-6); /* blue, through the other folder's unit */
    float texel[4] = {0};
    gl.GetTextureImage(image, 0, GL_RGBA, GL_FLOAT, sizeof texel, texel);
    CHECK_NEAR(texel[0], 1.0, 1e-6);
    CHECK(gl.GetError() == GL_NO_ERROR);

    /* a uniform block against its C mirror: each member at its offset,
     * exactly these members; a wrong offset, a missing member and one C
     * lacks each an error naming it */
    struct gl_program *pp;
    CHECK(gl_program_get_compute(&cache, "second/params.comp", NULL, NULL, &pp, &err));
    struct params_mirror { int32_t count; float gain, bias, pad; };
    const struct gl_block_member good[3] = {{"u_count", offsetof(struct params_mirror, count)},
                                            {"u_gain", offsetof(struct params_mirror, gain)},
                                            {"u_bias", offsetof(struct params_mirror, bias)}};
    CHECK(gl_program_check_block(pp, "Params", good, 3, sizeof(struct params_mirror), &err));
    const struct gl_block_member shifted[3] = {{"u_count", 0}, {"u_gain", 8}, {"u_bias", 4}};
    CHECK(!gl_program_check_block(pp, "Params", shifted, 3, sizeof(struct params_mirror), &err));
    CHECK_CONTAINS(err.message, "member 'u_gain' at byte 4, its C mirror's at 8");
    const struct gl_block_member misspelt[3] = {{"u_count", 0}, {"u_gian", 4}, {"u_bias", 8}};
    CHECK(!gl_program_check_block(pp, "Params", misspelt, 3, sizeof(struct params_mirror), &err));
    CHECK_CONTAINS(err.message, "no member 'u_gian'");
    CHECK(!gl_program_check_block(pp, "Params", good, 2, sizeof(struct params_mirror), &err));
    CHECK_CONTAINS(err.message, "has 3 members, its C mirror 2");
    CHECK(!gl_program_check_block(pp, "Parms", good, 3, sizeof(struct params_mirror), &err));
    CHECK_CONTAINS(err.message, "no uniform block 'Parms'");
    /* ... and as a pass holds it (gl_param_block): checked on first bind,
     * uploaded in one call, read by the program; a misspelt member stops
     * the bind with the member's name */
    struct gl_param_block block = {.name = "Params", .members = good, .count = 3,
                                   .size = sizeof(struct params_mirror)};
    const struct params_mirror values = {3, 2.0f, 0.5f, 0.0f};
    CHECK(gl_param_block_upload(&block, &values, &err));
    CHECK(gl_param_block_bind(&block, pp, &err) && block.checked_count == 1);
    CHECK(gl_param_block_bind(&block, pp, &err) && block.checked_count == 1); /* checked once */
    GLuint read_back; /* values[5]: six vec4 */
    gl.CreateBuffers(1, &read_back);
    gl.NamedBufferStorage(read_back, 6 * 4 * sizeof(float), NULL, GL_DYNAMIC_STORAGE_BIT);
    gl_program_bind_storage(pp, "Out", read_back);
    /* the work group as its shader declares it, read after link */
    CHECK(pp->local_size[0] == 1 && pp->local_size[1] == 1 && pp->local_size[2] == 1);
    gl_program_dispatch(pp, 1, 1, 1, GL_ALL_BARRIER_BITS);
    float from_block[24];
    gl.GetNamedBufferSubData(read_back, 0, sizeof from_block, from_block);
    CHECK_NEAR(from_block[20], 6.5, 1e-6); /* 3 x 2 + 0.5 */
    gl.DeleteBuffers(1, &read_back);
    /* 10 x 6 invocations asked of 8 x 4 groups: 2 x 2 groups, 128 run */
    struct gl_program *pg;
    CHECK(gl_program_get_compute(&cache, "second/grid.comp", NULL, NULL, &pg, &err));
    CHECK(pg->local_size[0] == 8 && pg->local_size[1] == 4 && pg->local_size[2] == 1);
    GLuint counter;
    const GLuint none = 0;
    gl.CreateBuffers(1, &counter);
    gl.NamedBufferStorage(counter, sizeof none, &none, GL_DYNAMIC_STORAGE_BIT);
    gl_program_bind_storage(pg, "Count", counter);
    gl_program_dispatch(pg, 10, 6, 1, GL_ALL_BARRIER_BITS);
    GLuint ran = 0;
    gl.GetNamedBufferSubData(counter, 0, sizeof ran, &ran);
    CHECK(ran == 128);
    gl.DeleteBuffers(1, &counter);
    gl_param_block_release(&block);
    struct gl_param_block wrong = {.name = "Params", .members = misspelt, .count = 3,
                                   .size = sizeof(struct params_mirror)};
    CHECK(gl_param_block_upload(&wrong, &values, &err));
    CHECK(!gl_param_block_bind(&wrong, pp, &err));
    CHECK_CONTAINS(err.message, "no member 'u_gian'");
    gl_param_block_release(&wrong);

    /* a block attached to a program (the renderer's look-ups of it): zeroed
     * and made once, the same block after, refused at another size, made
     * again after the program relinks (its locations may have moved) */
    bool made = false;
    int *attached = gl_program_attached(pa, 4 * sizeof(int), &made);
    CHECK(attached != NULL && made && attached[0] == 0 && attached[3] == 0);
    attached[0] = 7;
    int *again = gl_program_attached(pa, 4 * sizeof(int), &made);
    CHECK(again == attached && !made && again[0] == 7);
    CHECK(gl_program_attached(pa, 8 * sizeof(int), &made) == NULL && !made);

    /* a reload keeps every name's unit */
    write_shader(root, "first/a.comp", a); /* the same text, a newer time stamp */
    usleep(20000);
    write_shader(root, "first/a.comp", a);
    bool reloaded = false;
    CHECK(gl_program_cache_reload_changed(&cache, &reloaded, &err));
    CHECK(gl_program_unit(pa, GL_SLOT_TEXTURE, "u_x") == x && gl_program_unit(pa, GL_SLOT_TEXTURE, "u_y") == y);
    CHECK(sampler_value(pa, "u_x") == x);
    int *relinked = gl_program_attached(pa, 4 * sizeof(int), &made);
    CHECK(relinked != NULL && made && relinked[0] == 0);

    gl.DeleteBuffers(1, &out);
    GLuint textures[5] = {red, green, blue, grey, image};
    gl.DeleteTextures(5, textures);
    gl_program_cache_destroy(&cache);
    gl_context_destroy(ctx);
    char cmd[1100];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
    CHECK(system(cmd) == 0);
    return check_finish("test_program");
}
