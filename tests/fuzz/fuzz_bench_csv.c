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

static char path[320];
static struct bench_row rows[BENCH_CACHE_MAX_ROWS];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    char dir[256];
    snprintf(dir, sizeof dir, "/tmp/caustica-fuzz-csv.%ld", (long)getpid());
    snprintf(path, sizeof path, "%s/sweep.csv", dir);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "mkdir -p %s", dir);
    return system(cmd) == 0 ? 0 : 1;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    fwrite(data, 1, size, f);
    fclose(f);
    int count = 0;
    struct error err;
    bench_cache_read(path, rows, &count, &err);
    return 0;
}
