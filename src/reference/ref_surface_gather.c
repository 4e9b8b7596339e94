/* The reference's surface gathers: each pixel's photons within its
 * radius, the radius search that chooses the first radius and shrinks it
 * where the structure test sees detail, and the adaptive emission
 * (ref_sppm.c runs them). */
#define _POSIX_C_SOURCE 200809L
#include "reference/ref_sppm_internal.h"

/* Adapts each light's emission to where its photons were useful (what
 * the chunks logged, in chunk order: deterministic). */
/* Returns the fraction of the logged photons that were useful. */
double sppm_adapt_emission(struct aim_log *aims, struct ref_emitter *emitters, int light_count)
{
    double logged = 0.0, useful = 0.0;
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        for (size_t k = 0; k < aims[c].count; k++) {
            uint64_t a = aims[c].items[k];
            logged += 1.0;
            useful += (double)(a & 1u);
            struct ref_emitter *e = &emitters[a >> 40];
            size_t entry = (size_t)((a >> 1) & ((1ull << 39) - 1));
            e->sampled[entry] += 1.0;
            e->useful[entry] += (double)(a & 1u);
        }
        aims[c].count = 0;
    }
    for (int l = 0; l < light_count; l++)
        ref_emitter_adapt(&emitters[l]);
    return logged > 0.0 ? useful / logged : 0.0;
}

static void structure_sums(const struct ref_photon_rings *g, double area, double sum[STRUCTURE_SUMS],
                           double var[STRUCTURE_SUMS]);

/* ---- the surface gather --------------------------------------------------- */

/* Rows interleaved over the threads; each pixel sums the photons within
 * its radius (ref_photon_map.h: the gather from the pixels' side). */
static void *surface_gather_thread(void *arg)
{
    struct job *j = arg;
    bool stopped = false;
    for (int y = j->thread; y < j->o->height; y += j->threads) {
        /* Under a budget the gather stops at the deadline, row by row: a
         * pixel whose row it did not reach leaves this pass out of its
         * estimate (passes_missed), as if its photons had not been traced. */
        if (!stopped && j->gather_until > 0.0 && !j->gather_counts_only && log_now() >= j->gather_until) {
            stopped = true;
            atomic_store(&j->budget->cut, 1);
        }
        for (int x = 0; x < j->o->width; x++) {
            struct pixel *px = &j->pixels[(size_t)y * (size_t)j->o->width + (size_t)x];
            if (stopped) {
                px->passes_missed += j->pass_fraction;
                continue;
            }
            if (!px->vp.valid || !(px->radius > 0.0))
                continue;
            dvec3 flux;
            struct ref_photon_rings rings;
            bool test = !j->gather_counts_only && !j->independent && px->radius_floor > 0.0;
            long m = ref_photon_map_gather(j->photon_map, j->thread, px->vp.position, px->vp.normal, px->radius,
                                           j->light_scale, &flux, test ? &rings : NULL);
            px->m += m;
            if (m > 0 && !j->gather_counts_only)
                px->phi = dv_add(px->phi, dv_mul(px->vp.weight, flux));
            if (m > 0 && test) {
                /* the structure test's sums, in flux densities */
                double sum[STRUCTURE_SUMS], var[STRUCTURE_SUMS];
                structure_sums(&rings, 0.25 * MATH_PI * px->radius * px->radius, sum, var);
                for (int k = 0; k < STRUCTURE_SUMS; k++) {
                    px->structure[k] += sum[k];
                    px->structure_var[k] += var[k];
                }
                px->phi_inner = dv_add(px->phi_inner, dv_mul(px->vp.weight, dv(rings.inner_flux[0], rings.inner_flux[1],
                                                                            rings.inner_flux[2])));
                px->m_inner += rings.inner_count;
            }
        }
    }
    return NULL;
}


/* The pixels a gather serves: those with a visible point and a radius
 * (with `search`, only those still searching). */
static bool gathers(const struct pixel *px, const struct radius_search *search, size_t i)
{
    return px->vp.valid && px->radius > 0.0 && (!search || search[i].floor > 0.0);
}

