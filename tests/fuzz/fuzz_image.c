/* libFuzzer harness for the image readers (issue 31): PNG and JPEG from
 * memory (the texture path), and EXR, Radiance HDR and PFM from a file in a
 * private folder (their readers open files). The format is the one the
 * bytes' magic names; bytes without one go to the reader their first byte
 * picks, so that every reader sees arbitrary input. Each must refuse or
 * read without a sanitizer report, and without allocating more than the
 * file can hold (IMAGE_MAX_PIXELS and the header checks). */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/image.h"
#include "io/image_decode.h"

static char dir[256];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    snprintf(dir, sizeof dir, "/tmp/caustica-fuzz-image.%ld", (long)getpid());
    char cmd[300];
    snprintf(cmd, sizeof cmd, "mkdir -p %s", dir);
    return system(cmd) == 0 ? 0 : 1;
}

static void read_file(const char *ext, const uint8_t *data, size_t size)
{
    char path[320];
    snprintf(path, sizeof path, "%s/input.%s", dir, ext);
    FILE *f = fopen(path, "wb");
    if (!f)
        return;
    fwrite(data, 1, size, f);
    fclose(f);
    struct image img;
    struct error err;
    if (image_read(path, &img, &err))
        image_destroy(&img);
}

static void decode(const char *name, const uint8_t *data, size_t size)
{
    uint8_t *rgba = NULL;
    int w = 0, h = 0;
    struct error err;
    if (image_decode_rgba8(name, data, size, &rgba, &w, &h, &err))
        free(rgba);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const uint8_t png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const uint8_t exr[4] = {0x76, 0x2f, 0x31, 0x01};
    if (size >= 8 && memcmp(data, png, 8) == 0)
        decode("input.png", data, size);
    else if (size >= 2 && data[0] == 0xff && data[1] == 0xd8)
        decode("input.jpg", data, size);
    else if (size >= 4 && memcmp(data, exr, 4) == 0)
        read_file("exr", data, size);
    else if (size >= 2 && data[0] == '#' && data[1] == '?')
        read_file("hdr", data, size);
    else if (size >= 2 && data[0] == 'P' && (data[1] == 'F' || data[1] == 'f'))
        read_file("pfm", data, size);
    else if (size >= 1) {
        static const char *const exts[5] = {"png", "jpg", "exr", "hdr", "pfm"};
        int k = data[0] % 5;
        if (k < 2)
            decode(k == 0 ? "input.png" : "input.jpg", data + 1, size - 1);
        else
            read_file(exts[k], data + 1, size - 1);
    }
    return 0;
}
