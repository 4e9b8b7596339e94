/* Radiance HDR files (Greg Ward's RGBE: an 8-bit mantissa per channel and a
 * shared exponent, so about 1% relative precision over 76 orders of
 * magnitude). POV-Ray writes them (+FH), which is how the reference is
 * compared with it (examples/reference_vs_povray). Rows are stored top to
 * bottom ("-Y h +X w"), the order of struct image. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/log.h"
#include "core/fileio.h"
#include "io/image.h"

#define HDR_MAX_SIDE 65536

static void rgbe_encode(const float *rgb, unsigned char out[4])
{
    float r = isfinite(rgb[0]) && rgb[0] > 0 ? rgb[0] : 0, g = isfinite(rgb[1]) && rgb[1] > 0 ? rgb[1] : 0,
          b = isfinite(rgb[2]) && rgb[2] > 0 ? rgb[2] : 0;
    float m = fmaxf(r, fmaxf(g, b));
    if (m < 1e-32f) {
        memset(out, 0, 4);
        return;
    }
    int e;
    float scale = frexpf(m, &e) * 256.0f / m;
    out[0] = (unsigned char)fminf(r * scale, 255.0f);
    out[1] = (unsigned char)fminf(g * scale, 255.0f);
    out[2] = (unsigned char)fminf(b * scale, 255.0f);
    out[3] = (unsigned char)(e + 128);
}

static void rgbe_decode(const unsigned char in[4], float *rgb)
{
    if (in[3] == 0) {
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
        return;
    }
    /* the mantissa's centre, as Ward's reader does */
    float f = ldexpf(1.0f, (int)in[3] - (128 + 8));
    for (int c = 0; c < 3; c++)
        rgb[c] = ((float)in[c] + 0.5f) * f;
}

bool image_write_hdr(const char *path, const struct image *img, struct error *err)
{
    char tmp[4096];
    FILE *f = image_file_begin(path, tmp, sizeof tmp, err);
    if (!f)
        return false;
    bool ok = fprintf(f, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nSOFTWARE=caustica\n\n-Y %d +X %d\n", img->height,
                      img->width) > 0;
    long nonfinite = 0;
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; ok && i < n; i++) {
        const float *p = img->rgba + i * 4;
        nonfinite += !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]);
        unsigned char e[4];
        rgbe_encode(p, e);
        ok = fwrite(e, 1, 4, f) == 4;
    }
    if (!ok)
        error_set(err, "%s: write failed: %s", path, strerror(errno));
    else if (nonfinite)
        log_warn("%s: %ld pixel%s had NaN or Inf values, written as 0", path, nonfinite, nonfinite == 1 ? "" : "s");
    return image_file_finish(f, tmp, path, ok, err);
}

/* One scanline: flat RGBE, or the "new" run-length encoding (2 2 hi lo,
 * then each of the four components run-length coded on its own). */
static bool read_scanline(FILE *f, unsigned char *line, int w)
{
    unsigned char head[4];
    if (fread(head, 1, 4, f) != 4)
        return false;
    if (w < 8 || w > 0x7fff || head[0] != 2 || head[1] != 2 || (head[2] & 0x80)) {
        memcpy(line, head, 4);
        return fread(line + 4, 4, (size_t)w - 1, f) == (size_t)w - 1;
    }
    if (((int)head[2] << 8 | head[3]) != w)
        return false;
    unsigned char *channel = malloc((size_t)w);
    if (!channel)
        return false;
    bool ok = true;
    for (int c = 0; ok && c < 4; c++) {
        int x = 0;
        while (ok && x < w) {
            int count = fgetc(f);
            if (count == EOF) {
                ok = false;
            } else if (count > 128) {
                int value = fgetc(f);
                count -= 128;
                ok = value != EOF && x + count <= w;
                if (ok)
                    memset(channel + x, value, (size_t)count);
                x += count;
            } else {
                ok = count > 0 && x + count <= w && fread(channel + x, 1, (size_t)count, f) == (size_t)count;
                x += count;
            }
        }
        for (int k = 0; ok && k < w; k++)
            line[k * 4 + c] = channel[k];
    }
    free(channel);
    return ok;
}

bool image_read_hdr(const char *path, struct image *img, struct error *err)
{
    FILE *f = file_open_read(path, false, err);
    if (!f)
        return false;
    char line[512];
    bool magic = fgets(line, sizeof line, f) && strncmp(line, "#?", 2) == 0;
    bool rgbe = true;
    while (magic && fgets(line, sizeof line, f) && line[0] != '\n') {
        if (strncmp(line, "FORMAT=", 7) == 0 && strncmp(line + 7, "32-bit_rle_rgbe", 15) != 0)
            rgbe = false;
    }
    int w = 0, h = 0;
    char ys = 0, xs = 0;
    if (!magic || !fgets(line, sizeof line, f) || sscanf(line, "%cY %d %cX %d", &ys, &h, &xs, &w) != 4) {
        fclose(f);
        return error_set(err, "%s: not a Radiance HDR file (expected '#?RADIANCE' and a '-Y h +X w' line)", path);
    }
    if (!rgbe || ys != '-' || xs != '+' || w <= 0 || h <= 0 || w > HDR_MAX_SIDE || h > HDR_MAX_SIDE) {
        fclose(f);
        return error_set(err, "%s: only RGBE images stored '-Y h +X w' up to %d pixels a side are read", path,
                         HDR_MAX_SIDE);
    }
    /* the least a file of w x h holds, checked before the image is
     * allocated: a scanline is either flat (4 bytes a pixel) or run-length
     * encoded (a 4-byte header and at least 2 bytes per 127 pixels of each
     * of its 4 channels), whichever is smaller (flat, for w < 3) */
    struct stat st;
    long at = ftell(f);
    unsigned long long left = fstat(fileno(f), &st) == 0 && at >= 0 && st.st_size >= at
                                  ? (unsigned long long)(st.st_size - at) : 0;
    unsigned long long flat = 4ull * (unsigned long long)w;
    unsigned long long encoded = 4ull + 8ull * (((unsigned long long)w + 126) / 127);
    unsigned long long least = (unsigned long long)h * (flat < encoded ? flat : encoded);
    if (!image_check_header(path, w, h, least, left, err)) {
        fclose(f);
        return false;
    }
    if (!image_create(img, w, h, err)) {
        fclose(f);
        return error_prefix(err, "%s", path);
    }
    unsigned char *scan = malloc((size_t)w * 4);
    bool ok = scan != NULL;
    for (int y = 0; ok && y < h; y++) {
        ok = read_scanline(f, scan, w);
        for (int x = 0; ok && x < w; x++) {
            float *px = img->rgba + ((size_t)y * (size_t)w + (size_t)x) * 4;
            rgbe_decode(scan + x * 4, px);
            px[3] = 1.0f;
        }
    }
    free(scan);
    fclose(f);
    if (!ok) {
        image_destroy(img);
        return error_set(err, "%s: truncated or corrupt HDR data", path);
    }
    return true;
}
