#include "app/cli.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/log.h"

static const char usage_text[] =
"usage:\n"
    "  caustica render SCENE.lua [-o OUT.png|OUT.pfm|OUT.hdr|OUT.exr] [--aov pass.output]... [--frame N] [--size WxH]\n"
    "                  [--timings] [--set k=v ...]\n"
    "  caustica record SCENE.lua -o DIR|PATTERN [--frames SET] [--shard i/n] [--overwrite] [--size WxH]\n"
    "                  [--video OUT.mp4|OUT.gif] [--set k=v ...]   (SET: 1-100, 0-119:10, 1,5,10-20, A:B or a count;\n"
    "                  PATTERN: out/shot_####.png or .pfm; frames already there are skipped)\n"
    "  caustica run SCENE.lua [--frames N] [--screenshot OUT.png] [--keys space,left,right,s,r] [--size WxH]\n"
    "                [--set k=v ...]   (keys: space pauses, left/right step, s screenshot, r reload)\n"
    "  caustica test [PATH ...] [--update-refs] [--filter TEXT] [--report OUT.html]\n"
    "  caustica info SCENE.lua [--size WxH] [--no-render] [--set k=v ...]\n"
    "  caustica reference SCENE.lua -o OUT.pfm|OUT.hdr [--frame N] [--size WxH] [--photons N] [--spp N]\n"
    "                     [--time-budget S] [--report] [--aov tir|exit] [--seed S] [--radius R]\n"
    "                     [--antialias] [--set k=v ...]   (--antialias: pixel means, not pixel centres)\n"
    "  caustica compare A B [--mask M]\n"
    "  caustica convert IN.pfm|IN.hdr OUT.png [--exposure E]\n"
    "  caustica help [passes | PASS] [--markdown]\n"
    "  caustica bench SCENE.lua [--sweep key=v1,v2,...]... [--frames N] [--frame F] [--size WxH] [-o DIR]\n"
    "                 [--ref-photons N] [--ref-spp N] [--ref-antialias] [--error-frames K] [--set k=v ...]\n"
    "                 (--sweep technique=all|NAME,...: every technique the scene's `techniques` table declares)\n"
    "  caustica choose SCENE.lua --error E | --time MS [--size WxH] [-o DIR] [--ref-photons N] [--ref-spp N]\n"
    "                  [--ref-antialias] [--frames N] [--error-frames K] [--cached] [--set k=v ...]\n"
    "                  (reads the sweep from DIR's bench cache, or runs it; DIR: bench; --cached: never runs it)\n"
    "options for every verb: --backend osmesa|egl, --trusted (no sandbox), --verbose,\n"
    "  --script-timeout S (per call into the script, default 30, 0 = none),\n"
    "  --script-memory MB (Lua heap, default 4096, 0 = none),\n"
    "  --allow-read DIR (repeatable), --allow-write DIR (folders a sandboxed script may also use)\n";

void cli_usage(FILE *out) { fputs(usage_text, out); }

void cli_usage_verb(FILE *out, const char *verb)
{
    char prefix[64];
    snprintf(prefix, sizeof prefix, "  caustica %s ", verb);
    fputs("usage:\n", out);
    bool in_verb = false;
    for (const char *line = usage_text; *line;) {
        const char *end = strchr(line, '\n');
        size_t n = end ? (size_t)(end - line + 1) : strlen(line);
        bool verb_line = strncmp(line, "  caustica ", 11) == 0;
        bool options = strncmp(line, "options", 7) == 0 || (strncmp(line, "  --", 4) == 0);
        if (verb_line)
            in_verb = strncmp(line, prefix, strlen(prefix)) == 0;
        else if (strncmp(line, "    ", 4) != 0)
            in_verb = false;
        if (in_verb || options)
            fwrite(line, 1, n, out);
        line += n;
    }
}

void cli_print_error(const struct error *err) { fprintf(stderr, "caustica: %s\n", err->message); }

static bool parse_int(const char *s, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < -1000000000L || v > 1000000000L)
        return false;
    *out = (int)v;
    return true;
}

static bool usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "caustica: ");
    fprintf(stderr, fmt, arg);
    fputc('\n', stderr);
    cli_usage(stderr);
    return false;
}

