/* `caustica bench`'s results written out: results.csv and results.md,
 * each technique's error-time frontier (frontier.md, and the sweep's CSV
 * kept in the cache for `caustica choose`) and plot.svg. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <unistd.h>

#include "app/bench_internal.h"
#include "app/bench_plot.h"
#include "core/cpus.h"
#include "core/fileio.h"

/* Copies a small file (the results into the cache). */
static bool copy_file(const char *from, const char *to, struct error *err)
{
    char *data;
    size_t size;
    if (!file_read_all(from, &data, &size, err))
        return false;
    /* into the cache through an exclusive temporary and a rename: a link
     * planted at the entry's name is replaced, never written through */
    char tmp[4400];
    int fd = path_temporary_create(to, tmp, sizeof tmp, err);
    FILE *f = fd >= 0 ? fdopen(fd, "wb") : NULL;
    if (fd >= 0 && !f)
        close(fd);
    bool ok = f && fwrite(data, 1, size, f) == size;
    if (f && fclose(f) != 0)
        ok = false;
    free(data);
    if (ok && rename(tmp, to) != 0)
        ok = false;
    if (!ok && fd >= 0)
        remove(tmp);
    return ok ? true : fd < 0 ? false : error_set(err, "%s: cannot write", to);
}

/* The error a comparison ranks by. */
double bench_ranked_error(const struct result *r, bool caustic)
{
    return caustic && r->has_caustic ? r->caustic.rel_rmse : r->all.rel_rmse;
}

/* Its flicker in the same region (< 0: not measured). */
static double ranked_flicker(const struct result *r, bool caustic)
{
    return caustic && r->has_caustic ? r->flicker_caustic : r->flicker_all;
}

/* Marks the Pareto points of each series: faster than every point with a
 * lower error. */
static void mark_frontier(const struct result *results, int n, bool caustic, bool *on_front)
{
    for (int i = 0; i < n; i++) {
        on_front[i] = results[i].frame_ms > 0;
        double ei = bench_ranked_error(&results[i], caustic);
        for (int j = 0; j < n && on_front[i]; j++) {
            if (j == i || results[j].technique != results[i].technique)
                continue;
            double ej = bench_ranked_error(&results[j], caustic);
            bool dominates = results[j].frame_ms <= results[i].frame_ms && ej <= ei &&
                             (results[j].frame_ms < results[i].frame_ms || ej < ei || j < i);
            if (dominates)
                on_front[i] = false;
        }
    }
}

/* frontier.md: per technique, the best error within 33 ms, 100 ms and 1 s
 * a frame, with the settings that reach it. */
static void write_frontier(FILE *f, const struct technique_list *list, const struct result *results, int n,
                           const struct result *curve, int ncurve, bool caustic, const char *machine)
{
    static const double budgets[3] = {33.0, 100.0, 1000.0};
    fprintf(f, "Best %s reachable within a frame time (%s):\n\n",
            caustic ? "caustic-region rel_rmse" : "rel_rmse of the image", machine);
    fprintf(f, "| technique | ≤ 33 ms | ≤ 100 ms | ≤ 1 s | best (any time) |\n|---|---|---|---|---|\n");
    for (int t = 0; t <= list->count; t++) {
        bool reference = t == list->count;
        fprintf(f, "| %s |", reference ? "reference (CPU)" : list->items[t].name);
        const struct result *set = reference ? curve : results;
        int count = reference ? ncurve : n;
        for (int b = 0; b < 4; b++) {
            int best = -1;
            for (int i = 0; i < count; i++) {
                if (!reference && set[i].technique != t)
                    continue;
                if (reference && set[i].truth != 0)
                    continue;
                if (b < 3 && !(set[i].frame_ms <= budgets[b]))
                    continue;
                if (best < 0 || bench_ranked_error(&set[i], caustic) < bench_ranked_error(&set[best], caustic))
                    best = i;
            }
            if (best < 0) {
                fprintf(f, " — |");
                continue;
            }
            const char *settings = reference ? set[best].label : set[best].values[1];
            fprintf(f, " %.3f (%s, %.0f ms) |", bench_ranked_error(&set[best], caustic), settings, set[best].frame_ms);
        }
        fprintf(f, "\n");
    }
}

static const struct result *bench_row(const struct bench *b, int c)
{
    return c < b->nvariants ? &b->results[c] : &b->curve[c - b->nvariants];
}

void bench_renderer_label(const char *renderer, char *out, size_t size)
{
    snprintf(out, size, "%s", renderer && renderer[0] ? renderer : "unknown renderer");
    for (char *p = out; *p; p++)
        if (*p == ',' || *p == '\n')
            *p = ';';
}

static void bench_renderer_name(const struct bench *b, char *out, size_t size)
{
    bench_renderer_label(b->app->gl ? b->app->gl->renderer : NULL, out, size);
}

