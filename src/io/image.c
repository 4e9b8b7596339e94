#define _POSIX_C_SOURCE 200809L
#include "io/image.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <png.h>

#include "core/fileio.h"
#include "core/log.h"
#include "io/image_decode.h"

bool image_check_header(const char *path, long long width, long long height, unsigned long long min_bytes,
                        unsigned long long file_bytes, struct error *err)
{
    if (width < 1 || height < 1 || (unsigned long long)width * (unsigned long long)height > IMAGE_MAX_PIXELS)
        return error_set(err, "%s: a %lldx%lld image is out of range (at most %llu pixels)", path, width, height,
                         (unsigned long long)IMAGE_MAX_PIXELS);
    if (min_bytes > file_bytes)
        return error_set(err, "%s: truncated: its header says %lldx%lld, which needs at least %llu bytes, the file has "
                              "%llu", path, width, height, min_bytes, file_bytes);
    return true;
}

bool image_create(struct image *img, int width, int height, struct error *err)
{
    img->width = img->height = 0;
    img->rgba = NULL;
    if (width <= 0 || height <= 0 || width > 32768 || height > 32768)
        return error_set(err, "image size %dx%d is out of range", width, height);
    img->rgba = calloc((size_t)width * (size_t)height * 4, sizeof(float));
    if (!img->rgba)
        return error_set(err, "out of memory for a %dx%d image", width, height);
    img->width = width;
    img->height = height;
    return true;
}

void image_destroy(struct image *img)
{
    free(img->rgba);
    img->rgba = NULL;
    img->width = img->height = 0;
}

void image_flip_rows(struct image *img)
{
    size_t row = (size_t)img->width * 4;
    float *tmp = malloc(row * sizeof(float));
    if (!tmp)
        return;
    for (int y = 0; y < img->height / 2; y++) {
        float *a = img->rgba + (size_t)y * row;
        float *b = img->rgba + (size_t)(img->height - 1 - y) * row;
        memcpy(tmp, a, row * sizeof(float));
        memcpy(a, b, row * sizeof(float));
        memcpy(b, tmp, row * sizeof(float));
    }
    free(tmp);
}

float image_srgb_encode(float c)
{
    if (!(c > 0.0f))
        return 0.0f;
    if (c >= 1.0f)
        return 1.0f;
    return c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

float image_srgb_decode(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

bool image_path_is_png(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && (strcmp(path + n - 4, ".png") == 0 || strcmp(path + n - 4, ".PNG") == 0);
}

bool image_path_is_hdr(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && (strcmp(path + n - 4, ".hdr") == 0 || strcmp(path + n - 4, ".HDR") == 0);
}

bool image_path_is_pfm(const char *path)
{
    size_t n = strlen(path);
    return n > 4 && (strcmp(path + n - 4, ".pfm") == 0 || strcmp(path + n - 4, ".PFM") == 0);
}

/* Writes go to a temporary file beside `path` (path_temporary), renamed
 * into place by finish_atomic: an interrupted write never leaves a partial
 * image under the real name. */
FILE *image_file_begin(const char *path, char *tmp, size_t tmplen, struct error *err)
{
    if (!path_check_writable_dir(path, err))
        return NULL;
    int fd = path_temporary_create(path, tmp, tmplen, err);
    if (fd < 0)
        return NULL;
    FILE *f = fdopen(fd, "wb");
    if (!f) {
        error_set(err, "%s: cannot write: %s", path, strerror(errno));
        close(fd);
        remove(tmp);
    }
    return f;
}

bool image_file_finish(FILE *f, const char *tmp, const char *path, bool ok, struct error *err)
{
    if (ok && fflush(f) != 0)
        ok = error_set(err, "%s: write failed: %s", path, strerror(errno));
    if (fclose(f) != 0 && ok)
        ok = error_set(err, "%s: write failed: %s", path, strerror(errno));
    if (ok && rename(tmp, path) != 0)
        ok = error_set(err, "%s: cannot rename the finished file into place: %s", path, strerror(errno));
    if (!ok)
        remove(tmp);
    return ok;
}

/* libpng reports through these: the message goes into caustica's error
 * (with errno's reason for a failed write: "No space left on device")
 * instead of libpng printing "libpng error: Write Error" itself. */
struct png_failure {
    char message[256];
    int saved_errno;
};

static void png_failed(png_structp png, png_const_charp message)
{
    struct png_failure *f = png_get_error_ptr(png);
    f->saved_errno = errno;
    snprintf(f->message, sizeof f->message, "%s", message);
    png_longjmp(png, 1);
}

static void png_warned(png_structp png, png_const_charp message)
{
    (void)png;
    (void)message;
}

bool image_write_png_rgba8(const char *path, const uint8_t *rgba, int width, int height, struct error *err)
{
    char tmp[4096];
    FILE *f = image_file_begin(path, tmp, sizeof tmp, err);
    if (!f)
        return false;
    struct png_failure failure = {"", 0};
    errno = 0;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &failure, png_failed, png_warned);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        return image_file_finish(f, tmp, path, error_set(err, "%s: libpng initialisation failed", path), err);
    }
    png_bytep *rows = malloc((size_t)height * sizeof *rows);
    if (!rows || setjmp(png_jmpbuf(png))) {
        free(rows);
        png_destroy_write_struct(&png, &info);
        if (failure.saved_errno)
            error_set(err, "%s: write failed: %s", path, strerror(failure.saved_errno));
        else
            error_set(err, "%s: PNG encoding failed: %s", path, failure.message[0] ? failure.message : "out of memory");
        return image_file_finish(f, tmp, path, false, err);
    }
    /* an alpha channel only where it says something: a render is opaque
     * (alpha 255 everywhere made every viewer treat it as a cut-out) */
    bool opaque = true;
    for (size_t i = 0; opaque && i < (size_t)width * (size_t)height; i++)
        opaque = rgba[i * 4 + 3] == 255;
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8,
                 opaque ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    if (opaque)
        png_set_filler(png, 0, PNG_FILLER_AFTER); /* the rows keep their fourth byte: libpng strips it */
    for (int y = 0; y < height; y++)
        rows[y] = (png_bytep)(rgba + (size_t)y * (size_t)width * 4);
    png_write_image(png, rows);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(rows);
    return image_file_finish(f, tmp, path, true, err);
}

