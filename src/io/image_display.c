/* Display images (see image.h): the tone-mapped 8-bit sRGB output in the
 * formats people look at — PNG (image.c), JPEG for web pages (libjpeg, as
 * the texture decoder reads them) and TIFF for review tools (libtiff,
 * Deflate-compressed). Each is written to a temporary beside its path and
 * renamed, so a file appears complete or not at all. */
#include <errno.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include <jpeglib.h>
#include <tiffio.h>

#include "core/fileio.h"
#include "io/image.h"

/* 95: no visible blocks on a caustic's sharp edge, about a fifth of the PNG. */
#define IMAGE_JPEG_QUALITY 95

static bool ends_with_any(const char *path, const char *const *suffixes)
{
    size_t n = strlen(path);
    for (const char *const *s = suffixes; *s; s++) {
        size_t m = strlen(*s);
        if (n > m && strcasecmp(path + n - m, *s) == 0)
            return true;
    }
    return false;
}

bool image_path_is_jpeg(const char *path)
{
    static const char *const suffixes[] = {".jpg", ".jpeg", NULL};
    return ends_with_any(path, suffixes);
}

bool image_path_is_tiff(const char *path)
{
    static const char *const suffixes[] = {".tif", ".tiff", NULL};
    return ends_with_any(path, suffixes);
}

bool image_path_is_display(const char *path)
{
    return image_path_is_png(path) || image_path_is_jpeg(path) || image_path_is_tiff(path);
}

/* ---- JPEG ---------------------------------------------------------------- */

struct jpeg_failure {
    struct jpeg_error_mgr manager;
    jmp_buf escape;
    char message[JMSG_LENGTH_MAX];
};

static void jpeg_failed(j_common_ptr cinfo)
{
    struct jpeg_failure *failure = (struct jpeg_failure *)cinfo->err;
    (*cinfo->err->format_message)(cinfo, failure->message);
    longjmp(failure->escape, 1);
}

static bool write_jpeg(const char *path, const uint8_t *rgba, int width, int height, struct error *err)
{
    char tmp[4200];
    FILE *f = image_file_begin(path, tmp, sizeof tmp, err);
    if (!f)
        return false;
    uint8_t *row = malloc((size_t)width * 3);
    struct jpeg_compress_struct cinfo;
    struct jpeg_failure failure = {.message = ""};
    cinfo.err = jpeg_std_error(&failure.manager);
    failure.manager.error_exit = jpeg_failed;
    if (!row || setjmp(failure.escape)) {
        jpeg_destroy_compress(&cinfo);
        free(row);
        error_set(err, "%s: JPEG encoding failed: %s", path, row ? failure.message : "out of memory");
        return image_file_finish(f, tmp, path, false, err);
    }
    jpeg_create_compress(&cinfo);
    jpeg_stdio_dest(&cinfo, f);
    cinfo.image_width = (JDIMENSION)width;
    cinfo.image_height = (JDIMENSION)height;
    cinfo.input_components = 3;
    cinfo.in_color_space = JCS_RGB;
    jpeg_set_defaults(&cinfo);
    jpeg_set_quality(&cinfo, IMAGE_JPEG_QUALITY, TRUE);
    jpeg_start_compress(&cinfo, TRUE);
    while (cinfo.next_scanline < cinfo.image_height) {
        const uint8_t *src = rgba + (size_t)cinfo.next_scanline * (size_t)width * 4;
        for (int x = 0; x < width; x++)
            memcpy(row + (size_t)x * 3, src + (size_t)x * 4, 3); /* JPEG has no alpha */
        JSAMPROW rows[1] = {row};
        jpeg_write_scanlines(&cinfo, rows, 1);
    }
    jpeg_finish_compress(&cinfo);
    jpeg_destroy_compress(&cinfo);
    free(row);
    return image_file_finish(f, tmp, path, !ferror(f), err);
}

/* ---- TIFF ---------------------------------------------------------------- */

/* libtiff's messages go to stderr by default: kept for the error instead. */
static _Thread_local char tiff_message[256];

static void tiff_failed(const char *module, const char *fmt, va_list ap)
{
    (void)module;
    vsnprintf(tiff_message, sizeof tiff_message, fmt, ap);
}

static void tiff_silence(void)
{
    TIFFSetErrorHandler(tiff_failed);
    TIFFSetWarningHandler(NULL);
}

/* RGB, or RGBA where any pixel is not opaque (unassociated alpha, as the
 * PNG's), 8 bits, sRGB by convention (no ICC profile), Deflate. */
