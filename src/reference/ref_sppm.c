/* The reference estimator: eye paths traced exactly through specular
 * chains (Fresnel, Snell, total internal reflection, Beer-Lambert), direct
 * light by shadow rays at the first diffuse vertex, and caustics
 * (light -> specular+ -> diffuse) by stochastic progressive photon mapping
 * (Hachisuka & Jensen, SIGGRAPH Asia 2009): each iteration traces one eye
 * path per pixel to a visible point and a batch of photons, and shrinks
 * every pixel's gather radius by R' = R sqrt((N + a M) / (N + M)) with
 * a = 2/3, so bias and variance both go to zero as iterations grow
 * (docs/REFERENCE.md). The transport is the one caustica's scenes define:
 * lights are the emitters, the environment is seen directly and through
 * specular chains, diffuse surfaces get direct light, caustics and the
 * scene's ambient term, and there is no diffuse interreflection.
 * This file runs the stages (the pilot, each iteration, the estimates);
 * the stages are ref_eye_paths.c, ref_photon_trace.c, ref_volume_gather.c
 * and ref_surface_gather.c, the clock and progress ref_budget.c
 * (ref_sppm_internal.h). */
#define _POSIX_C_SOURCE 200809L
#include "core/huge_pages.h"
#include "reference/ref_sppm_internal.h"


void ref_options_default(struct ref_options *o)
{
    memset(o, 0, sizeof *o);
    o->width = o->height = 256;
    o->photons = 200000;
    o->iterations = 16;
    o->seed = 1;
}

/* The pilot: before the first photon pass, rounds of a quarter of its
 * photons each are traced only to learn where photons are useful and how
 * dense they fall (their light is thrown away), so that no iteration of
 * the estimate is spent on the first, unadapted pdf: where few photons
 * reach what the camera sees (a pool seen close up), that iteration's
 * noise would dominate the average. Rounds go on, each aimed by the last,
 * until a fifth of a round's photons are useful (at most PILOT_ROUNDS). */
static long share_photons(struct job *job, const struct ref_scene *rs, const struct ref_emitter *emitters, long photons);
static long photons_traced(const struct job *j, const struct budget *b, int l);

static void pilot_photons(struct job *job, int threads, struct budget *budget, struct volume_photons *volume_chunks,
                          long photons, struct pixel *pixels, size_t npix)
{
    int light_count = job->rs->light_count;
    long pilot = photons / 4 > 1 ? photons / 4 : 1;
    share_photons(job, job->rs, job->emitters, pilot);
    /* The pilot counts photons within PILOT_RADIUS times each pixel's
     * first radius (the last round's, the best aimed). */
    for (size_t i = 0; i < npix; i++)
        pixels[i].radius *= PILOT_RADIUS;
    /* the pilot only aims: under a budget it may take a quarter of what is
     * left, so that the estimate's own photons get the rest */
    double pilot_deadline = budget->deadline;
    if (budget->deadline > 0)
        pilot_deadline = log_now() + 0.25 * fmax(budget->deadline - log_now(), 0.0);
    /* The counts that set the radii must come from photons aimed as the
     * estimate's will be: once the aim has settled (or the rounds are
     * used up), one more round counts on the final pdf and is not adapted
     * after. Counting on the round before the last adaptation undercounted
     * wherever that adaptation moved photons into view (flat water seen
     * close up: two photons where 40 were meant, and the radius pinned at
     * its largest). */
    bool settled = false;
    for (int round = 0; round <= PILOT_ROUNDS; round++) {
        for (size_t i = 0; i < npix; i++)
            pixels[i].m = 0;
        job->iteration = -1 - round;
        budget->photon_deadline = sppm_photon_deadline(budget, pilot_deadline);
        double trace_start = log_now();
        sppm_run_threads(job, threads, sppm_photon_thread);
        double gather_start = log_now();
        sppm_gather_surface_photons(job, threads, NULL, true);
        sppm_gather_share_measured(budget, gather_start - trace_start, log_now() - gather_start);
        long long traced = 0;
        for (int l = 0; l < job->rs->light_count; l++)
            traced += photons_traced(job, budget, l);
        if (traced > 0)
            budget->seconds_per_traced = (gather_start - trace_start) / (double)traced;
        for (int c = 0; c < PHOTON_CHUNKS; c++)
            volume_chunks[c].count = 0;
        bool pilot_spent = atomic_load(&budget->photons_cut) != 0;
        atomic_store(&budget->photons_cut, 0);
        if (settled || pilot_spent || sppm_budget_spent(budget))
            break; /* the aims this round logged feed the first iteration's adaptation */
        settled = sppm_adapt_emission(job->aims, job->emitters, light_count) >= PILOT_USEFUL || round + 1 == PILOT_ROUNDS;
    }
    /* A first radius for the photon density (Issue 15, "a gather that
     * adapts", a k-nearest-neighbour choice): where the last round's m
     * photons fell within R_c = PILOT_RADIUS x R0, an iteration's photons
     * (4 times as many) put about k = gather_photons within
     * R_c sqrt(k / 4m). Kept within [RADIUS_MIN R0,
     * RADIUS_MAX R0] (R0: two pixel footprints): a bright caustic is
     * gathered tightly, a dim or even region widely (little noise). Then
     * counting passes correct the guess (knn_step) and the structure test
     * halves it where it would blur (structure_step). SPPM accepts any
     * starting radius and shrinks it from there. Each radius's bounds go to
     * those passes (no passes if out of memory: the first guesses stand). */
    struct radius_search *search = job->o->initial_radius > 0.0 ? NULL : malloc(npix * sizeof *search);
    for (size_t i = 0; i < npix; i++) {
        struct pixel *px = &pixels[i];
        if (search)
            search[i] = (struct radius_search){0.0, 0.0};
        if (job->o->initial_radius > 0.0) {
            px->radius /= PILOT_RADIUS; /* the user's radius (--radius) stands */
            px->m = 0;
            continue;
        }
        if (px->radius <= 0.0)
            continue;
        double r0 = px->radius / PILOT_RADIUS, r = RADIUS_MAX * r0;
        if (px->m > 0)
            r = PILOT_RADIUS * r0 * sqrt(job->gather_photons / (4.0 * (double)px->m));
        px->radius = fmin(fmax(r, RADIUS_MIN * r0), RADIUS_MAX * r0);
        if (search)
            search[i] = (struct radius_search){RADIUS_MIN * r0, RADIUS_MAX * r0};
        px->radius_floor = RADIUS_MIN * r0;
        px->m = 0;
    }
    if (search) {
        /* the searches take at most what is left of the pilot's share */
        sppm_radius_search(job, threads, search, true, KNN_PASSES, pilot_deadline);
        job->gather_photons = sppm_budget_gather_photons(budget, pixels, npix);
        for (size_t i = 0; i < npix; i++)
            search[i].floor = pixels[i].radius_floor;
        sppm_radius_search(job, threads, search, false, STRUCTURE_HALVINGS, pilot_deadline);
    }
    free(search);
    share_photons(job, job->rs, job->emitters, photons);
    job->iteration = 0;
    memset(job->caustic_photons, 0, sizeof job->caustic_photons);
    memset(job->caustic_power, 0, sizeof job->caustic_power);
}