bool image_read_png_rgba8(const char *path, uint8_t **out, int *width, int *height, struct error *err)
{
    /* the one PNG decoder (io/image_decode.c), with its checks and caps */
    char *data;
    size_t size;
    if (!file_read_all(path, &data, &size, err))
        return false;
    static const uint8_t signature[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
    /* a .jpg or .jpeg through the same decoder (it tells them by signature) */
    bool jpeg = image_path_is_jpeg(path) && size >= 3 && (uint8_t)data[0] == 0xff && (uint8_t)data[1] == 0xd8;
    const char *kind = image_path_is_jpeg(path) ? "JPEG" : "PNG";
    bool ok = (size >= 8 && memcmp(data, signature, 8) == 0) || jpeg
                  ? image_decode_rgba8(path, (const uint8_t *)data, size, 0, out, width, height, err)
                  : error_set(err, "%s: cannot read %s: not a %s file (no %s signature)", path, kind, kind, kind);
    free(data);
    return ok;
}

bool image_read_png(const char *path, struct image *img, struct error *err)
{
    uint8_t *buf;
    int w, h;
    if (!image_read_png_rgba8(path, &buf, &w, &h, err))
        return false;
    if (!image_create(img, w, h, err)) {
        free(buf);
        return false;
    }
    float lut[256];
    for (int i = 0; i < 256; i++)
        lut[i] = image_srgb_decode((float)i / 255.0f);
    size_t n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n; i++) {
        for (int c = 0; c < 3; c++)
            img->rgba[i * 4 + (size_t)c] = lut[buf[i * 4 + (size_t)c]];
        img->rgba[i * 4 + 3] = (float)buf[i * 4 + 3] / 255.0f;
    }
    free(buf);
    return true;
}

bool image_write_pfm(const char *path, const struct image *img, struct error *err)
{
    char tmp[4096];
    FILE *f = image_file_begin(path, tmp, sizeof tmp, err);
    if (!f)
        return false;
    /* PFM: "PF", size, scale < 0 for little-endian, rows bottom to top. */
    bool ok = fprintf(f, "PF\n%d %d\n-1.0\n", img->width, img->height) > 0;
    float *row = malloc((size_t)img->width * 3 * sizeof(float));
    ok = ok && row;
    /* No file caustica writes holds NaN or Inf: such values are written as
     * 0 and counted in a warning (a pass that makes them is a bug to find,
     * not a reason to poison every comparison made with the file). */
    long nonfinite = 0;
    for (int y = img->height - 1; ok && y >= 0; y--) {
        for (int x = 0; x < img->width; x++) {
            const float *p = img->rgba + ((size_t)y * (size_t)img->width + (size_t)x) * 4;
            bool bad = !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]);
            nonfinite += bad;
            for (int c = 0; c < 3; c++)
                row[x * 3 + c] = bad ? 0.0f : p[c];
        }
        ok = fwrite(row, sizeof(float), (size_t)img->width * 3, f) == (size_t)img->width * 3;
    }
    free(row);
    if (!ok)
        error_set(err, "%s: write failed: %s", path, errno ? strerror(errno) : "out of memory");
    else if (nonfinite)
        log_warn("%s: %ld pixel%s had NaN or Inf values, written as 0", path, nonfinite, nonfinite == 1 ? "" : "s");
    return image_file_finish(f, tmp, path, ok, err);
}

