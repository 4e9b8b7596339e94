/* The reference's photon tracing: each light's photons aimed by its
 * emitter (ref_emit.c), through the specular chains to the surfaces and
 * the media, in chunks the threads share (ref_sppm.c runs it). */
#define _POSIX_C_SOURCE 200809L
#include "reference/ref_sppm_internal.h"

static void aim_push(struct aim_log *log, int light, size_t entry, bool useful)
{
    if (log->count == log->capacity) {
        size_t cap = log->capacity ? log->capacity * 2 : 4096;
        uint64_t *p = realloc(log->items, cap * sizeof *p);
        if (!p)
            return; /* the adaptation sees one photon fewer: it stays valid */
        log->items = p;
        log->capacity = cap;
    }
    log->items[log->count++] = ((uint64_t)light << 40) | ((uint64_t)entry << 1) | (useful ? 1u : 0u);
}

/* Where a photon's path starts: from the light, or the reflected branch
 * of a photon split at an interface (sppm_specular_step). */
struct photon_start {
    dvec3 origin, dir, flux;
    struct media media;
    int depth, specular; /* bounces so far, and how many of them specular */
};

/* What every path of one emitted photon shares: its aim (the surface it
 * must meet first), where its photons go, and how many more reflected
 * branches it may start (PHOTON_BRANCHES in all). */
struct photon_tree {
    int light;
    int target_object;
    unsigned target_primitive;
    struct ref_surface_photons *hits;
    long long *caustic;
    double *power;
    struct volume_photons *volume;
    uint32_t aim;
    int branches_left;
};

static void trace_photon_path(struct job *j, struct photon_tree *tree, struct ref_rng *rng, struct photon_start st);

static void trace_photon(struct job *j, int light, long index, struct ref_surface_photons *hits, long long *caustic,
                         double *power, struct volume_photons *volume, struct aim_log *aims)
{
    const struct ref_scene *rs = j->rs;
    struct ref_rng rng = ref_rng_seed(j->o->seed, 7919u * (uint64_t)j->iteration + 2u + (uint64_t)light * 104729u,
                                      (uint64_t)index);
    dvec3 origin, dir, flux;
    int target_object;
    unsigned target_primitive;
    size_t entry;
    /* Photon `index` of this iteration is point (iteration x photons +
     * index) of the light's sequence: each iteration takes the next stretch
     * of it (the pilot one far beyond the rest). */
    uint64_t sequence = j->iteration < 0 ? ((uint64_t)-j->iteration << 40) + (uint64_t)index
                                         : (uint64_t)j->iteration * (uint64_t)j->photons_of[light] + (uint64_t)index;
    double point[3];
    ref_emit_point(sequence, j->emit_shift[light], point);
    if (!ref_emitter_sample(&j->emitters[light], rs, &rs->lights[light], j->photons_of[light], point, &origin, &dir,
                            &flux, &target_object, &target_primitive, &entry))
        return;
    size_t volume_before = volume->count;
    /* a surface photon is marked useful by the gather (gather_surface_photons),
     * a volume photon now: it is gathered wherever it lies */
    struct photon_tree tree = {light, target_object, target_primitive, hits, caustic, power, volume,
                               (uint32_t)aims->count, PHOTON_BRANCHES};
    /* (lights are outside every dielectric) */
    trace_photon_path(j, &tree, &rng, (struct photon_start){origin, dir, flux, {.count = 0}, 0, 0});
    aim_push(aims, light, entry, volume->count > volume_before);
}

static void trace_photon_path(struct job *j, struct photon_tree *tree, struct ref_rng *rng, struct photon_start st)
{
    const struct ref_scene *rs = j->rs;
    struct media media = st.media;
    dvec3 origin = st.origin, dir = st.dir, flux = st.flux;
    int specular = st.specular, light = tree->light;
    for (int depth = st.depth; depth < MAX_PHOTON_DEPTH; depth++) {
        struct ref_hit h;
        bool hit = ref_scene_intersect(rs, origin, dir, INFINITY, &h);
        /* Aimed at one triangle: if another surface comes first, this
         * direction belongs to that surface's own photons (or to direct
         * light, for an opaque one) and this photon carries nothing. */
        /* (an exact sphere is aimed at through its blown-up triangles,
         * ref_emit.c's aim_scale, whose facets facing the light tile its
         * whole outline: any hit on the sphere counts) */
        if (depth == 0 && (!hit || h.object != tree->target_object ||
                           (!j->rs->objects[h.object].sphere && h.primitive != tree->target_primitive)))
            return;
        if (sppm_scene_medium_here(rs, &media) && j->medium->present) {
            double ts = 0;
            dvec3 w = dv(1, 1, 1);
            enum ref_medium_event ev = ref_medium_track(j->medium, origin, dir, hit ? h.t : INFINITY, rng, &ts, &w);
            if (ev == REF_MEDIUM_ABSORB)
                return;
            if (ev == REF_MEDIUM_SCATTER) {
                /* Light -> specular+ -> medium: a volume caustic photon. One
                 * that scatters before any specular surface is direct
                 * single scattering, which the eye paths estimate. */
                if (specular > 0)
                    sppm_volume_push(tree->volume, dv_add(origin, dv_scale(dir, ts)), dir, dv_mul(flux, w), light);
                return;
            }
            flux = dv_mul(flux, w);
        }
        if (!hit)
            return;
        flux = sppm_attenuate(flux, sppm_medium_sigma(rs, &media), h.t);
        if (sppm_hit_is_diffuse(rs, &h, rng)) {
            if (specular > 0) {
                (*tree->caustic)++;
                tree->power[0] += flux.x;
                tree->power[1] += flux.y;
                tree->power[2] += flux.z;
                struct ref_surface_photon ph = {
                    {(float)h.position.x, (float)h.position.y, (float)h.position.z},
                    {(float)dir.x, (float)dir.y, (float)dir.z},
                    {(float)h.geometric_normal.x, (float)h.geometric_normal.y, (float)h.geometric_normal.z},
                    {(float)flux.x, (float)flux.y, (float)flux.z}, light, tree->aim};
                ref_surface_photons_push(tree->hits, &ph); /* out of memory: the photon is lost, the estimate stays finite */
            }
            return; /* L D paths are direct light, gathered by shadow rays */
        }
        struct specular_branch branch = {.taken = false};
        if (sppm_specular_step(rs, &h, &media, &dir, &origin, &flux, rng, tree->branches_left > 0 ? &branch : NULL))
            specular++;
        if (branch.taken) {
            /* the reflected way, on random numbers of its own (a stream
             * drawn from this path's, so a seed still fixes everything) */
            tree->branches_left--;
            uint64_t hi = ref_rng_u32(rng), lo = ref_rng_u32(rng);
            struct ref_rng branch_rng = ref_rng_seed(j->o->seed, (hi << 32) | lo, 1u);
            trace_photon_path(j, tree, &branch_rng,
                              (struct photon_start){branch.origin, branch.dir, branch.beta, branch.media, depth + 1,
                                                    specular});
        }
        if (dv_dot(flux, flux) < 1e-40)
            return;
    }
    atomic_fetch_add(&j->budget->paths_cut[2], 1); /* (every other way out returns) */
}

