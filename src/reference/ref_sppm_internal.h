/* What the stages of the reference estimator share (ref_sppm.c runs them:
 * ref_eye_paths.c, ref_photon_trace.c, ref_volume_gather.c,
 * ref_surface_gather.c): their limits, the per-pixel state, the job every
 * thread works on, the clock, and the functions one stage calls in
 * another. Private to src/reference. */
#ifndef CAUSTICA_REF_SPPM_INTERNAL_H
#define CAUSTICA_REF_SPPM_INTERNAL_H

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/cpus.h"
#include "core/log.h"
#include "core/vecmath.h"
#include "core/optics.h"
#include "reference/ref_emit.h"
#include "reference/ref_media.h"
#include "reference/ref_photon_map.h"
#include "reference/ref_rng.h"
#include "reference/ref_microfacet.h"
#include "reference/ref_scene.h"
#include "reference/reference.h"

/* Specular bounces a path may take: every loop has a cap. Light trapped
 * by total internal reflection in a glass wall runs along it (a light
 * guide, a whispering gallery) for hundreds of bounces before it leaves:
 * at a cap of 32, GlassVaseFlowers' vase wall cut 2% of its eye paths and
 * blacked out a band of its pixels (issue 50); at 1,024, 0.05% (paths
 * that orbit the vase's bulb by thousands of bounces), for 1.4 times the
 * render's time (5.8 -> 7.9 s at 192 px, 16 iterations). Photons keep a
 * cap of 32: followed to 1,024 too, the render took 4.5 times as long
 * (35 s) and the vase's image changed by 0.5% (relative RMS). A path cut
 * at its cap is counted (budget.paths_cut) and the render says so. */
#define MAX_DEPTH 1024
#define MAX_PHOTON_DEPTH 32
/* Reflected branches a photon may start (ref_photon_trace.c): past them
 * it chooses one way by Fresnel's odds as before. A branch is taken with
 * probability F, so a photon starts about sum F of them: the cap only
 * bounds light trapped in a glass wall. */
#define PHOTON_BRANCHES 8
#define MAX_MEDIA 8
#define SPPM_ALPHA (2.0 / 3.0)
#define PHOTON_CHUNKS 64
#define RADIUS_PIXELS 2.0  /* initial gather radius, in pixel footprints */
#define STRUCTURE_SUMS 3  /* the structure test's sums (structure_sums) */
#define GLOSSY_SAMPLES 4  /* directions drawn from a glTF surface's glossy lobes per eye path */
#define MAX_SEGMENTS 4     /* camera path segments through the medium kept for the volume gather */
#define VOLUME_SAMPLES 8   /* stratified points per segment where volume photons are gathered */   /* fixed, so the result does not depend on the thread count */

/* The media a path is inside: a small stack of object indices. */
struct media {
    int objects[MAX_MEDIA];
    int count;
};

/* The reflected way a photon also takes where it meets a smooth
 * dielectric interface that it can refract through (sppm_specular_step
 * with a branch): taken is false where there is none this time. */
struct specular_branch {
    bool taken;
    dvec3 dir, origin, beta;
    struct media media;
};

struct visible_point {
    bool valid;
    dvec3 position, normal; /* normal faces the eye */
    dvec3 weight;           /* path throughput x albedo / pi */
};

struct pixel {
    dvec3 direct;           /* sum over iterations of what the eye path gathered */
    int samples;            /* eye paths traced (an iteration cut short by the budget leaves some pixels one ahead) */
    /* an eye path that draws no random number is the same every iteration:
     * its radiance, traced once (trace_eye) */
    bool eye_fixed;
    dvec3 eye_once;
    dvec3 volume;           /* sum of the volume caustic estimates */
    double volume_samples;  /* the gathers' weights: their passes' fractions */
    /* the noise estimate: sums of the even and the odd iterations' own
     * estimates (eye path + volume + this iteration's photons / pi R^2) */
    dvec3 direct_seen, volume_seen, half[2];
    dvec3 half_photons[2];  /* the photon estimates, each weighted by its pass's fraction (a cut-short pass counts less) */
    dvec3 tau;              /* SPPM flux */
    double radius, n;
    /* the structure test, iteration by iteration (structure_restart): the
     * least radius (0: not tested), its sums (structure_sums) and their
     * variances since the radius was last halved, and the photon passes
     * before that (tau counts those after) */
    double radius_floor, structure[STRUCTURE_SUMS], structure_var[STRUCTURE_SUMS], passes_before;
    double passes_missed;   /* passes since then whose gather the budget stopped before this pixel's row */
    dvec3 phi_inner;        /* this iteration's photons within half the radius, and their count */
    long m_inner;
    double r1;              /* independent passes: the first pass's radius (the pilot's), 0: none found */
    dvec3 pppm;             /* independent passes: the sum of their photon estimates */
    struct visible_point vp;
    dvec3 phi;              /* this iteration's photons */
    long m;
};

