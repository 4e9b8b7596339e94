#include "app/bench_plot.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "core/fileio.h"

static const char *colours[PLOT_MAX_SERIES] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
                                               "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#393b79", "#637939",
                                               "#8c6d31", "#843c39", "#7b4173", "#000000"};

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

/* A time as people read it: "68.2 ms", "1.2 s", "14 s" (not 1.17e+03 ms). */
void bench_plot_format_ms(double ms, char *out, size_t size)
{
    if (!(ms >= 0) || !isfinite(ms))
        snprintf(out, size, "-");
    else if (ms < 1000.0)
        snprintf(out, size, "%.3g ms", ms);
    else if (ms < 10000.0)
        snprintf(out, size, "%.1f s", ms / 1000.0);
    else
        snprintf(out, size, "%.0f s", ms / 1000.0);
}

/* An axis tick in ms: "20", "500", then "1 s", "2 s" (no exponents). */
static void format_tick_ms(double ms, char *out, size_t size)
{
    if (ms < 1000.0)
        snprintf(out, size, "%g", ms);
    else
        snprintf(out, size, "%g s", ms / 1000.0);
}

/* Label placement: the first of a few spots beside a point whose box
 * overlaps no label placed before (else the first spot). */
struct label_box {
    double x0, y0, x1, y1;
};
static void place_label(struct label_box *boxes, int *nboxes, int max, double px, double py, double w, double h,
                        double *x, double *y)
{
    static const double spots[][2] = {{5, -4}, {5, 12}, {-5, -4}, {-5, 12}, {8, 4}, {-8, 4}, {0, -10}, {0, 18}};
    int best = 0;
    for (int k = 0; k < 8; k++) {
        double lx = spots[k][0] < 0 ? px + spots[k][0] - w : px + spots[k][0], ly = py + spots[k][1];
        bool clear = true;
        for (int b = 0; b < *nboxes && clear; b++)
            clear = lx + w < boxes[b].x0 || lx > boxes[b].x1 || ly < boxes[b].y0 || ly - h > boxes[b].y1;
        if (clear) {
            best = k;
            break;
        }
    }
    *x = spots[best][0] < 0 ? px + spots[best][0] - w : px + spots[best][0];
    *y = py + spots[best][1];
    if (*nboxes < max)
        boxes[(*nboxes)++] = (struct label_box){*x, *y - h, *x + w, *y};
}

static bool drawable(const struct plot_point *p)
{
    return p->x > 0 && p->y > 0 && isfinite(p->x) && isfinite(p->y);
}

/* Ticks for a log axis over [lo, hi] (log10 units): 1-2-5 steps per decade,
 * or every integer multiple when the axis spans less than a decade. */
static int log_ticks(double lo, double hi, double *ticks, int max)
{
    static const double fine[] = {1, 1.5, 2, 3, 4, 5, 6, 7, 8, 9};
    static const double coarse[] = {1, 2, 5};
    static const double decades[] = {1};
    const double *m = hi - lo < 1.0 ? fine : hi - lo < 3.0 ? coarse : decades;
    int nm = hi - lo < 1.0 ? 10 : hi - lo < 3.0 ? 3 : 1;
    int n = 0;
    for (int d = (int)floor(lo) - 1; d <= (int)ceil(hi) && n < max; d++)
        for (int k = 0; k < nm && n < max; k++) {
            double v = m[k] * pow(10.0, d), l = log10(v);
            if (l >= lo - 1e-9 && l <= hi + 1e-9)
                ticks[n++] = v;
        }
    return n;
}

/* Where the plot's parts lie in the SVG: the log axes' ranges, the plot
 * area, the side table's column. */
struct svg_frame {
    double lx0, lx1, ly0, ly1; /* log10 of the axes' ends */
    double left, top, pw, ph;  /* the plot area */
    double W, H, right;        /* the image; the side table's width */
    double legend_h, line, tx; /* the side table: the legend's height, a line's, its x */
};
static double svg_x(const struct svg_frame *fr, double v)
{
    return fr->left + (log10(v) - fr->lx0) / (fr->lx1 - fr->lx0) * fr->pw;
}
static double svg_y(const struct svg_frame *fr, double v)
{
    return fr->top + fr->ph - (log10(v) - fr->ly0) / (fr->ly1 - fr->ly0) * fr->ph;
}
#define PX_(v) svg_x(fr, v)
#define PY_(v) svg_y(fr, v)

