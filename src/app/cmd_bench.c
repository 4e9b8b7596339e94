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
#include <sys/stat.h>
#include <unistd.h>

#include "app/bench.h"
#include "app/bench_plot.h"
#include "app/cli.h"
#include "app/techniques.h"
#include "core/fileio.h"
#include "core/hash.h"
#include "core/cpus.h"
#include "core/log.h"
#include "graph/graph.h"
#include "reference/image_metrics.h"
#include "reference/reference.h"
#include "reference/reference_part.h"

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
    /* issue 32: the error of the change from each error frame to the next
     * (image_flicker_compute), means over the error frames, whole and in the
     * caustic region; < 0: not measured (a reference row) */
    double flicker_all, flicker_caustic;
    char report[300]; /* the passes' lines about the last frame (beam counts, fill rate) */
    int truth;        /* the ground truth set (scene parameters) it was measured against */
    int technique;
    int iterations;   /* a reference curve row's iterations (0: a GPU variant) */
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
    if (cli->truth_spp > 0) /* hashed only when given: the caches made before it keep their names */
        k = hash_fnv1a(k, &cli->truth_spp, sizeof cli->truth_spp);
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
    /* a cache entry is read only as a regular file of its own (no link to elsewhere, no FIFO) */
    struct stat entry, caustic_entry;
    bool linked = (lstat(path, &entry) == 0 && !S_ISREG(entry.st_mode)) ||
                  (lstat(cpath, &caustic_entry) == 0 && !S_ISREG(caustic_entry.st_mode));
    if (linked)
        return error_set(err, "%s: a cached truth that is not a regular file (a link, a FIFO): refused; remove it", path);
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

/* One bench run: what it measures, and what it has measured so far. */
enum { CURVE_LEVELS = 4, MAX_CURVES = 7 };
struct bench {
    struct app *app;
    const struct cli *cli;
    bool process_warm; /* a variant's timing frames have run once untimed in this process */
    const char *script, *dir;
    char cache[4200];
    struct sweep sweeps[16];
    int combos;
    struct technique_list *list;
    bool technique_sweep;
    int scene_frames;
    struct variant *variants;
    int nvariants;
    struct result *results;
    struct result curve[CURVE_LEVELS * MAX_CURVES]; /* the reference's own curve */
    int ncurve;
    double truth_error[MAX_CURVES]; /* the truth's own error (noise and bias), bounded from the curve; < 0: unknown */
    struct truth *truths;
    int ntruths;
    struct truth_set *sets;
    int nsets;
    int ncolumns;
    const char *columns[16];
    int frames, frame;        /* timing: frames from `frame` */
    int error_frames[MAX_ERROR_FRAMES], nerror;
    int level_max;            /* the reference curve's largest iteration count */
    struct ref_options truth_options;
    char pass_names[MAX_PASSES][PASS_NAME_MAX];
    int npasses;
    int width, height;
    bool caustic;             /* errors ranked in the caustic region */
    bool *on_front;           /* per variant: on its technique's frontier */
};

static void bench_release(struct bench *b)
{
    for (int i = 0; i < b->ntruths; i++)
        truth_release(&b->truths[i]);
    free(b->on_front);
    free(b->truths);
    free(b->sets);
    free(b->results);
    free(b->variants);
    free(b->list);
}

