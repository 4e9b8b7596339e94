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
 * 1 s (frontier.md), and keeps its CSV in the cache for `caustica choose`.
 * This file plans and times; the variants are bench_variants.c's, the
 * truths and errors bench_truth.c's, the tables and plot bench_report.c's
 * (bench_internal.h). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app/bench_internal.h"
#include "core/fileio.h"
#include "core/hash.h"
#include "core/log.h"

#define MAX_VALUES 16
#define MAX_COMBOS 256
#define MAX_PASSES 32
#define MAX_TRUTHS 64
#define MAX_ERROR_FRAMES 16

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
    k = bench_hash_params(k, &cli->params);
    long long ints[8] = {cli->width, cli->height, cli->frame, bench_timing_frames(cli),
                         cli->error_frames, cli->ref_photons, cli->ref_spp, cli->nsweeps};
    k = hash_fnv1a(k, ints, sizeof ints);
    for (int i = 0; i < cli->nsweeps; i++)
        k = hash_fnv1a(k, cli->sweeps[i], strlen(cli->sweeps[i]) + 1);
    if (cli->antialias)
        k = hash_fnv1a(k, "antialias", 9);
    /* truths of exact spheres since issue 53 (those before traced their triangles) */
    k = hash_fnv1a(k, cli->tessellated ? "tessellated" : "spheres", cli->tessellated ? 11 : 7);
    if (cli->truth_spp > 0) /* hashed only when given: the caches made before it keep their names */
        k = hash_fnv1a(k, &cli->truth_spp, sizeof cli->truth_spp);
    snprintf(out, size, "%s/cache/sweep_%016llx.csv", dir, (unsigned long long)k);
    return true;
}

static bool apply_overrides(struct session *s, const struct variant *v, struct error *err)
{
    for (int k = 0; k < v->override_count; k++)
        if (!session_set_pass_param(s, v->override_keys[k], v->override_values[k], err))
            return error_prefix(err, "%s=%s", v->override_keys[k], v->override_values[k]);
    return true;
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

static void bench_release(struct bench *b)
{
    for (int i = 0; i < b->ntruths; i++)
        bench_truth_release(&b->truths[i]);
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
        if (!bench_parse_sweep(cli->sweeps[i], &b->sweeps[i], err))
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
        ok = bench_technique_variants(b->list, &cli->params, b->variants, &b->nvariants, err);
    else if (ok) {
        b->nvariants = b->combos;
        ok = bench_sweep_variants(b->sweeps, cli->nsweeps, &cli->params, b->variants, b->combos, err);
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
    b->truth_options.tessellated = cli->tessellated;
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