/* The frame: the title, the ticks and their labels, the frame-time guides, the axes' names. */
static void svg_axes(FILE *f, const struct plot *plot, const struct svg_frame *fr)
{
    const double lx0 = fr->lx0, lx1 = fr->lx1, ly0 = fr->ly0, ly1 = fr->ly1;
    const double left = fr->left, top = fr->top, pw = fr->pw, ph = fr->ph, W = fr->W, H = fr->H, right = fr->right;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" font-family=\"sans-serif\" "
               "font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n", W, H);
    fprintf(f, "<text x=\"%.0f\" y=\"24\" font-size=\"15\" text-anchor=\"middle\">", (W - right + left) / 2);
    escape(f, plot->title);
    fputs("</text>\n", f);
    double ticks[64];
    int nt = log_ticks(lx0, lx1, ticks, 64);
    for (int k = 0; k < nt; k++) {
        double x = PX_(ticks[k]);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", x, top, x, top + ph);
        /* with many ticks, labels at 1, 2, 3 and 5 only: they would overlap */
        double mantissa = ticks[k] / pow(10.0, floor(log10(ticks[k]) + 1e-9));
        bool labelled = nt <= 8 || fabs(mantissa - 1) < 1e-6 || fabs(mantissa - 2) < 1e-6 ||
                        fabs(mantissa - 3) < 1e-6 || fabs(mantissa - 5) < 1e-6;
        if (labelled) {
            char text[32];
            format_tick_ms(ticks[k], text, sizeof text);
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">%s</text>\n", x, top + ph + 18, text);
        }
    }
    /* the frame-time budgets a reader asks about: 30 fps, 10 fps, 1 fps */
    static const double guides[3] = {1000.0 / 30.0, 100.0, 1000.0};
    static const char *const guide_names[3] = {"33 ms (30 fps)", "100 ms", "1 s"};
    for (int k = 0; k < 3; k++) {
        double l = log10(guides[k]);
        if (l < lx0 || l > lx1)
            continue;
        double x = PX_(guides[k]);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#888\" stroke-dasharray=\"5 4\"/>\n",
                x, top, x, top + ph);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" fill=\"#555\">%s</text>\n", x + 3, top + 12,
                guide_names[k]);
    }
    nt = log_ticks(ly0, ly1, ticks, 64);
    for (int k = 0; k < nt; k++) {
        double y = PY_(ticks[k]);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>\n", left, y, left + pw, y);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n", left - 6, y + 4, ticks[k]);
    }
    fprintf(f, "<rect x=\"%.0f\" y=\"%.0f\" width=\"%.0f\" height=\"%.0f\" fill=\"none\" stroke=\"black\"/>\n", left, top,
            pw, ph);
    fprintf(f, "<text x=\"%.0f\" y=\"%.0f\" text-anchor=\"middle\">", left + pw / 2, top + ph + 44);
    escape(f, plot->x_label);
    fprintf(f, "</text>\n<text transform=\"translate(20 %.0f) rotate(-90)\" text-anchor=\"middle\">", top + ph / 2);
    escape(f, plot->y_label);
    fputs("</text>\n", f);
}

/* The series (and their joined frontier lines), then what the markers and bars mean. */
static void svg_legend(FILE *f, const struct plot *plot, const struct svg_frame *fr)
{
    const double top = fr->top, tx = fr->tx;
    for (int s = 0; s < plot->series_count; s++) {
        const char *c = colours[s % PLOT_MAX_SERIES];
        if (plot->series_lines[s]) {
            /* its joined points in the order of x (selection: the counts are small) */
            fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" points=\"", c);
            double last = -INFINITY;
            for (;;) {
                int next = -1;
                for (int i = 0; i < plot->count; i++) {
                    const struct plot_point *p = &plot->points[i];
                    if (p->series == s && p->joined && drawable(p) && p->x > last &&
                        (next < 0 || p->x < plot->points[next].x))
                        next = i;
                }
                if (next < 0)
                    break;
                last = plot->points[next].x;
                fprintf(f, "%.1f,%.1f ", PX_(plot->points[next].x), PY_(plot->points[next].y));
            }
            fputs("\"/>\n", f);
        }
        double ly = top + 10 + 20 * s;
        fprintf(f, "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"5\" fill=\"%s\"/><text x=\"%.0f\" y=\"%.0f\">", tx, ly, c,
                tx + 10, ly + 4);
        escape(f, plot->series_names[s]);
        fputs("</text>\n", f);
    }
    {
        /* what the two kinds of marker mean */
        double ly = top + 10 + 20 * plot->series_count;
        fprintf(f, "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"4\" fill=\"#444\" stroke=\"#444\"/><text x=\"%.0f\" y=\"%.0f\" "
                   "font-size=\"10\">on its technique's frontier (nothing faster is as good)</text>\n",
                tx, ly, tx + 10, ly + 4);
        fprintf(f, "<circle cx=\"%.0f\" cy=\"%.0f\" r=\"4\" fill=\"white\" stroke=\"#444\"/><text x=\"%.0f\" y=\"%.0f\" "
                   "font-size=\"10\">hollow: dominated (a faster setting is as good or better)</text>\n",
                tx, ly + 18, tx + 10, ly + 22);
        bool bars = false;
        for (int i = 0; i < plot->count; i++)
            bars |= plot->points[i].y_low > 0 && plot->points[i].y_low < 0.98 * plot->points[i].y;
        if (bars)
            fprintf(f, "<line x1=\"%.0f\" y1=\"%.0f\" x2=\"%.0f\" y2=\"%.0f\" stroke=\"#444\"/><text x=\"%.0f\" y=\"%.0f\" "
                       "font-size=\"10\">bar: the error less the truth's own (from the reference curve)</text>\n",
                    tx, ly + 30, tx, ly + 42, tx + 10, ly + 40);
    }
}