bool cli_parse(int argc, char **argv, struct app *app, struct cli *cli)
{
    memset(cli, 0, sizeof *cli);
    cli->frames_from = cli->frames_to = -1;
    cli->max_error = cli->max_time_ms = -1.0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *next = i + 1 < argc ? argv[i + 1] : NULL;
#define NEED_VALUE()                                        \
    do {                                                    \
        if (!next)                                          \
            return usage_error("%s needs a value", a);      \
        i++;                                                \
    } while (0)
        if (strcmp(a, "-o") == 0 || strcmp(a, "--output") == 0) {
            NEED_VALUE();
            cli->output = next;
        } else if (strcmp(a, "--frame") == 0) {
            NEED_VALUE();
            if (!parse_int(next, &cli->frame) || cli->frame < 0)
                return usage_error("--frame needs a frame number >= 0, got '%s'", next);
        } else if (strcmp(a, "--frames") == 0) {
            NEED_VALUE();
            char message[300];
            if (!frame_set_parse(next, &cli->frame_set, message, sizeof message))
                return usage_error("%s", message);
            cli->frames_set = true;
            cli->frames_from = cli->frame_set.ranges[0].from;
            cli->frames_to = cli->frame_set.ranges[0].to;
            for (int k = 1; k < cli->frame_set.count; k++) {
                if (cli->frame_set.ranges[k].from < cli->frames_from)
                    cli->frames_from = cli->frame_set.ranges[k].from;
                if (cli->frame_set.ranges[k].to > cli->frames_to)
                    cli->frames_to = cli->frame_set.ranges[k].to;
            }
        } else if (strcmp(a, "--video") == 0) {
            NEED_VALUE();
            cli->video = next;
        } else if (strcmp(a, "--overwrite") == 0) {
            cli->overwrite = true;
        } else if (strcmp(a, "--shard") == 0) {
            NEED_VALUE();
            int used = 0;
            if (sscanf(next, "%d/%d%n", &cli->shard_index, &cli->shard_count, &used) != 2 || next[used] ||
                cli->shard_count < 1 || cli->shard_index < 0 || cli->shard_index >= cli->shard_count)
                return usage_error("--shard needs i/n with 0 <= i < n (e.g. $SLURM_ARRAY_TASK_ID/4), got '%s'", next);
        } else if (strcmp(a, "--size") == 0) {
            NEED_VALUE();
            if (sscanf(next, "%dx%d", &cli->width, &cli->height) != 2 || cli->width < 1 || cli->height < 1 ||
                cli->width > 16384 || cli->height > 16384)
                return usage_error("--size needs WxH (1..16384), got '%s'", next);
        } else if (strcmp(a, "--backend") == 0) {
            NEED_VALUE();
            if (!gl_backend_parse(next, &app->backend) || app->backend == GL_BACKEND_GLFW)
                return usage_error("--backend must be osmesa or egl, got '%s'", next);
        } else if (strcmp(a, "--set") == 0) {
            NEED_VALUE();
            struct error err;
            if (!lua_params_add(&cli->params, next, &err))
                return usage_error("%s", err.message);
        } else if (strcmp(a, "--screenshot") == 0) {
            NEED_VALUE();
            cli->screenshot = next;
        } else if (strcmp(a, "--keys") == 0) {
            NEED_VALUE();
            cli->keys = next;
        } else if (strcmp(a, "--mask") == 0) {
            NEED_VALUE();
            cli->mask = next;
        } else if (strcmp(a, "--filter") == 0) {
            NEED_VALUE();
            cli->filter = next;
        } else if (strcmp(a, "--photons") == 0) {
            NEED_VALUE();
            char *end;
            cli->photons = strtol(next, &end, 10);
            if (end == next || *end || cli->photons < 0 || cli->photons > 2000000000L)
                return usage_error("--photons needs a count >= 0, got '%s'", next);
        } else if (strcmp(a, "--spp") == 0) {
            NEED_VALUE();
            if (!parse_int(next, &cli->spp) || cli->spp < 1)
                return usage_error("--spp needs a count >= 1, got '%s'", next);
        } else if (strcmp(a, "--exposure") == 0) {
            NEED_VALUE();
            char *end;
            cli->exposure = strtod(next, &end);
            if (end == next || *end || !(cli->exposure > 0))
                return usage_error("--exposure needs a positive number, got '%s'", next);
        } else if (strcmp(a, "--time-budget") == 0 || strcmp(a, "--radius") == 0) {
            NEED_VALUE();
            char *end;
            double v = strtod(next, &end);
            if (end == next || *end || !(v > 0) || v > 1e9)
                return usage_error("this option needs a positive number, got '%s'", next);
            if (a[2] == 't')
                cli->time_budget = v;
            else
                cli->radius = v;
        } else if (strcmp(a, "--aov") == 0) {
            NEED_VALUE();
            /* `reference --aov tir|exit`: a debug output; `render/record --aov pass.output`: an EXR layer */
            if (strcmp(next, "tir") == 0)
                cli->aov = 1;
            else if (strcmp(next, "exit") == 0)
                cli->aov = 2;
            else if (strchr(next, '.') && cli->aov_count < 8)
                cli->aovs[cli->aov_count++] = next;
            else
                return usage_error("--aov needs tir or exit (reference) or pass.output (render, record to .exr), "
                                   "at most 8, got '%s'", next);
        } else if (strcmp(a, "--antialias") == 0 || strcmp(a, "--ref-antialias") == 0) {
            cli->antialias = true;
        } else if (strcmp(a, "--report") == 0) {
            /* `test --report out.html` names a page; `reference --report` is a switch */
            size_t n = next ? strlen(next) : 0;
            if (n > 5 && strcmp(next + n - 5, ".html") == 0) {
                cli->report_html = next;
                i++;
            } else {
                cli->report = true;
            }
        } else if (strcmp(a, "--seed") == 0) {
            NEED_VALUE();
            char *end;
            cli->seed = strtoll(next, &end, 10);
            if (end == next || *end || cli->seed < 0)
                return usage_error("--seed needs an integer >= 0, got '%s'", next);
        } else if (strcmp(a, "--sweep") == 0) {
            NEED_VALUE();
            if (cli->nsweeps >= 16 || !strchr(next, '=') || next[0] == '=')
                return usage_error("--sweep needs key=v1,v2,... (at most 16 sweeps), got '%s'", next);
            cli->sweeps[cli->nsweeps++] = next;
        } else if (strcmp(a, "--ref-photons") == 0) {
            NEED_VALUE();
            char *end;
            cli->ref_photons = strtol(next, &end, 10);
            if (end == next || *end || cli->ref_photons < 0)
                return usage_error("--ref-photons needs a count >= 0, got '%s'", next);
        } else if (strcmp(a, "--ref-spp") == 0) {
            NEED_VALUE();
            if (!parse_int(next, &cli->ref_spp) || cli->ref_spp < 8)
                return usage_error("--ref-spp needs a count >= 8, got '%s'", next);
        } else if (strcmp(a, "--error-frames") == 0) {
            NEED_VALUE();
            if (!parse_int(next, &cli->error_frames) || cli->error_frames < 1 || cli->error_frames > 16)
                return usage_error("--error-frames needs a count in 1..16, got '%s'", next);
        } else if (strcmp(a, "--error") == 0 || strcmp(a, "--time") == 0) {
            NEED_VALUE();
            char *end;
            double v = strtod(next, &end);
            if (end == next || *end || !(v > 0) || v > 1e12)
                return usage_error(strcmp(a, "--error") == 0 ? "--error needs a relative error > 0 (e.g. 0.1), got '%s'"
                                                             : "--time needs milliseconds a frame > 0, got '%s'", next);
            if (strcmp(a, "--error") == 0)
                cli->max_error = v;
            else
                cli->max_time_ms = v;
        } else if (strcmp(a, "--timings") == 0) {
            cli->timings = true;
        } else if (strcmp(a, "--update-refs") == 0) {
            cli->update_refs = true;
        } else if (strcmp(a, "--cached") == 0) {
            cli->cached_only = true;
        } else if (strcmp(a, "--no-render") == 0) {
            cli->no_render = true;
        } else if (strcmp(a, "--script-timeout") == 0 || strcmp(a, "--script-memory") == 0) {
            NEED_VALUE();
            char *end;
            double v = strtod(next, &end);
            if (end == next || *end || !(v >= 0) || v > 1e9)
                return usage_error("this option needs a number >= 0 (0 = no limit), got '%s'", next);
            if (strcmp(a, "--script-timeout") == 0)
                app->script_timeout = v;
            else
                app->script_memory = v * 1024.0 * 1024.0;
        } else if (strcmp(a, "--allow-read") == 0) {
            NEED_VALUE();
            if (app->allow_read_count >= (int)(sizeof app->allow_read / sizeof app->allow_read[0]))
                return usage_error("at most 8 --allow-read folders (%s)", next);
            app->allow_read[app->allow_read_count++] = next;
        } else if (strcmp(a, "--allow-write") == 0) {
            NEED_VALUE();
            app->allow_write = next;
        } else if (strcmp(a, "--trusted") == 0) {
            app->trusted = true;
        } else if (strcmp(a, "--verbose") == 0 || strcmp(a, "-v") == 0) {
            log_set_verbose(true);
        } else if (a[0] == '-' && a[1]) {
            return usage_error("unknown option '%s'", a);
        } else {
            if (cli->npositional >= 64)
                return usage_error("too many arguments (%s)", a);
            cli->positional[cli->npositional++] = a;
        }
#undef NEED_VALUE
    }
    return true;
}