/* Shares the iteration's photons between the lights in proportion to the
 * power each sends towards its specular targets (every light that has
 * targets gets at least one). */
static long share_photons(struct job *job, const struct ref_scene *rs, const struct ref_emitter *emitters, long photons)
{
    double power = 0.0;
    for (int l = 0; l < rs->light_count; l++)
        power += emitters[l].power;
    long total = 0;
    for (int l = 0; l < rs->light_count; l++) {
        long n = 0;
        if (emitters[l].power > 0.0 && power > 0.0)
            n = (long)fmax(1.0, floor((double)photons * emitters[l].power / power + 0.5));
        job->first_of[l] = total;
        job->photons_of[l] = n;
        total += n;
    }
    job->photons_total = total;
    return total;
}

/* How many of light l's photons the finished chunks traced. */
static long photons_traced(const struct job *j, const struct budget *b, int l)
{
    long n = 0;
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        long begin, end;
        sppm_chunk_range(j, c, &begin, &end);
        end = b->chunk_reached[c];
        long lo = begin > j->first_of[l] ? begin : j->first_of[l];
        long hi = end < j->first_of[l] + j->photons_of[l] ? end : j->first_of[l] + j->photons_of[l];
        if (hi > lo)
            n += hi - lo;
    }
    return n;
}

/* Half the RMS difference of the even and odd iterations' means over the
 * RMS of the image, in grey (struct ref_stats.noise). */
static double noise_estimate(const struct pixel *pixels, size_t npix, int iterations, const double fraction[2])
{
    int n_even = (iterations + 1) / 2, n_odd = iterations / 2;
    if (n_odd == 0)
        return 0.0;
    double diff = 0.0, level = 0.0;
    for (size_t i = 0; i < npix; i++) {
        const struct pixel *px = &pixels[i];
        double a = (px->half[0].x + px->half[0].y + px->half[0].z) / (3.0 * n_even);
        double b = (px->half[1].x + px->half[1].y + px->half[1].z) / (3.0 * n_odd);
        if (fraction[0] > 0.0 && fraction[1] > 0.0) {
            a += (px->half_photons[0].x + px->half_photons[0].y + px->half_photons[0].z) / (3.0 * fraction[0]);
            b += (px->half_photons[1].x + px->half_photons[1].y + px->half_photons[1].z) / (3.0 * fraction[1]);
        }
        diff += (a - b) * (a - b);
        level += 0.25 * (a + b) * (a + b);
    }
    return level > 0.0 ? 0.5 * sqrt(diff / level) : 0.0;
}