bool image_read_pfm(const char *path, struct image *img, struct error *err)
{
    FILE *f = file_open_read(path, false, err);
    if (!f)
        return false;
    char magic[3] = "";
    int w = 0, h = 0;
    double scale = 0;
    if (fscanf(f, "%2s %d %d %lf", magic, &w, &h, &scale) != 4 || fgetc(f) == EOF ||
        (strcmp(magic, "PF") != 0 && strcmp(magic, "Pf") != 0)) {
        fclose(f);
        return error_set(err, "%s: not a PFM file (expected a 'PF' or 'Pf' header)", path);
    }
    int channels = magic[1] == 'F' ? 3 : 1;
    if (!(scale < 0 || scale > 0)) { /* 0 or NaN: neither byte order */
        fclose(f);
        return error_set(err, "%s: not a PFM file (its scale must be non-zero: < 0 little-endian, > 0 big-endian)",
                         path);
    }
    /* the scale's sign says the file's byte order; the host's is tested */
    const uint32_t probe = 1;
    bool swap = (scale > 0) == (*(const uint8_t *)&probe == 1);
    /* what the header claims against what the file holds, before any allocation */
    struct stat st;
    long at = ftell(f);
    unsigned long long left = fstat(fileno(f), &st) == 0 && at >= 0 && st.st_size >= at
                                  ? (unsigned long long)(st.st_size - at) : 0;
    if (!image_check_header(path, w, h,
                            w > 0 && h > 0 ? (unsigned long long)w * (unsigned long long)h * (unsigned)channels * 4u : 0,
                            left, err)) {
        fclose(f);
        return false;
    }
    if (!image_create(img, w, h, err)) {
        fclose(f);
        return error_prefix(err, "%s", path);
    }
    float *row = malloc((size_t)w * (size_t)channels * sizeof(float));
    bool ok = row != NULL;
    for (int y = h - 1; ok && y >= 0; y--) {
        ok = fread(row, sizeof(float), (size_t)w * (size_t)channels, f) == (size_t)w * (size_t)channels;
        for (size_t i = 0; ok && swap && i < (size_t)w * (size_t)channels; i++) {
            uint32_t bits;
            memcpy(&bits, &row[i], 4);
            bits = (bits >> 24) | ((bits >> 8) & 0xff00u) | ((bits << 8) & 0xff0000u) | (bits << 24);
            memcpy(&row[i], &bits, 4);
        }
        for (int x = 0; ok && x < w; x++) {
            float *px = img->rgba + ((size_t)y * (size_t)w + (size_t)x) * 4;
            for (int c = 0; c < 3; c++)
                px[c] = row[x * channels + (channels == 3 ? c : 0)];
            px[3] = 1.0f;
        }
    }
    free(row);
    fclose(f);
    if (!ok) {
        image_destroy(img);
        return error_set(err, "%s: truncated PFM data", path);
    }
    return true;
}

bool image_path_file(const char *path, char *out, size_t size)
{
    const char *colon = strstr(path, ".exr:");
    size_t n = colon ? (size_t)(colon + 4 - path) : strlen(path);
    if (n + 1 > size)
        return false;
    memcpy(out, path, n);
    out[n] = '\0';
    return true;
}

bool image_read(const char *path, struct image *img, struct error *err)
{
    /* "file.exr:layer" reads a named layer of an EXR */
    const char *colon = strstr(path, ".exr:");
    if (colon) {
        char file[4200];
        snprintf(file, sizeof file, "%.*s", (int)(colon + 4 - path), path);
        return image_read_exr_layer(file, colon + 5, img, err);
    }
    if (image_path_is_pfm(path))
        return image_read_pfm(path, img, err);
    if (image_path_is_png(path) || image_path_is_jpeg(path))
        return image_read_png(path, img, err);
    if (image_path_is_tiff(path))
        return image_read_tiff(path, img, err);
    if (image_path_is_hdr(path))
        return image_read_hdr(path, img, err);
    if (image_path_is_exr(path))
        return image_read_exr(path, img, err);
    return error_set(err, "%s: unknown image format (use .png, .jpg, .tif, .pfm, .hdr or .exr)", path);
}

bool image_write(const char *path, const struct image *img, struct error *err)
{
    if (image_path_is_pfm(path))
        return image_write_pfm(path, img, err);
    if (image_path_is_hdr(path))
        return image_write_hdr(path, img, err);
    if (image_path_is_exr(path))
        return image_write_exr(path, img, NULL, 0, NULL, err);
    if (!image_path_is_display(path))
        return error_set(err, "%s: unknown image format (use .png, .jpg, .tif, .pfm, .hdr or .exr)", path);
    size_t n = (size_t)img->width * (size_t)img->height;
    uint8_t *bytes = calloc(n ? n * 4 : 4, 1);
    if (!bytes)
        return error_set(err, "%s: out of memory", path);
    long nonfinite = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = img->rgba + i * 4;
        bool bad = !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]);
        nonfinite += bad;
        for (int c = 0; c < 3; c++)
            bytes[i * 4 + (size_t)c] = bad ? 0 : (uint8_t)lrintf(image_srgb_encode(p[c]) * 255.0f);
        bytes[i * 4 + 3] = 255;
    }
    bool ok = image_write_display8(path, bytes, img->width, img->height, err);
    if (ok && nonfinite)
        log_warn("%s: %ld pixel%s had NaN or Inf values, written as 0", path, nonfinite, nonfinite == 1 ? "" : "s");
    free(bytes);
    return ok;
}