/* Sets the map's levels for the radii of the pixels that gather, and
 * counts how many read each level (for ref_photon_map_build); false when
 * none gathers. */
static bool map_levels_for(struct job *job, const struct radius_search *search,
                           size_t per_level[REF_PHOTON_MAP_LEVELS])
{
    size_t npix = (size_t)job->o->width * (size_t)job->o->height;
    double rmax = 0.0;
    for (size_t i = 0; i < npix; i++)
        if (gathers(&job->pixels[i], search, i))
            rmax = fmax(rmax, job->pixels[i].radius);
    if (!(rmax > 0.0))
        return false;
    ref_photon_map_prepare(job->photon_map, rmax);
    memset(per_level, 0, REF_PHOTON_MAP_LEVELS * sizeof *per_level);
    for (size_t i = 0; i < npix; i++)
        if (gathers(&job->pixels[i], search, i))
            per_level[ref_photon_map_level_of(job->photon_map, job->pixels[i].radius)]++;
    return true;
}

/* Gathers the traced surface photons into the visible points (their flux
 * into phi and their count into m, or for the pilot only the count), each
 * light's photons scaled by light_scale, tells each chunk's aim log which
 * of its photons a visible point took (the adaptive emission's "useful"),
 * and empties the chunks. */
void sppm_gather_surface_photons(struct job *job, int threads, const double *light_scale, bool counts_only)
{
    struct ref_photon_map *map = job->photon_map;
    size_t npix = (size_t)job->o->width * (size_t)job->o->height;
    size_t per_level[REF_PHOTON_MAP_LEVELS];
    if (map_levels_for(job, NULL, per_level)) {
        double build_start = log_now();
        bool built = ref_photon_map_build(map, job->chunks, PHOTON_CHUNKS, per_level, threads);
        if (counts_only && map->count > 0)
            job->budget->seconds_per_mapped = (log_now() - build_start) / (double)map->count;
        if (!built) {
            if (!job->budget->map_warned)
                log_warn("reference: out of memory for the photon map: an iteration's caustic photons are lost "
                         "(fewer --photons would fit)");
            job->budget->map_warned = true;
            map->count = 0;
        }
        if (map->count > 0) {
            job->light_scale = light_scale;
            job->gather_counts_only = counts_only;
            double scan_start = log_now();
            sppm_run_threads(job, threads, surface_gather_thread);
            if (counts_only) {
                long long taken = 0;
                for (size_t i = 0; i < npix; i++)
                    taken += job->pixels[i].m;
                if (taken > 0)
                    job->budget->seconds_per_gathered = (log_now() - scan_start) / (double)taken;
            }
        }
        ref_photon_map_collect_marks(map);
        size_t i = 0;
        for (int c = 0; c < PHOTON_CHUNKS && map->count > 0; c++)
            for (size_t k = 0; k < job->chunks[c].count; k++, i++)
                if (ref_photon_map_was_used(map, i) &&
                    job->chunks[c].items[k].aim < job->aims[c].count)
                    job->aims[c].items[job->chunks[c].items[k].aim] |= 1u;
    }
    for (int c = 0; c < PHOTON_CHUNKS; c++)
        job->chunks[c].count = 0;
}


/* ---- the structure test ------------------------------------------------- */

/* A wide radius is cheap noise reduction where the light is even and a
 * blur where it is not: a focus, a fold, the edge of a shadow or of a
 * caustic band. After Kaplanyan & Dachsbacher ("Adaptive progressive
 * photon mapping", TOG 2013: the radius that balances a kernel's bias
 * against its noise), but tested instead of estimated: the pilot's last
 * round, aimed as the estimate will be, is gathered at each pixel's first
 * radius in two parts, the disc of half the radius and the ring around it.
 * On even light their flux densities agree; where they differ by more than
 * STRUCTURE_Z standard deviations of the difference (the flux's own noise,
 * from the sum of the squared fluxes) the disc's bias is above its noise,
 * and the radius is halved and tested again, down to its floor. A dim
 * region with few photons cannot show a difference and keeps its wide
 * radius, which is right: its noise is the larger error there. */
#define STRUCTURE_Z 3.0
#define RESTART_Z 5.0 /* stricter: the test is repeated every iteration */

