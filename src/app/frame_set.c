/* Frame sets and output patterns (see frame_set.h). */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/frame_set.h"

static bool parse_number(const char *s, size_t n, int *out)
{
    if (n == 0 || n > 9)
        return false;
    int v = 0;
    for (size_t i = 0; i < n; i++) {
        if (s[i] < '0' || s[i] > '9')
            return false;
        v = v * 10 + (s[i] - '0');
    }
    *out = v;
    return true;
}

static bool add_range(struct frame_set *set, int from, int to, int step, const char *item, size_t n, char *message,
                      size_t size)
{
    if (set->count >= FRAME_SET_MAX_RANGES) {
        snprintf(message, size, "--frames: at most %d ranges", FRAME_SET_MAX_RANGES);
        return false;
    }
    if (to < from || step < 1) {
        snprintf(message, size, "--frames: '%.*s' runs backwards or has a step below 1", (int)n, item);
        return false;
    }
    set->ranges[set->count].from = from;
    set->ranges[set->count].to = to;
    set->ranges[set->count].step = step;
    set->count++;
    return true;
}

bool frame_set_parse(const char *text, struct frame_set *set, char *message, size_t size)
{
    memset(set, 0, sizeof *set);
    const char *p = text;
    bool single_count = strpbrk(text, ",-:") == NULL;
    while (*p) {
        const char *end = strchr(p, ',');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        const char *dash = memchr(p, '-', n), *colon = memchr(p, ':', n);
        int a, b, step = 1;
        bool ok;
        if (dash) {
            /* A-B or A-B:S */
            size_t bn = colon ? (size_t)(colon - dash - 1) : n - (size_t)(dash - p) - 1;
            ok = parse_number(p, (size_t)(dash - p), &a) && parse_number(dash + 1, bn, &b) &&
                 (!colon || (colon > dash && parse_number(colon + 1, n - (size_t)(colon - p) - 1, &step)));
        } else if (colon) {
            /* A:B, inclusive (the older form) */
            ok = parse_number(p, (size_t)(colon - p), &a) && parse_number(colon + 1, n - (size_t)(colon - p) - 1, &b);
        } else {
            ok = parse_number(p, n, &a);
            b = a;
            if (ok && single_count) {
                /* a lone N: the first N frames */
                if (a < 1) {
                    snprintf(message, size, "--frames: a count must be 1 or more, got '%s'", text);
                    return false;
                }
                b = a - 1;
                a = 0;
            }
        }
        if (!ok) {
            snprintf(message, size,
                     "--frames: '%.*s' is not a frame, A-B, A-B:STEP or A:B (frames are whole numbers >= 0)", (int)n,
                     p);
            return false;
        }
        if (!add_range(set, a, b, step, p, n, message, size))
            return false;
        if (!end)
            break;
        p = end + 1;
        if (!*p) {
            snprintf(message, size, "--frames: '%s' ends with a comma", text);
            return false;
        }
    }
    if (set->count == 0) {
        snprintf(message, size, "--frames: no frames in '%s'", text);
        return false;
    }
    long total = 0;
    for (int i = 0; i < set->count; i++)
        total += (set->ranges[i].to - set->ranges[i].from) / set->ranges[i].step + 1;
    if (total > FRAME_SET_MAX_FRAMES) {
        snprintf(message, size, "--frames: '%s' names %ld frames, more than %d", text, total, FRAME_SET_MAX_FRAMES);
        return false;
    }
    return true;
}

static int compare_ints(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

int *frame_set_list(const struct frame_set *set, int *count)
{
    long total = 0;
    for (int i = 0; i < set->count; i++)
        total += (set->ranges[i].to - set->ranges[i].from) / set->ranges[i].step + 1;
    int *list = malloc((size_t)(total > 0 ? total : 1) * sizeof *list);
    if (!list)
        return NULL;
    int n = 0;
    for (int i = 0; i < set->count; i++)
        for (int f = set->ranges[i].from; f <= set->ranges[i].to; f += set->ranges[i].step) {
            list[n++] = f;
            if (f > INT_MAX - set->ranges[i].step)
                break;
        }
    qsort(list, (size_t)n, sizeof *list, compare_ints);
    int unique = 0;
    for (int i = 0; i < n; i++)
        if (unique == 0 || list[unique - 1] != list[i])
            list[unique++] = list[i];
    *count = unique;
    return list;
}

bool output_pattern_is_pattern(const char *pattern) { return strchr(pattern, '#') != NULL; }

static bool image_extension(const char *path, size_t *at)
{
    static const char *const exts[] = {".png", ".pfm", ".hdr", ".exr"};
    size_t n = strlen(path);
    for (int i = 0; i < 4; i++)
        if (n > 4 && strcmp(path + n - 4, exts[i]) == 0 && path[n - 5] != '/') {
            *at = n - 4;
            return true;
        }
    return false;
}

bool output_pattern_normalize(const char *given, char *out, size_t size, char *note, size_t notelen)
{
    note[0] = '\0';
    size_t o = 0;
    bool printf_style = false;
    for (const char *p = given; *p;) {
        /* %d or %0Nd (ffmpeg's and Blender's convention): N #, or one # */
        int width = 0, used = 0;
        if (p[0] == '%' && (sscanf(p, "%%0%dd%n", &width, &used) == 1 || (p[1] == 'd' && (used = 2) > 0)) &&
            used > 0 && p[used - 1] == 'd' && width >= 0 && width <= 9) {
            for (int k = 0; k < (width > 0 ? width : 1); k++) {
                if (o + 1 >= size)
                    return false;
                out[o++] = '#';
            }
            p += used;
            printf_style = true;
            continue;
        }
        if (o + 1 >= size)
            return false;
        out[o++] = *p++;
    }
    out[o] = '\0';
    size_t at;
    if (!printf_style && !strchr(out, '#') && image_extension(out, &at)) {
        /* a file name without a frame number: every frame would overwrite it */
        if (strlen(out) + 5 >= size)
            return false;
        memmove(out + at + 5, out + at, strlen(out + at) + 1);
        memcpy(out + at, "_####", 5);
        snprintf(note, notelen, "-o %s names no frame number: writing %s", given, out);
    }
    return true;
}

bool output_pattern_path(const char *pattern, int frame, char *out, size_t size)
{
    if (!output_pattern_is_pattern(pattern)) {
        int w = snprintf(out, size, "%s/frame_%04d.png", pattern, frame);
        return w > 0 && (size_t)w < size;
    }
    size_t o = 0;
    for (const char *p = pattern; *p;) {
        if (*p == '#') {
            int width = 0;
            while (p[width] == '#')
                width++;
            int w = snprintf(out + o, size - o, "%0*d", width, frame);
            if (w < 0 || (size_t)w >= size - o)
                return false;
            o += (size_t)w;
            p += width;
        } else {
            if (o + 1 >= size)
                return false;
            out[o++] = *p++;
        }
    }
    out[o] = '\0';
    return true;
}