/* A pixel's eye-path segments through the medium this iteration, for the
 * volume gather: an array of their own, made only for a scene with a
 * medium (inside struct pixel they were 40% of its 880 bytes, which every
 * render at 512^2 zeroed and faulted in for nothing). */
struct pixel_segments {
    struct {
        dvec3 origin, dir, beta;
        double t0, t1;
    } segments[MAX_SEGMENTS];
    int count;
};

/* What the threads of one render share: the clock they all stop by. */
struct budget {
    double deadline;        /* log_now() time; 0: none */
    double photon_deadline; /* when photons stop: the deadline less what the gathers after them need */
    atomic_int cut;         /* set when an eye or gather pass stopped early for the deadline */
    atomic_int photons_cut; /* set when the photon pass did */
    atomic_long paths_cut[3]; /* eye paths, glossy rays, photons cut at MAX_DEPTH bounces (their light is lost) */
    long chunk_reached[PHOTON_CHUNKS]; /* where each chunk's photons stopped (its end, unless cut) */
    double start, last_print;
    bool tty;
    bool log_lines;         /* progress asked for, off a terminal: one line an iteration */
    int iteration;
    long long emitted_before;
    int line_length;        /* of the progress line on the terminal, to blank what a shorter one leaves */
    double last_line;       /* when the last whole progress line went to the log */
    bool map_warned;        /* the photon map's out-of-memory warning was given */
    double gather_share;    /* of a photon stage's time, what the surface gather after the tracing took, last time */
    bool gather_seen;       /* an iteration's gather has set gather_share (before it, the pilot's rates predict it) */
    double seconds_per_traced, seconds_per_mapped, seconds_per_gathered; /* the pilot's rates: a photon traced, put
                                                                          * in the map, taken by a visible point */
    /* the first k-nearest-neighbour pass: its seconds, the pixels it
     * served and the photons they counted (sppm_budget_gather_photons) */
    double knn_seconds;
    atomic_llong knn_pixels, knn_counted;
};

struct job {
    const struct ref_scene *rs;
    const struct ref_options *o;
    double gather_photons; /* photons a first radius is chosen to hold (GATHER_PHOTONS, or fewer under a budget) */
    struct pixel *pixels;
    struct pixel_segments *segments; /* per pixel; NULL without a medium */
    int iteration;
    int thread, threads;
    const struct media *camera_media;
    const struct ref_medium *medium;
    double pixel_angle; /* radians a pixel spans at the image centre */
    double pixel_size;  /* an orthographic camera's pixel, in scene units */
    /* volume photons */
    struct volume_photons *volume_chunks;
    struct volume_grid *volume_grid;
    int volume_rows;    /* which rows a volume gather does: VOLUME_ROWS_* */
    int volume_samples; /* stratified points per segment (VOLUME_SAMPLES but in a budget's first gather) */
    atomic_int volume_rows_left; /* rows a first gather under a budget could not reach */
    struct budget *budget;
    /* photons: light l emits photons_of[l] of them, photon k of the
     * iteration belongs to the light whose range [first_of[l], first_of[l] +
     * photons_of[l]) holds it */
    struct ref_emitter *emitters;
    struct aim_log *aims;     /* PHOTON_CHUNKS of them */
    double pass_fraction;     /* of the photons of the pass just traced (1 unless the budget cut it) */
    double gather_until;      /* when an iteration's surface gather stops (0: no budget) */
    bool independent;         /* passes that share no state (ref_options.shard_count > 0) */
    bool pilot_done;          /* the pilot ran before the passes (independent passes) */
    double emit_shift[SCENE_MAX_GPU_LIGHTS][3]; /* each light's random rotation of its emission sequence */
    long photons_of[SCENE_MAX_GPU_LIGHTS], first_of[SCENE_MAX_GPU_LIGHTS];
    long photons_total;
    struct ref_photon_map *photon_map; /* the iterations' map, its arrays kept between them */
    const double *light_scale;         /* the gather's scale of each light's photons */
    bool gather_counts_only;           /* the pilot's gather: photons per pixel into m, no flux */
    struct radius_search *radius_search; /* the pilot's radius passes: per pixel */
    bool radius_search_knn;              /* their kind: k nearest neighbours, or the structure test */
    bool radius_search_measured;         /* the first knn pass: its pixels and counts go to the budget */
    double radius_search_until;          /* their deadline (0: none), checked every row */
    struct ref_surface_photons *chunks;
    long long caustic_photons[PHOTON_CHUNKS];
    double caustic_power[PHOTON_CHUNKS][3]; /* flux the photons brought to diffuse surfaces */
};