void sppm_chunk_range(const struct job *j, int c, long *begin, long *end)
{
    *begin = (long)((long long)j->photons_total * c / PHOTON_CHUNKS);
    *end = (long)((long long)j->photons_total * (c + 1) / PHOTON_CHUNKS);
}

/* Progress while photons are traced (thread 0 only), at most 4 times a
 * second: with millions of photons an iteration can take many seconds. */
static void photon_progress(const struct job *j, int chunks_done)
{
    struct budget *b = j->budget;
    double now = log_now();
    if (!b->tty || now - b->last_print < 0.25)
        return;
    b->last_print = now;
    if (b->deadline > 0)
        sppm_progress_line(b, "reference: iteration %d (%d%% of its photons), %.1f s of %.1f s", b->iteration + 1,
                      100 * chunks_done / PHOTON_CHUNKS, now - b->start, b->deadline - b->start);
    else
        sppm_progress_line(b, "reference: iteration %d/%d (%d%% of its photons), %.1f s", b->iteration + 1,
                      j->o->iterations, 100 * chunks_done / PHOTON_CHUNKS, now - b->start);
}

/* Photons in 64 fixed chunks (so the sums do not depend on the thread
 * count). The clock is checked every PHOTON_BATCH photons, after each
 * thread's first batch: a budget ends within a batch's time whatever the
 * photon count, and the photons traced are counted per light. */
#define PHOTON_BATCH 64 /* a few ms of photons even on a loaded machine: the budget ends within that */
void *sppm_photon_thread(void *arg)
{
    struct job *j = arg;
    int done = 0;
    bool first = true;
    for (int c = j->thread; c < PHOTON_CHUNKS; c += j->threads) {
        long begin, end;
        sppm_chunk_range(j, c, &begin, &end);
        j->budget->chunk_reached[c] = begin;
        int light = 0;
        for (long k = begin; k < end; k++) {
            if ((k - begin) % PHOTON_BATCH == 0) {
                if (!first && sppm_budget_photons_spent(j->budget))
                    return NULL;
                j->budget->chunk_reached[c] = k;
                if (j->thread == 0)
                    photon_progress(j, done);
            }
            first = false;
            while (light + 1 < j->rs->light_count && k >= j->first_of[light + 1])
                light++;
            trace_photon(j, light, k - j->first_of[light], &j->chunks[c], &j->caustic_photons[c],
                         j->caustic_power[c], &j->volume_chunks[c], &j->aims[c]);
            j->budget->chunk_reached[c] = k + 1;
        }
        done += j->threads;
    }
    return NULL;
}

void sppm_run_threads(struct job *base, int threads, void *(*fn)(void *))
{
    struct job jobs[64];
    pthread_t ids[64];
    if (threads > 64)
        threads = 64;
    for (int t = 0; t < threads; t++) {
        jobs[t] = *base;
        jobs[t].thread = t;
        jobs[t].threads = threads;
        memset(jobs[t].caustic_photons, 0, sizeof jobs[t].caustic_photons);
        memset(jobs[t].caustic_power, 0, sizeof jobs[t].caustic_power);
    }
    int started = 0;
    for (int t = 1; t < threads; t++)
        if (pthread_create(&ids[t], NULL, fn, &jobs[t]) == 0)
            started = t;
        else
            break;
    /* the calling thread takes slot 0, and the slots of threads that did not start */
    for (int t = 0; t < threads; t++)
        if (t == 0 || t > started)
            fn(&jobs[t]);
    for (int t = 1; t <= started; t++)
        pthread_join(ids[t], NULL);
    for (int t = 0; t < threads; t++)
        for (int c = 0; c < PHOTON_CHUNKS; c++) {
            base->caustic_photons[c] += jobs[t].caustic_photons[c];
            for (int k = 0; k < 3; k++)
                base->caustic_power[c][k] += jobs[t].caustic_power[c][k];
        }
}
