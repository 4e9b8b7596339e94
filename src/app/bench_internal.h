/* What the files of `caustica bench` share (cmd_bench.c runs it; its
 * variants are bench_variants.c's, its ground truths bench_truth.c's, its
 * tables and plots bench_report.c's): the limits, a variant, a result, a
 * truth, the bench itself. Private to src/app. */
#ifndef CAUSTICA_BENCH_INTERNAL_H
#define CAUSTICA_BENCH_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "app/app.h"
#include "app/bench.h"
#include "app/cli.h"
#include "app/techniques.h"
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
    /* issue 32: the error of the change from each error frame to the next
     * (image_flicker_compute), means over the error frames, whole and in the
     * caustic region; < 0: not measured (a reference row) */
    double flicker_all, flicker_caustic;
    char report[300]; /* the passes' lines about the last frame (beam counts, fill rate) */
    int truth;        /* the ground truth set (scene parameters) it was measured against */
    int technique;
    int iterations;   /* a reference curve row's iterations (0: a GPU variant) */
};

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

/* bench_variants.c: a --sweep "key=v1,v2" into `s`; the variants of a
 * technique sweep (every technique of `list` at each of its settings) or
 * of the sweeps' combinations, on top of the session's `base` parameters;
 * a hash of scene parameters (what a truth and the sweep cache key hold). */
bool bench_parse_sweep(const char *text, struct sweep *s, struct error *err);
bool bench_technique_variants(const struct technique_list *list, const struct lua_params *base, struct variant *out,
                              int *count, struct error *err);
bool bench_sweep_variants(const struct sweep *sweeps, int nsweeps, const struct lua_params *base, struct variant *out,
                          int combos, struct error *err);
uint64_t bench_hash_params(uint64_t k, const struct lua_params *params);

/* bench_truth.c: the truth set a variant is measured against (its scene
 * parameters), the truth of one frame of a set (cached, or made), a
 * variant's error on one error frame against it, the reference's own curve
 * and the truth's own error bounded from it. */
bool bench_truth_set(struct bench *b, const struct variant *v, int *out, struct error *err);
bool bench_truth(struct bench *b, const struct variant *v, int set, int frame, int *out, struct error *err);
bool bench_add_error(const struct truth *t, const struct image *image, struct result *r, int e, int *with_mask,
                     struct error *err);
bool bench_reference_curve(struct bench *b, struct error *err);
void bench_truth_error(struct bench *b);
void bench_truth_release(struct truth *t);

/* bench_report.c: the error a result is ranked by (the caustic region's
 * where --caustic); results.csv and results.md; the frontier; the plot. */
double bench_ranked_error(const struct result *r, bool caustic);
bool bench_write_tables(struct bench *b, FILE **md_out, struct error *err);
bool bench_write_frontier(struct bench *b, FILE *md, struct error *err);
bool bench_write_plot(struct bench *b, bool flicker, struct error *err);

#endif