/* Volume caustic photons: where light that went through specular
 * surfaces scattered in the medium (flux already weighted by sigma_s). */
struct volume_photon {
    float position[3], dir[3], flux[3];
    int light;
};

struct volume_photons {
    struct volume_photon *items;
    size_t count, capacity;
};

/* The volume photons sorted by cell (cells of the gather's radius): a
 * dense grid over their bounds where it fits (dense: the cells of a row
 * along x lie together, so a gather reads 9 runs of 3 cells), else a hash
 * of the cells (size slots, 27 read a gather). */
struct volume_grid {
    double radius, cell;
    bool dense;
    dvec3 origin;       /* dense: the corner of cell (0, 0, 0) */
    long nx, ny, nz;    /* dense: cells along each axis */
    size_t size;        /* cells (dense) or slots (hash) */
    size_t *start;      /* size + 1 offsets into items */
    struct volume_photon *items; /* sorted by cell */
};

enum { VOLUME_ROWS_ALL, VOLUME_ROWS_PROBE, VOLUME_ROWS_REST };
#define VOLUME_PROBE_STRIDE 32
#define VOLUME_PROBE_SAMPLES 2

/* What each chunk's photons were aimed at, and whether they reached a
 * visible point: (light << 40) | (entry << 1) | useful, for the adaptive
 * emission (ref_emitter_adapt). */
struct aim_log {
    uint64_t *items;
    size_t count, capacity;
};

/* The pilot's radius passes: each pass, every pixel still searching
 * (search[i].floor > 0) reads the map (the pilot's last round, aimed as
 * the estimate will be) at its radius and moves it. */
struct radius_search {
    double floor, ceiling; /* the radius stays within these; floor 0: settled */
};

/* The first radius (docs/REFERENCE.md, "Against POV-Ray, per pixel at
 * 512^2": chosen there on the ball lens at its focus and beyond it, flat
 * water and the TIR cube, at 2, 4 and 8 s, three seeds each). 400 photons
 * a gather since the photons are split at interfaces and weighted by a
 * kernel (issue 53): 200 left the floor 2.5 radii below the ball at 1.41%
 * in 8 s, 800 buys less than one iteration in 2 s at 512^2 and costs the
 * focus and the cube their later iterations; before the split 400 had
 * blurred the focus (its photons' Fresnel coins made them noisy enough
 * that the structure tests could not see it). 40 left flat water's
 * per-pixel noise at 6.7% in 2 s. A radius up to 32 pixel footprints lets
 * an even, sparsely lit floor gather as widely as POV-Ray's photon counts
 * do (up to 8 left flat water at 3.3%, 64 let a dim pixel beside a bright
 * band reach across it before the tests below could stop it). */
#define PILOT_RADIUS 2.0     /* the pilot counts photons within this many first radii */
#define GATHER_PHOTONS 400.0 /* photons a first radius is chosen to hold, about, per iteration */
/* Under a time budget where the first gather of that many would take
 * more than FIRST_GATHER_SHARE of the rest, fewer, down to
 * GATHER_PHOTONS_MIN (ref_budget.c's sppm_budget_gather_photons) */
