/* libFuzzer harness for the bench cache `caustica choose` reads (issue 31):
 * the bytes become DIR/cache/sweep.csv, which bench_cache_read must refuse
 * with a line number or read without a sanitizer report. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/bench_cache.h"
#include "fuzz_files.h"

static char path[320];
static struct bench_row rows[BENCH_CACHE_MAX_ROWS];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    char dir[256];
    if (!fuzz_private_dir("csv", dir, sizeof dir))
        return 1;
    snprintf(path, sizeof path, "%s/sweep.csv", dir);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!fuzz_write_file(path, data, size))
        return 0;
    int count = 0;
    struct error err;
    bench_cache_read(path, rows, &count, &err);
    return 0;
}