/* What a render adds up over its iterations. */
struct sppm_totals {
    long long emitted, caustic_total;
    double caustic_power[3];
    double photon_passes;                  /* iterations whose photons were traced, a cut-short one counting as its fraction */
    double half_fraction[2];               /* the same, of the even and of the odd iterations (the noise estimate) */
    double gather_seconds, gather_photons; /* the last volume gather's cost */
    double volume_radius;
    double volume_radius_first; /* independent passes: pass 0's, the others' shrink from it */
    int independent_passes;     /* independent passes done (0: SPPM) */
    /* seconds spent in each stage so far (--report): the eye pass, the
     * pilot, photon tracing, the volume gather, the per-pixel update */
    double stage_eye, stage_pilot, stage_photons, stage_photon_gather, stage_gather, stage_update;
    double gather_kept;   /* the share of the first gather's volume photons kept for the budget (1: all) */
    int gather_samples;   /* the points per ray segment it used (0: VOLUME_SAMPLES) */
    int gather_rows_left; /* rows it could not reach at all */
};

/* Independent passes: pass p's gather area (surface: r^2; volume: r^3)
 * over pass 0's, prod_{i=1..p} (i + alpha) / (i + 1) (Knaus & Zwicker
 * 2011, eq. 15 with alpha = 2/3): fixed by p alone, so a pass needs no
 * other to know its radius. */
static double pass_shrink(int p)
{
    double f = 1.0;
    for (int i = 1; i <= p; i++)
        f *= (i + SPPM_ALPHA) / (i + 1.0);
    return f;
}

/* Keeps each volume photon with probability `keep` (a hash of its place
 * and the seed, so a run is repeatable for the photons it traced), its
 * flux divided by `keep`: an unbiased thinning (Russian roulette). */
static void volume_photons_thin(struct volume_photons *chunks, double keep, uint64_t seed)
{
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        size_t kept = 0;
        for (size_t k = 0; k < chunks[c].count; k++) {
            struct ref_rng rng = ref_rng_seed(seed, 7000003u + (uint64_t)c, (uint64_t)k);
            if (ref_rng_uniform(&rng) >= keep)
                continue;
            struct volume_photon vp = chunks[c].items[k];
            for (int q = 0; q < 3; q++)
                vp.flux[q] = (float)(vp.flux[q] / keep);
            chunks[c].items[kept++] = vp;
        }
        chunks[c].count = kept;
    }
}

/* One iteration's photons (Hachisuka & Jensen 2009): traced into the
 * visible points' grid (the first iteration after a pilot that aims the
 * lights), reduced in chunk order, the volume photons gathered, and each
 * visible point's radius and flux updated. */
/* This iteration's photon deadline under a budget (sppm_photon_deadline),
 * and on the first iteration the gather's share of the time, from the
 * pilot's rates. */
static void plan_photon_budget(struct job *job, const struct sppm_totals *t, size_t npix)
{
    struct budget *budget = job->budget;
    const struct pixel *pixels = job->pixels;
    /* With a medium, the volume gather after the photons must fit in the
     * budget too: reserve what the last one cost per photon for this
     * iteration's photons (the first iteration, with nothing to go by,
     * gives photons half of what is left). */
    /* the work after the photons (the per-pixel update, the estimates, the
     * file) gets 3% of the budget, so the whole stays inside it */
    budget->photon_deadline = budget->deadline > 0 ? budget->deadline - 0.03 * job->o->time_budget : 0.0;
    atomic_store(&budget->photons_cut, 0);
    if (budget->deadline > 0 && job->medium->present) {
        double now = log_now(), left = budget->deadline - now;
        double reserve = t->gather_photons > 0 ? t->gather_seconds * (double)job->photons_total / t->gather_photons
                                               : 0.5 * left;
        budget->photon_deadline = fmin(budget->photon_deadline, now + fmax(left - reserve, 0.1 * left));
    }
    if (!budget->gather_seen && budget->seconds_per_traced > 0.0 && budget->seconds_per_gathered > 0.0) {
        /* The first iteration's gather, from the pilot's rates: every
         * photon goes into the map, and each visible point takes about
         * gather_photons at twice the cost of the pilot's counting gather
         * (the flux and the structure sums). The pilot's own gathers, at
         * its small counting radius, cost far less than this one, and
         * photons traced by their share overran a 1 s budget by a third at
         * 512^2. */
        double gather = budget->seconds_per_mapped * (double)job->photons_total +
                        2.0 * budget->seconds_per_gathered * job->gather_photons *
                            (double)sppm_gathering_points(pixels, npix);
        double trace = budget->seconds_per_traced * (double)job->photons_total;
        budget->gather_share = fmin(gather / (gather + trace), 0.9);
    }
    budget->photon_deadline = sppm_photon_deadline(budget, budget->photon_deadline);
}

/* With a medium: this iteration's volume photons scaled as the surface
 * ones, then gathered along the eye rays (sppm_volume_thread); under a
 * budget the first gather is probed and thinned to fit. */