/* results.csv and results.md (md left open for the frontier). */
bool bench_write_tables(struct bench *b, FILE **md_out, struct error *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/results.csv", b->dir);
    FILE *csv = fopen(path, "w");
    snprintf(path, sizeof path, "%s/results.md", b->dir);
    FILE *md = fopen(path, "w");
    if (!csv || !md) {
        if (csv)
            fclose(csv);
        if (md)
            fclose(md);
        return error_set(err, "%s: cannot write the results", b->dir);
    }
    fprintf(csv, "kind");
    {
        char renderer[256];
        bench_renderer_name(b, renderer, sizeof renderer);
        fprintf(md, "Measured on %s, %d CPU%s, at %dx%d.\n\n", renderer, cpus_available(),
                cpus_available() == 1 ? "" : "s", b->width, b->height);
    }
    fprintf(md, "| variant |");
    for (int k = 0; k < b->ncolumns; k++)
        fprintf(csv, ",%s", b->columns[k]);
    fprintf(csv, ",frame_ms,frame_ratio");
    fprintf(md, " frame ms | × first |");
    for (int p = 0; p < b->npasses; p++) {
        fprintf(csv, ",%s_ms", b->pass_names[p]);
        fprintf(md, " %s ms |", b->pass_names[p]);
    }
    fprintf(csv, ",rmse,rel_rmse,psnr,ssim,caustic_rel_rmse,error,flicker,renderer,cpus\n");
    /* which machine measured it: the GL renderer (its commas made ';': the
     * CSV has none) and the CPUs the process could use */
    char renderer[256];
    bench_renderer_name(b, renderer, sizeof renderer);
    fprintf(md, " rel_rmse | psnr | ssim | caustic rel_rmse | flicker | passes' reports |\n|---|");
    for (int p = 0; p < b->npasses + 7; p++)
        fprintf(md, "---:|");
    fprintf(md, "---|\n");
    for (int c = 0; c < b->nvariants + b->ncurve; c++) {
        const struct result *r = bench_row(b, c);
        fprintf(csv, "%s", c < b->nvariants ? "gpu" : "reference");
        for (int k = 0; k < b->ncolumns; k++)
            fprintf(csv, ",%s", r->values[k]); /* a reference row: its scene's parameters */
        /* the frame time relative to the first variant (e.g. plain shading) */
        double ratio = b->results[0].frame_ms > 0 ? r->frame_ms / b->results[0].frame_ms : 0.0;
        fprintf(csv, ",%.4f,%.4f", r->frame_ms, ratio);
        fprintf(md, "| %s | %.3f | %.2f |", r->label, r->frame_ms, ratio);
        for (int p = 0; p < b->npasses; p++) {
            if (c < b->nvariants && r->pass_ms[p] >= 0) {
                fprintf(csv, ",%.4f", r->pass_ms[p]);
                fprintf(md, " %.3f |", r->pass_ms[p]);
            } else {
                fprintf(csv, ",");
                fprintf(md, " |");
            }
        }
        char caustic_text[32] = "";
        if (r->has_caustic)
            snprintf(caustic_text, sizeof caustic_text, "%.6g", r->caustic.rel_rmse);
        char flicker_text[32] = "";
        if (ranked_flicker(r, b->caustic) >= 0)
            snprintf(flicker_text, sizeof flicker_text, "%.6g", ranked_flicker(r, b->caustic));
        fprintf(csv, ",%.6g,%.6g,%.4g,%.6g,%s,%.6g,%s,%s,%d\n", r->all.rmse, r->all.rel_rmse, r->all.psnr, r->all.ssim,
                caustic_text, bench_ranked_error(r, b->caustic), flicker_text, c < b->nvariants ? renderer : "CPU reference",
                cpus_available());
        fprintf(md, " %.4f | %.2f | %.4f | %s | %s | %s |\n", r->all.rel_rmse, r->all.psnr, r->all.ssim,
                r->has_caustic ? caustic_text : "-", flicker_text[0] ? flicker_text : "-",
                c < b->nvariants ? r->report : "");
    }
    for (int t = 0; t < b->nsets && t < MAX_CURVES; t++)
        if (b->truth_error[t] > 0)
            fprintf(md, "\nThe ground truth's own error%s%s (its noise and bias, bounded from the reference curve): "
                        "at most %.4g; an error near it is the truth's as much as the variant's (the plot's bars).\n",
                    b->sets[t].label[0] ? " for " : "", b->sets[t].label, b->truth_error[t]);
    if (b->nerror > 1) {
        fprintf(md, "\nErrors are means over frames");
        for (int i = 0; i < b->nerror; i++)
            fprintf(md, "%s %d", i ? "," : "", b->error_frames[i]);
        fprintf(md, " (of %d); times are medians of %d frames from frame %d.\n", b->scene_frames, b->frames,
                b->frame);
    }
    fprintf(md, "\nFlicker: the error of each error frame's change to the next frame against the truth's change, "
                "relative to the truth (on a still scene the per-pixel standard deviation over frames; "
                "docs/TEMPORAL.md).\n");
    fclose(csv);
    *md_out = md;
    return true;
}

