#define _POSIX_C_SOURCE 200809L
#include "app/bench_cache.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fileio.h"

/* Splits a CSV line in place (the bench's fields have no commas or quotes). */
static int split(char *line, char **fields, int max)
{
    int n = 0;
    for (char *p = line; n < max;) {
        fields[n++] = p;
        char *comma = strchr(p, ',');
        if (!comma)
            break;
        *comma = '\0';
        p = comma + 1;
    }
    return n;
}

bool bench_cache_read(const char *path, struct bench_row *rows, int *count, struct error *err)
{
    FILE *f = file_open_read(path, true, err); /* a cache entry: no link, no FIFO */
    if (!f)
        return false;
    char line[8192];
    char *fields[128];
    int col_technique = -1, col_settings = -1, col_ms = -1, col_error = -1, col_renderer = -1, col_flicker = -1, n = 0;
    bool header = true;
    int line_number = 0;
    while (fgets(line, sizeof line, f)) {
        line_number++;
        line[strcspn(line, "\r\n")] = '\0';
        int nf = split(line, fields, 128);
        if (header) {
            for (int i = 0; i < nf; i++) {
                if (strcmp(fields[i], "technique") == 0)
                    col_technique = i;
                else if (strcmp(fields[i], "settings") == 0)
                    col_settings = i;
                else if (strcmp(fields[i], "frame_ms") == 0)
                    col_ms = i;
                else if (strcmp(fields[i], "error") == 0)
                    col_error = i;
                else if (strcmp(fields[i], "renderer") == 0)
                    col_renderer = i;
                else if (strcmp(fields[i], "flicker") == 0)
                    col_flicker = i;
            }
            header = false;
            if (col_technique < 0 || col_settings < 0 || col_ms < 0 || col_error < 0) {
                fclose(f);
                return error_set(err, "%s: not a technique sweep's results (no technique, settings, frame_ms and "
                                      "error columns)", path);
            }
            continue;
        }
        int last = col_error;
        if (col_technique > last)
            last = col_technique;
        if (col_settings > last)
            last = col_settings;
        if (col_ms > last)
            last = col_ms;
        if (nf <= last || strcmp(fields[0], "gpu") != 0 || n >= BENCH_CACHE_MAX_ROWS)
            continue;
        struct bench_row *r = &rows[n++];
        snprintf(r->technique, sizeof r->technique, "%s", fields[col_technique]);
        snprintf(r->settings, sizeof r->settings, "%s", fields[col_settings]);
        /* numbers checked, not taken on trust: "abc" would be 0.0 ms, the fastest */
        char *end_ms, *end_error;
        r->ms = strtod(fields[col_ms], &end_ms);
        r->error = strtod(fields[col_error], &end_error);
        if (end_ms == fields[col_ms] || *end_ms || end_error == fields[col_error] || *end_error || !isfinite(r->ms) ||
            !isfinite(r->error) || r->ms < 0 || r->error < 0) {
            fclose(f);
            return error_set(err, "%s:%d: frame_ms '%s' and error '%s' must be finite numbers >= 0 (a damaged cache "
                                  "entry: remove it, and bench measures again)", path, line_number,
                             fields[col_ms], fields[col_error]);
        }
        snprintf(r->renderer, sizeof r->renderer, "%s", col_renderer >= 0 && nf > col_renderer ? fields[col_renderer] : "");
        r->flicker = -1.0;
        if (col_flicker >= 0 && nf > col_flicker && fields[col_flicker][0]) {
            char *end;
            r->flicker = strtod(fields[col_flicker], &end);
            if (*end || !isfinite(r->flicker) || r->flicker < 0) {
                fclose(f);
                return error_set(err, "%s:%d: flicker '%s' must be a finite number >= 0 or empty (a damaged cache "
                                      "entry: remove it, and bench measures again)", path, line_number,
                                 fields[col_flicker]);
            }
        }
    }
    fclose(f);
    *count = n;
    return n > 0 ? true : error_set(err, "%s: no measured variants", path);
}