/* The points: a marker with its number, and the numbered side table. */
static void svg_points(FILE *f, const struct plot *plot, const struct svg_frame *fr)
{
    const double top = fr->top, legend_h = fr->legend_h, line = fr->line, tx = fr->tx;
    int number = 0;
    struct label_box boxes[512];
    int nboxes = 0;
    /* the points: a marker with its number, and the numbered side table */
    for (int i = 0; i < plot->count; i++) {
        const struct plot_point *p = &plot->points[i];
        if (!drawable(p))
            continue;
        const char *c = colours[p->series % PLOT_MAX_SERIES];
        number++;
        /* a point off its series' line (dominated by a faster, better one) is hollow */
        bool hollow = plot->series_lines[p->series % PLOT_MAX_SERIES] && !p->joined;
        if (p->y_low > 0 && isfinite(p->y_low) && p->y_low < 0.98 * p->y) {
            /* how much of the error may be the truth's own */
            fprintf(f, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-opacity=\"0.6\"/>"
                       "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-opacity=\"0.6\"/>\n",
                    PX_(p->x), PY_(p->y), PX_(p->x), PY_(p->y_low), c, PX_(p->x) - 3, PY_(p->y_low), PX_(p->x) + 3,
                    PY_(p->y_low), c);
        }
        fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"%s\" stroke=\"%s\"/>\n", PX_(p->x), PY_(p->y),
                hollow ? "white" : c, c);
        double lx, ly;
        char num[16];
        snprintf(num, sizeof num, "%d", number);
        place_label(boxes, &nboxes, 512, PX_(p->x), PY_(p->y), 5.5 * (double)strlen(num), 9, &lx, &ly);
        fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"9\" fill=\"%s\">%d</text>\n", lx, ly, c, number);
        fprintf(f, "<text x=\"%.0f\" y=\"%.0f\" font-size=\"10\" fill=\"%s\">%d  ", tx,
                top + legend_h + line * number, c, number);
        escape(f, p->label);
        char time[32];
        bench_plot_format_ms(p->x, time, sizeof time);
        fprintf(f, " (%s, %.3g)</text>\n", time, p->y);
    }
}

#undef PX_
#undef PY_

bool bench_plot_write_svg(const char *path, const struct plot *plot, struct error *err)
{
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    int drawn = 0;
    for (int i = 0; i < plot->count; i++) {
        const struct plot_point *p = &plot->points[i];
        if (!drawable(p))
            continue;
        xmin = fmin(xmin, p->x);
        xmax = fmax(xmax, p->x);
        ymin = fmin(ymin, p->y_low > 0 && isfinite(p->y_low) ? fmin(p->y, p->y_low) : p->y);
        ymax = fmax(ymax, p->y);
        drawn++;
    }
    if (!drawn) {
        xmin = 1;
        xmax = 10;
        ymin = 0.01;
        ymax = 1;
    }
    /* the axes fitted to the data, with a margin so no point sits on the frame */
    double lx0 = log10(xmin), lx1 = log10(xmax), ly0 = log10(ymin), ly1 = log10(ymax);
    double px = fmax(0.06 * (lx1 - lx0), 0.03), py = fmax(0.06 * (ly1 - ly0), 0.03);
    lx0 -= px;
    lx1 += px;
    ly0 -= py;
    ly1 += py;
    /* the side table: one numbered line per point, under the legend */
    const double line = 13;
    /* the side table as wide as its longest line (10 px font: ~5.6 px a character) */
    size_t longest = 0;
    for (int i = 0; i < plot->count; i++)
        if (strlen(plot->points[i].label) > longest)
            longest = strlen(plot->points[i].label);
    const double right = fmin(fmax(400.0, 5.6 * (double)(longest + 28) + 30.0), 900.0);
    const double W = 580 + right, left = 80, top = 50, bottom = 60;
    double legend_h = 20.0 * plot->series_count + 66; /* the series, then filled / hollow, the bars */
    double H = fmax(520, top + legend_h + line * drawn + 20);
    double pw = W - left - right, ph = fmin(H, 520) - top - bottom;
    char tmp[4200];
    int fd = path_temporary_create(path, tmp, sizeof tmp, err);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f) {
        if (fd >= 0) {
            close(fd);
            remove(tmp);
        }
        return fd >= 0 ? error_set(err, "%s: cannot write: %s", path, strerror(errno)) : false;
    }
    const struct svg_frame frame = {.lx0 = lx0, .lx1 = lx1, .ly0 = ly0, .ly1 = ly1, .left = left, .top = top, .pw = pw,
                                    .ph = ph, .W = W, .H = H, .right = right, .legend_h = legend_h, .line = line,
                                    .tx = W - right + 20};
    svg_axes(f, plot, &frame);
    svg_legend(f, plot, &frame);
    svg_points(f, plot, &frame);
    fputs("</svg>\n", f);
    bool ok = fclose(f) == 0;
    if (!ok || rename(tmp, path) != 0) {
        remove(tmp);
        return error_set(err, "%s: cannot write the plot", path);
    }
    return true;
}
