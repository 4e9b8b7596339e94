/* Float RGBA images in linear radiance, rows top to bottom, and their files:
 * PNG (8-bit sRGB, libpng), PFM (linear float RGB) and Radiance HDR (RGBE,
 * image_hdr.c). */
#ifndef CAUSTICA_IMAGE_H
#define CAUSTICA_IMAGE_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "core/error.h"

struct image {
    int width, height;
    float *rgba; /* owned, width * height * 4 */
};

/* The most pixels one image read from a file may have (2^27: 16384 x 8192, a
 * large equirectangular sky; 2 GiB as float RGBA). Every reader checks it,
 * and that the file can hold what its header claims, before it allocates. */
#define IMAGE_MAX_PIXELS (1ull << 27)
/* Whether a header's width x height may be read from a file of `file_bytes`
 * that needs at least `min_bytes` for it; false with a message naming both. */
bool image_check_header(const char *path, long long width, long long height, unsigned long long min_bytes,
                        unsigned long long file_bytes, struct error *err);
bool image_create(struct image *img, int width, int height, struct error *err);
void image_destroy(struct image *img);
void image_flip_rows(struct image *img);

float image_srgb_encode(float linear);
float image_srgb_decode(float encoded);

/* Writes 8-bit sRGB RGBA (already tone mapped) bytes to PNG, atomically:
 * the file appears complete or not at all. An RGB file where every pixel
 * is opaque (a render), RGBA otherwise. */
bool image_write_png_rgba8(const char *path, const uint8_t *rgba, int width, int height, struct error *err);
/* Display images (image_display.c): .png, .jpg/.jpeg (quality 95, no
 * alpha) and .tif/.tiff (8-bit, Deflate; alpha only where not opaque) of
 * the same tone-mapped 8-bit sRGB bytes, by the path's extension. */
bool image_path_is_display(const char *path);
bool image_path_is_jpeg(const char *path);
bool image_path_is_tiff(const char *path);
bool image_write_display8(const char *path, const uint8_t *rgba, int width, int height, struct error *err);
/* A TIFF of any kind libtiff reads, as linear float (sRGB decoded). */
bool image_read_tiff(const char *path, struct image *img, struct error *err);
/* Reads a PNG as linear float (sRGB decoded). */
bool image_read_png(const char *path, struct image *img, struct error *err);
/* Reads a PNG's 8-bit RGBA bytes, undecoded (owned by the caller). */
bool image_read_png_rgba8(const char *path, uint8_t **rgba, int *width, int *height, struct error *err);
bool image_write_pfm(const char *path, const struct image *img, struct error *err);
bool image_read_pfm(const char *path, struct image *img, struct error *err);
/* Picks the format by extension (.png, .pfm, .hdr or .exr). PNG gets a plain clamp and
 * sRGB encoding; tone-mapped output comes from the GPU path instead. */
bool image_read(const char *path, struct image *img, struct error *err);
/* The file a path names, without a reader's suffix ("x.exr:layer" -> "x.exr"):
 * what a sandbox must check, since it is what gets opened. False when too long. */
bool image_path_file(const char *path, char *out, size_t size);
bool image_write(const char *path, const struct image *img, struct error *err);
/* Radiance RGBE (.hdr): what POV-Ray (+FH) and most HDR tools write. Reads
 * flat and run-length encoded scanlines; writes flat ones. */
bool image_write_hdr(const char *path, const struct image *img, struct error *err);
bool image_read_hdr(const char *path, struct image *img, struct error *err);
bool image_path_is_png(const char *path);
bool image_path_is_hdr(const char *path);
/* Every image file is written to a hidden temporary beside `path` and
 * renamed into place when complete (`ok`); begin returns NULL with `err` set. */
FILE *image_file_begin(const char *path, char *tmp, size_t tmplen, struct error *err);
bool image_file_finish(FILE *f, const char *tmp, const char *path, bool ok, struct error *err);
bool image_path_is_pfm(const char *path);

/* OpenEXR (image_exr.c): linear float RGBA, with named layers (channels
 * "name.R" ...) for extra outputs. */
struct image_layer {
    const char *name;
    const struct image *image;
    bool depth;     /* one channel, "name.Z", from the image's R (a depth: the caller makes it a distance) */
    bool object_id; /* its A is an object id + 1 (a G-buffer normal's w): left out; the file's objectId is the
                     * first surface's (image_exr_info.surface), glass included */
};
/* What a compositor reads from the header besides the pixels: the standard
 * chromaticities (Rec. 709 / sRGB primaries, D65: the renderer's linear
 * RGB), worldToCamera and worldToNDC (OpenEXR's row-vector matrices, which
 * are OpenGL's column-major arrays as they are), and caustica's own. */
struct image_exr_info {
    bool camera;                         /* the matrices below are set */
    float world_to_camera[16], world_to_ndc[16];
    int frame;
    double time, fps;
    const char *scene, *renderer, *output; /* NULL: left out */
    bool half; /* the image's own R, G, B, A as 16-bit half floats (a beauty pass, as compositors take it);
                * layers, depth and objectId stay 32-bit */
    /* NULL, or the first surface of every object (renderer_first_surface):
     * its G written as the channel Z, its B as objectId (0: none) */
    const struct image *surface;
};
bool image_path_is_exr(const char *path);
/* `info` may be NULL (no camera, no caustica attributes; the chromaticities still). */
bool image_write_exr(const char *path, const struct image *img, const struct image_layer *layers, int nlayers,
                     const struct image_exr_info *info, struct error *err);
bool image_read_exr(const char *path, struct image *img, struct error *err);
/* One named layer's R, G, B, A (NULL: the top-level channels). */
bool image_read_exr_layer(const char *path, const char *layer, struct image *img, struct error *err);

#endif