static void gather_volume_photons(struct job *job, int it, int threads, struct sppm_totals *t, const double *scale,
                                  long long traced)
{
    struct budget *budget = job->budget;
    struct volume_photons *volume_chunks = job->volume_chunks;
    for (int c = 0; c < PHOTON_CHUNKS; c++)
        for (size_t k = 0; k < volume_chunks[c].count; k++) {
            struct volume_photon *vp = &volume_chunks[c].items[k];
            for (int q = 0; q < 3; q++)
                vp->flux[q] = (float)(vp->flux[q] * scale[vp->light]);
        }
    /* Volume caustics: gather this iteration's volume photons with the
     * current radius, which shrinks as r^3 ~ i^(alpha - 1) (Knaus &
     * Zwicker 2011), so the average over iterations converges. */
    if (job->independent)
        t->volume_radius = t->volume_radius_first * cbrt(pass_shrink(job->iteration));
    struct volume_grid vgrid;
    sppm_volume_grid_build(&vgrid, volume_chunks, PHOTON_CHUNKS, t->volume_radius);
    job->volume_grid = &vgrid;
    double volume_start = log_now();
    if (it == 0 && budget->deadline > 0) {
        /* The first gather under a budget has no earlier one to go by:
         * every 16th row first, timed, and if the rest would pass the
         * deadline the volume photons are thinned for it (each kept
         * with probability f, its flux divided by f: the same
         * expectation, more noise), so the budget holds however the
         * machine is loaded. */
        job->volume_rows = VOLUME_ROWS_PROBE;
        job->volume_samples = VOLUME_PROBE_SAMPLES;
        sppm_run_threads(job, threads, sppm_volume_thread);
        job->volume_samples = VOLUME_SAMPLES;
        /* the rest at full samples: the cost is about linear in them */
        double rest = (log_now() - volume_start) * (VOLUME_PROBE_STRIDE - 1) * VOLUME_SAMPLES / VOLUME_PROBE_SAMPLES;
        double left = budget->deadline - log_now();
        if (rest > 0.9 * left) {
            /* fewer points along each ray first (the march is most of
             * the cost, photons or not), then fewer photons */
            double fit = fmax(0.9 * left / rest, 0.0);
            int samples = (int)floor(VOLUME_SAMPLES * fit);
            job->volume_samples = samples < 1 ? 1 : samples;
            t->gather_samples = job->volume_samples;
            double still = rest * job->volume_samples / VOLUME_SAMPLES;
            if (still > 0.9 * left) {
                double keep = fmax(0.9 * left / still, 1e-3);
                volume_photons_thin(volume_chunks, keep, job->o->seed);
                sppm_volume_grid_release(&vgrid);
                sppm_volume_grid_build(&vgrid, volume_chunks, PHOTON_CHUNKS, t->volume_radius);
                t->gather_kept = keep;
            }
        }
        job->volume_rows = VOLUME_ROWS_REST;
        atomic_store(&job->volume_rows_left, 0);
    }
    sppm_run_threads(job, threads, sppm_volume_thread);
    if (job->volume_rows == VOLUME_ROWS_REST)
        t->gather_rows_left = atomic_load(&job->volume_rows_left);
    job->volume_rows = VOLUME_ROWS_ALL;
    job->volume_samples = VOLUME_SAMPLES;
    t->gather_seconds = log_now() - volume_start;
    t->stage_gather += t->gather_seconds;
    t->gather_photons = (double)traced;
    sppm_volume_grid_release(&vgrid);
    for (int c = 0; c < PHOTON_CHUNKS; c++)
        volume_chunks[c].count = 0;
    if (!job->independent)
        t->volume_radius *= cbrt((it + 1 + SPPM_ALPHA) / (it + 2.0));
}

/* SPPM radius and flux update (Hachisuka & Jensen 2009, eq. 6-7), with
 * the progressive estimate of independent passes (pppm). */
static void update_pixels(struct job *job, int it, size_t npix, double pass_fraction, const struct sppm_totals *t)
{
    struct pixel *pixels = job->pixels;
    for (size_t i = 0; i < npix; i++) {
        struct pixel *px = &pixels[i];
        if (px->m > 0 && px->radius > 0 && pass_fraction > 0) {
            dvec3 e = dv_scale(px->phi, 1.0 / (pass_fraction * MATH_PI * px->radius * px->radius));
            px->half_photons[it % 2] = dv_add(px->half_photons[it % 2], dv_scale(e, pass_fraction));
            if (job->independent)
                px->pppm = dv_add(px->pppm, e);
        }
        /* (never on an iteration the budget cut short: the estimate would
         * start again from a fraction of an iteration's photons) */
        if (px->m > 0 && !job->independent && pass_fraction >= 1.0 &&
            sppm_structure_restart(px, t->photon_passes - pass_fraction)) {
            /* the estimate starts again with this iteration's photons
             * within the new radius */
            px->phi = px->phi_inner;
            px->m = px->m_inner;
        }
        if (px->m > 0 && !job->independent) {
            double n_new = px->n + SPPM_ALPHA * (double)px->m;
            double r_new = px->radius * sqrt(n_new / (px->n + (double)px->m));
            double shrink = (r_new * r_new) / (px->radius * px->radius);
            px->tau = dv_scale(dv_add(px->tau, px->phi), shrink);
            px->n = n_new;
            px->radius = r_new;
        }
        px->phi = px->phi_inner = dv(0, 0, 0);
        px->m = px->m_inner = 0;
    }
}

