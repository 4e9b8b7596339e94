/* Decoding the 8-bit images that textures are made of: PNG (libpng's
 * simplified API) and JPEG (libjpeg), from memory, recognised by their
 * signature. Sizes are bounded before any pixel memory is allocated. */
#ifndef CAUSTICA_IMAGE_DECODE_H
#define CAUSTICA_IMAGE_DECODE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/error.h"

/* The largest side and area a texture may have (16384 and 2^26 texels:
 * 256 MiB of RGBA8), so a hostile header cannot ask for more. */
#define IMAGE_DECODE_MAX_SIDE 16384
#define IMAGE_DECODE_MAX_TEXELS (1u << 26)

/* RGBA8 texels (row 0 the top row) owned by the caller; `name` is the
 * file or glTF image named in messages. `max_bytes` (0: only the caps
 * above) bounds the texels' size, checked from the header before they are
 * allocated: what a script's --script-memory leaves it. */
bool image_decode_rgba8(const char *name, const uint8_t *bytes, size_t size, unsigned long long max_bytes,
                        uint8_t **rgba, int *width, int *height, struct error *err);

#endif
