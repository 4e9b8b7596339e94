/* The technique sweep that `caustica bench` caches (DIR/cache/sweep_*.csv)
 * as `caustica choose` reads it back: one row per GPU variant, every number
 * checked (a damaged entry is refused with its line). */
#ifndef CAUSTICA_BENCH_CACHE_H
#define CAUSTICA_BENCH_CACHE_H

#include <stdbool.h>

#include "core/error.h"

#define BENCH_CACHE_MAX_ROWS 512

struct bench_row {
    char technique[64], settings[256];
    char renderer[256]; /* the GL renderer that measured it ("" in a cache from before it was recorded) */
    double ms, error;
    double flicker; /* < 0: not measured (a cache from before issue 32, or an empty cell) */
    bool excluded; /* the technique leaves out part of the scene */
};

/* The rows of `path` (at most BENCH_CACHE_MAX_ROWS, the GPU variants), read
 * only from a regular file of its own (no link, no FIFO); false with a
 * message naming the file and line otherwise. */
bool bench_cache_read(const char *path, struct bench_row *rows, int *count, struct error *err);

#endif