static void photon_iteration(struct job *job, int it, int threads, size_t npix, struct sppm_totals *t)
{
    const struct ref_scene *rs = job->rs;
    struct budget *budget = job->budget;
    struct pixel *pixels = job->pixels;
    struct volume_photons *volume_chunks = job->volume_chunks;
    double stage_start = log_now();
    if (it == 0 && !job->pilot_done)
        pilot_photons(job, threads, budget, volume_chunks, job->o->photons, pixels, npix);
    t->stage_pilot += log_now() - stage_start;
    stage_start = log_now();
    plan_photon_budget(job, t, npix);
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        long begin, end;
        sppm_chunk_range(job, c, &begin, &end);
        budget->chunk_reached[c] = begin; /* a chunk no thread reached traced nothing */
    }
    sppm_run_threads(job, threads, sppm_photon_thread);
    double gather_start = log_now();
    t->stage_photons += gather_start - stage_start;
    /* An iteration cut short by the budget traced a fraction f of its
     * photons: it counts as f of an iteration (the estimate divides the flux
     * by the photons traced, as a photon map does), rather than being scaled
     * up to a whole one, which would give its few photons a weight they
     * cannot carry. Each light's photons are scaled by f x (its photons) /
     * (those traced), 1 unless the cut left the lights unevenly traced;
     * without a budget every scale is 1 and f = 1. */
    long traced_of[SCENE_MAX_GPU_LIGHTS];
    long long traced = 0;
    for (int l = 0; l < rs->light_count; l++) {
        traced_of[l] = photons_traced(job, budget, l);
        traced += traced_of[l];
    }
    double pass_fraction = job->photons_total > 0 ? (double)traced / (double)job->photons_total : 0.0;
    double scale[SCENE_MAX_GPU_LIGHTS];
    for (int l = 0; l < rs->light_count; l++)
        scale[l] = traced_of[l] > 0 ? pass_fraction * (double)job->photons_of[l] / (double)traced_of[l] : 0.0;
    /* Each pixel sums its photons in the map's order: the same sums
     * whatever the thread count. */
    job->pass_fraction = pass_fraction;
    job->gather_until = budget->deadline > 0 ? budget->deadline - 0.03 * job->o->time_budget : 0.0;
    sppm_gather_surface_photons(job, threads, scale, false);
    sppm_gather_share_measured(budget, gather_start - stage_start, log_now() - gather_start);
    budget->gather_seen = true;
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        t->caustic_total += job->caustic_photons[c];
        /* (the power statistic is scaled for the whole pass, exact unless
         * several lights share a pass the budget cut short) */
        for (int k = 0; k < 3; k++)
            t->caustic_power[k] += job->caustic_power[c][k];
    }
    if (!job->independent) /* independent passes keep the pilot's aim: no pass may depend on another */
        sppm_adapt_emission(job->aims, job->emitters, rs->light_count);
    t->stage_photon_gather += log_now() - gather_start;
    t->emitted += traced;
    t->photon_passes += pass_fraction;
    t->half_fraction[it % 2] += pass_fraction;
    job->pass_fraction = pass_fraction;
    if (job->medium->present)
        gather_volume_photons(job, it, threads, t, scale, traced);
    /* SPPM radius and flux update (Hachisuka & Jensen 2009, eq. 6-7). */
    stage_start = log_now();
    update_pixels(job, it, npix, pass_fraction, t);
    t->stage_update += log_now() - stage_start;
}

/* After iteration `it`: the eye-path and volume estimates into the noise
 * halves, the report line and the progress line. */
static void iteration_report(const struct job *job, int it, size_t npix, double start, const struct sppm_totals *t)
{
    const struct ref_options *o = job->o;
    struct pixel *pixels = job->pixels;
    for (size_t i = 0; i < npix; i++) {
        struct pixel *px = &pixels[i];
        dvec3 d = dv_add(dv_sub(px->direct, px->direct_seen), dv_sub(px->volume, px->volume_seen));
        px->half[it % 2] = dv_add(px->half[it % 2], d);
        px->direct_seen = px->direct;
        px->volume_seen = px->volume;
    }
    bool tty = job->budget->tty;
    if (o->report) {
        double noise = noise_estimate(pixels, npix, it + 1, t->half_fraction);
        if (tty) {
            fputc('\n', stderr);
            job->budget->line_length = 0;
        }
        if (it == 0)
            fprintf(stderr, "reference: iteration 1: %lld photons, %.2f s, first radii for %.0f photons a gather "
                    "(the noise estimate starts at 2)", t->emitted, log_now() - start, job->gather_photons);
        else
            fprintf(stderr, "reference: iteration %d: %lld photons, %.2f s, noise ~%.3g%% (even vs odd iterations)",
                    it + 1, t->emitted, log_now() - start, 100.0 * noise);
        fprintf(stderr,
                "; so far: eye %.2f s, pilot %.2f s, photons %.2f s, photon gather %.2f s, volume gather %.2f s, "
                "update %.2f s\n",
                t->stage_eye, t->stage_pilot, t->stage_photons, t->stage_photon_gather, t->stage_gather,
                t->stage_update);
    }
    double elapsed = log_now() - start;
    /* Under a time budget the iteration count is open-ended: show the
     * clock against the budget instead of a count that will never be
     * reached. */
    if (tty && o->time_budget > 0)
        sppm_progress_line(job->budget, "reference: iteration %d, %lld photons, %.1f s of %.1f s", it + 1, t->emitted,
                      elapsed, o->time_budget);
    else if (tty)
        sppm_progress_line(job->budget, "reference: iteration %d/%d, %lld photons, %.0f s left", it + 1, o->iterations,
                      t->emitted, elapsed / (it + 1) * (o->iterations - it - 1));
    else if (job->budget->log_lines && !o->report &&
             (it == 0 || it + 1 == o->iterations || log_now() - job->budget->last_line >= 5.0)) {
        /* a farm's log: whole lines, the first and last iteration and one every 5 s between */
        job->budget->last_line = log_now();
        if (o->time_budget > 0)
            fprintf(stderr, "reference: iteration %d, %lld photons, %.1f s of %.1f s\n", it + 1, t->emitted, elapsed,
                    o->time_budget);
        else
            fprintf(stderr, "reference: iteration %d/%d, %lld photons, %.1f s\n", it + 1, o->iterations, t->emitted,
                    elapsed);
        fflush(stderr);
    }
}

