/* libFuzzer harness for the .part file `caustica merge` and `bench --truth`
 * read beside a sharded reference's image (src/reference/reference_part.c):
 * the bytes become DIR/x.pfm.part, which reference_part_read must refuse
 * with its line or read into sane values, without a sanitizer report. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_files.h"
#include "reference/reference_part.h"

static char image[320], part_path[340];
static struct reference_part part;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    char dir[256];
    if (!fuzz_private_dir("part", dir, sizeof dir))
        return 1;
    snprintf(image, sizeof image, "%s/x.pfm", dir);
    snprintf(part_path, sizeof part_path, "%s.part", image);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!fuzz_write_file(part_path, data, size))
        return 0;
    struct error err;
    if (reference_part_read(image, &part, &err)) {
        /* what merge relies on once the read succeeds */
        if (part.passes < 1 || part.passes > part.passes_total || part.shard_count < 1 || part.width < 1 ||
            part.height < 1 || part.shard_parts < 1)
            abort();
        for (int i = 0; i < part.shard_parts; i++)
            if (part.shards[i] < 0 || part.shards[i] >= part.shard_count)
                abort();
    }
    return 0;
}
