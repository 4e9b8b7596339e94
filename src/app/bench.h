/* What `caustica bench` shares with `caustica choose`: where a technique
 * sweep's results are cached. */
#ifndef CAUSTICA_BENCH_H
#define CAUSTICA_BENCH_H

#include <stdbool.h>
#include <stddef.h>

#include "app/cli.h"

/* DIR/cache/sweep_<key>.csv, the key a hash of everything that determines
 * the sweep's measurements: the script's text, --set, --size, --frame,
 * --frames, --error-frames, --ref-photons, --ref-spp and the sweeps. */
/* Frames timed per variant: --frames, else 3 for a technique sweep, 5 otherwise. */
int bench_timing_frames(const struct cli *cli);
bool bench_sweep_cache_path(const struct cli *cli, const char *dir, char *out, size_t size, struct error *err);

/* The GL renderer's name as the bench cache records it (its commas made ';'). */
void bench_renderer_label(const char *renderer, char *out, size_t size);

#endif
