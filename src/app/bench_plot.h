/* A log-log plot of error against time as an SVG file a browser opens. */
#ifndef CAUSTICA_BENCH_PLOT_H
#define CAUSTICA_BENCH_PLOT_H

#include <stdbool.h>
#include <stddef.h>

#include "core/error.h"

#define PLOT_MAX_SERIES 16

struct plot_point {
    double x, y;       /* time (ms), error; points with x or y <= 0 are left out */
    char label[128];
    int series;        /* 0.. : colour and legend entry */
    bool joined;       /* on its series' line (when the series has one), joined in the order of x */
    double y_low;      /* > 0: a bar from y down to y_low (the error less the truth's own noise) */
};

struct plot {
    const char *title, *x_label, *y_label;
    const char *series_names[PLOT_MAX_SERIES];
    bool series_lines[PLOT_MAX_SERIES]; /* join the series' points flagged `joined` */
    int series_count;
    struct plot_point *points;
    int count;
};

/* Points off their series' line are drawn hollow (dominated); the legend
 * says so. Dashed guides at 33 ms, 100 ms and 1 s; times read "1.2 s", not
 * "1.17e+03 ms"; point numbers placed clear of one another where they can be. */
bool bench_plot_write_svg(const char *path, const struct plot *plot, struct error *err);
/* "68.2 ms", "1.2 s", "14 s". */
void bench_plot_format_ms(double ms, char *out, size_t size);

#endif