/* The sweeps, the scene's frame count and techniques, and the variants. */
static bool bench_plan(struct bench *b, int *exit_code, struct error *err)
{
    const struct cli *cli = b->cli;
    b->combos = 1;
    *exit_code = EXIT_USAGE;
    for (int i = 0; i < cli->nsweeps; i++) {
        if (!parse_sweep(cli->sweeps[i], &b->sweeps[i], err))
            return false;
        b->combos *= b->sweeps[i].count;
        if (b->combos > MAX_COMBOS)
            return error_set(err, "bench: more than %d combinations", MAX_COMBOS);
    }
    *exit_code = EXIT_SCENE_ERROR;
    snprintf(b->cache, sizeof b->cache, "%s/cache", b->dir);
    if (!dir_ensure(b->dir, err) || !dir_ensure(b->cache, err))
        return false;
    b->list = calloc(1, sizeof *b->list);
    b->variants = calloc(MAX_COMBOS, sizeof *b->variants);
    b->results = calloc(MAX_COMBOS, sizeof *b->results);
    b->truths = calloc(MAX_TRUTHS, sizeof *b->truths);
    b->sets = calloc(MAX_TRUTHS, sizeof *b->sets);
    if (!b->list || !b->variants || !b->results || !b->truths || !b->sets)
        return error_set(err, "out of memory");
    /* The scene as the script returns it: its frame count, and the techniques it declares. */
    b->scene_frames = 1;
    struct session_options so = {.script = b->script, .params = cli->params, .width = cli->width,
                                 .height = cli->height, .past_last_frame = true};
    struct session *probe = NULL;
    bool ok = session_open(b->app, &so, &probe, err);
    if (ok) {
        b->scene_frames = probe->frames;
        struct error no_table;
        bool declared = techniques_read(probe, b->list, &no_table);
        for (int i = 0; i < cli->nsweeps; i++) {
            if (strcmp(b->sweeps[i].key, "technique") != 0 ||
                (!declared && strcmp(cli->sweeps[i], "technique=all") != 0))
                continue; /* without a declaration technique=a,b is an ordinary scene parameter */
            b->technique_sweep = true;
            if (!declared)
                ok = error_set(err, "%s", no_table.message);
            else if (cli->nsweeps != 1)
                ok = error_set(err, "--sweep technique=... sweeps each technique's own settings (the scene's "
                                    "techniques table); give it alone");
            else
                ok = techniques_select(b->list, cli->sweeps[i] + strlen("technique="), err);
        }
        session_close(probe);
    }
    if (ok && b->technique_sweep)
        ok = technique_variants(b->list, &cli->params, b->variants, &b->nvariants, err);
    else if (ok) {
        b->nvariants = b->combos;
        ok = sweep_variants(b->sweeps, cli->nsweeps, &cli->params, b->variants, b->combos, err);
    }
    if (!ok) {
        *exit_code = b->technique_sweep ? EXIT_USAGE : EXIT_SCENE_ERROR;
        return false;
    }
    b->ncolumns = b->technique_sweep ? 2 : cli->nsweeps;
    for (int k = 0; k < cli->nsweeps && !b->technique_sweep; k++)
        b->columns[k] = b->sweeps[k].key;
    if (b->technique_sweep) {
        b->columns[0] = "technique";
        b->columns[1] = "settings";
    }
    b->frames = bench_timing_frames(cli);
    b->frame = cli->frame;
    b->nerror = pick_error_frames(cli->error_frames ? cli->error_frames : b->technique_sweep ? 3 : 1, b->frame,
                                  b->scene_frames, b->error_frames);
    if (b->nerror > 1) {
        printf("errors: the mean over frames");
        for (int i = 0; i < b->nerror; i++)
            printf("%s %d", i ? "," : "", b->error_frames[i]);
        printf(" of %d\n", b->scene_frames);
    }
    /* The reference curve: L/8, L/4, L/2, L iterations against 16 L. */
    b->level_max = cli->ref_spp > 0 ? cli->ref_spp : 8;
    ref_options_default(&b->truth_options);
    b->truth_options.photons = cli->ref_photons > 0 ? cli->ref_photons : 100000;
    if (cli->truth_spp > 0 && cli->truth_spp < b->level_max)
        return error_set(err, "--truth-spp %d is below --ref-spp %d: the truth must run at least as long as the "
                              "curve's longest reference", cli->truth_spp, b->level_max);
    b->truth_options.iterations = cli->truth_spp > 0 ? cli->truth_spp : 16 * b->level_max;
    b->truth_options.progress = true;
    b->truth_options.antialias = cli->antialias;
    b->npasses = -1;
    return true;
}

/* One timed frame's kept passes into per_pass[column][f] (the columns are
 * the union of the passes seen in any variant); returns the frame's total. */
