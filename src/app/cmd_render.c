/* `caustica render` and `caustica record`. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/cli.h"
#include "app/frame_set.h"
#include "app/video.h"
#include "core/fileio.h"
#include "core/log.h"
#include "graph/graph.h"

static bool open_session(struct app *app, struct cli *cli, const char *write_dir, struct session **s)
{
    struct session_options o = {.script = cli->positional[0], .params = cli->params, .width = cli->width,
                                .height = cli->height, .write_dir = write_dir, .frame_count = cli->frame_count,
                                .fps = cli->fps};
    struct error err;
    if (!session_open(app, &o, s, &err)) {
        cli_print_error(&err);
        return false;
    }
    for (int i = 0; i < cli->aov_count; i++)
        (*s)->aovs[i] = cli->aovs[i];
    (*s)->aov_count = cli->aov_count;
    (*s)->exr_half = cli->half;
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
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    const char *out = cli->output ? cli->output : "out.png";
    struct error err;
    if (!image_path_is_display(out) && !image_path_is_pfm(out) && !image_path_is_hdr(out) && !image_path_is_exr(out)) {
        fprintf(stderr, "caustica: -o %s: the output must end in .png, .jpg, .tif, .pfm, .hdr or .exr\n", out);
        return EXIT_USAGE;
    }
    if (cli->half && !image_path_is_exr(out)) {
        fprintf(stderr, "caustica: --half: half floats are for an EXR output (-o %s)\n", out);
        return EXIT_USAGE;
    }
    if (cli->aov_count && !image_path_is_exr(out)) {
        fprintf(stderr, "caustica: --aov: extra layers need an EXR output (-o %s)\n", out);
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
    struct gl_program_lookups lookups = {0, 0};
    bool ok = session_render(s, cli->frame, &err);
    if (ok && cli->timings) {
        /* Time a second, fresh run of the frame: the first paid for shader
         * compilation, and rendering the same frame again would only reuse
         * what did not change (shadow maps). */
        ok = session_reload(s, &err);
        struct gl_program_lookups before = gl_program_lookups_so_far();
        ok = ok && session_render(s, cli->frame, &err);
        struct gl_program_lookups after = gl_program_lookups_so_far();
        lookups.uniforms = after.uniforms - before.uniforms;
        lookups.units = after.units - before.units;
    }
    ok = ok && session_write_image(s, out, &err);
    if (ok && cli->timings) {
        printf("%s frame %d at %dx%d on %s (%s)\n", s->script, cli->frame, s->width, s->height,
               gl_backend_name(app->backend), app->gl ? app->gl->renderer : "?");
        print_timings(s);
        printf("look-ups by name this frame: %llu uniform locations, %llu sampler, image and block units\n",
               lookups.uniforms, lookups.units);
    }
    session_close(s);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    /* Say where it went (a farm's log, and a user who gave no -o). */
    if (!log_quiet())
        printf("wrote %s\n", out);
    return 0;
}

/* Removes the folders dir_ensure_all made for this run (from `dir` up to
 * `created`), each only while empty. */
static void remove_created_folders(const char *dir, const char *created)
{
    if (!created[0])
        return;
    char path[4096];
    snprintf(path, sizeof path, "%s", dir);
    for (;;) {
        if (rmdir(path) != 0 || strcmp(path, created) == 0)
            return;
        char *slash = strrchr(path, '/');
        if (!slash || slash == path)
            return;
        *slash = '\0';
    }
}

