/* `caustica reference`: the ground truth of one frame as linear radiance
 * (PFM or Radiance HDR). */
#include <stdio.h>

#include "app/cli.h"
#include "core/fileio.h"
#include "reference/reference.h"
#include "reference/reference_part.h"

int cmd_reference(struct app *app, struct cli *cli)
{
    if (cli->npositional != 1 || !cli->output) {
        fprintf(stderr, "caustica: reference needs one scene script and -o OUT.pfm\n");
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    int status = cli_check_radiance_output(cli, "the reference");
    if (status != 0)
        return status;
    struct error err;
    struct session_options so = {.script = cli->positional[0], .params = cli->params, .width = cli->width,
                                 .height = cli->height, .fps = cli->fps};
    struct session *s;
    if (!session_open(app, &so, &s, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    struct ref_options o;
    ref_options_default(&o);
    if (cli->photons >= 0) /* (0: no photons, no caustics: the eye paths alone) */
        o.photons = cli->photons;
    if (cli->spp > 0)
        o.iterations = cli->spp;
    if (cli->time_budget > 0) {
        o.time_budget = cli->time_budget;
        if (cli->spp <= 0)
            o.iterations = 1 << 30; /* until the budget is spent */
    }
    if (cli->shard_count > 0) {
        if (cli->time_budget > 0 || cli->aov) {
            fprintf(stderr, "caustica: reference --shard renders a fixed set of passes: not with %s\n",
                    cli->time_budget > 0 ? "--time-budget (the shards' passes would not add up)" : "--aov");
            session_close(s);
            return EXIT_USAGE;
        }
        o.shard_index = cli->shard_index;
        o.shard_count = cli->shard_count;
    }
    if (cli->seed > 0)
        o.seed = (uint64_t)cli->seed;
    o.initial_radius = cli->radius;
    o.progress = true;
    o.report = cli->report;
    o.aov = (enum ref_aov)cli->aov;
    o.antialias = cli->antialias;
    o.tessellated = cli->tessellated;
    struct image img = {0};
    struct ref_stats st = {0};
    bool ok;
    if (image_path_is_exr(cli->output) && o.aov == REF_AOV_NONE) {
        /* EXR: the image, its caustic part as the layer "caustic", and the header a compositor reads */
        struct image caustic = {0};
        struct image_layer layer = {.name = "caustic", .image = &caustic};
        struct image_exr_info info;
        ok = session_reference_parts(s, cli->frame, &o, &img, &caustic, &st, &err);
        session_exr_info(s, &info);
        info.renderer = "caustica reference (CPU, progressive photon mapping)";
        ok = ok && image_write_exr(cli->output, &img, &layer, 1, &info, &err);
        image_destroy(&caustic);
    } else {
        ok = session_reference(s, cli->frame, &o, &img, &st, &err) && image_write(cli->output, &img, &err);
    }
    if (ok && o.aov != REF_AOV_NONE)
        printf("%s: the %s output (two interfaces, traced exactly) -> %s\n", s->script,
               o.aov == REF_AOV_TIR ? "tir" : "exit", cli->output);
    else if (ok) {
        /* the noise estimate compares even and odd iterations: one has none */
        char noise[48];
        if (st.iterations > 1)
            snprintf(noise, sizeof noise, "noise ~%.2g%%", 100.0 * st.noise);
        else
            snprintf(noise, sizeof noise, "noise unknown (one iteration)");
        /* which estimator ran: a plain run's SPPM shrinks each pixel's radius
         * with its own photons; --shard's independent passes (what merge
         * averages) fix each pass's radius by its index. Both converge to
         * the same image; at a finite count they differ within the noise. */
        char estimator[96];
        if (o.shard_count > 0)
            snprintf(estimator, sizeof estimator, "by independent passes (shard %d/%d, radii fixed per pass)",
                     o.shard_index, o.shard_count);
        else
            snprintf(estimator, sizeof estimator, "by SPPM (radii shrunk per pixel)");
        printf("%s: %d iteration%s, %lld photons (%lld caustic), %.2f s on %d thread%s, %s, %s -> %s\n", s->script,
               st.iterations, st.iterations == 1 ? "" : "s", st.photons, st.caustic_photons, st.seconds, st.threads,
               st.threads == 1 ? "" : "s", noise, estimator, cli->output);
    }
    if (ok && o.shard_count > 0) {
        /* what caustica merge needs to weigh this part and to check that
         * parts belong together */
        struct reference_part part = {.frame = cli->frame, .width = img.width, .height = img.height,
                                      .seed = o.seed, .photons = o.photons, .passes_total = o.iterations,
                                      .shard_count = o.shard_count, .passes = st.passes, .photons_emitted = st.photons};
        snprintf(part.scene, sizeof part.scene, "%.1000s", s->script);
        part.shards[0] = o.shard_index;
        part.shard_parts = 1;
        ok = reference_part_write(cli->output, &part, &err);
    }
    image_destroy(&img);
    session_close(s);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