static double bench_frame_times(struct bench *b, const struct graph *g, int variant, int f,
                                double per_pass[MAX_PASSES][1024])
{
    if (b->npasses < 0)
        b->npasses = 0;
    double total = b->app->renderer.deform_ms;
    for (int p = 0; p < MAX_PASSES; p++)
        per_pass[p][f] = -1.0;
    for (int i = 0; i < g->count; i++) {
        const struct graph_entry *e = &g->entries[i];
        if (e->state != GRAPH_PASS_KEPT)
            continue;
        total += e->last_ms;
        int col = -1;
        for (int p = 0; p < b->npasses; p++)
            if (strcmp(b->pass_names[p], e->pass->name) == 0)
                col = p;
        if (col < 0 && b->npasses < MAX_PASSES) {
            col = b->npasses++;
            snprintf(b->pass_names[col], PASS_NAME_MAX, "%s", e->pass->name);
            for (int c2 = 0; c2 < variant; c2++)
                b->results[c2].pass_ms[col] = -1.0; /* earlier variants did not have it */
        }
        if (col >= 0)
            per_pass[col][f] = e->last_ms;
    }
    return total;
}

/* The most frames any pass of the session accumulates over (a pass's
 * `accumulate` parameter, issue 32; 1: none keeps a history). */
static int session_history_frames(const struct session *s)
{
    int most = 1;
    for (int i = 0; i < s->graph->count; i++) {
        const struct pass *p = s->graph->entries[i].pass;
        int k = pass_param_index(p->desc, "accumulate");
        if (k >= 0 && p->desc->params[k].type == PASS_PARAM_INTEGER && pass_int(p, k) > most)
            most = pass_int(p, k);
    }
    return most;
}

/* Times variant `c` (median of the frames after a warm-up) and reads its
 * images on the error frames and the frames after them (the flicker's). A
 * variant that accumulates over N frames is measured on an error frame
 * after the N frames before it (all from frame 0, where fewer): what a
 * viewer of the animation sees there. */
static bool bench_time_variant(struct bench *b, int c, struct image images[MAX_ERROR_FRAMES],
                               struct image next[MAX_ERROR_FRAMES], struct error *err)
{
    const struct variant *v = &b->variants[c];
    struct result *r = &b->results[c];
    snprintf(r->label, sizeof r->label, "%s", v->label);
    memcpy(r->values, v->values, sizeof r->values);
    r->technique = v->technique;
    struct session_options so = {.script = b->script, .params = v->params, .width = b->cli->width,
                                 .height = b->cli->height, .past_last_frame = true};
    struct session *s = NULL;
    bool ok = session_open(b->app, &so, &s, err) && apply_overrides(s, v, err) &&
              session_render(s, b->frame, err); /* warm-up: this variant's shaders, uploads */
    /* The first variant timed in the process also pays the process's own
     * first use (the driver's shader variants for each state, first-touch
     * of its memory: on llvmpipe a first variant measured 1,257 ms against
     * 277 ms for the next, shade 779 against 17): all its timing frames run
     * once untimed before the timed run. */
    if (ok && !b->process_warm) {
        for (int f = 1; ok && f < b->frames; f++)
            ok = session_render(s, b->frame + f, err);
        b->process_warm = ok;
        if (ok)
            log_info("bench: warm-up: %d untimed frame%s of '%s' before the first timed variant", b->frames,
                     b->frames == 1 ? "" : "s", v->label);
    }
    ok = ok && session_reload(s, err) && apply_overrides(s, v, err);
    static double totals[1024], per_pass[MAX_PASSES][1024];
    bool have[MAX_ERROR_FRAMES] = {false}, have_next[MAX_ERROR_FRAMES] = {false};
    int last = -1; /* the last frame rendered since the session (re)started */
    int history = ok ? session_history_frames(s) : 1;
    for (int f = 0; ok && f < b->frames; f++) {
        ok = session_render(s, b->frame + f, err);
        last = b->frame + f;
        /* an accumulating variant's frame counts once its history is full
         * (or holds every frame from the animation's start) */
        bool warm = history <= 1 || f >= history || b->frame == 0;
        for (int e = 0; ok && e < b->nerror; e++) {
            if (b->error_frames[e] == last && !have[e] && warm)
                have[e] = ok = session_read_linear(s, &images[e], err);
            else if (b->error_frames[e] + 1 == last && have[e] && !have_next[e])
                have_next[e] = ok = session_read_linear(s, &next[e], err);
        }
        if (ok)
            totals[f] = bench_frame_times(b, s->graph, c, f, per_pass);
    }
    for (int i = 0; ok && i < s->graph->count; i++) {
        const struct graph_entry *e = &s->graph->entries[i];
        size_t filled = strlen(r->report);
        if (e->state == GRAPH_PASS_KEPT && e->pass->report[0] && filled + 4 < sizeof r->report)
            snprintf(r->report + filled, sizeof r->report - filled, "%s%.40s: %.200s", filled ? "; " : "",
                     e->pass->name, e->pass->report);
    }
    if (ok) {
        r->frame_ms = median(totals, b->frames);
        for (int p = 0; p < b->npasses; p++)
            r->pass_ms[p] = per_pass[p][0] < 0 ? -1.0 : median(per_pass[p], b->frames);
        b->width = s->width;
        b->height = s->height;
    }
    /* the error frames (and the frames after them) the timing run did not
     * pass through, in order: going back reloads the script, and its pass
     * settings with it */
    for (int e = 0; ok && e < b->nerror; e++) {
        int target = b->error_frames[e];
        if (!have[e] || last != target) {
            if (have[e] && have_next[e])
                continue;
            image_destroy(&images[e]);
            have[e] = false;
            /* from the N frames before it (each frame's history is the frames before) */
            int start = history > 1 ? (target - history > 0 ? target - history : 0) : target;
            if (start <= last || start < s->advanced) {
                ok = session_reload(s, err) && apply_overrides(s, v, err);
                last = -1;
            }
            for (int f = start; ok && f <= target; f++) {
                ok = session_render(s, f, err);
                last = f;
            }
            have[e] = ok = ok && session_read_linear(s, &images[e], err);
        }
        ok = ok && session_render(s, target + 1, err);
        last = target + 1;
        have_next[e] = ok = ok && session_read_linear(s, &next[e], err);
    }
    if (s)
        session_close(s);
    return ok;
}