/* A technique sweep's frontier table (results.md, frontier.md, stdout) and
 * the CSV kept for `caustica choose`. */
bool bench_write_frontier(struct bench *b, FILE *md, struct error *err)
{
    mark_frontier(b->results, b->nvariants, b->caustic, b->on_front);
    char machine[400], path[4400];
    snprintf(machine, sizeof machine, "%dx%d, %s, %d CPU cores", b->width, b->height,
             b->app->gl ? b->app->gl->renderer : "?", cpus_available());
    snprintf(path, sizeof path, "%s/frontier.md", b->dir);
    FILE *fr = fopen(path, "w");
    if (!fr)
        return error_set(err, "%s: cannot write", path);
    write_frontier(fr, b->list, b->results, b->nvariants, b->curve, b->ncurve, b->caustic, machine);
    fclose(fr);
    fputs("\n", md);
    write_frontier(md, b->list, b->results, b->nvariants, b->curve, b->ncurve, b->caustic, machine);
    write_frontier(stdout, b->list, b->results, b->nvariants, b->curve, b->ncurve, b->caustic, machine);
    char cached[4400], from[4400];
    snprintf(from, sizeof from, "%s/results.csv", b->dir);
    return bench_sweep_cache_path(b->cli, b->dir, cached, sizeof cached, err) && copy_file(from, cached, err);
}

/* plot.svg: every variant and each reference curve, error against time;
 * with `flicker`, flicker.svg: every variant's flicker against time (the
 * reference's curve has none; the lines join each technique's points on its
 * error frontier, so the two plots read together). */
bool bench_write_plot(struct bench *b, bool flicker, struct error *err)
{
    static struct plot_point points[MAX_COMBOS + CURVE_LEVELS * MAX_CURVES];
    int np = 0;
    int techniques = b->technique_sweep ? b->list->count : 1;
    for (int c = 0; c < b->nvariants + b->ncurve; c++) {
        const struct result *r = bench_row(b, c);
        points[np].x = r->frame_ms;
        points[np].y = flicker ? ranked_flicker(r, b->caustic) : bench_ranked_error(r, b->caustic);
        /* series 0 (or one per technique): the GPU variants; then one reference curve per scene */
        points[np].series = c < b->nvariants ? (b->technique_sweep ? r->technique : 0) : techniques + r->truth;
        points[np].joined = c < b->nvariants ? b->on_front[c] : true;
        /* the bar: down to the error with the truth's own taken out (in quadrature) */
        double n = c < b->nvariants && r->truth >= 0 && r->truth < MAX_CURVES ? b->truth_error[r->truth] : -1.0;
        if (flicker)
            n = -1.0;
        points[np].y_low = n > 0 ? sqrt(fmax(points[np].y * points[np].y - n * n, 0.0025 * points[np].y * points[np].y))
                                 : 0.0;
        snprintf(points[np].label, sizeof points[np].label, "%.120s", r->label);
        np++;
    }
    char title[600];
    const char *what = flicker ? "flicker" : "error";
    if (b->nerror > 1)
        snprintf(title, sizeof title, "%s: %s against time (mean of %d frames, %dx%d)", b->script, what, b->nerror,
                 b->width, b->height);
    else
        snprintf(title, sizeof title, "%s: %s against time (frame %d, %dx%d)", b->script, what, b->frame, b->width,
                 b->height);
    struct plot plot = {
        .title = title,
        .x_label = "time per frame (ms), log",
        .y_label = flicker ? (b->caustic ? "flicker (error of the frame-to-frame change) in the caustic region, log"
                                         : "flicker (error of the frame-to-frame change), log")
                           : b->caustic ? "rel_rmse in the caustic region, log" : "rel_rmse, log",
        .series_names = {"GPU variants"},
        .series_lines = {false},
        .series_count = 1,
        .points = points,
        .count = np,
    };
    if (b->technique_sweep) {
        for (int t = 0; t < b->list->count && t < PLOT_MAX_SERIES; t++) {
            plot.series_names[t] = b->list->items[t].name;
            plot.series_lines[t] = true; /* its frontier */
        }
        plot.series_count = b->list->count;
    }
    char names[MAX_CURVES][260];
    for (int t = 0; !flicker && t < b->nsets && t < MAX_CURVES && techniques + t < PLOT_MAX_SERIES; t++) {
        snprintf(names[t], sizeof names[t], "reference%s%s", b->sets[t].label[0] ? ": " : "", b->sets[t].label);
        plot.series_names[techniques + t] = names[t];
        plot.series_lines[techniques + t] = true;
        plot.series_count = techniques + t + 1;
    }
    char path[4400];
    snprintf(path, sizeof path, "%s/%s.svg", b->dir, flicker ? "flicker" : "plot");
    return bench_plot_write_svg(path, &plot, err);
}
