/* libFuzzer harness for one image reader (issue 31), built five times, once
 * per reader, with FUZZ_IMAGE_FORMAT set to png, jpeg, exr, hdr or pfm
 * (fuzz_png ... fuzz_pfm): PNG and JPEG go through the texture decoder from
 * memory, EXR, Radiance HDR and PFM through their file readers from a file
 * in a private folder (those readers open files). Every input goes to the
 * one reader whatever its magic says, so that each reader gets the whole
 * run's mutations. Each must refuse or read without a sanitizer report, and
 * without allocating more than the file can hold (IMAGE_MAX_PIXELS and
 * image_check_header in io/image.h). */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/image.h"
#include "io/image_decode.h"
#include "fuzz_files.h"

#define FUZZ_STRINGIFY2(x) #x
#define FUZZ_STRINGIFY(x) FUZZ_STRINGIFY2(x)
#ifndef FUZZ_IMAGE_FORMAT
#error "build with -DFUZZ_IMAGE_FORMAT=png (or jpeg, exr, hdr, pfm)"
#endif
static const char format[] = FUZZ_STRINGIFY(FUZZ_IMAGE_FORMAT);

static char dir[256];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return fuzz_private_dir(format, dir, sizeof dir) ? 0 : 1;
}

static void read_path(const char *path)
{
    struct image img;
    struct error err;
    if (image_read(path, &img, &err))
        image_destroy(&img);
}

/* The file readers: PNG's file reader too (image_read_png, 16-bit aware),
 * and for EXR a named layer as well ("file.exr:caustic", as the reference
 * writes it), whose channel lookup is its own code. */
static void read_file(const uint8_t *data, size_t size)
{
    char path[320];
    snprintf(path, sizeof path, "%s/input.%s", dir, format);
    if (!fuzz_write_file(path, data, size))
        return;
    read_path(path);
    if (strcmp(format, "exr") == 0) {
        char layer[340];
        snprintf(layer, sizeof layer, "%s:caustic", path);
        read_path(layer);
    }
}

/* The decoder picks PNG or JPEG by signature; an input without this
 * harness's signature gets it put in front, so that the mutations reach the
 * decoder rather than the signature check. */
static void decode(const uint8_t *data, size_t size)
{
    static const uint8_t png[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
    static const uint8_t jpeg[3] = {0xff, 0xd8, 0xff};
    const uint8_t *signature = strcmp(format, "png") == 0 ? png : jpeg;
    size_t signature_size = strcmp(format, "png") == 0 ? sizeof png : sizeof jpeg;
    uint8_t *bytes = malloc(size + signature_size);
    if (!bytes)
        return;
    size_t n = 0;
    if (size < signature_size || memcmp(data, signature, signature_size) != 0) {
        memcpy(bytes, signature, signature_size);
        n = signature_size;
    }
    if (size)
        memcpy(bytes + n, data, size);
    n += size;
    char name[32];
    snprintf(name, sizeof name, "input.%s", format);
    uint8_t *rgba = NULL;
    int w = 0, h = 0;
    struct error err;
    if (image_decode_rgba8(name, bytes, n, 0, &rgba, &w, &h, &err))
        free(rgba);
    free(bytes);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (strcmp(format, "png") == 0 || strcmp(format, "jpeg") == 0)
        decode(data, size);
    if (strcmp(format, "jpeg") != 0)
        read_file(data, size);
    return 0;
}