/* The truth set of variant `v`'s scene parameters (pass parameters and a
 * technique's selectors do not change the scene), made on first need. */
static bool bench_truth_set(struct bench *b, const struct variant *v, int *out, struct error *err)
{
    uint64_t set_key = hash_params(1469598103934665603ULL, &v->truth_params);
    for (int i = 0; i < b->nsets; i++)
        if (b->sets[i].key == set_key) {
            *out = i;
            return true;
        }
    if (b->nsets >= MAX_TRUTHS)
        return error_set(err, "more than %d distinct scenes", MAX_TRUTHS);
    int set = b->nsets++;
    struct truth_set *ts = &b->sets[set];
    ts->key = set_key;
    ts->params = v->truth_params;
    ts->width = b->width;
    ts->height = b->height;
    size_t filled = 0;
    for (int k = 0; k < b->cli->nsweeps && !b->technique_sweep; k++) {
        if (strchr(b->sweeps[k].key, '.'))
            continue;
        snprintf(ts->values[k], sizeof ts->values[k], "%s", v->values[k]);
        int w = snprintf(ts->label + filled, sizeof ts->label - filled, "%s%s=%s", filled ? " " : "",
                         b->sweeps[k].key, v->values[k]);
        if (w > 0 && filled + (size_t)w < sizeof ts->label)
            filled += (size_t)w;
    }
    *out = set;
    return true;
}

/* The truth from --truth FILE: a reference's image (a merged one, from
 * any number of nodes), its caustic layer where it is an EXR with one; its
 * .part, where there is one, must be of this frame and size. */
