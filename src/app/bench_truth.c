/* `caustica bench`'s ground truths: the reference's image of each error
 * frame, cached by a hash of scene, parameters, frame, size and reference
 * settings (or read from --truth), the caustic region's mask, a variant's
 * error against it, and the reference's own curve (its error at growing
 * iteration counts against a 16x longer run). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "app/bench_internal.h"
#include "core/fileio.h"
#include "core/hash.h"
#include "core/log.h"
#include "reference/reference_part.h"

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
    k = bench_hash_params(k, params);
    int ints[3] = {frame, w, h};
    k = hash_fnv1a(k, ints, sizeof ints);
    k = hash_fnv1a(k, &ro->photons, sizeof ro->photons);
    k = hash_fnv1a(k, &ro->iterations, sizeof ro->iterations);
    k = hash_fnv1a(k, &ro->seed, sizeof ro->seed);
    if (ro->antialias) /* only then: the point-sampled truths keep their keys */
        k = hash_fnv1a(k, "antialias", 9);
    /* truths of exact spheres since issue 53 (those before traced their triangles) */
    k = hash_fnv1a(k, ro->tessellated ? "tessellated" : "spheres", ro->tessellated ? 11 : 7);
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

void bench_truth_release(struct truth *t)
{
    image_destroy(&t->image);
    image_destroy(&t->caustic);
    image_destroy(&t->mask);
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

/* The truth set of variant `v`'s scene parameters (pass parameters and a
 * technique's selectors do not change the scene), made on first need. */
bool bench_truth_set(struct bench *b, const struct variant *v, int *out, struct error *err)
{
    uint64_t set_key = bench_hash_params(1469598103934665603ULL, &v->truth_params);
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
bool bench_truth(struct bench *b, const struct variant *v, int set, int frame, int *out, struct error *err)
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
bool bench_add_error(const struct truth *t, const struct image *image, struct result *r, int e, int *with_mask,
                     struct error *err)
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

/* The reference's own curve, for each distinct scene (its scene
 * parameters): 1/8, 1/4, 1/2 and all of the truth's iterations / 16,
 * over the same error frames. */
bool bench_reference_curve(struct bench *b, struct error *err)
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
void bench_truth_error(struct bench *b)
{
    for (int t = 0; t < MAX_CURVES; t++)
        b->truth_error[t] = -1.0;
    double K = b->truth_options.iterations;
    for (int c = 0; c < b->ncurve; c++) {
        const struct result *r = &b->curve[c];
        double e = bench_ranked_error(r, b->caustic), k = r->iterations;
        if (r->truth < 0 || r->truth >= MAX_CURVES || !(e > 0) || !(k > 0) || !isfinite(e))
            continue;
        double bound = e * sqrt(k / (K + k));
        if (b->truth_error[r->truth] < 0 || bound < b->truth_error[r->truth])
            b->truth_error[r->truth] = bound;
    }
}