/* record's options that do not go together (EXIT_USAGE), or 0. */
static int record_check_options(const struct cli *cli)
{
    if (cli->npositional != 1 || !cli->output) {
        fprintf(stderr, "caustica: record needs one scene script and -o DIR or -o PATTERN (out/shot_####.png)\n");
        cli_usage_hint(cli->verb);
        return EXIT_USAGE;
    }
    if (cli->half && !image_path_is_exr(cli->output)) {
        fprintf(stderr, "caustica: --half: half floats are for EXR frames (-o %s)\n", cli->output);
        return EXIT_USAGE;
    }
    if (cli->aov_count && !image_path_is_exr(cli->output)) {
        fprintf(stderr, "caustica: --aov: extra layers need an EXR pattern (-o 'out/f_####.exr')\n");
        return EXIT_USAGE;
    }
    if (cli->video && !video_path_supported(cli->video)) {
        fprintf(stderr, "caustica: --video %s: a video must end in .mp4 or .gif\n", cli->video);
        return EXIT_USAGE;
    }
    if (cli->video && cli->shard_count > 0) {
        fprintf(stderr, "caustica: --video with --shard would encode only this shard's frames; run record again "
                        "without --shard once every shard is done (the frames on disk are skipped) to encode them all\n");
        return EXIT_USAGE;
    }
    return 0;
}

/* -o DIR writes DIR/frame_####.png; -o out/shot_####.png names each file
 * by its frame (a run of # is the zero-padded frame number; %04d is
 * taken as ####, and out/shot.png, which every frame would overwrite,
 * as out/shot_####.png). */
static int record_output(const struct cli *cli, char *output, size_t output_size, char *dir, size_t dir_size)
{
    char note[4400];
    if (!output_pattern_normalize(cli->output, output, output_size, note, sizeof note)) {
        fprintf(stderr, "caustica: -o %s: the path is too long\n", cli->output);
        return EXIT_USAGE;
    }
    if (note[0] && !log_quiet())
        fprintf(stderr, "caustica: %s\n", note);
    bool pattern = output_pattern_is_pattern(output);
    if (pattern) {
        if (!image_path_is_display(output) && !image_path_is_pfm(output) && !image_path_is_hdr(output) &&
            !image_path_is_exr(output)) {
            fprintf(stderr, "caustica: -o %s: a frame pattern must end in .png, .jpg, .tif, .pfm, .hdr or .exr\n",
                    cli->output);
            return EXIT_USAGE;
        }
        if (strchr(output, '/') && strchr(strchr(output, '#'), '/')) {
            fprintf(stderr, "caustica: -o %s: the # run must be in the file name, not in a folder\n", cli->output);
            return EXIT_USAGE;
        }
        path_dirname(output, dir, dir_size);
    } else {
        snprintf(dir, dir_size, "%s", output);
    }
    return 0;
}

/* The frames to render: the set given (in order, each once), or the
 * script's; NULL (said) where one is past the script's last frame. */
static int *record_frames(const struct cli *cli, const struct session *s, int *count)
{
    int *frames;
    *count = 0;
    if (cli->frames_set) {
        frames = frame_set_list(&cli->frame_set, count);
    } else {
        *count = s->frames;
        frames = malloc((size_t)(*count > 0 ? *count : 1) * sizeof *frames);
        for (int f = 0; frames && f < *count; f++)
            frames[f] = f;
    }
    if (!frames) {
        fprintf(stderr, "caustica: out of memory for the list of frames\n");
        return NULL;
    }
    /* The whole set checked before the first frame: not two frames, then an error. */
    for (int k = 0; k < *count; k++) {
        if (frames[k] >= s->frames) {
            fprintf(stderr, "caustica: --frames: frame %d is past the script's last frame %d (it returns frames = %d; "
                            "raise it, or ask for frames up to %d)\n", frames[k], s->frames - 1, s->frames,
                    s->frames - 1);
            free(frames);
            return NULL;
        }
    }
    /* A shard of a farm's array job: every n-th frame of the set, from the
     * i-th (interleaved, so each shard spans the whole animation). */
    if (cli->shard_count > 0) {
        int kept = 0;
        for (int k = 0; k < *count; k++)
            if (k % cli->shard_count == cli->shard_index)
                frames[kept++] = frames[k];
        *count = kept;
    }
    return frames;
}