static bool truth_from_file(const char *path, int frame, int w, int h, struct truth *t, struct error *err)
{
    char part_path[4300];
    snprintf(part_path, sizeof part_path, "%s.part", path);
    if (file_exists(part_path)) {
        struct reference_part *part = malloc(sizeof *part);
        if (!part)
            return error_set(err, "--truth %s: out of memory", path);
        bool ok = reference_part_read(path, part, err);
        if (ok && (part->frame != frame || part->width != w || part->height != h))
            ok = error_set(err, "--truth %s: a reference of frame %d at %dx%d; bench measures frame %d at %dx%d", path,
                           part->frame, part->width, part->height, frame, w, h);
        free(part);
        if (!ok)
            return false;
    }
    if (!image_read(path, &t->image, err))
        return false;
    if (t->image.width != w || t->image.height != h)
        return error_set(err, "--truth %s: %dx%d, bench measures %dx%d (--size)", path, t->image.width,
                         t->image.height, w, h);
    t->frame = frame;
    char layer[4300];
    snprintf(layer, sizeof layer, "%s:caustic", path);
    struct error ignore;
    if (image_path_is_exr(path) && image_read(layer, &t->caustic, &ignore)) {
        t->has_mask = caustic_mask(&t->image, &t->caustic, &t->mask, &ignore);
    } else {
        log_warn("--truth %s: no caustic layer (reference -o x.exr writes one): errors over the whole image only",
                 path);
        t->has_mask = false;
    }
    log_info("ground truth from %s (one frame: no flicker measured, which needs the truth of the frame after it)",
             path);
    return true;
}

/* The truth of set `set` at error frame `frame` (rendered or read from the cache). */
static bool bench_truth(struct bench *b, const struct variant *v, int set, int frame, int *out, struct error *err)
{
    for (int i = 0; i < b->ntruths; i++)
        if (b->truths[i].set == set && b->truths[i].frame == frame) {
            *out = i;
            return true;
        }
    if (b->ntruths >= MAX_TRUTHS)
        return error_set(err, "more than %d ground truths (scenes x error frames)", MAX_TRUTHS);
    if (b->cli->truth) {
        if (set != 0 || b->nerror > 1)
            return error_set(err, "--truth %s is one frame of one scene: %s", b->cli->truth,
                             set != 0 ? "this sweep changes the scene (sweep pass parameters or techniques with it)"
                                      : "use --error-frames 1");
        if (!truth_from_file(b->cli->truth, frame, b->width, b->height, &b->truths[b->ntruths], err))
            return false;
    } else if (!get_truth(b->app, b->script, &v->truth_params, frame, b->width, b->height, &b->truth_options,
                          b->cache, &b->truths[b->ntruths], err)) {
        return false;
    }
    b->truths[b->ntruths].set = set;
    *out = b->ntruths++;
    return true;
}

/* `image`'s error against truth `t`, whole and in the caustic region, added
 * to r's means (e: how many frames are in them already). */
static bool bench_add_error(const struct truth *t, const struct image *image, struct result *r, int e,
                            int *with_mask, struct error *err)
{
    struct image_metrics m;
    if (!image_metrics_compute(image, &t->image, NULL, &m, err))
        return false;
    metrics_add(&r->all, &m, e);
    if (t->has_mask) {
        if (!image_metrics_compute(image, &t->image, &t->mask, &m, err))
            return false;
        metrics_add(&r->caustic, &m, (*with_mask)++);
    }
    return true;
}

/* Variant c: timed, then measured against its truths; one line on stdout. */
static bool bench_variant(struct bench *b, int c, struct error *err)
{
    struct result *r = &b->results[c];
    struct image images[MAX_ERROR_FRAMES], next[MAX_ERROR_FRAMES];
    memset(images, 0, sizeof images);
    memset(next, 0, sizeof next);
    bool ok = bench_time_variant(b, c, images, next, err) && bench_truth_set(b, &b->variants[c], &r->truth, err);
    int with_mask = 0, with_flicker = 0;
    r->flicker_all = r->flicker_caustic = 0.0;
    for (int e = 0; ok && e < b->nerror; e++) {
        int t = -1, t1 = -1;
        ok = bench_truth(b, &b->variants[c], r->truth, b->error_frames[e], &t, err) &&
             bench_add_error(&b->truths[t], &images[e], r, e, &with_mask, err);
        if (ok && b->cli->truth) {
            /* one frame's truth from elsewhere: the truth's change to the next
             * frame is unknown, so no flicker (truth_from_file says so) */
            r->flicker_all = r->flicker_caustic = -1.0;
            continue;
        }
        ok = ok && bench_truth(b, &b->variants[c], r->truth, b->error_frames[e] + 1, &t1, err);
        double fa = 0.0, fc = 0.0;
        const struct truth *t0 = ok ? &b->truths[t] : NULL;
        ok = ok && image_flicker_compute(&images[e], &next[e], &t0->image, &b->truths[t1].image, NULL, &fa, err) &&
             (!t0->has_mask || image_flicker_compute(&images[e], &next[e], &t0->image, &b->truths[t1].image,
                                                     &t0->mask, &fc, err));
        if (ok) {
            r->flicker_all += (fa - r->flicker_all) / (e + 1);
            if (t0->has_mask)
                r->flicker_caustic += (fc - r->flicker_caustic) / ++with_flicker;
        }
    }
    r->has_caustic = with_mask > 0;
    for (int e = 0; e < b->nerror; e++) {
        image_destroy(&images[e]);
        image_destroy(&next[e]);
    }
    if (ok) {
        printf("%-40s %9.3f ms (x%.2f of the first)  rel_rmse %.4f  caustic rel_rmse %s%.4f  flicker %.4f\n", r->label,
               r->frame_ms, b->results[0].frame_ms > 0 ? r->frame_ms / b->results[0].frame_ms : 0.0, r->all.rel_rmse,
               r->has_caustic ? "" : "(none) ", r->has_caustic ? r->caustic.rel_rmse : 0.0,
               r->has_caustic ? r->flicker_caustic : r->flicker_all);
        if (r->report[0])
            printf("    %s\n", r->report);
        fflush(stdout);
    }
    return ok;
}

