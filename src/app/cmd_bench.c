/* `caustica bench`: error against run time. For every variant — a
 * combination of the swept values (scene parameters, or pass parameters as
 * pass.param), or with `--sweep technique=all` every technique the scene
 * declares at each of its settings — it renders N frames after a warm-up,
 * takes the median frame and per-pass times, measures the error against the
 * ground truth on one frame or, with --error-frames K, the mean over K
 * frames spread over the animation (each truth cached by a hash of scene,
 * parameters, frame, size and reference settings), and writes results.csv,
 * results.md and plot.svg. The plot also carries the reference renderer's
 * own curve: its error at growing iteration counts against a 16x longer
 * run. A technique sweep draws each technique's error-time frontier as its
 * own curve, tabulates the best error each reaches within 33 ms, 100 ms and
 * 1 s (frontier.md), and keeps its CSV in the cache for `caustica choose`. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/bench.h"
#include "app/bench_plot.h"
#include "app/cli.h"
#include "app/techniques.h"
#include "core/fileio.h"
#include "core/hash.h"
#include "core/log.h"
#include "graph/graph.h"
#include "reference/image_metrics.h"
#include "reference/reference.h"

#define MAX_VALUES 16
#define MAX_COMBOS 256
#define MAX_PASSES 32
#define MAX_TRUTHS 64
#define MAX_ERROR_FRAMES 16

struct sweep {
    char key[64];
    char values[MAX_VALUES][64];
    int count;
};

/* One thing to measure: the scene parameters its session opens with, the
 * pass parameters set after, and the scene parameters that change the scene
 * (the ground truth's; a technique's selectors do not). */
struct variant {
    char label[256];
    char values[16][64]; /* its CSV columns: one per sweep, or technique and settings */
    struct lua_params params, truth_params;
    int override_count;
    char override_keys[16][64], override_values[16][64];
    int technique; /* -1 outside a technique sweep */
};