/* The video preview: every frame of the set, written now or before. */
static bool record_video(const struct cli *cli, const char *output, const int *frames, int count, double video_fps,
                         struct error *err)
{
    char **paths = calloc((size_t)(count > 0 ? count : 1), sizeof *paths);
    int n = 0;
    for (int k = 0; paths && k < count; k++) {
        char path[4200];
        if (output_pattern_path(output, frames[k], path, sizeof path) && file_exists(path))
            paths[n++] = strdup(path);
    }
    bool ok = paths && video_encode((const char *const *)paths, n, video_fps, cli->video, cli->crf, err);
    if (!paths)
        error_set(err, "out of memory");
    for (int k = 0; paths && k < n; k++)
        free(paths[k]);
    free(paths);
    if (ok)
        printf("wrote %s (%d frame%s at %g fps)\n", cli->video, n, n == 1 ? "" : "s", video_fps);
    return ok;
}

int cmd_record(struct app *app, struct cli *cli)
{
    int rc = record_check_options(cli);
    if (rc)
        return rc;
    struct error err;
    char output[4096], dir[4096];
    if ((rc = record_output(cli, output, sizeof output, dir, sizeof dir)) != 0)
        return rc;
    char created[4096];
    if (!dir_ensure_all(dir, created, sizeof created, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    /* An earlier record killed mid-write left its temporaries here. */
    int stale = path_remove_stale_temporaries(dir);
    if (stale)
        log_info("removed %d stale temporary file%s of an earlier run from %s", stale, stale == 1 ? "" : "s", dir);
    struct session *s;
    if (!open_session(app, cli, app->allow_write ? app->allow_write : dir, &s)) {
        remove_created_folders(dir, created); /* made for this run, still empty: nothing left behind */
        return EXIT_SCENE_ERROR;
    }
    int count = 0;
    int *frames = record_frames(cli, s, &count);
    if (!frames) {
        session_close(s);
        remove_created_folders(dir, created);
        return EXIT_SCENE_ERROR;
    }
    bool tty = isatty(STDERR_FILENO);
    double start = log_now();
    bool ok = true;
    int written = 0, skipped = 0;
    double video_fps = s->fps;
    char first[4200] = "", last[4200] = "";
    for (int k = 0; k < count && ok; k++) {
        char path[4200];
        if (!output_pattern_path(output, frames[k], path, sizeof path)) {
            ok = error_set(&err, "-o %s: the path of frame %d is too long", cli->output, frames[k]);
            break;
        }
        /* Resume: a frame whose file is there was finished by an earlier run
         * (files are written to a temporary and renamed into place). */
        if (!cli->overwrite && file_exists(path)) {
            skipped++;
            continue;
        }
        double frame_start = log_now();
        ok = session_render(s, frames[k], &err) && session_write_image(s, path, &err);
        if (!ok)
            break;
        if (!written)
            snprintf(first, sizeof first, "%s", path);
        snprintf(last, sizeof last, "%s", path);
        written++;
        double elapsed = log_now() - start;
        double fps = elapsed > 0 ? written / elapsed : 0;
        if (log_quiet()) {
        } else if (tty) {
            fprintf(stderr, "\rframe %d (%d/%d)  %.1f fps  %.0f s left   ", frames[k], k + 1, count, fps,
                    fps > 0 ? (count - k - 1) / fps : 0.0);
            fflush(stderr);
        } else {
            /* off a terminal (a farm's log): one line a frame on stdout, as it
             * is written (stderr keeps errors and warnings only) */
            printf("frame %d (%d/%d) %.2f s -> %s\n", frames[k], k + 1, count, log_now() - frame_start, path);
            fflush(stdout);
        }
    }
    if (tty && !log_quiet() && written)
        fputc('\n', stderr);
    session_close(s);
    if (ok && cli->video)
        ok = record_video(cli, output, frames, count, video_fps, &err);
    free(frames);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    if (written && !log_quiet())
        printf("wrote %d frame%s: %s .. %s\n", written, written == 1 ? "" : "s", first, last);
    if (skipped && !log_quiet())
        printf("skipped %d frame%s already written (--overwrite renders them again)\n", skipped,
               skipped == 1 ? "" : "s");
    if (!written && !skipped)
        printf("no frames to render (the shard or the set is empty)\n");
    return 0;
}
