#include "io/image_decode.h"

#include <setjmp.h>
#include <stdio.h> /* before jpeglib.h, which uses FILE */
#include <stdlib.h>
#include <string.h>

#include <jpeglib.h>
#include <png.h>

static bool size_ok(const char *name, unsigned long w, unsigned long h, unsigned long long max_bytes,
                    struct error *err)
{
    if (w == 0 || h == 0 || w > IMAGE_DECODE_MAX_SIDE || h > IMAGE_DECODE_MAX_SIDE ||
        (unsigned long long)w * h > IMAGE_DECODE_MAX_TEXELS)
        return error_set(err, "%s: image of %lux%lu texels (at most %d per side and %u in all)", name, w, h,
                         IMAGE_DECODE_MAX_SIDE, IMAGE_DECODE_MAX_TEXELS);
    if ((unsigned long long)w * h * 4ull > max_bytes)
        return error_set(err, "%s: image of %lux%lu texels needs %.2f MB, more than the %.2f MB it may use", name, w,
                         h, (double)w * (double)h * 4.0 / 1048576.0, (double)max_bytes / 1048576.0);
    return true;
}

static uint32_t read_be32(const uint8_t *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | (uint32_t)p[3];
}

/* The chunk structure, checked before libpng sees it: libpng allocates a
 * chunk's claimed length before reading it (a 700-byte file whose tEXt
 * chunk claims 1.7 GB cost 1.7 GB and 4 s, found by fuzz_png), so no chunk
 * may claim more than the file holds; and the image data must be enough
 * for the header's size: deflate packs at most 1032 bytes into one (RFC
 * 1951: a 258-byte match in under 2 bits, hence ~1032:1), so w x h at the
 * header's bits per pixel needs at least raw/1032 bytes of IDAT. */
static bool png_check_chunks(const char *name, const uint8_t *b, size_t size, struct error *err)
{
    size_t at = 8;
    unsigned long long idat = 0;
    uint32_t w = 0, h = 0;
    int depth = 0, colour = -1;
    while (size - at >= 12) {
        uint32_t length = read_be32(b + at);
        const uint8_t *type = b + at + 4;
        if (length > size - at - 12)
            return error_set(err, "%s: truncated PNG: chunk '%.4s' claims %lu bytes, the file has %zu left", name,
                             (const char *)type, (unsigned long)length, size - at - 12);
        if (memcmp(type, "IHDR", 4) == 0 && length >= 13) {
            w = read_be32(b + at + 8);
            h = read_be32(b + at + 12);
            depth = b[at + 16];
            colour = b[at + 17];
        } else if (memcmp(type, "IDAT", 4) == 0) {
            idat += length;
        } else if (memcmp(type, "IEND", 4) == 0) {
            break;
        }
        at += 12 + (size_t)length;
    }
    if (colour < 0)
        return true; /* no header: libpng says what is wrong */
    int channels = colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1;
    unsigned long long row = 1 + ((unsigned long long)w * (unsigned long long)(depth * channels) + 7) / 8;
    unsigned long long least = row * h / 1032;
    if (idat < least)
        return error_set(err, "%s: truncated: its header says %lux%lu, which needs at least %llu bytes of image "
                              "data, the file has %llu", name, (unsigned long)w, (unsigned long)h, least, idat);
    return true;
}

static bool decode_png(const char *name, const uint8_t *bytes, size_t size, unsigned long long max_bytes,
                       uint8_t **out, int *width, int *height, struct error *err)
{
    if (!png_check_chunks(name, bytes, size, err))
        return false;
    png_image pi;
    memset(&pi, 0, sizeof pi);
    pi.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&pi, bytes, size))
        return error_set(err, "%s: cannot read PNG: %s", name, pi.message);
    if (!size_ok(name, pi.width, pi.height, max_bytes, err)) {
        png_image_free(&pi);
        return false;
    }
    /* 8-bit RGBA: sRGB-encoded as colour files are (the simplified API
     * converts 16-bit and linear files to it). */
    pi.format = PNG_FORMAT_RGBA;
    uint8_t *buf = malloc(PNG_IMAGE_SIZE(pi));
    if (!buf) {
        png_image_free(&pi);
        return error_set(err, "%s: out of memory for %ux%u texels", name, pi.width, pi.height);
    }
    if (!png_image_finish_read(&pi, NULL, buf, 0, NULL)) {
        free(buf);
        return error_set(err, "%s: cannot decode PNG: %s", name, pi.message);
    }
    *out = buf;
    *width = (int)pi.width;
    *height = (int)pi.height;
    return true;
}

