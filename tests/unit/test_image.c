#define _DEFAULT_SOURCE
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <unistd.h>

#include "check.h"
#include "core/fileio.h"
#include "io/image.h"
#include "reference/image_metrics.h"

int main(void)
{
    struct error err;
    struct image a, b;
    CHECK(image_create(&a, 16, 8, &err));
    for (int i = 0; i < 16 * 8; i++) {
        a.rgba[i * 4 + 0] = (float)i / 128.0f;
        a.rgba[i * 4 + 1] = 0.5f;
        a.rgba[i * 4 + 2] = 2.5f; /* HDR survives PFM */
        a.rgba[i * 4 + 3] = 1.0f;
    }
    char dir[] = "/tmp/caustica-test-image-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char pfm[256], png[256];
    snprintf(pfm, sizeof pfm, "%s/a.pfm", dir);
    snprintf(png, sizeof png, "%s/a.png", dir);

    /* PFM round trip is exact, rows keep their order */
    CHECK(image_write_pfm(pfm, &a, &err));
    CHECK(image_read_pfm(pfm, &b, &err));
    CHECK(b.width == 16 && b.height == 8);
    struct image_metrics m;
    CHECK(image_metrics_compute(&a, &b, NULL, &m, &err));
    CHECK_NEAR(m.rmse, 0, 0);
    CHECK_NEAR(b.rgba[(5 * 16 + 3) * 4], (5 * 16 + 3) / 128.0, 1e-7);
    image_destroy(&b);

    /* PNG: clamped and 8-bit sRGB, so within half a code value after decoding */
    CHECK(image_write(png, &a, &err));
    CHECK(image_read_png(png, &b, &err));
    float worst = 0;
    for (int i = 0; i < 16 * 8; i++) {
        float want = a.rgba[i * 4] > 1 ? 1 : a.rgba[i * 4];
        float got = b.rgba[i * 4];
        float enc_err = fabsf(image_srgb_encode(got) - image_srgb_encode(want));
        if (enc_err > worst)
            worst = enc_err;
    }
    CHECK(worst <= 0.5f / 255.0f + 1e-6f);
    CHECK_NEAR(b.rgba[2], 1.0, 1e-6); /* 2.5 clamps to 1 */
    image_destroy(&b);

    /* HDR (RGBE): 8-bit mantissas under an exponent shared by the pixel's
     * channels, so each value is within 1/256 of the pixel's largest one,
     * rounded to the mantissa's centre (2.5 is kept) */
    char hdr[256];
    snprintf(hdr, sizeof hdr, "%s/a.hdr", dir);
    CHECK(image_write(hdr, &a, &err));
    CHECK(image_read(hdr, &b, &err));
    CHECK(b.width == 16 && b.height == 8);
    int hdr_bad = 0;
    for (int i = 0; i < 16 * 8; i++)
        for (int c = 0; c < 3; c++)
            hdr_bad += fabsf(b.rgba[i * 4 + c] - a.rgba[i * 4 + c]) > 2.5f / 256.0f;
    CHECK(hdr_bad == 0);
    image_destroy(&b);
    unlink(hdr);

    /* HDR run-length encoded scanlines, as POV-Ray writes them: a 9-pixel
     * row whose red run is 9 x 128, green 9 literal values, blue a run,
     * exponent a run of 129 (values k/256 * 2 in green). */
    {
        FILE *f = fopen(hdr, "wb");
        CHECK(f != NULL);
        fputs("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 9\n", f);
        const unsigned char row[] = {2, 2, 0, 9, 128 + 9, 128, 9, 0, 16, 32, 48, 64, 80, 96, 112, 128, 128 + 9, 0,
                                     128 + 9, 129};
        fwrite(row, 1, sizeof row, f);
        fclose(f);
        CHECK(image_read_hdr(hdr, &b, &err));
        CHECK(b.width == 9 && b.height == 1);
        CHECK_NEAR(b.rgba[0], (128 + 0.5) / 256.0 * 2.0, 1e-6);
        CHECK_NEAR(b.rgba[4 * 3 + 1], (48 + 0.5) / 256.0 * 2.0, 1e-6);
        CHECK_NEAR(b.rgba[4 * 8 + 2], 0.5 / 256.0 * 2.0, 1e-6);
        image_destroy(&b);
        /* a truncated file is an error, not a partial image */
        f = fopen(hdr, "wb");
        fputs("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 9\n", f);
        fwrite(row, 1, sizeof row, f);
        fclose(f);
        CHECK(!image_read_hdr(hdr, &b, &err));
        CHECK_CONTAINS(err.message, "truncated");
        unlink(hdr);
    }

    /* tiny images round-trip: a 2x2 and a 1x1 HDR are flat scanlines,
     * smaller than an encoded scanline's least size (the size check before
     * allocation once refused them) */
    for (int side = 1; side <= 2; side++) {
        struct image tiny;
        CHECK(image_create(&tiny, side, side, &err));
        for (int i = 0; i < side * side * 4; i++)
            tiny.rgba[i] = 0.25f * (float)(i % 4);
        CHECK(image_write(hdr, &tiny, &err));
        CHECK(image_read(hdr, &b, &err));
        CHECK(b.width == side && b.height == side);
        CHECK_NEAR(b.rgba[4 * (side * side - 1) + 2], 0.5, 0.5 / 128);
        image_destroy(&b);
        image_destroy(&tiny);
    }
    unlink(hdr);

    /* PFM in both byte orders: the scale's sign says which (< 0 little-
     * endian, > 0 big-endian); the same pixel values either way, and a zero
     * scale refused */
    {
        char pfm[256];
        snprintf(pfm, sizeof pfm, "%s/order.pfm", dir);
        const float values[6] = {0.5f, 1.5f, -2.0f, 3.25f, 0.0f, 1e-3f};
        for (int big = 0; big <= 2; big++) {
            FILE *f = fopen(pfm, "wb");
            CHECK(f != NULL);
            fprintf(f, "PF\n2 1\n%s\n", big == 2 ? "0" : big ? "1.0" : "-1.0");
            for (int i = 0; i < 6; i++) {
                uint32_t bits;
                memcpy(&bits, &values[i], 4);
                unsigned char bytes[4];
                for (int k = 0; k < 4; k++)
                    bytes[k] = (unsigned char)(bits >> (big ? 24 - 8 * k : 8 * k));
                fwrite(bytes, 1, 4, f);
            }
            fclose(f);
            if (big == 2) {
                CHECK(!image_read(pfm, &b, &err));
                CHECK_CONTAINS(err.message, "non-zero");
                continue;
            }
            CHECK(image_read(pfm, &b, &err));
            CHECK(b.width == 2 && b.height == 1);
            CHECK(b.rgba[0] == 0.5f && b.rgba[1] == 1.5f && b.rgba[2] == -2.0f);
            CHECK(b.rgba[4] == 3.25f && b.rgba[5] == 0.0f && b.rgba[6] == 1e-3f);
            image_destroy(&b);
        }
        unlink(pfm);
    }

    /* no temporary files are left behind */
    char tmp[300];
    path_temporary(png, tmp, sizeof tmp);
    CHECK(!file_exists(tmp));

    /* metrics: a known difference */
    CHECK(image_create(&b, 16, 8, &err));
    memcpy(b.rgba, a.rgba, 16 * 8 * 4 * sizeof(float));
    b.rgba[0] += 0.3f;
    CHECK(image_metrics_compute(&a, &b, NULL, &m, &err));
    CHECK_NEAR(m.max, 0.3, 1e-6);
    CHECK_NEAR(m.rmse, sqrt(0.09 / (16 * 8 * 3)), 1e-6);
    b.rgba[5] = NAN;
    CHECK(image_metrics_compute(&a, &b, NULL, &m, &err));
    CHECK(m.nan == 1);
    CHECK(isfinite(m.rmse));

    /* a mask restricts the comparison to its lit pixels */
    struct image mask;
    CHECK(image_create(&mask, 16, 8, &err));
    for (int c = 0; c < 3; c++)
        mask.rgba[4 + c] = 1.0f; /* only pixel 1, which a and b share */
    b.rgba[5] = a.rgba[5];
    CHECK(image_metrics_compute(&a, &b, &mask, &m, &err));
    CHECK(m.pixels == 1);
    CHECK_NEAR(m.rmse, 0.0, 0.0);
    mask.rgba[0] = 1.0f; /* and pixel 0, where they differ by 0.3 in red */
    CHECK(image_metrics_compute(&a, &b, &mask, &m, &err));
    CHECK(m.pixels == 2);
    CHECK_NEAR(m.rmse, sqrt(0.09 / 6.0), 1e-6);
    image_destroy(&mask);

    /* flicker (issue 32): a still truth of 1 everywhere and two frames with
     * independent noise of standard deviation 0.1 read about 0.1 (the
     * per-pixel standard deviation); frames that follow the truth's change
     * exactly read 0 however large the change; a technique that stands still
     * while the truth brightens by 0.2 reads 0.2 / sqrt(2) / 1.1 */
    {
        const int w = 128, h = 128;
        struct image t0, t1, f0, f1;
        CHECK(image_create(&t0, w, h, &err) && image_create(&t1, w, h, &err) && image_create(&f0, w, h, &err) &&
              image_create(&f1, w, h, &err));
        uint32_t state = 12345u;
        for (int i = 0; i < w * h * 4; i++) {
            t0.rgba[i] = t1.rgba[i] = 1.0f;
            double g[2];
            for (int k = 0; k < 2; k++) { /* a normal deviate from 12 uniforms */
                double sum = 0.0;
                for (int j = 0; j < 12; j++) {
                    state = state * 1664525u + 1013904223u;
                    sum += (state >> 8) / 16777216.0;
                }
                g[k] = sum - 6.0;
            }
            f0.rgba[i] = (float)(1.0 + 0.1 * g[0]);
            f1.rgba[i] = (float)(1.0 + 0.1 * g[1]);
        }
        double fl = -1.0;
        CHECK(image_flicker_compute(&f0, &f1, &t0, &t1, NULL, &fl, &err));
        CHECK_NEAR(fl, 0.1, 0.005);
        for (int i = 0; i < w * h * 4; i++) {
            t1.rgba[i] = 1.0f + 0.2f;
            f0.rgba[i] = 0.5f;
            f1.rgba[i] = 0.5f + 0.2f;
        }
        CHECK(image_flicker_compute(&f0, &f1, &t0, &t1, NULL, &fl, &err));
        CHECK_NEAR(fl, 0.0, 1e-6);
        for (int i = 0; i < w * h * 4; i++)
            f1.rgba[i] = f0.rgba[i];
        CHECK(image_flicker_compute(&f0, &f1, &t0, &t1, NULL, &fl, &err));
        CHECK_NEAR(fl, 0.2 / sqrt(2.0) / 1.1, 1e-5);
        f1.rgba[0] = NAN; /* left out, never a NaN result */
        CHECK(image_flicker_compute(&f0, &f1, &t0, &t1, NULL, &fl, &err) && isfinite(fl));
        struct image small;
        CHECK(image_create(&small, 4, 4, &err));
        CHECK(!image_flicker_compute(&f0, &small, &t0, &t1, NULL, &fl, &err));
        CHECK_CONTAINS(err.message, "differ in size");
        image_destroy(&small);
        image_destroy(&t0);
        image_destroy(&t1);
        image_destroy(&f0);
        image_destroy(&f1);
    }

    /* size mismatch and unwritable folders are errors, not crashes */
    struct image c;
    CHECK(image_create(&c, 4, 4, &err));
    CHECK(!image_metrics_compute(&a, &c, NULL, &m, &err));
    CHECK_CONTAINS(err.message, "differ in size");
    CHECK(!image_write_pfm("/proc/self/nope.pfm", &a, &err));
    CHECK_CONTAINS(err.message, "not writable");
    CHECK(!image_read_pfm("/nonexistent.pfm", &c, &err));
    CHECK(!image_create(&c, 0, 4, &err));

    image_destroy(&a);
    image_destroy(&b);
    unlink(pfm);
    unlink(png);
    rmdir(dir);
    return check_finish("test_image");
}
