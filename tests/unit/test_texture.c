/* Texture decoding (PNG, JPEG, hostile headers) and the reference's
 * sampling (wrap modes, bilinear at texel centres, transform, sRGB). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <jpeglib.h>

#include "check.h"
#include "io/image_decode.h"
#include "scene/scene.h"

/* A w x h JPEG of one grey level, encoded with libjpeg into memory. */
static unsigned char *make_jpeg(int w, int h, int grey, unsigned long *size)
{
    struct jpeg_compress_struct ci;
    struct jpeg_error_mgr jerr;
    ci.err = jpeg_std_error(&jerr);
    jpeg_create_compress(&ci);
    unsigned char *out = NULL;
    jpeg_mem_dest(&ci, &out, size);
    ci.image_width = (JDIMENSION)w;
    ci.image_height = (JDIMENSION)h;
    ci.input_components = 3;
    ci.in_color_space = JCS_RGB;
    jpeg_set_defaults(&ci);
    jpeg_set_quality(&ci, 95, TRUE);
    jpeg_start_compress(&ci, TRUE);
    unsigned char *row = malloc((size_t)w * 3);
    memset(row, grey, (size_t)w * 3);
    while (ci.next_scanline < ci.image_height) {
        JSAMPROW rows[1] = {row};
        jpeg_write_scanlines(&ci, rows, 1);
    }
    jpeg_finish_compress(&ci);
    jpeg_destroy_compress(&ci);
    free(row);
    return out;
}