struct result {
    char label[256];
    char values[16][64];
    double frame_ms;
    double pass_ms[MAX_PASSES];
    struct image_metrics all, caustic; /* means over the error frames */
    bool has_caustic;
    char report[300]; /* the passes' lines about the last frame (beam counts, fill rate) */
    int truth;        /* the ground truth set (scene parameters) it was measured against */
    int technique;
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

static uint64_t hash_params(uint64_t k, const struct lua_params *params)
{
    for (int i = 0; i < params->count; i++) {
        k = hash_fnv1a(k, params->keys[i], strlen(params->keys[i]) + 1);
        k = hash_fnv1a(k, params->values[i], strlen(params->values[i]) + 1);
    }
    return k;
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
    k = hash_params(k, params);
    int ints[3] = {frame, w, h};
    k = hash_fnv1a(k, ints, sizeof ints);
    k = hash_fnv1a(k, &ro->photons, sizeof ro->photons);
    k = hash_fnv1a(k, &ro->iterations, sizeof ro->iterations);
    k = hash_fnv1a(k, &ro->seed, sizeof ro->seed);
    if (ro->antialias) /* only then: the point-sampled truths keep their keys */
        k = hash_fnv1a(k, "antialias", 9);
    *key = k;
    return true;
}

int bench_timing_frames(const struct cli *cli)
{
    if (cli->frames_set)
        return cli->frames_to - cli->frames_from + 1 > 1024 ? 1024 : cli->frames_to - cli->frames_from + 1;
    for (int i = 0; i < cli->nsweeps; i++)
        if (strncmp(cli->sweeps[i], "technique=", 10) == 0)
            return 3; /* a technique sweep renders many variants over several frames each */
    return 5;
}

bool bench_sweep_cache_path(const struct cli *cli, const char *dir, char *out, size_t size, struct error *err)
{
    char *text;
    size_t n;
    if (!file_read_all(cli->positional[0], &text, &n, err))
        return false;
    uint64_t k = hash_fnv1a(1469598103934665603ULL, text, n);
    free(text);
    k = hash_params(k, &cli->params);
    long long ints[8] = {cli->width, cli->height, cli->frame, bench_timing_frames(cli),
                         cli->error_frames, cli->ref_photons, cli->ref_spp, cli->nsweeps};
    k = hash_fnv1a(k, ints, sizeof ints);
    for (int i = 0; i < cli->nsweeps; i++)
        k = hash_fnv1a(k, cli->sweeps[i], strlen(cli->sweeps[i]) + 1);
    if (cli->antialias)
        k = hash_fnv1a(k, "antialias", 9);
    snprintf(out, size, "%s/cache/sweep_%016llx.csv", dir, (unsigned long long)k);
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

/* The ground truth of one frame of one scene (its scene parameters). */
struct truth {
    uint64_t key;
    int set;       /* which truth set (distinct scene parameters) it belongs to */
    int frame;
    struct image image, caustic, mask;
    bool has_mask;
};

/* A distinct scene (its parameters that change the scene): one curve of the
 * reference, and one truth per error frame. */
struct truth_set {
    uint64_t key;        /* hash_params of `params` */
    char label[200];     /* its scene parameters ("depth=0.5"), empty without scene sweeps */
    char values[16][64]; /* per sweep: the scene parameter's value, empty for a pass parameter */
    struct lua_params params;
    int width, height;
};

static bool get_truth(struct app *app, const char *script, const struct lua_params *params, int frame, int w, int h,
                      const struct ref_options *ro, const char *cache_dir, struct truth *t, struct error *err)
{
    if (!truth_key(script, params, frame, w, h, ro, &t->key, err))
        return false;
    t->frame = frame;
    char path[4400], cpath[4400];
    snprintf(path, sizeof path, "%s/truth_%016llx.pfm", cache_dir, (unsigned long long)t->key);
    snprintf(cpath, sizeof cpath, "%s/truth_%016llx_caustic.pfm", cache_dir, (unsigned long long)t->key);
    if (file_exists(path) && file_exists(cpath) && image_read_pfm(path, &t->image, err) &&
        image_read_pfm(cpath, &t->caustic, err)) {
        log_info("ground truth from the cache: %s", path);
    } else {
        fprintf(stderr, "caustica: bench: rendering the ground truth of frame %d (%d iterations of %ld photons) ...\n",
                frame, ro->iterations, ro->photons);
        struct session_options so = {.script = script, .params = *params, .width = w, .height = h,
                                     .past_last_frame = true};
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
    return true;
}

static void truth_release(struct truth *t)
{
    image_destroy(&t->image);
    image_destroy(&t->caustic);
    image_destroy(&t->mask);
}

static bool apply_overrides(struct session *s, const struct variant *v, struct error *err)
{
    for (int k = 0; k < v->override_count; k++)
        if (!session_set_pass_param(s, v->override_keys[k], v->override_values[k], err))
            return error_prefix(err, "%s=%s", v->override_keys[k], v->override_values[k]);
    return true;
}

/* Accumulates one frame's metrics into a running mean. */
static void metrics_add(struct image_metrics *sum, const struct image_metrics *m, int n_before)
{
    double w = 1.0 / (n_before + 1);
    sum->rmse += (m->rmse - sum->rmse) * w;
    sum->rel_rmse += (m->rel_rmse - sum->rel_rmse) * w;
    sum->psnr += (m->psnr - sum->psnr) * w;
    sum->ssim += (m->ssim - sum->ssim) * w;
    sum->max = fmax(sum->max, m->max);
    sum->nan += m->nan;
    sum->pixels += m->pixels;
}

/* Copies a small file (the results into the cache). */
static bool copy_file(const char *from, const char *to, struct error *err)
{
    char *data;
    size_t size;
    if (!file_read_all(from, &data, &size, err))
        return false;
    FILE *f = fopen(to, "wb");
    bool ok = f && fwrite(data, 1, size, f) == size;
    if (f && fclose(f) != 0)
        ok = false;
    free(data);
    return ok ? true : error_set(err, "%s: cannot write", to);
}

/* The frames the error is measured on: --frame alone, or K spread evenly
 * over the animation (first and last included). */
static int pick_error_frames(int k, int first, int scene_frames, int *out)
{
    if (k <= 1 || scene_frames <= 1) {
        out[0] = first;
        return 1;
    }
    if (k > scene_frames)
        k = scene_frames;
    int n = 0;
    for (int i = 0; i < k; i++) {
        int f = (int)lround((double)i * (scene_frames - 1) / (k - 1));
        if (n == 0 || out[n - 1] != f)
            out[n++] = f;
    }
    return n;
}

static bool params_merge(struct lua_params *into, const char *key, const char *value, struct error *err)
{
    char assignment[400];
    snprintf(assignment, sizeof assignment, "%.63s=%.300s", key, value);
    return lua_params_add(into, assignment, err);
}

/* The variants of a technique sweep: every declared technique at each of its settings. */
static bool technique_variants(const struct technique_list *list, const struct lua_params *base, struct variant *out,
                               int *count, struct error *err)
{
    int n = 0;
    for (int t = 0; t < list->count; t++) {
        const struct technique *tech = &list->items[t];
        for (int p = 0; p < tech->point_count; p++) {
            if (n >= MAX_COMBOS)
                return error_set(err, "more than %d settings in all", MAX_COMBOS);
            struct variant *v = &out[n++];
            memset(v, 0, sizeof *v);
            v->technique = t;
            v->params = *base;
            v->truth_params = *base;
            for (int k = 0; k < tech->set_count; k++)
                if (!params_merge(&v->params, tech->set_keys[k], tech->set_values[k], err))
                    return false;
            const struct technique_point *pt = &tech->points[p];
            for (int k = 0; k < pt->count; k++) {
                if (technique_key_is_pass(pt->keys[k])) {
                    snprintf(v->override_keys[v->override_count], 64, "%s", pt->keys[k]);
                    snprintf(v->override_values[v->override_count++], 64, "%s", pt->values[k]);
                } else if (!params_merge(&v->params, pt->keys[k], pt->values[k], err) ||
                           !params_merge(&v->truth_params, pt->keys[k], pt->values[k], err)) {
                    return false;
                }
            }
            snprintf(v->values[0], sizeof v->values[0], "%s", tech->name);
            technique_point_label(pt, v->values[1], sizeof v->values[1]);
            snprintf(v->label, sizeof v->label, "%s: %s", tech->name, v->values[1]);
        }
    }
    *count = n;
    return true;
}

/* The variants of --sweep key=... (every combination, first sweep slowest). */
static bool sweep_variants(const struct sweep *sweeps, int nsweeps, const struct lua_params *base, struct variant *out,
                           int combos, struct error *err)
{
    for (int c = 0; c < combos; c++) {
        struct variant *v = &out[c];
        memset(v, 0, sizeof *v);
        v->technique = -1;
        v->params = *base;
        int rest = c, choice[16];
        for (int k = nsweeps - 1; k >= 0; k--) {
            choice[k] = rest % sweeps[k].count;
            rest /= sweeps[k].count;
        }
        size_t used = 0;
        for (int k = 0; k < nsweeps; k++) {
            const char *value = sweeps[k].values[choice[k]];
            snprintf(v->values[k], sizeof v->values[k], "%s", value);
            int w = snprintf(v->label + used, sizeof v->label - used, "%s%s=%s", k ? " " : "", sweeps[k].key, value);
            if (w > 0 && used + (size_t)w < sizeof v->label)
                used += (size_t)w;
            if (strchr(sweeps[k].key, '.')) {
                snprintf(v->override_keys[v->override_count], 64, "%.63s", sweeps[k].key);
                snprintf(v->override_values[v->override_count++], 64, "%s", value);
            } else if (!params_merge(&v->params, sweeps[k].key, value, err)) {
                return false;
            }
        }
        if (nsweeps == 0)
            snprintf(v->label, sizeof v->label, "default");
        v->truth_params = v->params;
    }
    return true;
}

/* The error a comparison ranks by. */
static double ranked_error(const struct result *r, bool caustic)
{
    return caustic && r->has_caustic ? r->caustic.rel_rmse : r->all.rel_rmse;
}

/* Marks the Pareto points of each series: faster than every point with a
 * lower error. */
static void mark_frontier(const struct result *results, int n, bool caustic, bool *on_front)
{
    for (int i = 0; i < n; i++) {
        on_front[i] = results[i].frame_ms > 0;
        double ei = ranked_error(&results[i], caustic);
        for (int j = 0; j < n && on_front[i]; j++) {
            if (j == i || results[j].technique != results[i].technique)
                continue;
            double ej = ranked_error(&results[j], caustic);
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
                if (best < 0 || ranked_error(&set[i], caustic) < ranked_error(&set[best], caustic))
                    best = i;
            }
            if (best < 0) {
                fprintf(f, " — |");
                continue;
            }
            const char *settings = reference ? set[best].label : set[best].values[1];
            fprintf(f, " %.3f (%s, %.0f ms) |", ranked_error(&set[best], caustic), settings, set[best].frame_ms);
        }
        fprintf(f, "\n");
    }
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
    /* The scene as the script returns it: its frame count, and the techniques it declares. */
    struct technique_list *list = calloc(1, sizeof *list);
    struct variant *variants = calloc(MAX_COMBOS, sizeof *variants);
    struct result *results = calloc(MAX_COMBOS, sizeof *results);
    struct truth *truths = calloc(MAX_TRUTHS, sizeof *truths);
    struct truth_set *sets = calloc(MAX_TRUTHS, sizeof *sets);
    if (!list || !variants || !results || !truths || !sets) {
        free(list), free(variants), free(results), free(truths), free(sets);
        fprintf(stderr, "caustica: out of memory\n");
        return EXIT_SCENE_ERROR;
    }
    bool technique_sweep = false;
    int scene_frames = 1, nvariants = 0;
    bool ok = true;
    {
        struct session_options so = {.script = script, .params = cli->params, .width = cli->width,
                                     .height = cli->height, .past_last_frame = true};
        struct session *probe = NULL;
        ok = session_open(app, &so, &probe, &err);
        if (ok) {
            scene_frames = probe->frames;
            struct error no_table;
            bool declared = techniques_read(probe, list, &no_table);
            for (int i = 0; i < cli->nsweeps; i++) {
                if (strcmp(sweeps[i].key, "technique") != 0 || (!declared && strcmp(cli->sweeps[i], "technique=all") != 0))
                    continue; /* without a declaration technique=a,b is an ordinary scene parameter */
                technique_sweep = true;
                if (!declared)
                    ok = error_set(&err, "%s", no_table.message);
                else if (cli->nsweeps != 1)
                    ok = error_set(&err, "--sweep technique=... sweeps each technique's own settings (the scene's "
                                         "techniques table); give it alone");
                else
                    ok = techniques_select(list, cli->sweeps[i] + strlen("technique="), &err);
            }
            session_close(probe);
        }
    }
    if (ok && technique_sweep)
        ok = technique_variants(list, &cli->params, variants, &nvariants, &err);
    else if (ok) {
        nvariants = combos;
        ok = sweep_variants(sweeps, cli->nsweeps, &cli->params, variants, combos, &err);
    }
    if (!ok) {
        cli_print_error(&err);
        free(list), free(variants), free(results), free(truths), free(sets);
        return technique_sweep ? EXIT_USAGE : EXIT_SCENE_ERROR;
    }
    int ncolumns = technique_sweep ? 2 : cli->nsweeps;
    const char *columns[16];
    for (int k = 0; k < cli->nsweeps && !technique_sweep; k++)
        columns[k] = sweeps[k].key;
    if (technique_sweep) {
        columns[0] = "technique";
        columns[1] = "settings";
    }
    int frames = bench_timing_frames(cli);
    int frame = cli->frame;
    int error_frames[MAX_ERROR_FRAMES];
    int nerror = pick_error_frames(cli->error_frames ? cli->error_frames : technique_sweep ? 3 : 1, frame,
                                   scene_frames, error_frames);
    if (nerror > 1) {
        printf("errors: the mean over frames");
        for (int i = 0; i < nerror; i++)
            printf("%s %d", i ? "," : "", error_frames[i]);
        printf(" of %d\n", scene_frames);
    }
    /* The reference curve: L/8, L/4, L/2, L iterations against 16 L. */
    int level_max = cli->ref_spp > 0 ? cli->ref_spp : 8;
    struct ref_options truth_options;
    ref_options_default(&truth_options);
    truth_options.photons = cli->ref_photons > 0 ? cli->ref_photons : 100000;
    truth_options.iterations = 16 * level_max;
    truth_options.progress = true;
    truth_options.antialias = cli->antialias;

    char pass_names[MAX_PASSES][PASS_NAME_MAX];
    int npasses = -1, ntruths = 0, nsets = 0;
    int width = 0, height = 0;
    for (int c = 0; ok && c < nvariants; c++) {
        const struct variant *v = &variants[c];
        struct result *r = &results[c];
        snprintf(r->label, sizeof r->label, "%s", v->label);
        memcpy(r->values, v->values, sizeof r->values);
        r->technique = v->technique;
        struct session_options so = {.script = script, .params = v->params, .width = cli->width, .height = cli->height,
                                     .past_last_frame = true};
        struct session *s = NULL;
        ok = session_open(app, &so, &s, &err) && apply_overrides(s, v, &err) &&
             session_render(s, frame, &err) /* warm-up: shader compilation, uploads */ &&
             session_reload(s, &err) && apply_overrides(s, v, &err);
        double totals[1024], per_pass[MAX_PASSES][1024];
        struct image images[MAX_ERROR_FRAMES];
        bool have[MAX_ERROR_FRAMES] = {false};
        memset(images, 0, sizeof images);
        for (int f = 0; ok && f < frames; f++) {
            ok = session_render(s, frame + f, &err);
            if (!ok)
                break;
            for (int e = 0; ok && e < nerror; e++)
                if (error_frames[e] == frame + f && !have[e])
                    have[e] = ok = session_read_linear(s, &images[e], &err);
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
        /* the error frames the timing run did not pass through (in order:
         * going back reloads the script, and its pass settings with it) */
        for (int e = 0; ok && e < nerror; e++) {
            if (have[e])
                continue;
            if (error_frames[e] < s->advanced)
                ok = session_reload(s, &err) && apply_overrides(s, v, &err);
            ok = ok && session_render(s, error_frames[e], &err);
            have[e] = ok = ok && session_read_linear(s, &images[e], &err);
        }
        session_close(s);
        /* the ground truths for these scene parameters (pass parameters and
         * a technique's selectors do not change them) */
        uint64_t set_key = hash_params(1469598103934665603ULL, &v->truth_params);
        int set = -1;
        for (int i = 0; i < nsets; i++)
            if (sets[i].key == set_key)
                set = i;
        if (ok && set < 0) {
            if (nsets >= MAX_TRUTHS)
                ok = error_set(&err, "more than %d distinct scenes", MAX_TRUTHS);
            else {
                set = nsets++;
                struct truth_set *ts = &sets[set];
                ts->key = set_key;
                ts->params = v->truth_params;
                ts->width = width;
                ts->height = height;
                size_t filled = 0;
                for (int k = 0; k < cli->nsweeps && !technique_sweep; k++) {
                    if (strchr(sweeps[k].key, '.'))
                        continue;
                    snprintf(ts->values[k], sizeof ts->values[k], "%s", v->values[k]);
                    int w = snprintf(ts->label + filled, sizeof ts->label - filled, "%s%s=%s", filled ? " " : "",
                                     sweeps[k].key, v->values[k]);
                    if (w > 0 && filled + (size_t)w < sizeof ts->label)
                        filled += (size_t)w;
                }
            }
        }
        r->truth = set;
        int with_mask = 0;
        for (int e = 0; ok && e < nerror; e++) {
            int t = -1;
            for (int i = 0; i < ntruths; i++)
                if (truths[i].set == set && truths[i].frame == error_frames[e])
                    t = i;
            if (t < 0) {
                if (ntruths >= MAX_TRUTHS) {
                    ok = error_set(&err, "more than %d ground truths (scenes x error frames)", MAX_TRUTHS);
                    break;
                }
                ok = get_truth(app, script, &v->truth_params, error_frames[e], width, height, &truth_options, cache,
                               &truths[ntruths], &err);
                if (ok) {
                    truths[ntruths].set = set;
                    t = ntruths++;
                }
            }
            struct image_metrics m;
            ok = ok && image_metrics_compute(&images[e], &truths[t].image, NULL, &m, &err);
            if (ok)
                metrics_add(&r->all, &m, e);
            if (ok && truths[t].has_mask) {
                ok = image_metrics_compute(&images[e], &truths[t].image, &truths[t].mask, &m, &err);
                if (ok)
                    metrics_add(&r->caustic, &m, with_mask++);
            }
        }
        r->has_caustic = with_mask > 0;
        for (int e = 0; e < nerror; e++)
            image_destroy(&images[e]);
        if (ok) {
            printf("%-40s %9.3f ms (x%.2f of the first)  rel_rmse %.4f  caustic rel_rmse %s%.4f\n", r->label, r->frame_ms,
                   results[0].frame_ms > 0 ? r->frame_ms / results[0].frame_ms : 0.0, r->all.rel_rmse,
                   r->has_caustic ? "" : "(none) ", r->has_caustic ? r->caustic.rel_rmse : 0.0);
            if (r->report[0])
                printf("    %s\n", r->report);
            fflush(stdout);
        }
    }
    /* The reference's own curve, for each distinct scene (its scene
     * parameters): 1/8, 1/4, 1/2 and all of the truth's iterations / 16,
     * over the same error frames. */
    enum { CURVE_LEVELS = 4, MAX_CURVES = 7 };
    struct result curve[CURVE_LEVELS * MAX_CURVES];
    int ncurve = 0;
    for (int t = 0; ok && t < nsets && t < MAX_CURVES; t++) {
        for (int level = level_max / 8; ok && level <= level_max; level *= 2) {
            struct result *r = &curve[ncurve++];
            memset(r, 0, sizeof *r);
            r->truth = t;
            r->technique = -1;
            snprintf(r->label, sizeof r->label, "reference %d it%s%s", level, sets[t].label[0] ? " " : "",
                     sets[t].label);
            for (int k = 0; k < ncolumns; k++)
                snprintf(r->values[k], sizeof r->values[k], "%s", technique_sweep ? "" : sets[t].values[k]);
            if (technique_sweep) {
                snprintf(r->values[0], sizeof r->values[0], "reference");
                snprintf(r->values[1], sizeof r->values[1], "%d it", level);
            }
            int with_mask = 0;
            for (int e = 0; ok && e < nerror; e++) {
                int ti = -1;
                for (int i = 0; i < ntruths; i++)
                    if (truths[i].set == t && truths[i].frame == error_frames[e])
                        ti = i;
                struct ref_options ro = truth_options;
                ro.iterations = level;
                ro.progress = false;
                ro.seed = truth_options.seed + 1000u + (uint64_t)level; /* independent of the truth's samples */
                struct session_options so = {.script = script, .params = sets[t].params, .width = sets[t].width,
                                             .height = sets[t].height, .past_last_frame = true};
                struct session *s = NULL;
                struct image img = {0};
                struct ref_stats st = {0};
                ok = session_open(app, &so, &s, &err);
                if (ok) {
                    ok = session_reference(s, error_frames[e], &ro, &img, &st, &err);
                    session_close(s);
                }
                r->frame_ms += (st.seconds * 1000.0 - r->frame_ms) / (e + 1);
                struct image_metrics m;
                ok = ok && image_metrics_compute(&img, &truths[ti].image, NULL, &m, &err);
                if (ok)
                    metrics_add(&r->all, &m, e);
                if (ok && truths[ti].has_mask) {
                    ok = image_metrics_compute(&img, &truths[ti].image, &truths[ti].mask, &m, &err);
                    if (ok)
                        metrics_add(&r->caustic, &m, with_mask++);
                }
                image_destroy(&img);
            }
            r->has_caustic = with_mask > 0;
            if (ok)
                printf("%-40s %9.1f ms  rel_rmse %.4f  caustic rel_rmse %.4f\n", r->label, r->frame_ms,
                       r->all.rel_rmse, r->caustic.rel_rmse);
        }
    }
    /* the error ranked: the caustic region's where there is one (or the
     * scene's techniques table says "image") */
    bool caustic = nsets > 0 && results[0].has_caustic &&
                   !(technique_sweep && list->metric == TECHNIQUE_METRIC_IMAGE);
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
        for (int k = 0; k < ncolumns; k++)
            fprintf(csv, ",%s", columns[k]);
        fprintf(csv, ",frame_ms,frame_ratio");
        fprintf(md, " frame ms | × first |");
        for (int p = 0; p < npasses; p++) {
            fprintf(csv, ",%s_ms", pass_names[p]);
            fprintf(md, " %s ms |", pass_names[p]);
        }
        fprintf(csv, ",rmse,rel_rmse,psnr,ssim,caustic_rel_rmse,error\n");
        fprintf(md, " rel_rmse | psnr | ssim | caustic rel_rmse | passes' reports |\n|---|");
        for (int p = 0; p < npasses + 6; p++)
            fprintf(md, "---:|");
        fprintf(md, "---|\n");
        for (int c = 0; c < nvariants + ncurve; c++) {
            const struct result *r = c < nvariants ? &results[c] : &curve[c - nvariants];
            fprintf(csv, "%s", c < nvariants ? "gpu" : "reference");
            for (int k = 0; k < ncolumns; k++)
                fprintf(csv, ",%s", r->values[k]); /* a reference row: its scene's parameters */
            /* the frame time relative to the first variant (e.g. plain shading) */
            double ratio = results[0].frame_ms > 0 ? r->frame_ms / results[0].frame_ms : 0.0;
            fprintf(csv, ",%.4f,%.4f", r->frame_ms, ratio);
            fprintf(md, "| %s | %.3f | %.2f |", r->label, r->frame_ms, ratio);
            for (int p = 0; p < npasses; p++) {
                if (c < nvariants && r->pass_ms[p] >= 0) {
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
            fprintf(csv, ",%.6g,%.6g,%.4g,%.6g,%s,%.6g\n", r->all.rmse, r->all.rel_rmse, r->all.psnr, r->all.ssim,
                    caustic_text, ranked_error(r, caustic));
            fprintf(md, " %.4f | %.2f | %.4f | %s | %s |\n", r->all.rel_rmse, r->all.psnr, r->all.ssim,
                    r->has_caustic ? caustic_text : "-", c < nvariants ? r->report : "");
        }
        if (nerror > 1) {
            fprintf(md, "\nErrors are means over frames");
            for (int i = 0; i < nerror; i++)
                fprintf(md, "%s %d", i ? "," : "", error_frames[i]);
            fprintf(md, " (of %d); times are medians of %d frames from frame %d.\n", scene_frames, frames, frame);
        }
    }
    if (csv)
        fclose(csv);
    bool *on_front = calloc((size_t)nvariants + 1, sizeof *on_front);
    if (ok && technique_sweep) {
        /* the frontier table, in results.md, frontier.md and on stdout */
        mark_frontier(results, nvariants, caustic, on_front);
        char machine[400];
        snprintf(machine, sizeof machine, "%dx%d, %s, %ld CPU cores", width, height, app->gl ? app->gl->renderer : "?",
                 sysconf(_SC_NPROCESSORS_ONLN));
        snprintf(path, sizeof path, "%s/frontier.md", dir);
        FILE *fr = fopen(path, "w");
        if (!fr)
            ok = error_set(&err, "%s: cannot write", path);
        else {
            write_frontier(fr, list, results, nvariants, curve, ncurve, caustic, machine);
            fclose(fr);
            fputs("\n", md);
            write_frontier(md, list, results, nvariants, curve, ncurve, caustic, machine);
            write_frontier(stdout, list, results, nvariants, curve, ncurve, caustic, machine);
        }
    }
    if (md)
        fclose(md);
    if (ok && technique_sweep) {
        /* kept for `caustica choose` */
        char cached[4400], from[4400];
        snprintf(from, sizeof from, "%s/results.csv", dir);
        ok = bench_sweep_cache_path(cli, dir, cached, sizeof cached, &err) && copy_file(from, cached, &err);
    }
    if (ok) {
        struct plot_point points[MAX_COMBOS + CURVE_LEVELS * MAX_CURVES];
        int np = 0;
        int techniques = technique_sweep ? list->count : 1;
        for (int c = 0; c < nvariants + ncurve; c++) {
            const struct result *r = c < nvariants ? &results[c] : &curve[c - nvariants];
            points[np].x = r->frame_ms;
            points[np].y = ranked_error(r, caustic);
            /* series 0 (or one per technique): the GPU variants; then one reference curve per scene */
            points[np].series = c < nvariants ? (technique_sweep ? r->technique : 0) : techniques + r->truth;
            points[np].joined = c < nvariants ? on_front[c] : true;
            snprintf(points[np].label, sizeof points[np].label, "%.120s", r->label);
            np++;
        }
        char title[600];
        snprintf(title, sizeof title, "%s: error against time (%s %d, %dx%d)", script, nerror > 1 ? "frames" : "frame",
                 nerror > 1 ? nerror : frame, width, height);
        if (nerror > 1)
            snprintf(title, sizeof title, "%s: error against time (mean of %d frames, %dx%d)", script, nerror, width,
                     height);
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
        if (technique_sweep) {
            for (int t = 0; t < list->count && t < PLOT_MAX_SERIES; t++) {
                plot.series_names[t] = list->items[t].name;
                plot.series_lines[t] = true; /* its frontier */
            }
            plot.series_count = list->count;
        }
        char names[MAX_CURVES][260];
        for (int t = 0; t < nsets && t < MAX_CURVES && techniques + t < PLOT_MAX_SERIES; t++) {
            snprintf(names[t], sizeof names[t], "reference%s%s", sets[t].label[0] ? ": " : "", sets[t].label);
            plot.series_names[techniques + t] = names[t];
            plot.series_lines[techniques + t] = true;
            plot.series_count = techniques + t + 1;
        }
        snprintf(path, sizeof path, "%s/plot.svg", dir);
        ok = bench_plot_write_svg(path, &plot, &err);
        if (ok)
            printf("wrote %s/results.csv, %s/results.md%s and %s/plot.svg\n", dir, dir,
                   technique_sweep ? ", frontier.md" : "", dir);
    }
    free(on_front);
    for (int i = 0; i < ntruths; i++)
        truth_release(&truths[i]);
    free(truths);
    free(sets);
    free(results);
    free(variants);
    free(list);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