/* The estimates into the image (and the caustic part into caustic_out):
 * direct and volume radiance averaged over their samples, plus the photon
 * estimate L = tau / (passes pi R^2) (each pass carries the lights' power
 * between its photons, flux per photon = power / photons). */
static void write_estimates(const struct pixel *pixels, size_t npix, const struct sppm_totals *t, struct image *out,
                            struct image *caustic_out)
{
    double passes = t->photon_passes > 0 ? t->photon_passes : 1;
    for (size_t i = 0; i < npix; i++) {
        const struct pixel *px = &pixels[i];
        dvec3 l = px->samples > 0 ? dv_scale(px->direct, 1.0 / px->samples) : dv(0, 0, 0);
        /* (volume_samples sums the gathers' pass fractions) */
        dvec3 volume = px->volume_samples > 0 ? dv_scale(px->volume, 1.0 / px->volume_samples) : dv(0, 0, 0);
        l = dv_add(l, volume);
        dvec3 lc = dv(0, 0, 0);
        if (t->independent_passes > 0)
            lc = dv_scale(px->pppm, 1.0 / t->independent_passes); /* the passes' mean */
        else if (t->emitted > 0 && px->radius > 0 && px->n > 0 && passes - px->passes_before - px->passes_missed > 0)
            lc = dv_scale(px->tau, 1.0 / ((passes - px->passes_before - px->passes_missed) * MATH_PI * px->radius *
                                          px->radius));
        l = dv_add(l, lc);
        if (caustic_out) {
            /* the caustic part: surface caustics and volume caustics */
            float *cd = caustic_out->rgba + i * 4;
            cd[0] = (float)(lc.x + volume.x);
            cd[1] = (float)(lc.y + volume.y);
            cd[2] = (float)(lc.z + volume.z);
            cd[3] = 1.0f;
        }
        float *dst = out->rgba + i * 4;
        dst[0] = (float)l.x;
        dst[1] = (float)l.y;
        dst[2] = (float)l.z;
        dst[3] = 1.0f;
    }
}

/* The render's buffers: per pixel, per photon chunk, the budget. */
struct sppm_buffers {
    struct pixel *pixels;
    struct pixel_segments *segments; /* with a medium alone */
    struct ref_surface_photons *chunks;
    struct volume_photons *volume_chunks;
    struct aim_log *aims;
    struct budget *budget;
};

static void sppm_buffers_release(struct sppm_buffers *b)
{
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        if (b->chunks)
            ref_surface_photons_release(&b->chunks[c]);
        if (b->volume_chunks)
            free(b->volume_chunks[c].items);
        if (b->aims)
            free(b->aims[c].items);
    }
    free(b->aims);
    free(b->budget);
    free(b->volume_chunks);
    free(b->chunks);
    free(b->pixels);
    free(b->segments);
}

static bool sppm_buffers_create(struct sppm_buffers *b, size_t npix, bool medium)
{
    memset(b, 0, sizeof *b);
    /* (huge_pages.h: the first eye pass faulted these in 4 KiB at a time) */
    b->pixels = huge_pages_calloc(npix, sizeof *b->pixels);
    b->segments = medium ? huge_pages_calloc(npix, sizeof *b->segments) : NULL;
    b->chunks = calloc(PHOTON_CHUNKS, sizeof *b->chunks);
    b->volume_chunks = calloc(PHOTON_CHUNKS, sizeof *b->volume_chunks);
    b->aims = calloc(PHOTON_CHUNKS, sizeof *b->aims);
    b->budget = calloc(1, sizeof *b->budget);
    return b->pixels && (!medium || b->segments) && b->chunks && b->volume_chunks && b->aims && b->budget;
}

/* A budget that did not buy one whole iteration says so: the image is
 * an unbiased estimate, but a noisier one than a single iteration at
 * the scene's settings, which a user of --time-budget would not guess. */