#define GATHER_PHOTONS_MIN 100.0
#define FIRST_GATHER_SHARE 0.3
#define RADIUS_MIN 0.0625    /* the first radius stays within these multiples of two pixel footprints */
#define RADIUS_MAX 16.0

/* the structure test's limits (ref_surface_gather.c), which the pilot sets up */
#define STRUCTURE_HALVINGS 6
#define KNN_PASSES 4

#define PILOT_ROUNDS 4
#define PILOT_USEFUL 0.2

/* ref_eye_paths.c: media along a path, what a surface is, the eye threads */
dvec3 sppm_medium_sigma(const struct ref_scene *rs, const struct media *m);
bool sppm_scene_medium_here(const struct ref_scene *rs, const struct media *m);
dvec3 sppm_attenuate(dvec3 beta, dvec3 sigma, double t);
void sppm_media_at(const struct ref_scene *rs, dvec3 p, struct media *m);
/* one step through a specular surface (Fresnel's choice, the media);
 * false when the path went on as it was, through a thin-walled pane; with
 * a branch (photons), a smooth dielectric interface is not a choice: the
 * path refracts with 1 - F of its flux and the branch, taken with
 * probability F, reflects with all of it */
bool sppm_specular_step(const struct ref_scene *rs, const struct ref_hit *h, struct media *media, dvec3 *dir,
                        dvec3 *origin, dvec3 *beta, struct ref_rng *rng, struct specular_branch *branch);
bool sppm_hit_is_diffuse(const struct ref_scene *rs, const struct ref_hit *h, struct ref_rng *rng);
void *sppm_camera_thread(void *arg);

/* ref_volume_gather.c: the volume photons and their gather */
void sppm_volume_push(struct volume_photons *v, dvec3 p, dvec3 d, dvec3 flux, int light);
void sppm_volume_grid_build(struct volume_grid *g, const struct volume_photons *chunks, int nchunks, double radius);
void sppm_volume_grid_release(struct volume_grid *g);
/* In-scattered radiance of the grid's photons at x towards -view (the
 * volume radiance estimate within the grid's radius, Henyey-Greenstein
 * phase with asymmetry phase_g). */
dvec3 sppm_volume_estimate(const struct volume_grid *g, double phase_g, dvec3 x, dvec3 view);
void *sppm_volume_thread(void *arg);

/* ref_photon_trace.c: the photon threads */
void sppm_chunk_range(const struct job *j, int c, long *begin, long *end);
void *sppm_photon_thread(void *arg);
void sppm_run_threads(struct job *base, int threads, void *(*fn)(void *));

/* ref_surface_gather.c: the gathers, the adaptive emission and the radii */
double sppm_adapt_emission(struct aim_log *aims, struct ref_emitter *emitters, int light_count);
void sppm_gather_surface_photons(struct job *job, int threads, const double *light_scale, bool counts_only);
bool sppm_structure_restart(struct pixel *px, double passes_now);
void sppm_radius_search(struct job *job, int threads, struct radius_search *search, bool knn, int passes,
                          double until);

/* ref_sppm.c: the clock and its progress lines */
void sppm_progress_line(struct budget *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
bool sppm_budget_photons_spent(struct budget *b);
bool sppm_budget_spent(struct budget *b);
/* ref_budget.c: photons a first radius holds under the budget (GATHER_PHOTONS
 * or fewer, the radii shrunk to match), from the first k-nearest-neighbour
 * pass's rate */
double sppm_budget_gather_photons(const struct budget *budget, struct pixel *pixels, size_t npix);
/* the pixels that gather: those with a visible point and a radius */
size_t sppm_gathering_points(const struct pixel *pixels, size_t npix);
/* ref_budget.c: when a photon stage that must end by `until` (0: no
 * budget) stops tracing to leave its surface gather the time the last one
 * took; that share, measured. */
void sppm_budget_start(struct budget *budget, const struct ref_options *o, double start);
double sppm_photon_deadline(const struct budget *b, double until);
void sppm_gather_share_measured(struct budget *b, double trace_seconds, double gather_seconds);

#endif