/* Whether sums show structure: a difference (a sum whose mean is 0 on
 * even light) above STRUCTURE_Z of its standard deviation. */
static bool structure_significant(double sum, double var, double z)
{
    return var > 0.0 && sum * sum > z * z * var;
}

/* Two kinds of structure: curvature (a focus, a ridge), where the inner
 * disc's flux density (over pi r^2 / 4) differs from the ring's (over
 * 3 pi r^2 / 4), inner vs ring / 3; and an edge or a slope, where the flux
 * leans to one side (a step through the centre: the disc and the ring are
 * cut alike, and only the moments see it). Each as a sum whose mean is 0
 * on even light, with its variance, per `area` (pi r^2 / 4 for densities). */
static void structure_sums(const struct ref_photon_rings *g, double area, double sum[STRUCTURE_SUMS],
                           double var[STRUCTURE_SUMS])
{
    sum[0] = (g->inner - g->ring / 3.0) / area;
    var[0] = (g->inner_sq + g->ring_sq / 9.0) / (area * area);
    for (int k = 0; k < 2; k++) {
        sum[1 + k] = g->moment[k] / (4.0 * area);
        var[1 + k] = g->moment_sq[k] / (16.0 * area * area);
    }
}

static bool structure_any(const double sum[STRUCTURE_SUMS], const double var[STRUCTURE_SUMS], double z)
{
    for (int k = 0; k < STRUCTURE_SUMS; k++)
        if (structure_significant(sum[k], var[k], z))
            return true;
    return false;
}

static bool structure_shows(const struct ref_photon_rings *g)
{
    double sum[STRUCTURE_SUMS], var[STRUCTURE_SUMS];
    structure_sums(g, 1.0, sum, var);
    return structure_any(sum, var, STRUCTURE_Z);
}

/* The same test iteration by iteration, on the sums of every iteration's
 * gather since the radius was last halved (the estimate's own photons:
 * the differences average over iterations, so ever smaller biases show as
 * the noise they would hide in falls). Where it shows, the pixel's photon
 * estimate starts again at half the radius: what it gathered so far holds
 * the bias, and SPPM's own shrinking would keep it (Kaplanyan & Dachsbacher
 * 2013 adapt the radius in the same spirit from an estimated Laplacian).
 * Sequential passes only: independent passes share no state.
 *
 * Where only the moments show it (a slope, or an edge through the centre)
 * what was gathered is kept at a quarter of its weight (RESTART_KEEP): a
 * slope leans the flux to one side but leaves a symmetric kernel's
 * estimate unbiased, and an edge off the centre shows in the inner disc
 * against the ring as well. At the ball lens's focus, whose irradiance
 * falls as r^(-4/3), every restart was a moment's: thrown away each time,
 * the estimates there started over again and again as their noise fell,
 * and the per-pixel error outside the central 32 x 32 pixels grew from
 * 0.7% at 8 s to 1.9% at 16 s; kept whole, the TIR cube's band edges kept
 * their blur (2.17% -> 2.52% at 24 iterations); at a quarter, the cube
 * 2.23% and the focus 1.42% where starting over left 2.66% (24 iterations
 * of 200,000 photons at 512^2, one seed; issue 53). */
#define RESTART_KEEP 0.25
bool sppm_structure_restart(struct pixel *px, double passes_now)
{
    if (!(px->radius_floor > 0.0) || 0.5 * px->radius < px->radius_floor)
        return false;
    if (!structure_any(px->structure, px->structure_var, RESTART_Z))
        return false;
    px->radius *= 0.5;
    if (!structure_significant(px->structure[0], px->structure_var[0], RESTART_Z)) {
        /* tau and n for the half radius (a quarter of the disc), then a
         * quarter of the weight: the passes so far count as a quarter of
         * their number */
        px->tau = dv_scale(px->tau, 0.25 * RESTART_KEEP);
        px->n *= 0.25 * RESTART_KEEP;
        px->passes_before += (1.0 - RESTART_KEEP) * (passes_now - px->passes_before - px->passes_missed);
        memset(px->structure, 0, sizeof px->structure);
        memset(px->structure_var, 0, sizeof px->structure_var);
        return true;
    }
    px->tau = dv(0, 0, 0);
    px->n = 0.0;
    px->passes_before = passes_now;
    px->passes_missed = 0.0;
    memset(px->structure, 0, sizeof px->structure);
    memset(px->structure_var, 0, sizeof px->structure_var);
    return true;
}


