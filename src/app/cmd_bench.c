/* `caustica bench`: error against run time. For every combination of the
 * swept values (scene parameters, or pass parameters as pass.param) it
 * renders N frames after a warm-up, takes the median frame and per-pass
 * times, measures the error of the first frame against the ground truth
 * (cached by a hash of scene, parameters, frame, size and reference
 * settings), and writes results.csv, results.md and plot.svg. The plot
 * also carries the reference renderer's own curve: its error at growing
 * iteration counts against a 16x longer run. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/bench_plot.h"
#include "app/cli.h"
#include "core/fileio.h"
#include "core/hash.h"
#include "core/log.h"
#include "graph/graph.h"
#include "reference/image_metrics.h"
#include "reference/reference.h"

#define MAX_VALUES 16
#define MAX_COMBOS 256
#define MAX_PASSES 32

struct sweep {
    char key[64];
    char values[MAX_VALUES][64];
    int count;
};

struct result {
    char label[256];
    char values[16][64];
    double frame_ms;
    double pass_ms[MAX_PASSES];
    struct image_metrics all, caustic;
    bool has_caustic;
    char report[300]; /* the passes' lines about the last frame (beam counts, fill rate) */
    int truth;        /* the ground truth it was measured against (its scene parameters) */
};

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_doubles);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static bool parse_sweep(const char *text, struct sweep *s, struct error *err)
{
    const char *eq = strchr(text, '=');
    snprintf(s->key, sizeof s->key, "%.*s", (int)(eq - text), text);
    s->count = 0;
    const char *p = eq + 1;
    while (*p) {
        const char *comma = strchr(p, ',');
        size_t n = comma ? (size_t)(comma - p) : strlen(p);
        if (n == 0 || n >= sizeof s->values[0] || s->count >= MAX_VALUES)
            return error_set(err, "--sweep %s: empty, too long or more than %d values", text, MAX_VALUES);
        snprintf(s->values[s->count++], sizeof s->values[0], "%.*s", (int)n, p);
        p = comma ? comma + 1 : p + n;
    }
    return s->count > 0 ? true : error_set(err, "--sweep %s: no values", text);
}


/* FNV-1a over everything that determines a ground-truth image. */
static bool truth_key(const char *script, const struct lua_params *params, int frame, int w, int h,
                      const struct ref_options *ro, uint64_t *key, struct error *err)
{
    char *text;
    size_t size;
    if (!file_read_all(script, &text, &size, err))
        return false;
    uint64_t k = hash_fnv1a(1469598103934665603ULL, text, size);
    free(text);
    for (int i = 0; i < params->count; i++) {
        k = hash_fnv1a(k, params->keys[i], strlen(params->keys[i]) + 1);
        k = hash_fnv1a(k, params->values[i], strlen(params->values[i]) + 1);
    }
    int ints[3] = {frame, w, h};
    k = hash_fnv1a(k, ints, sizeof ints);
    k = hash_fnv1a(k, &ro->photons, sizeof ro->photons);
    k = hash_fnv1a(k, &ro->iterations, sizeof ro->iterations);
    k = hash_fnv1a(k, &ro->seed, sizeof ro->seed);
    *key = k;
    return true;
}

/* The mask of the caustic region: where the truth's caustic part is at
 * least 10% of its radiance. */
static bool caustic_mask(const struct image *truth, const struct image *caustic, struct image *mask, struct error *err)
{
    if (!image_create(mask, truth->width, truth->height, err))
        return false;
    size_t n = (size_t)truth->width * (size_t)truth->height;
    long count = 0;
    for (size_t i = 0; i < n; i++) {
        float lt = truth->rgba[i * 4] + truth->rgba[i * 4 + 1] + truth->rgba[i * 4 + 2];
        float lc = caustic->rgba[i * 4] + caustic->rgba[i * 4 + 1] + caustic->rgba[i * 4 + 2];
        bool in = lc > 0.0f && lc >= 0.1f * lt;
        for (int c = 0; c < 3; c++)
            mask->rgba[i * 4 + (size_t)c] = in ? 1.0f : 0.0f;
        count += in;
    }
    return count > 0;
}

struct truth {
    uint64_t key;
    char label[200];  /* its scene parameters ("depth=0.5"), empty without scene sweeps */
    char values[16][64]; /* per sweep: the scene parameter's value, empty for a pass parameter */
    struct image image, caustic, mask;
    bool has_mask;
    struct lua_params params;
    int width, height;
};