/* The reference's own curve, for each distinct scene (its scene
 * parameters): 1/8, 1/4, 1/2 and all of the truth's iterations / 16,
 * over the same error frames. */
static bool bench_reference_curve(struct bench *b, struct error *err)
{
    bool ok = true;
    for (int t = 0; ok && t < b->nsets && t < MAX_CURVES; t++) {
        const struct truth_set *ts = &b->sets[t];
        /* (at least 1 iteration: --ref-spp under 8 would start the doubling at 0) */
        for (int level = b->level_max >= 8 ? b->level_max / 8 : 1; ok && level <= b->level_max; level *= 2) {
            struct result *r = &b->curve[b->ncurve++];
            memset(r, 0, sizeof *r);
            r->truth = t;
            r->technique = -1;
            r->iterations = level;
            r->flicker_all = r->flicker_caustic = -1.0; /* not measured */
            snprintf(r->label, sizeof r->label, "reference %d it%s%s", level, ts->label[0] ? " " : "", ts->label);
            for (int k = 0; k < b->ncolumns; k++)
                snprintf(r->values[k], sizeof r->values[k], "%s", b->technique_sweep ? "" : ts->values[k]);
            if (b->technique_sweep) {
                snprintf(r->values[0], sizeof r->values[0], "reference");
                snprintf(r->values[1], sizeof r->values[1], "%d it", level);
            }
            int with_mask = 0;
            for (int e = 0; ok && e < b->nerror; e++) {
                int ti = -1;
                for (int i = 0; i < b->ntruths; i++)
                    if (b->truths[i].set == t && b->truths[i].frame == b->error_frames[e])
                        ti = i;
                struct ref_options ro = b->truth_options;
                ro.iterations = level;
                ro.progress = false;
                ro.seed = b->truth_options.seed + 1000u + (uint64_t)level; /* independent of the truth's samples */
                struct session_options so = {.script = b->script, .params = ts->params, .width = ts->width,
                                             .height = ts->height, .past_last_frame = true};
                struct session *s = NULL;
                struct image img = {0};
                struct ref_stats st = {0};
                ok = session_open(b->app, &so, &s, err);
                if (ok) {
                    ok = session_reference(s, b->error_frames[e], &ro, &img, &st, err);
                    session_close(s);
                }
                r->frame_ms += (st.seconds * 1000.0 - r->frame_ms) / (e + 1);
                ok = ok && bench_add_error(&b->truths[ti], &img, r, e, &with_mask, err);
                image_destroy(&img);
            }
            r->has_caustic = with_mask > 0;
            if (ok)
                printf("%-40s %9.1f ms  rel_rmse %.4f  caustic rel_rmse %.4f\n", r->label, r->frame_ms,
                       r->all.rel_rmse, r->caustic.rel_rmse);
        }
    }
    return ok;
}

