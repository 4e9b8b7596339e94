/* `caustica merge PART... -o OUT`: the parts of a reference rendered with
 * `reference --shard i/n` averaged into the estimate one run of all their
 * passes makes. Each part's image is the mean of its independent passes
 * (probabilistic progressive photon mapping: passes share no state, Knaus
 * & Zwicker 2011), so the merge is the passes-weighted mean of the parts;
 * the parts are checked to belong together (scene, frame, size, seed,
 * photons, pass count, shard count) and to hold disjoint shards. An EXR
 * part's "caustic" layer is merged the same way. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "core/fileio.h"
#include "core/log.h"
#include "io/image.h"
#include "reference/reference_part.h"

/* The passes p < total with p % count among the shards marked in `have`:
 * shard s holds total / count of them, and one more when s < total % count
 * (counted per shard, not per pass: a part may claim 2^31 - 1 passes). */
static long long passes_of(const bool *have, int count, int total)
{
    long long n = 0;
    for (int s = 0; s < count; s++)
        if (have[s])
            n += total / count + (s < total % count ? 1 : 0);
    return n;
}

static bool same_kind(const struct reference_part *a, const struct reference_part *b, const char *path,
                      struct error *err)
{
    if (strcmp(a->scene, b->scene) != 0)
        return error_set(err, "%s: a part of %s, not of %s", path, b->scene, a->scene);
    if (a->frame != b->frame || a->width != b->width || a->height != b->height)
        return error_set(err, "%s: frame %d at %dx%d, the first part is frame %d at %dx%d", path, b->frame, b->width,
                         b->height, a->frame, a->width, a->height);
    if (a->seed != b->seed || a->photons != b->photons || a->passes_total != b->passes_total ||
        a->shard_count != b->shard_count)
        return error_set(err, "%s: rendered with other settings (seed, --photons, --spp or the shard count differ "
                              "from the first part's): its passes are not the same estimate's", path);
    return true;
}

int cmd_merge(struct app *app, struct cli *cli)
{
    (void)app;
    if (cli->npositional < 1 || !cli->output) {
        fprintf(stderr, "caustica: merge needs the parts and -o OUT.pfm\n");
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    int status = cli_check_radiance_output(cli, "a merged reference");
    if (status != 0)
        return status;
    struct error err;
    struct reference_part *first = calloc(2, sizeof *first);
    bool *have = calloc(REFERENCE_PART_MAX_SHARDS, sizeof *have);
    double *sum = NULL, *sum_caustic = NULL;
    size_t n = 0;
    long long passes = 0, emitted = 0; /* sums of the parts' counts: past int's range is possible */
    bool ok = first && have, caustic = true;
    if (!ok)
        error_set(&err, "merge: out of memory");
    struct reference_part *part = first ? first + 1 : NULL;
    for (int k = 0; ok && k < cli->npositional; k++) {
        const char *path = cli->positional[k];
        struct image img = {0}, layer = {0};
        ok = reference_part_read(path, k == 0 ? first : part, &err);
        const struct reference_part *p = k == 0 ? first : part;
        ok = ok && (k == 0 || same_kind(first, part, path, &err)) && image_read(path, &img, &err);
        if (ok && (img.width != p->width || img.height != p->height))
            ok = error_set(&err, "%s: the image is %dx%d, its .part says %dx%d", path, img.width, img.height, p->width,
                           p->height);
        for (int i = 0; ok && i < p->shard_parts; i++) {
            if (have[p->shards[i]])
                ok = error_set(&err, "%s: shard %d/%d is already in an earlier part: merged once only", path,
                               p->shards[i], p->shard_count);
            have[p->shards[i]] = true;
        }
        if (ok && k == 0) {
            n = (size_t)p->width * (size_t)p->height * 4;
            sum = calloc(n, sizeof *sum);
            sum_caustic = calloc(n, sizeof *sum_caustic);
            if (!sum || !sum_caustic)
                ok = error_set(&err, "merge: out of memory for %dx%d", p->width, p->height);
        }
        /* the caustic layer, where every part has one (reference -o x.exr) */
        if (ok && caustic) {
            char layer_path[4300];
            snprintf(layer_path, sizeof layer_path, "%s:caustic", path);
            struct error ignored;
            caustic = image_path_is_exr(path) && image_read(layer_path, &layer, &ignored) &&
                      layer.width == img.width && layer.height == img.height;
        }
        for (size_t i = 0; ok && i < n; i++) {
            sum[i] += (double)img.rgba[i] * p->passes;
            if (caustic)
                sum_caustic[i] += (double)layer.rgba[i] * p->passes;
        }
        passes += ok ? p->passes : 0;
        if (ok && emitted > LLONG_MAX - p->photons_emitted)
            ok = error_set(&err, "%s: photons_emitted past what the parts can add up to", path);
        emitted += ok ? p->photons_emitted : 0;
        image_destroy(&img);
        image_destroy(&layer);
    }
    long long expected = ok ? passes_of(have, first->shard_count, first->passes_total) : 0;
    if (ok && passes != expected)
        ok = error_set(&err, "merge: the parts hold %lld passes, their shards %lld (a part cut short or edited?)",
                       passes, expected);
    struct image out = {0}, out_caustic = {0};
    ok = ok && image_create(&out, first->width, first->height, &err) &&
         (!caustic || image_create(&out_caustic, first->width, first->height, &err));
    for (size_t i = 0; ok && i < n; i++) {
        out.rgba[i] = (float)(sum[i] / (double)passes);
        if (caustic)
            out_caustic.rgba[i] = (float)(sum_caustic[i] / (double)passes);
    }
    if (ok && image_path_is_exr(cli->output) && caustic) {
        struct image_layer layer = {.name = "caustic", .image = &out_caustic};
        ok = image_write_exr(cli->output, &out, &layer, 1, NULL, &err);
    } else if (ok) {
        ok = image_write(cli->output, &out, &err);
    }
    if (ok) {
        struct reference_part merged = *first;
        merged.shard_parts = 0;
        for (int i = 0; i < first->shard_count; i++)
            if (have[i])
                merged.shards[merged.shard_parts++] = i;
        merged.passes = (int)passes; /* equal to passes_of(), at most passes_total (an int) */
        merged.photons_emitted = emitted;
        ok = reference_part_write(cli->output, &merged, &err);
        if (ok && merged.shard_parts < first->shard_count) {
            char missing[256] = "";
            for (int i = 0, shown = 0; i < first->shard_count && shown < 16; i++)
                if (!have[i]) {
                    snprintf(missing + strlen(missing), sizeof missing - strlen(missing), "%s%d", shown ? ", " : "", i);
                    shown++;
                }
            fprintf(stderr,
                    "caustica: warning: merged %d of %d shards (%lld of %d passes): the estimate of those passes; "
                    "missing: %s%s\n",
                    merged.shard_parts, first->shard_count, passes, first->passes_total, missing,
                    first->shard_count - merged.shard_parts > 16 ? ", ..." : "");
        }
        if (ok && !log_quiet())
            printf("merged %d part%s (%lld of %d passes, %lld photons) -> %s\n", cli->npositional,
                   cli->npositional == 1 ? "" : "s", passes, first->passes_total, emitted, cli->output);
    }
    image_destroy(&out);
    image_destroy(&out_caustic);
    free(sum);
    free(sum_caustic);
    free(have);
    free(first);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
