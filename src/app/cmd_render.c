/* `caustica render` and `caustica record`. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/cli.h"
#include "core/fileio.h"
#include "core/log.h"
#include "graph/graph.h"

static bool open_session(struct app *app, struct cli *cli, const char *write_dir, struct session **s)
{
    struct session_options o = {.script = cli->positional[0], .params = cli->params, .width = cli->width,
                                .height = cli->height, .write_dir = write_dir};
    struct error err;
    if (!session_open(app, &o, s, &err)) {
        cli_print_error(&err);
        return false;
    }
    return true;
}

static void print_timings(const struct session *s)
{
    const struct graph *g = s->graph;
    double total = s->app->renderer.deform_ms;
    printf("%-16s %-22s %10s %6s %12s\n", "pass", "kind", "ms", "draws", "triangles");
    printf("%-16s %-22s %10.3f\n", "(geometry)", "morphs and deformers", s->app->renderer.deform_ms);
    for (int i = 0; i < g->count; i++) {
        const struct graph_entry *e = &g->entries[i];
        if (e->state != GRAPH_PASS_KEPT) {
            printf("%-16s %-22s %10s  (left out: %s)\n", e->pass->name, e->pass->desc->name, "-", e->reason);
            continue;
        }
        if (e->last_need != PASS_RUN)
            printf("%-16s %-22s %10s  (%s)\n", e->pass->name, e->pass->desc->name, "-", e->last_why);
        else
            printf("%-16s %-22s %10.3f %6ld %12ld\n", e->pass->name, e->pass->desc->name, e->last_ms, e->last_draws,
                   e->last_triangles);
        for (int k = 0; e->last_need == PASS_RUN && k < e->pass->stages.count; k++)
            printf("  %-14s %-22s %10.3f\n", e->pass->stages.names[k], "", e->pass->stages.ms[k]);
        if (e->last_need == PASS_RUN && e->pass->report[0])
            printf("  %s\n", e->pass->report);
        total += e->last_ms;
    }
    printf("%-16s %-22s %10.3f\n", "total", "", total);
}

int cmd_render(struct app *app, struct cli *cli)
{
    if (cli->npositional != 1) {
        fprintf(stderr, "caustica: render needs one scene script\n");
        cli_usage(stderr);
        return EXIT_USAGE;
    }
    const char *out = cli->output ? cli->output : "out.png";
    struct error err;
    if (!image_path_is_png(out) && !image_path_is_pfm(out) && !image_path_is_hdr(out)) {
        fprintf(stderr, "caustica: -o %s: the output must end in .png, .pfm or .hdr\n", out);
        return EXIT_USAGE;
    }
    /* Check the destination before any work, so a bad path costs nothing. */
    if (!path_check_writable_dir(out, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    char out_dir[4096];
    path_dirname(out, out_dir, sizeof out_dir);
    path_remove_stale_temporaries(out_dir);
    /* The script itself may write nowhere (--allow-write DIR aside): the
     * output image is written by caustica, not by the script. */
    struct session *s;
    if (!open_session(app, cli, NULL, &s))
        return EXIT_SCENE_ERROR;
    bool ok = session_render(s, cli->frame, &err);
    if (ok && cli->timings) {
        /* Time a second, fresh run of the frame: the first paid for shader
         * compilation, and rendering the same frame again would only reuse
         * what did not change (shadow maps). */
        ok = session_reload(s, &err) && session_render(s, cli->frame, &err);
    }
    ok = ok && session_write_image(s, out, &err);
    if (ok && cli->timings) {
        printf("%s frame %d at %dx%d on %s (%s)\n", s->script, cli->frame, s->width, s->height,
               gl_backend_name(app->backend), app->gl ? app->gl->renderer : "?");
        print_timings(s);
    }
    session_close(s);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    /* Without -o the user did not say where: say it (always). */
    if (!cli->output && !cli->timings)
        printf("wrote %s\n", out);
    else if (!cli->timings)
        log_info("wrote %s", out);
    return 0;
}

int cmd_record(struct app *app, struct cli *cli)
{
    if (cli->npositional != 1 || !cli->output) {
        fprintf(stderr, "caustica: record needs one scene script and -o DIR\n");
        cli_usage(stderr);
        return EXIT_USAGE;
    }
    struct error err;
    bool existed = file_exists(cli->output);
    if (!dir_ensure(cli->output, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    /* An earlier record killed mid-write left its temporaries here. */
    int stale = path_remove_stale_temporaries(cli->output);
    if (stale)
        log_info("removed %d stale temporary file%s of an earlier run from %s", stale, stale == 1 ? "" : "s",
                 cli->output);
    struct session *s;
    if (!open_session(app, cli, app->allow_write ? app->allow_write : cli->output, &s)) {
        if (!existed)
            rmdir(cli->output); /* made for this run, and still empty: nothing left behind */
        return EXIT_SCENE_ERROR;
    }
    int from = cli->frames_set ? cli->frames_from : 0;
    int to = cli->frames_set ? cli->frames_to : s->frames - 1;
    int total = to - from + 1;
    bool tty = isatty(STDERR_FILENO);
    double start = log_now();
    bool ok = true;
    for (int f = from; f <= to && ok; f++) {
        char path[4200];
        snprintf(path, sizeof path, "%s/frame_%04d.png", cli->output, f);
        /* Each PNG is written to a temporary file and renamed into place. */
        ok = session_render(s, f, &err) && session_write_image(s, path, &err);
        int done = f - from + 1;
        double elapsed = log_now() - start;
        double fps = elapsed > 0 ? done / elapsed : 0;
        if (tty) {
            fprintf(stderr, "\rframe %d/%d  %.1f fps  %.0f s left   ", done, total, fps,
                    fps > 0 ? (total - done) / fps : 0.0);
            fflush(stderr);
        }
    }
    if (tty)
        fputc('\n', stderr);
    session_close(s);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    printf("wrote %d frames to %s/frame_%04d.png .. frame_%04d.png\n", total, cli->output, from, to);
    return 0;
}
