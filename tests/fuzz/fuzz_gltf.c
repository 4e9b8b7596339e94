/* libFuzzer harness for the glTF loading path (issue 9): the bytes become a
 * .glb (when they start with "glTF") or a .gltf file in a private folder,
 * which gltf_load must refuse or load without a sanitizer report. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_files.h"
#include "io/gltf.h"

static char dir[256];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return fuzz_private_dir("gltf", dir, sizeof dir) ? 0 : 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[320];
    bool binary = size >= 4 && memcmp(data, "glTF", 4) == 0;
    snprintf(path, sizeof path, "%s/input.%s", dir, binary ? "glb" : "gltf");
    if (!fuzz_write_file(path, data, size))
        return 0;
    struct gltf_mesh m;
    struct error err;
    if (gltf_load(path, &m, &err))
        gltf_mesh_free(&m);
    return 0;
}