static bool get_truth(struct app *app, const char *script, const struct lua_params *params, int frame, int w, int h,
                      const struct ref_options *ro, const char *cache_dir, struct truth *t, struct error *err)
{
    if (!truth_key(script, params, frame, w, h, ro, &t->key, err))
        return false;
    char path[4400], cpath[4400];
    snprintf(path, sizeof path, "%s/truth_%016llx.pfm", cache_dir, (unsigned long long)t->key);
    snprintf(cpath, sizeof cpath, "%s/truth_%016llx_caustic.pfm", cache_dir, (unsigned long long)t->key);
    if (file_exists(path) && file_exists(cpath) && image_read_pfm(path, &t->image, err) &&
        image_read_pfm(cpath, &t->caustic, err)) {
        log_info("ground truth from the cache: %s", path);
    } else {
        fprintf(stderr, "caustica: bench: rendering the ground truth (%d iterations of %ld photons) ...\n", ro->iterations,
                ro->photons);
        struct session_options so = {.script = script, .params = *params, .width = w, .height = h};
        struct session *s;
        if (!session_open(app, &so, &s, err))
            return false;
        struct ref_stats st;
        bool ok = session_reference_parts(s, frame, ro, &t->image, &t->caustic, &st, err);
        session_close(s);
        if (!ok || !image_write_pfm(path, &t->image, err) || !image_write_pfm(cpath, &t->caustic, err))
            return false;
    }
    struct error ignore;
    t->has_mask = caustic_mask(&t->image, &t->caustic, &t->mask, &ignore);
    t->params = *params;
    t->width = w;
    t->height = h;
    return true;
}

static void truth_release(struct truth *t)
{
    image_destroy(&t->image);
    image_destroy(&t->caustic);
    image_destroy(&t->mask);
}

static bool apply_overrides(struct session *s, const struct sweep *sweeps, int nsweeps, const int *choice,
                            struct error *err)
{
    for (int k = 0; k < nsweeps; k++) {
        if (!strchr(sweeps[k].key, '.'))
            continue;
        if (!session_set_pass_param(s, sweeps[k].key, sweeps[k].values[choice[k]], err))
            return error_prefix(err, "--sweep %s", sweeps[k].key);
    }
    return true;
}