int main(void)
{
    struct error err;

    /* JPEG: decoded to RGBA, opaque, the grey level within the codec's error */
    unsigned long jsize = 0;
    unsigned char *jpeg = make_jpeg(16, 8, 128, &jsize);
    CHECK(jpeg && jsize > 0);
    struct texture *t = texture_decode("grey.jpg", jpeg, jsize, 0, &err);
    CHECK(t != NULL);
    CHECK(t->width == 16 && t->height == 8);
    CHECK(abs(t->texels[(3 * 16 + 5) * 4] - 128) <= 2 && t->texels[3] == 255);
    texture_destroy(t);

    /* A budget (what --script-memory leaves a script) is checked from the
     * header: 16x8 texels need 512 bytes; 511 refuses, 512 reads */
    t = texture_decode("budget.jpg", jpeg, jsize, 511, &err);
    CHECK(t == NULL);
    CHECK(strstr(err.message, "more than the") != NULL);
    t = texture_decode("budget.jpg", jpeg, jsize, 512, &err);
    CHECK(t != NULL && texture_bytes(t) == 512);
    texture_destroy(t);

    /* A JPEG cut short or with a corrupt body is an error, never a crash */
    t = texture_decode("cut.jpg", jpeg, jsize / 2, 0, &err);
    CHECK(t == NULL);
    CHECK(strstr(err.message, "cut.jpg") != NULL);
    unsigned char *bad = malloc(jsize);
    memcpy(bad, jpeg, jsize);
    for (unsigned long i = 20; i < jsize; i += 7)
        bad[i] ^= 0x5a;
    t = texture_decode("corrupt.jpg", bad, jsize, 0, &err);
    if (t) /* libjpeg may recover a damaged scan: then it is an image of the right size */
        CHECK(t->width == 16 && t->height == 8);
    texture_destroy(t);
    free(bad);
    free(jpeg);

    /* A PNG header asking for 100000 x 100000 texels is refused before any allocation */
    static const unsigned char huge_png[] = {
        0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 'I', 'H', 'D', 'R',
        0x00, 0x01, 0x86, 0xa0, 0x00, 0x01, 0x86, 0xa0, 8, 6, 0, 0, 0, 0x00, 0x00, 0x00, 0x00};
    t = texture_decode("huge.png", huge_png, sizeof huge_png, 0, &err);
    CHECK(t == NULL);
    CHECK(strstr(err.message, "huge.png") != NULL);
    /* Chunks are checked before libpng allocates them: a tEXt chunk that
     * claims 1.7 GB in a 60-byte file (fuzz_png: it cost 1.7 GB and 4 s),
     * and an 8192x8192 RGBA header with 10 bytes of image data (deflate
     * cannot pack 256 MB into fewer than ~260 kB) */
    static const unsigned char text_png[] = {
        0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0, 16, 0, 0, 0, 12,
        8, 0, 0, 0, 0, 0, 0, 0, 0, 0x65, 0xee, 0x00, 0xe7, 't', 'E', 'X', 't', 'a', 0, 'b', 0, 0, 0, 0};
    t = texture_decode("text_chunk.png", text_png, sizeof text_png, 0, &err);
    CHECK(t == NULL);
    CHECK(strstr(err.message, "chunk 'tEXt' claims 1710096615 bytes") != NULL);
    static const unsigned char thin_png[] = {
        0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0x20, 0, 0, 0, 0x20, 0,
        8, 6, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 10, 'I', 'D', 'A', 'T', 0x78, 0x9c, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    t = texture_decode("thin.png", thin_png, sizeof thin_png, 0, &err);
    CHECK(t == NULL);
    CHECK(strstr(err.message, "needs at least 260119 bytes of image data, the file has 10") != NULL);
    t = texture_decode("text.png", (const unsigned char *)"hello", 5, 0, &err);
    CHECK(t == NULL && strstr(err.message, "not a PNG or JPEG") != NULL);

    /* Sampling: a 2 x 1 texture, black then white, linear bytes (normal slot) */
    t = texture_create("two", 2, 1, &err);
    CHECK(t != NULL);
    memset(t->texels + 4, 255, 4);
    struct texture_ref ref;
    texture_ref_init(&ref);
    ref.texture = t;
    float uv[2] = {0.25f, 0.5f};
    CHECK_NEAR(texture_sample(&ref, uv, false).x, 0.0, 1e-6); /* texel centre */
    uv[0] = 0.5f;
    CHECK_NEAR(texture_sample(&ref, uv, false).x, 0.5, 1e-6); /* halfway */
    uv[0] = 0.0f;
    CHECK_NEAR(texture_sample(&ref, uv, false).x, 0.5, 1e-6); /* repeat: the left edge blends with the last texel */
    t->wrap_s = TEXTURE_CLAMP;
    CHECK_NEAR(texture_sample(&ref, uv, false).x, 0.0, 1e-6);
    t->wrap_s = TEXTURE_MIRROR;
    uv[0] = 1.25f; /* mirrors to 0.75: the white texel's centre */
    CHECK_NEAR(texture_sample(&ref, uv, false).x, 1.0, 1e-6);
    uv[0] = -0.25f; /* mirrors to 0.25 */
    CHECK_NEAR(texture_sample(&ref, uv, false).x, 0.0, 1e-6);
    /* sRGB: byte 255 is 1, and half the byte range is about 0.214 linear */
    t->texels[0] = 128;
    t->nearest = true;
    uv[0] = 0.25f;
    CHECK_NEAR(texture_sample(&ref, uv, true).x, 0.2158605, 1e-5);
    /* the transform: u' = u + 0.5 moves the black texel's centre onto white */
    ref.transform[4] = 0.5f;
    t->texels[0] = 0;
    CHECK_NEAR(texture_sample(&ref, uv, false).x, 1.0, 1e-6);
    /* coordinates that are not finite or far away stay finite */
    float far[2] = {1e30f, -1e30f}, nan_uv[2] = {0.0f / 0.0f, 1.0f / 0.0f};
    vec3 v = texture_sample(&ref, far, false);
    CHECK(math_finite3(v));
    v = texture_sample(&ref, nan_uv, true);
    CHECK(math_finite3(v));
    texture_destroy(t);

    /* Material references: assign retains, release drops */
    struct texture *k = texture_create_checker(2, vec3_make(1, 1, 1), vec3_make(0, 0, 0), &err);
    struct material a, b;
    material_init(&a, MATERIAL_DIFFUSE);
    material_init(&b, MATERIAL_DIFFUSE);
    a.base_color.texture = k; /* a holds the creation reference */
    material_assign(&b, &a);
    CHECK(k->references == 2);
    material_assign(&b, &b);
    CHECK(k->references == 2);
    material_release(&a);
    CHECK(k->references == 1 && b.base_color.texture == k);
    material_release(&b);
    CHECK(texture_create_checker(0, vec3_make(1, 1, 1), vec3_make(0, 0, 0), &err) == NULL);
    return check_finish("test_texture");
}
