#include "app/bench_plot.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/fileio.h"

static const char *colours[8] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#7f7f7f"};

static void escape(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '<')
            fputs("&lt;", f);
        else if (*s == '>')
            fputs("&gt;", f);
        else if (*s == '&')
            fputs("&amp;", f);
        else
            fputc(*s, f);
    }
}

bool bench_plot_write_svg(const char *path, const struct plot *plot, struct error *err)
{
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (int i = 0; i < plot->count; i++) {
        const struct plot_point *p = &plot->points[i];
        if (!(p->x > 0) || !(p->y > 0) || !isfinite(p->x) || !isfinite(p->y))
            continue;
        xmin = fmin(xmin, p->x);
        xmax = fmax(xmax, p->x);
        ymin = fmin(ymin, p->y);
        ymax = fmax(ymax, p->y);
    }
    if (!(xmin <= xmax)) {
        xmin = 1;
        xmax = 10;
        ymin = 0.01;
        ymax = 1;
    }
    /* whole decades, with room so no point sits on the frame */
    double lx0 = floor(log10(xmin) - 0.1), lx1 = ceil(log10(xmax) + 0.1), ly0 = floor(log10(ymin) - 0.1),
           ly1 = ceil(log10(ymax) + 0.1);
    if (lx1 <= lx0)
        lx1 = lx0 + 1;
    if (ly1 <= ly0)
        ly1 = ly0 + 1;
    const double W = 760, H = 520, left = 80, right = 230, top = 50, bottom = 60;
    double pw = W - left - right, ph = H - top - bottom;
    char tmp[4200];
    path_temporary(path, tmp, sizeof tmp);
    FILE *f = fopen(tmp, "w");
    if (!f)
        return error_set(err, "%s: cannot write: %s", path, strerror(errno));
#define PX(v) (left + (log10(v) - lx0) / (lx1 - lx0) * pw)
#define PY(v) (top + ph - (log10(v) - ly0) / (ly1 - ly0) * ph)
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" font-family=\"sans-serif\" "
               "font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n", W, H);
    fprintf(f, "<text x=\"%.0f\" y=\"24\" font-size=\"15\" text-anchor=\"middle\">", left + pw / 2);
    escape(f, plot->title);
    fputs("</text>\n", f);
    /* grid and ticks per decade */
    for (double d = lx0; d <= lx1 + 1e-9; d++) {
        double x = left + (d - lx0) / (lx1 - lx0) * pw;
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", x, top, x, top + ph);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%g</text>\n", x, top + ph + 18, pow(10, d));
    }
    for (double d = ly0; d <= ly1 + 1e-9; d++) {
        double y = top + ph - (d - ly0) / (ly1 - ly0) * ph;
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", left, y, left + pw, y);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", left - 6, y + 4, pow(10, d));
    }
    fprintf(f, "<rect x=\"%.0f\" y=\"%.0f\" width=\"%.0f\" height=\"%.0f\" fill=\"none\" stroke=\"black\"/>\n", left, top,
            pw, ph);
    fprintf(f, "<text x=\"%.0f\" y=\"%.0f\" text-anchor=\"middle\">", left + pw / 2, H - 14);
    escape(f, plot->x_label);
    fprintf(f, "</text>\n<text transform=\"translate(20 %.0f) rotate(-90)\" text-anchor=\"middle\">", top + ph / 2);
    escape(f, plot->y_label);
    fputs("</text>\n", f);
    for (int s = 0; s < plot->series_count; s++) {
        const char *c = colours[s % 8];
        if (plot->series_lines[s]) {
            fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" points=\"", c);
            for (int i = 0; i < plot->count; i++) {
                const struct plot_point *p = &plot->points[i];
                if (p->series == s && p->x > 0 && p->y > 0 && isfinite(p->x) && isfinite(p->y))
                    fprintf(f, "%.1f,%.1f ", PX(p->x), PY(p->y));
            }
            fputs("\"/>\n", f);
        }
        for (int i = 0; i < plot->count; i++) {
            const struct plot_point *p = &plot->points[i];
            if (p->series != s || !(p->x > 0) || !(p->y > 0) || !isfinite(p->x) || !isfinite(p->y))
                continue;
            fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\"/>\n", PX(p->x), PY(p->y), c);
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"9\" fill=\"%s\">", PX(p->x) + 6,
                    PY(p->y) - 5 + 11.0 * (i % 2), c); /* alternate above and below: fewer collisions */
            escape(f, p->label);
            fprintf(f, " (%.3g ms, %.3g)</text>\n", p->x, p->y);
        }
        double ly = top + 10 + 20 * s;
        fprintf(f, "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"5\" fill=\"%s\"/><text x=\"%.0f\" y=\"%.0f\">", W - right + 20,
                ly, c, W - right + 30, ly + 4);
        escape(f, plot->series_names[s]);
        fputs("</text>\n", f);
    }
#undef PX
#undef PY
    fputs("</svg>\n", f);
    bool ok = fclose(f) == 0;
    if (!ok || rename(tmp, path) != 0) {
        remove(tmp);
        return error_set(err, "%s: cannot write the plot", path);
    }
    return true;
}