static bool write_tiff(const char *path, const uint8_t *rgba, int width, int height, bool alpha, struct error *err)
{
    tiff_silence();
    char tmp[4200];
    int fd = path_temporary_create(path, tmp, sizeof tmp, err);
    if (fd < 0)
        return false;
    tiff_message[0] = '\0';
    TIFF *tif = TIFFFdOpen(fd, tmp, "w");
    if (!tif) {
        close(fd);
        remove(tmp);
        return error_set(err, "%s: cannot write TIFF: %s", path, tiff_message[0] ? tiff_message : strerror(errno));
    }
    int channels = alpha ? 4 : 3;
    bool ok = TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, (uint32_t)width) &&
              TIFFSetField(tif, TIFFTAG_IMAGELENGTH, (uint32_t)height) &&
              TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, channels) && TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, 8) &&
              TIFFSetField(tif, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT) &&
              TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG) &&
              TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_RGB) &&
              TIFFSetField(tif, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE) &&
              TIFFSetField(tif, TIFFTAG_PREDICTOR, PREDICTOR_HORIZONTAL) &&
              TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(tif, 0)) &&
              TIFFSetField(tif, TIFFTAG_SOFTWARE, "caustica");
    if (ok && alpha) {
        uint16_t extra[1] = {EXTRASAMPLE_UNASSALPHA};
        ok = TIFFSetField(tif, TIFFTAG_EXTRASAMPLES, 1, extra);
    }
    uint8_t *row = ok ? malloc((size_t)width * (size_t)channels) : NULL;
    ok = ok && row;
    for (int y = 0; ok && y < height; y++) {
        const uint8_t *src = rgba + (size_t)y * (size_t)width * 4;
        for (int x = 0; x < width; x++)
            memcpy(row + (size_t)x * (size_t)channels, src + (size_t)x * 4, (size_t)channels);
        ok = TIFFWriteScanline(tif, row, (uint32_t)y, 0) == 1;
    }
    free(row);
    ok = ok && TIFFFlush(tif);
    TIFFClose(tif); /* closes fd */
    if (!ok) {
        remove(tmp);
        return error_set(err, "%s: TIFF write failed: %s", path, tiff_message[0] ? tiff_message : "out of memory");
    }
    if (rename(tmp, path) != 0) {
        int saved = errno;
        remove(tmp);
        return error_set(err, "%s: cannot move the finished file into place: %s", path, strerror(saved));
    }
    return true;
}

bool image_read_tiff(const char *path, struct image *img, struct error *err)
{
    tiff_silence();
    tiff_message[0] = '\0';
    FILE *check = file_open_read(path, false, err); /* a regular file, never a FIFO */
    if (!check)
        return false;
    fclose(check);
    TIFF *tif = TIFFOpen(path, "r");
    if (!tif)
        return error_set(err, "%s: cannot read TIFF: %s", path, tiff_message[0] ? tiff_message : "not a TIFF file");
    uint32_t w = 0, h = 0;
    TIFFGetField(tif, TIFFTAG_IMAGEWIDTH, &w);
    TIFFGetField(tif, TIFFTAG_IMAGELENGTH, &h);
    if (w < 1 || h < 1 || w > 16384 || h > 16384 || (unsigned long long)w * h > IMAGE_MAX_PIXELS) {
        TIFFClose(tif);
        return error_set(err, "%s: a TIFF of %ux%u is out of range (1..16384 a side)", path, w, h);
    }
    uint32_t *raster = _TIFFmalloc((tmsize_t)((size_t)w * h * sizeof(uint32_t)));
    /* libtiff's RGBA interface: any photometric and bit depth, as 8-bit RGBA, bottom row first */
    bool ok = raster && TIFFReadRGBAImageOriented(tif, w, h, raster, ORIENTATION_TOPLEFT, 0);
    TIFFClose(tif);
    if (!ok) {
        _TIFFfree(raster);
        return error_set(err, "%s: cannot read TIFF: %s", path, tiff_message[0] ? tiff_message : "out of memory");
    }
    if (!image_create(img, (int)w, (int)h, err)) {
        _TIFFfree(raster);
        return false;
    }
    for (size_t i = 0; i < (size_t)w * h; i++) {
        uint32_t p = raster[i];
        img->rgba[i * 4 + 0] = image_srgb_decode((float)TIFFGetR(p) / 255.0f);
        img->rgba[i * 4 + 1] = image_srgb_decode((float)TIFFGetG(p) / 255.0f);
        img->rgba[i * 4 + 2] = image_srgb_decode((float)TIFFGetB(p) / 255.0f);
        img->rgba[i * 4 + 3] = (float)TIFFGetA(p) / 255.0f;
    }
    _TIFFfree(raster);
    return true;
}

bool image_write_display8(const char *path, const uint8_t *rgba, int width, int height, struct error *err)
{
    bool opaque = true;
    for (size_t i = 0; opaque && i < (size_t)width * (size_t)height; i++)
        opaque = rgba[i * 4 + 3] == 255;
    if (image_path_is_jpeg(path))
        return write_jpeg(path, rgba, width, height, err);
    if (image_path_is_tiff(path))
        return write_tiff(path, rgba, width, height, !opaque, err);
    if (image_path_is_png(path))
        return image_write_png_rgba8(path, rgba, width, height, err);
    return error_set(err, "%s: not a display image format (.png, .jpg, .jpeg, .tif, .tiff)", path);
}