int cmd_bench(struct app *app, struct cli *cli)
{
    if (cli->npositional != 1) {
        fprintf(stderr, "caustica: bench needs one scene script\n");
        cli_usage(stderr);
        return EXIT_USAGE;
    }
    const char *script = cli->positional[0];
    const char *dir = cli->output ? cli->output : "bench";
    struct error err;
    struct sweep sweeps[16];
    int combos = 1;
    for (int i = 0; i < cli->nsweeps; i++) {
        if (!parse_sweep(cli->sweeps[i], &sweeps[i], &err)) {
            cli_print_error(&err);
            return EXIT_USAGE;
        }
        combos *= sweeps[i].count;
        if (combos > MAX_COMBOS) {
            fprintf(stderr, "caustica: bench: more than %d combinations\n", MAX_COMBOS);
            return EXIT_USAGE;
        }
    }
    char cache[4200];
    snprintf(cache, sizeof cache, "%s/cache", dir);
    if (!dir_ensure(dir, &err) || !dir_ensure(cache, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    int frames = cli->frames_set ? cli->frames_to - cli->frames_from + 1 : 5;
    int frame = cli->frame;
    /* The reference curve: L/8, L/4, L/2, L iterations against 16 L. */
    int level_max = cli->ref_spp > 0 ? cli->ref_spp : 8;
    struct ref_options truth_options;
    ref_options_default(&truth_options);
    truth_options.photons = cli->ref_photons > 0 ? cli->ref_photons : 100000;
    truth_options.iterations = 16 * level_max;
    truth_options.progress = true;

    struct result *results = calloc(MAX_COMBOS, sizeof *results);
    char pass_names[MAX_PASSES][PASS_NAME_MAX];
    int npasses = -1;
    struct truth *truths = calloc(MAX_COMBOS, sizeof *truths);
    int ntruths = 0;
    int choice[16] = {0};
    bool ok = results != NULL && truths != NULL;
    int width = 0, height = 0;
    for (int c = 0; ok && c < combos; c++) {
        /* the c-th combination, first sweep varying slowest */
        int rest = c;
        for (int k = cli->nsweeps - 1; k >= 0; k--) {
            choice[k] = rest % sweeps[k].count;
            rest /= sweeps[k].count;
        }
        struct lua_params params = cli->params;
        struct result *r = &results[c];
        size_t used = 0;
        for (int k = 0; k < cli->nsweeps; k++) {
            const char *v = sweeps[k].values[choice[k]];
            snprintf(r->values[k], sizeof r->values[k], "%s", v);
            int w = snprintf(r->label + used, sizeof r->label - used, "%s%s=%s", k ? " " : "", sweeps[k].key, v);
            if (w > 0 && used + (size_t)w < sizeof r->label)
                used += (size_t)w;
            if (!strchr(sweeps[k].key, '.')) {
                char assignment[200];
                snprintf(assignment, sizeof assignment, "%s=%s", sweeps[k].key, v);
                ok = lua_params_add(&params, assignment, &err);
            }
        }
        if (cli->nsweeps == 0)
            snprintf(r->label, sizeof r->label, "default");
        struct session_options so = {.script = script, .params = params, .width = cli->width, .height = cli->height,
                                     .past_last_frame = true};
        struct session *s = NULL;
        ok = ok && session_open(app, &so, &s, &err) && apply_overrides(s, sweeps, cli->nsweeps, choice, &err) &&
             session_render(s, frame, &err) /* warm-up: shader compilation, uploads */ &&
             session_reload(s, &err) && apply_overrides(s, sweeps, cli->nsweeps, choice, &err);
        double totals[1024], per_pass[MAX_PASSES][1024];
        struct image img = {0};
        if (frames > 1024)
            frames = 1024;
        for (int f = 0; ok && f < frames; f++) {
            ok = session_render(s, frame + f, &err);
            if (!ok)
                break;
            if (f == 0)
                ok = session_read_linear(s, &img, &err);
            const struct graph *g = s->graph;
            if (npasses < 0)
                npasses = 0;
            /* every kept pass counts in the frame; the columns are the union
             * of the passes seen in any variant */
            double total = app->renderer.deform_ms;
            for (int p = 0; p < MAX_PASSES; p++)
                per_pass[p][f] = -1.0;
            for (int i = 0; i < g->count; i++) {
                const struct graph_entry *e = &g->entries[i];
                if (e->state != GRAPH_PASS_KEPT)
                    continue;
                total += e->last_ms;
                int col = -1;
                for (int p = 0; p < npasses; p++)
                    if (strcmp(pass_names[p], e->pass->name) == 0)
                        col = p;
                if (col < 0 && npasses < MAX_PASSES) {
                    col = npasses++;
                    snprintf(pass_names[col], PASS_NAME_MAX, "%s", e->pass->name);
                    for (int c2 = 0; c2 < c; c2++)
                        results[c2].pass_ms[col] = -1.0; /* earlier variants did not have it */
                }
                if (col >= 0)
                    per_pass[col][f] = e->last_ms;
            }
            totals[f] = total;
        }
        for (int i = 0; ok && i < s->graph->count; i++) {
            const struct graph_entry *e = &s->graph->entries[i];
            size_t filled = strlen(r->report);
            if (e->state == GRAPH_PASS_KEPT && e->pass->report[0] && filled + 4 < sizeof r->report)
                snprintf(r->report + filled, sizeof r->report - filled, "%s%.40s: %.200s", filled ? "; " : "",
                         e->pass->name, e->pass->report);
        }
        if (ok) {
            r->frame_ms = median(totals, frames);
            for (int p = 0; p < npasses; p++)
                r->pass_ms[p] = per_pass[p][0] < 0 ? -1.0 : median(per_pass[p], frames);
            width = s->width;
            height = s->height;
        }
        session_close(s);
        /* the ground truth for these scene parameters (pass parameters do not change it) */
        int t = -1;
        uint64_t key = 0;
        ok = ok && truth_key(script, &params, frame, width, height, &truth_options, &key, &err);
        for (int i = 0; ok && i < ntruths; i++)
            if (truths[i].key == key)
                t = i;
        if (ok && t < 0) {
            ok = get_truth(app, script, &params, frame, width, height, &truth_options, cache, &truths[ntruths], &err);
            if (ok) {
                t = ntruths++;
                struct truth *tr = &truths[t];
                size_t filled = 0;
                for (int k = 0; k < cli->nsweeps; k++) {
                    if (strchr(sweeps[k].key, '.'))
                        continue;
                    snprintf(tr->values[k], sizeof tr->values[k], "%s", r->values[k]);
                    int w = snprintf(tr->label + filled, sizeof tr->label - filled, "%s%s=%s", filled ? " " : "",
                                     sweeps[k].key, r->values[k]);
                    if (w > 0 && filled + (size_t)w < sizeof tr->label)
                        filled += (size_t)w;
                }
            }
        }
        r->truth = t;
        if (ok) {
            ok = image_metrics_compute(&img, &truths[t].image, NULL, &r->all, &err);
            r->has_caustic = truths[t].has_mask;
            if (ok && r->has_caustic)
                ok = image_metrics_compute(&img, &truths[t].image, &truths[t].mask, &r->caustic, &err);
            printf("%-40s %9.3f ms (x%.2f of the first)  rel_rmse %.4f  caustic rel_rmse %s%.4f\n", r->label, r->frame_ms,
                   results[0].frame_ms > 0 ? r->frame_ms / results[0].frame_ms : 0.0, r->all.rel_rmse,
                   r->has_caustic ? "" : "(none) ", r->has_caustic ? r->caustic.rel_rmse : 0.0);
            if (r->report[0])
                printf("    %s\n", r->report);
            fflush(stdout);
        }
        image_destroy(&img);
    }
    /* The reference's own curve, for each distinct scene (its scene
     * parameters): 1/8, 1/4, 1/2 and all of the truth's iterations / 16. */
    enum { CURVE_LEVELS = 4, MAX_CURVES = 7 };
    struct result curve[CURVE_LEVELS * MAX_CURVES];
    int ncurve = 0;
    for (int t = 0; ok && t < ntruths && t < MAX_CURVES; t++) {
        for (int level = level_max / 8; ok && level <= level_max; level *= 2) {
            struct ref_options ro = truth_options;
            ro.iterations = level;
            ro.progress = false;
            ro.seed = truth_options.seed + 1000u + (uint64_t)level; /* independent of the truth's samples */
            struct session_options so = {.script = script, .params = truths[t].params, .width = truths[t].width,
                                         .height = truths[t].height};
            struct session *s = NULL;
            struct image img = {0};
            struct ref_stats st = {0};
            ok = session_open(app, &so, &s, &err);
            if (ok) {
                ok = session_reference(s, frame, &ro, &img, &st, &err);
                session_close(s);
            }
            struct result *r = &curve[ncurve++];
            memset(r, 0, sizeof *r);
            r->truth = t;
            snprintf(r->label, sizeof r->label, "reference %d it%s%s", level, truths[t].label[0] ? " " : "",
                     truths[t].label);
            for (int k = 0; k < cli->nsweeps; k++)
                snprintf(r->values[k], sizeof r->values[k], "%s", truths[t].values[k]);
            r->frame_ms = st.seconds * 1000.0;
            ok = ok && image_metrics_compute(&img, &truths[t].image, NULL, &r->all, &err);
            r->has_caustic = truths[t].has_mask;
            if (ok && r->has_caustic)
                ok = image_metrics_compute(&img, &truths[t].image, &truths[t].mask, &r->caustic, &err);
            if (ok)
                printf("%-40s %9.1f ms  rel_rmse %.4f  caustic rel_rmse %.4f\n", r->label, r->frame_ms,
                       r->all.rel_rmse, r->caustic.rel_rmse);
            image_destroy(&img);
        }
    }
    /* results.csv, results.md, plot.svg */
    char path[4400];
    FILE *csv = NULL, *md = NULL;
    if (ok) {
        snprintf(path, sizeof path, "%s/results.csv", dir);
        csv = fopen(path, "w");
        snprintf(path, sizeof path, "%s/results.md", dir);
        md = fopen(path, "w");
        ok = csv && md;
        if (!ok)
            error_set(&err, "%s: cannot write the results", dir);
    }
    if (ok) {
        fprintf(csv, "kind");
        fprintf(md, "| variant |");
        for (int k = 0; k < cli->nsweeps; k++)
            fprintf(csv, ",%s", sweeps[k].key);
        fprintf(csv, ",frame_ms,frame_ratio");
        fprintf(md, " frame ms | × first |");
        for (int p = 0; p < npasses; p++) {
            fprintf(csv, ",%s_ms", pass_names[p]);
            fprintf(md, " %s ms |", pass_names[p]);
        }
        fprintf(csv, ",rmse,rel_rmse,psnr,ssim,caustic_rel_rmse\n");
        fprintf(md, " rel_rmse | psnr | ssim | caustic rel_rmse | passes' reports |\n|---|");
        for (int p = 0; p < npasses + 6; p++)
            fprintf(md, "---:|");
        fprintf(md, "---|\n");
        for (int c = 0; c < combos + ncurve; c++) {
            const struct result *r = c < combos ? &results[c] : &curve[c - combos];
            fprintf(csv, "%s", c < combos ? "gpu" : "reference");
            for (int k = 0; k < cli->nsweeps; k++)
                fprintf(csv, ",%s", r->values[k]); /* a reference row: its scene's parameters */
            /* the frame time relative to the first variant (e.g. plain shading) */
            double ratio = results[0].frame_ms > 0 ? r->frame_ms / results[0].frame_ms : 0.0;
            fprintf(csv, ",%.4f,%.4f", r->frame_ms, ratio);
            fprintf(md, "| %s | %.3f | %.2f |", r->label, r->frame_ms, ratio);
            for (int p = 0; p < npasses; p++) {
                if (c < combos && r->pass_ms[p] >= 0) {
                    fprintf(csv, ",%.4f", r->pass_ms[p]);
                    fprintf(md, " %.3f |", r->pass_ms[p]);
                } else {
                    fprintf(csv, ",");
                    fprintf(md, " |");
                }
            }
            char caustic[32] = "";
            if (r->has_caustic)
                snprintf(caustic, sizeof caustic, "%.6g", r->caustic.rel_rmse);
            fprintf(csv, ",%.6g,%.6g,%.4g,%.6g,%s\n", r->all.rmse, r->all.rel_rmse, r->all.psnr, r->all.ssim, caustic);
            fprintf(md, " %.4f | %.2f | %.4f | %s | %s |\n", r->all.rel_rmse, r->all.psnr, r->all.ssim,
                    r->has_caustic ? caustic : "-", c < combos ? r->report : "");
        }
    }
    if (csv)
        fclose(csv);
    if (md)
        fclose(md);
    if (ok) {
        bool caustic = ntruths > 0 && truths[0].has_mask;
        struct plot_point points[MAX_COMBOS + CURVE_LEVELS * MAX_CURVES];
        int np = 0;
        for (int c = 0; c < combos + ncurve; c++) {
            const struct result *r = c < combos ? &results[c] : &curve[c - combos];
            points[np].x = r->frame_ms;
            points[np].y = caustic && r->has_caustic ? r->caustic.rel_rmse : r->all.rel_rmse;
            /* series 0: the GPU variants; 1..: one reference curve per scene */
            points[np].series = c < combos ? 0 : 1 + r->truth;
            snprintf(points[np].label, sizeof points[np].label, "%.120s", r->label);
            np++;
        }
        char title[600];
        snprintf(title, sizeof title, "%s: error against time (frame %d, %dx%d)", script, frame, width, height);
        struct plot plot = {
            .title = title,
            .x_label = "time per frame (ms), log",
            .y_label = caustic ? "rel_rmse in the caustic region, log" : "rel_rmse, log",
            .series_names = {"GPU variants"},
            .series_lines = {false},
            .series_count = 1,
            .points = points,
            .count = np,
        };
        char names[MAX_CURVES][260];
        for (int t = 0; t < ntruths && t < MAX_CURVES; t++) {
            snprintf(names[t], sizeof names[t], "reference%s%s", truths[t].label[0] ? ": " : "", truths[t].label);
            plot.series_names[1 + t] = names[t];
            plot.series_lines[1 + t] = true;
            plot.series_count = 2 + t;
        }
        snprintf(path, sizeof path, "%s/plot.svg", dir);
        ok = bench_plot_write_svg(path, &plot, &err);
        if (ok)
            printf("wrote %s/results.csv, %s/results.md and %s/plot.svg\n", dir, dir, dir);
    }
    for (int i = 0; i < ntruths; i++)
        truth_release(&truths[i]);
    free(truths);
    free(results);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
