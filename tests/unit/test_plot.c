/* The bench plot (app/bench_plot.c): times read as people read them, the
 * frame-time guides where the axis reaches them, the marker legend, and
 * point numbers that do not land on one another. */
#include <stdlib.h>
#include <string.h>

#include "app/bench_plot.h"
#include "check.h"
#include "core/fileio.h"

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    static char buf[1 << 16];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return buf;
}

int main(void)
{
    char t[32];
    bench_plot_format_ms(68.24, t, sizeof t);
    CHECK(strcmp(t, "68.2 ms") == 0);
    bench_plot_format_ms(1170.0, t, sizeof t);
    CHECK(strcmp(t, "1.2 s") == 0);
    bench_plot_format_ms(14321.0, t, sizeof t);
    CHECK(strcmp(t, "14 s") == 0);
    bench_plot_format_ms(-1.0, t, sizeof t);
    CHECK(strcmp(t, "-") == 0);

    /* four points crowded near one time and error, and two far apart */
    struct plot_point points[6] = {
        {.x = 20, .y = 0.5, .label = "a", .series = 0, .joined = true},
        {.x = 20.5, .y = 0.51, .label = "b", .series = 0, .joined = false},
        {.x = 21, .y = 0.49, .label = "c", .series = 1, .joined = true},
        {.x = 20.2, .y = 0.5, .label = "d", .series = 1, .joined = true},
        {.x = 150, .y = 0.2, .label = "e", .series = 0, .joined = true},
        {.x = 1170, .y = 0.1, .label = "f", .series = 1, .joined = true, .y_low = 0.06},
    };
    struct plot plot = {.title = "t", .x_label = "frame time", .y_label = "error", .series_names = {"one", "two"},
                        .series_lines = {true, true}, .series_count = 2, .points = points, .count = 6};
    struct error err;
    const char *path = "/tmp/caustica_test_plot.svg";
    CHECK(bench_plot_write_svg(path, &plot, &err));
    char *svg = read_all(path);
    CHECK(svg != NULL);
    if (svg) {
        CHECK(strstr(svg, ">33 ms (30 fps)</text>") && strstr(svg, ">100 ms</text>") && strstr(svg, ">1 s</text>"));
        CHECK(strstr(svg, "stroke-dasharray"));
        CHECK(strstr(svg, "(1.2 s, 0.1)") && !strstr(svg, "e+03"));
        CHECK(strstr(svg, "hollow: dominated"));
        CHECK(strstr(svg, "bar: the error less the truth's own") && strstr(svg, "stroke-opacity=\"0.6\""));
        CHECK(strstr(svg, "fill=\"white\" stroke=\"#1f77b4\"")); /* b: off its line, hollow */
        /* the numbers 1-4 of the crowded points: no two at the same spot */
        double xs[4], ys[4];
        int found = 0;
        for (const char *p = svg; (p = strstr(p, "font-size=\"9\"")) != NULL && found < 4; p++) {
            const char *open = p;
            while (open > svg && strncmp(open, "<text x=", 8) != 0)
                open--;
            if (sscanf(open, "<text x=\"%lf\" y=\"%lf\"", &xs[found], &ys[found]) == 2)
                found++;
        }
        CHECK(found == 4);
        for (int i = 0; i < found; i++)
            for (int j = i + 1; j < found; j++)
                CHECK(fabs(xs[i] - xs[j]) > 5 || fabs(ys[i] - ys[j]) > 8);
    }
    remove(path);
    return check_finish("test_plot");
}