/* How much of a measured error may be the truth's own: a curve run of k
 * iterations against the truth of K has error e_k^2 ~ n_k^2 + n_K^2 with
 * n_K = n_k sqrt(k / K) (noise falls as 1/sqrt(iterations)), so n_K ~
 * e_k sqrt(k / (K + k)); the least over the curve bounds it (the curve's
 * bias counts against it too: an upper bound). */
static void bench_truth_error(struct bench *b)
{
    for (int t = 0; t < MAX_CURVES; t++)
        b->truth_error[t] = -1.0;
    double K = b->truth_options.iterations;
    for (int c = 0; c < b->ncurve; c++) {
        const struct result *r = &b->curve[c];
        double e = ranked_error(r, b->caustic), k = r->iterations;
        if (r->truth < 0 || r->truth >= MAX_CURVES || !(e > 0) || !(k > 0) || !isfinite(e))
            continue;
        double bound = e * sqrt(k / (K + k));
        if (b->truth_error[r->truth] < 0 || bound < b->truth_error[r->truth])
            b->truth_error[r->truth] = bound;
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
static bool bench_write_tables(struct bench *b, FILE **md_out, struct error *err)
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
                caustic_text, ranked_error(r, b->caustic), flicker_text, c < b->nvariants ? renderer : "CPU reference",
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
static bool bench_write_frontier(struct bench *b, FILE *md, struct error *err)
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
static bool bench_write_plot(struct bench *b, bool flicker, struct error *err)
{
    static struct plot_point points[MAX_COMBOS + CURVE_LEVELS * MAX_CURVES];
    int np = 0;
    int techniques = b->technique_sweep ? b->list->count : 1;
    for (int c = 0; c < b->nvariants + b->ncurve; c++) {
        const struct result *r = bench_row(b, c);
        points[np].x = r->frame_ms;
        points[np].y = flicker ? ranked_flicker(r, b->caustic) : ranked_error(r, b->caustic);
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

int cmd_bench(struct app *app, struct cli *cli)
{
    if (cli->npositional != 1) {
        fprintf(stderr, "caustica: bench needs one scene script\n");
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    struct bench b = {.app = app, .cli = cli, .script = cli->positional[0], .dir = cli->output ? cli->output : "bench"};
    struct error err;
    int code = EXIT_SCENE_ERROR;
    bool ok = bench_plan(&b, &code, &err);
    if (ok)
        code = EXIT_SCENE_ERROR;
    double started = log_now();
    for (int c = 0; ok && c < b.nvariants; c++) {
        /* where a long sweep stands, on stderr (the table lines are stdout's) */
        if (!log_quiet() && b.nvariants > 1) {
            double spent = log_now() - started;
            if (c > 0)
                fprintf(stderr, "caustica: bench: variant %d/%d (%.0f s so far, about %.0f s left)\n", c + 1,
                        b.nvariants, spent, spent / c * (b.nvariants - c));
            else
                fprintf(stderr, "caustica: bench: variant 1/%d\n", b.nvariants);
        }
        ok = bench_variant(&b, c, &err);
    }
    ok = ok && bench_reference_curve(&b, &err);
    /* the error ranked: the caustic region's where there is one (or the
     * scene's techniques table says "image") */
    b.caustic = b.nsets > 0 && b.results[0].has_caustic &&
                !(b.technique_sweep && b.list->metric == TECHNIQUE_METRIC_IMAGE);
    if (ok)
        bench_truth_error(&b); /* in the ranked metric */
    FILE *md = NULL;
    ok = ok && bench_write_tables(&b, &md, &err);
    b.on_front = ok ? calloc((size_t)b.nvariants + 1, sizeof *b.on_front) : NULL;
    if (ok && !b.on_front)
        ok = error_set(&err, "out of memory");
    if (ok && b.technique_sweep)
        ok = bench_write_frontier(&b, md, &err);
    if (md)
        fclose(md);
    ok = ok && bench_write_plot(&b, false, &err) && bench_write_plot(&b, true, &err);
    if (ok)
        printf("wrote %s/results.csv, %s/results.md%s, %s/plot.svg and %s/flicker.svg\n", b.dir, b.dir,
               b.technique_sweep ? ", frontier.md" : "", b.dir, b.dir);
    bench_release(&b);
    if (!ok) {
        cli_print_error(&err);
        return code;
    }
    return 0;
}