/* A k-nearest-neighbour radius (after the pilot's first guess from the
 * count within R_c): the radius that holds the gather_photons an
 * iteration would put there (a quarter of them in the pilot's round),
 * found by counting at the radius and moving it, within a factor 2 of the
 * count. A count at R_c only sees the density around the pixel: a dim
 * pixel beside a bright caustic would reach far into it. */
static long knn_step(const struct job *j, struct pixel *px, struct radius_search *s)
{
    double want = j->gather_photons / 4.0;
    long c = ref_photon_map_count(j->photon_map, px->vp.position, px->vp.normal, px->radius, (long)(8.0 * want));
    double r = px->radius;
    if ((double)c > 2.0 * want)
        r *= fmax(sqrt(want / (double)c), 0.25);
    else if ((double)c < 0.5 * want)
        r *= c > 0 ? fmin(sqrt(want / (double)c), 2.0) : 2.0;
    r = fmin(fmax(r, s->floor), s->ceiling);
    if (r == px->radius)
        s->floor = 0.0; /* settled */
    px->radius = r;
    return c;
}

static void structure_step(const struct job *j, struct pixel *px, struct radius_search *s)
{
    struct ref_photon_rings g;
    ref_photon_map_rings(j->photon_map, px->vp.position, px->vp.normal, px->radius, &g);
    if (structure_shows(&g) && 0.5 * px->radius >= s->floor)
        px->radius *= 0.5;
    else
        s->floor = 0.0; /* settled */
}

static void *radius_search_thread(void *arg)
{
    struct job *j = arg;
    long long served = 0, counted = 0;
    for (int y = j->thread; y < j->o->height; y += j->threads) {
        if (j->radius_search_until > 0.0 && log_now() >= j->radius_search_until)
            break; /* the rows left keep the radii they have */
        for (int x = 0; x < j->o->width; x++) {
            size_t i = (size_t)y * (size_t)j->o->width + (size_t)x;
            struct pixel *px = &j->pixels[i];
            struct radius_search *s = &j->radius_search[i];
            if (!(s->floor > 0.0) || !px->vp.valid)
                continue;
            if (j->radius_search_knn) {
                counted += knn_step(j, px, s);
                served++;
            } else {
                structure_step(j, px, s);
            }
        }
    }
    if (j->radius_search_measured) {
        atomic_fetch_add(&j->budget->knn_pixels, served);
        atomic_fetch_add(&j->budget->knn_counted, counted);
    }
    return NULL;
}

/* Up to `passes` passes of k-nearest-neighbour steps (knn) or structure
 * steps over the pixels `search` marks, each with the map's levels built
 * for the radii of that pass; stops at `until` (0: no deadline). The
 * search marks are spent (every pixel settled) when it returns. */
void sppm_radius_search(struct job *job, int threads, struct radius_search *search, bool knn, int passes,
                          double until)
{
    struct ref_photon_map *map = job->photon_map;
    job->radius_search = search;
    job->radius_search_knn = knn;
    job->radius_search_until = until;
    for (int pass = 0; pass < passes && map->count > 0; pass++) {
        if (until > 0.0 && log_now() >= until)
            break;
        size_t per_level[REF_PHOTON_MAP_LEVELS];
        if (!map_levels_for(job, search, per_level))
            break; /* every pixel settled */
        if (!ref_photon_map_build_levels(map, per_level, threads))
            break; /* out of memory: the radii stand */
        double pass_start = log_now();
        job->radius_search_measured = knn && pass == 0;
        sppm_run_threads(job, threads, radius_search_thread);
        if (job->radius_search_measured)
            job->budget->knn_seconds = log_now() - pass_start;
        job->radius_search_measured = false;
    }
    job->radius_search = NULL;
}