static void warn_short_budget(const struct ref_options *o, const struct sppm_totals *t, bool caustics, double start)
{
    if (o->time_budget <= 0)
        return;
    char parts[5][96];
    int n = 0;
    double elapsed = log_now() - start;
    if (t->stage_eye > o->time_budget)
        snprintf(parts[n++], sizeof parts[0], "the first eye pass alone took %.1f s", t->stage_eye);
    if (caustics && t->photon_passes < 0.999)
        snprintf(parts[n++], sizeof parts[0], "%.2g%% of one iteration's photons",
                 100.0 * t->photon_passes);
    if (t->gather_samples > 0)
        snprintf(parts[n++], sizeof parts[0], "the medium's gather at %d of %d points a ray",
                 t->gather_samples, VOLUME_SAMPLES);
    if (t->gather_kept < 1.0)
        snprintf(parts[n++], sizeof parts[0], "with %.2g%% of its photons", 100.0 * t->gather_kept);
    if (t->gather_rows_left > 0)
        snprintf(parts[n++], sizeof parts[0], "%d rows left without the medium's light", t->gather_rows_left);
    char list[512] = "";
    for (int i = 0; i < n; i++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", parts[i]);
    if (n > 0)
        log_warn("reference: --time-budget %g s bought less than one full iteration (%s; %.2f s in all): the image "
                 "is %s than one iteration would make it; raise --time-budget",
                 o->time_budget, list, elapsed, t->gather_rows_left > 0 ? "incomplete, and noisier" : "noisier");
}

/* Paths cut at the bounce cap lose their light: say so where it shows
 * (an eye path's pixel, a glossy reflection), or where photons lost
 * more than 1% of the caustic ones. */
static void warn_cut_paths(struct budget *budget, const struct sppm_totals *t)
{
    long cut[3];
    for (int k = 0; k < 3; k++)
        cut[k] = atomic_load(&budget->paths_cut[k]);
    if (cut[0] + cut[1] > 0 || cut[2] > t->caustic_total / 100)
        log_warn("reference: %ld eye paths and %ld glossy rays were cut after %d specular bounces, %ld photons "
                 "after %d (light trapped by total internal reflection): the light they carried is missing from "
                 "the image", cut[0], cut[1], MAX_DEPTH, cut[2], MAX_PHOTON_DEPTH);
}

/* The pilot, the same in every shard (it depends on the seed
 * alone): pass 0's eye paths aim the lights and give each pixel its
 * first radius; what they gathered is not kept, since a shard
 * without pass 0 renders none of it. */
static void independent_pilot(struct job *job, int threads, bool caustics, size_t npix, struct sppm_totals *t)
{
    double eye_start = log_now();
    job->iteration = 0;
    sppm_run_threads(job, threads, sppm_camera_thread);
    t->stage_eye += log_now() - eye_start;
    if (caustics) {
        double pilot_start = log_now();
        pilot_photons(job, threads, job->budget, job->volume_chunks, job->o->photons, job->pixels, npix);
        t->stage_pilot += log_now() - pilot_start;
        job->pilot_done = true;
    }
    for (size_t i = 0; i < npix; i++) {
        struct pixel *px = &job->pixels[i];
        double r1 = px->radius;
        memset(px, 0, sizeof *px);
        px->r1 = r1;
    }
}

/* What the render measured, for the caller's report. */
static void fill_stats(struct ref_stats *stats, const struct pixel *pixels, size_t npix, const struct sppm_totals *t,
                       int it, int threads, double start)
{
    double passes = t->photon_passes > 0 ? t->photon_passes : 1;
    stats->noise = noise_estimate(pixels, npix, it > 0 ? it : 1, t->half_fraction);
    stats->iterations = it > 0 ? it : 1;
    stats->photons = t->emitted;
    stats->caustic_photons = t->caustic_total;
    stats->seconds = log_now() - start;
    stats->threads = threads < 64 ? threads : 64; /* run_threads' cap */
    stats->passes = t->independent_passes;
    for (int k = 0; k < 3; k++)
        stats->caustic_power[k] = t->caustic_power[k] / passes;
}

bool ref_render_parts(struct renderer *r, struct scene *scene, const struct ref_options *o, struct image *out,
                      struct image *caustic_out, struct ref_stats *stats, struct error *err)
{
    if (o->aov != REF_AOV_NONE) {
        if (caustic_out)
            memset(caustic_out, 0, sizeof *caustic_out);
        if (stats)
            memset(stats, 0, sizeof *stats);
        return ref_render_aov(r, scene, o, out, err);
    }
    double start = log_now();
    struct ref_scene rs;
    if (!ref_scene_build(&rs, r, scene, o->tessellated, err))
        return false;
    struct ref_emitter emitters[SCENE_MAX_GPU_LIGHTS];
    memset(emitters, 0, sizeof emitters);
    bool caustics = rs.has_specular_bounds && rs.light_count > 0 && o->photons > 0;
    for (int l = 0; caustics && l < rs.light_count; l++)
        if (!ref_emitter_build(&emitters[l], &rs, &rs.lights[l], err)) {
            for (int k = 0; k < l; k++)
                ref_emitter_release(&emitters[k]);
            ref_scene_release(&rs);
            return false;
        }
    size_t npix = (size_t)o->width * (size_t)o->height;
    struct sppm_buffers buf;
    struct ref_medium medium;
    ref_medium_init(&medium, scene->medium);
    if (!sppm_buffers_create(&buf, npix, medium.present) || !image_create(out, o->width, o->height, err) ||
        (caustic_out && !image_create(caustic_out, o->width, o->height, err))) {
        image_destroy(out);
        sppm_buffers_release(&buf);
        for (int l = 0; l < rs.light_count; l++)
            ref_emitter_release(&emitters[l]);
        ref_scene_release(&rs);
        return err && err->message[0] ? false : error_set(err, "reference: out of memory");
    }
    double fov = (double)scene->camera.fov * MATH_PI / 180.0;
    double pixel_angle = 2.0 * tan(0.5 * fov) / o->height;
    double pixel_size = (double)scene->camera.ortho_width / (double)o->width;
    int threads = o->threads > 0 ? o->threads : cpus_available();
    if (threads < 1)
        threads = 1;
    struct sppm_totals totals = {.gather_kept = 1.0};
    if (medium.present) {
        dvec3 ext = dv_sub(medium.hi, medium.lo);
        totals.volume_radius = o->volume_radius > 0 ? o->volume_radius : 0.01 * sqrt(dv_dot(ext, ext));
    }
    struct media camera_media;
    dvec3 cam_origin, cam_dir;
    ref_scene_camera_ray(&rs, o->width * 0.5, o->height * 0.5, o->width, o->height, &cam_origin, &cam_dir);
    sppm_media_at(&rs, cam_origin, &camera_media);

    struct budget *budget = buf.budget;
    sppm_budget_start(budget, o, start);
    struct ref_photon_map photon_map = {0};
    struct job job = {.rs = &rs, .o = o, .pixels = buf.pixels, .segments = buf.segments, .camera_media = &camera_media, .medium = &medium,
                      .volume_chunks = buf.volume_chunks, .pixel_angle = pixel_angle, .pixel_size = pixel_size,
                      .gather_photons = GATHER_PHOTONS,
                      .chunks = buf.chunks, .budget = budget, .emitters = emitters, .aims = buf.aims,
                      .photon_map = &photon_map};
    if (caustics && share_photons(&job, &rs, emitters, o->photons) == 0)
        caustics = false;
    for (int l = 0; l < rs.light_count; l++) {
        struct ref_rng shift_rng = ref_rng_seed(o->seed, 11u, (uint64_t)l);
        for (int k = 0; k < 3; k++)
            job.emit_shift[l][k] = ref_rng_uniform(&shift_rng);
    }
    totals.volume_radius_first = totals.volume_radius;
    job.independent = o->shard_count > 0;
    if (job.independent)
        independent_pilot(&job, threads, caustics, npix, &totals);
    int it = 0;
    int pass = job.independent ? o->shard_index : 0, pass_stride = job.independent ? o->shard_count : 1;
    for (; pass < o->iterations; it++, pass += pass_stride) {
        job.iteration = job.independent ? pass : it;
        budget->iteration = it;
        memset(job.caustic_photons, 0, sizeof job.caustic_photons);
        memset(job.caustic_power, 0, sizeof job.caustic_power);
        /* independent passes: pass p's radius from its index alone */
        double shrink = job.independent ? sqrt(pass_shrink(pass)) : 1.0;
        for (size_t i = 0; job.independent && i < npix; i++)
            buf.pixels[i].radius = buf.pixels[i].r1 * shrink;
        double eye_start = log_now();
        sppm_run_threads(&job, threads, sppm_camera_thread);
        totals.stage_eye += log_now() - eye_start;
        if (atomic_load(&budget->cut))
            break; /* the eye pass ran out of time: no photons for a half-traced set of visible points */
        for (size_t i = 0; job.independent && i < npix; i++)
            if (buf.pixels[i].r1 <= 0.0) /* no visible point in pass 0: this pass's own first radius */
                buf.pixels[i].radius *= shrink;
        if (caustics)
            photon_iteration(&job, it, threads, npix, &totals);
        if (job.independent)
            totals.independent_passes++;
        iteration_report(&job, it, npix, start, &totals);
        /* (photons stopped early only to leave the gather its time do not
         * end the render: the next iteration may still fit) */
        double elapsed = log_now() - start;
        if (atomic_load(&budget->cut) || (o->time_budget > 0 && elapsed >= o->time_budget)) {
            it++;
            break;
        }
    }
    if (budget->tty)
        fputc('\n', stderr);
    warn_short_budget(o, &totals, caustics, start);
    warn_cut_paths(budget, &totals);
    write_estimates(buf.pixels, npix, &totals, out, caustic_out);
    if (stats)
        fill_stats(stats, buf.pixels, npix, &totals, it, threads, start);
    ref_photon_map_release(&photon_map);
    sppm_buffers_release(&buf);
    for (int l = 0; l < rs.light_count; l++)
        ref_emitter_release(&emitters[l]);
    ref_scene_release(&rs);
    return true;
}