struct jpeg_failure {
    struct jpeg_error_mgr mgr;
    jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

static void jpeg_failed(j_common_ptr cinfo)
{
    struct jpeg_failure *f = (struct jpeg_failure *)cinfo->err;
    f->mgr.format_message(cinfo, f->message);
    longjmp(f->jump, 1);
}

/* Warnings of a damaged file are not printed by the library, but counted
 * (the default emit_message would count them; this one replaces it). */
static void jpeg_quiet(j_common_ptr cinfo, int level)
{
    if (level < 0)
        cinfo->err->num_warnings++;
}

static bool decode_jpeg(const char *name, const uint8_t *bytes, size_t size, unsigned long long max_bytes,
                        uint8_t **out, int *width, int *height, struct error *err)
{
    struct jpeg_decompress_struct cinfo;
    struct jpeg_failure failure;
    /* volatile: changed between setjmp and a longjmp back to it */
    uint8_t *volatile buf = NULL;
    uint8_t *volatile row = NULL;
    cinfo.err = jpeg_std_error(&failure.mgr);
    failure.mgr.error_exit = jpeg_failed;
    failure.mgr.emit_message = jpeg_quiet;
    if (setjmp(failure.jump)) {
        jpeg_destroy_decompress(&cinfo);
        free(buf);
        free(row);
        return error_set(err, "%s: cannot decode JPEG: %s", name, failure.message);
    }
    jpeg_create_decompress(&cinfo);
    jpeg_mem_src(&cinfo, bytes, (unsigned long)size);
    jpeg_read_header(&cinfo, TRUE);
    /* at least about 2 bits for each 8x8 block of a JPEG's data: a header
     * claiming 16384x4096 in 3000 bytes is refused before the image is made */
    unsigned long long least = (unsigned long long)cinfo.image_width * cinfo.image_height / 256ull;
    if (least > size) {
        jpeg_destroy_decompress(&cinfo);
        return error_set(err, "%s: truncated: its header says %ux%u, which needs at least %llu bytes, the file has %zu",
                         name, cinfo.image_width, cinfo.image_height, least, size);
    }
    if (!size_ok(name, cinfo.image_width, cinfo.image_height, max_bytes, err)) {
        jpeg_destroy_decompress(&cinfo);
        return false;
    }
    cinfo.out_color_space = JCS_RGB; /* greyscale and YCbCr alike */
    jpeg_start_decompress(&cinfo);
    size_t w = cinfo.output_width, h = cinfo.output_height;
    buf = malloc(w * h * 4);
    row = malloc(w * 3);
    if (!buf || !row) {
        jpeg_destroy_decompress(&cinfo);
        free(buf);
        free(row);
        return error_set(err, "%s: out of memory for %zux%zu texels", name, w, h);
    }
    while (cinfo.output_scanline < h) {
        size_t y = cinfo.output_scanline;
        JSAMPROW rows[1] = {row};
        if (jpeg_read_scanlines(&cinfo, rows, 1) != 1)
            break;
        for (size_t x = 0; x < w; x++) {
            buf[(y * w + x) * 4] = row[x * 3];
            buf[(y * w + x) * 4 + 1] = row[x * 3 + 1];
            buf[(y * w + x) * 4 + 2] = row[x * 3 + 2];
            buf[(y * w + x) * 4 + 3] = 255;
        }
    }
    /* libjpeg pads a truncated file with grey and only warns ("premature end
     * of data"): a warning means the file is damaged, and the image is refused */
    bool complete = cinfo.output_scanline == h && cinfo.err->num_warnings == 0;
    if (complete)
        jpeg_finish_decompress(&cinfo);
    complete = complete && cinfo.err->num_warnings == 0;
    jpeg_destroy_decompress(&cinfo);
    free(row);
    if (!complete) {
        free(buf);
        return error_set(err, "%s: the JPEG ends early or is damaged (libjpeg warned): refused", name);
    }
    *out = buf;
    *width = (int)w;
    *height = (int)h;
    return true;
}

bool image_decode_rgba8(const char *name, const uint8_t *bytes, size_t size, unsigned long long max_bytes,
                        uint8_t **rgba, int *width, int *height, struct error *err)
{
    if (max_bytes == 0)
        max_bytes = 4ull * IMAGE_DECODE_MAX_TEXELS;
    static const uint8_t png_signature[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
    if (size >= 8 && memcmp(bytes, png_signature, 8) == 0)
        return decode_png(name, bytes, size, max_bytes, rgba, width, height, err);
    if (size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff)
        return decode_jpeg(name, bytes, size, max_bytes, rgba, width, height, err);
    return error_set(err, "%s: not a PNG or JPEG image (textures are PNG or JPEG)", name);
}
