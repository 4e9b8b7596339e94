/* The command line: one table of options says which verbs take each, what
 * its value is, its meaning, default and limits; the parser, the usage
 * errors and `VERB --help` all read it. GNU conventions: `--opt value` or
 * `--opt=value`, `--` ends the options, an abbreviation is refused with the
 * full name it stands for. */
#include "app/cli.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/fileio.h"
#include "core/log.h"
#include "core/suggest.h"
#include "io/image.h"

enum {
    VB_RENDER = 1u << 0, VB_RECORD = 1u << 1, VB_RUN = 1u << 2, VB_TEST = 1u << 3, VB_INFO = 1u << 4,
    VB_REFERENCE = 1u << 5, VB_COMPARE = 1u << 6, VB_CONVERT = 1u << 7, VB_BENCH = 1u << 8, VB_CHOOSE = 1u << 9,
    VB_MERGE = 1u << 10,
    VB_SCENE = VB_RENDER | VB_RECORD | VB_RUN | VB_INFO | VB_REFERENCE | VB_BENCH | VB_CHOOSE,
    VB_ALL = 0x7ffu,
};

static const struct cli_verb {
    const char *name;
    unsigned bit;
    const char *synopsis; /* after "caustica VERB " */
    const char *summary;
} cli_verbs[] = {
    {"render", VB_RENDER, "SCENE.lua [-o OUT.png|OUT.pfm|OUT.hdr|OUT.exr] [options]",
     "renders one frame of a scene script offscreen"},
    {"record", VB_RECORD, "SCENE.lua -o DIR|PATTERN [options]",
     "renders frames of the animation to numbered images (frames already there are skipped)"},
    {"run", VB_RUN, "SCENE.lua [options]",
     "opens a window and plays the scene (space pauses, left/right step, s screenshot, r reload)"},
    {"test", VB_TEST, "[PATH ...] [options]", "runs regression tests (Lua files of caustica.test cases)"},
    {"info", VB_INFO, "SCENE.lua [options]", "prints the scene, the render graph (with the blocks it adds) and lint"},
    {"reference", VB_REFERENCE, "SCENE.lua -o OUT.pfm|OUT.hdr|OUT.exr [options]",
     "renders the exact ground truth on the CPU (progressive photon mapping)"},
    {"compare", VB_COMPARE, "A B [A_NEXT B_NEXT] [options]",
     "prints the error of image A against image B: rmse, rel_rmse (over B's RMS), psnr, ssim, max, nan, and "
     "log_rmse (of log(1 + value): robust to a few hot pixels); with the next frames of both, flicker (the error "
     "of A's change to A_NEXT against B's to B_NEXT, docs/TEMPORAL.md)"},
    {"merge", VB_MERGE, "PART... -o OUT.pfm|OUT.hdr|OUT.exr",
     "averages the parts of a reference rendered with --shard (each PART beside its PART.part) into the estimate "
     "one run of all their passes makes: that of `reference --shard 0/1` (independent passes, each pass's radii "
     "fixed by its index), not of a plain `reference` (SPPM, radii shrunk per pixel): the two converge to the same "
     "image but differ within their noise at a finite count"},
    {"convert", VB_CONVERT, "IN OUT [options]",
     "converts an image: reads .png, .pfm, .hdr, .exr (IN.exr:layer for one layer); writes .png, .pfm, .hdr, .exr"},
    {"bench", VB_BENCH, "SCENE.lua [--sweep key=v1,v2,...]... [options]",
     "times variants of a scene and measures their error against the reference"},
    {"choose", VB_CHOOSE, "SCENE.lua --error E | --time MS [--flicker F] [options]",
     "picks the fastest technique under an error, or the most accurate under a frame time"},
};


static const struct cli_option {
    const char *name, *alias; /* --name, and a short form or NULL */
    const char *value;        /* what follows, NULL for a switch */
    unsigned verbs;
    const char *help;         /* meaning; default; limits */
} cli_options[] = {
    {"--output", "-o", "OUT", VB_RENDER,
     "the image: .png (8-bit sRGB, tone-mapped), .pfm, .hdr or .exr (linear); default out.png; its folder must "
     "exist"},
    {"--output", "-o", "DIR|PATTERN", VB_RECORD,
     "a folder (frames as DIR/frame_0000.png), or a pattern such as out/f_####.png (.png, .pfm, .hdr, .exr); "
     "required"},
    {"--output", "-o", "OUT", VB_REFERENCE, "the image, .pfm, .hdr or .exr (linear radiance); required"},
    {"--output", "-o", "OUT", VB_MERGE, "the merged image, .pfm, .hdr or .exr (and OUT.part beside it); required"},
    {"--output", "-o", "DIR", VB_BENCH | VB_CHOOSE,
     "the folder of results (results.md, results.csv, plot.svg) and cached ground truths; default bench"},
    {"--frame", NULL, "N", VB_RENDER | VB_REFERENCE, "the frame to render; default 0; >= 0"},
    {"--frame", NULL, "F", VB_BENCH, "the first frame timed; default 0; >= 0"},
    {"--frames", NULL, "SET", VB_RECORD,
     "the frames, as 1-100, 0-119:10 (every 10th), 1,5,10-20, A:B or a count N (0..N-1); default the whole "
     "animation"},
    {"--frames", NULL, "N", VB_RUN, "play N frames, then exit (default: until the window closes)"},
    {"--frames", NULL, "N", VB_BENCH | VB_CHOOSE,
     "frames timed per variant, the median taken (default 5; 3 with a technique sweep; at most 1024)"},
    {"--frame-count", NULL, "N", VB_RENDER | VB_RECORD | VB_RUN,
     "the animation's length in frames instead of the script's `frames` (1..10000000): record renders 0..N-1"},
    {"--fps", NULL, "N", VB_RENDER | VB_RECORD | VB_RUN | VB_INFO | VB_REFERENCE,
     "frames a second instead of the script's `fps` (0.01..10000; a glTF file with no script plays its animations "
     "at it, its frame count following)"},
    {"--video", NULL, "OUT.mp4|OUT.gif", VB_RECORD,
     "also encode every frame of the set with ffmpeg (H.264, BT.709/sRGB tagged, an odd size padded by a pixel; "
     "not with --shard)"},
    {"--crf", NULL, "Q", VB_RECORD, "the video's quality, 0 (lossless) .. 51 (worst); default 18"},
    {"--overwrite", NULL, NULL, VB_RECORD, "render frames whose file exists (default: skip them)"},
    {"--script", NULL, NULL, VB_INFO,
     "for a glTF file: print the Lua scene script it is rendered with (its camera, lights, floor, graph and "
     "animations), to save and edit"},
    {"--shard", NULL, "i/n", VB_RECORD,
     "render every n-th frame of the set from the i-th, 0 <= i < n (one job of an array)"},
    {"--shard", NULL, "i/n", VB_REFERENCE,
     "render the independent passes p of --spp with p % n == i (probabilistic progressive photon mapping: passes "
     "share no state), writing OUT and OUT.part for caustica merge; 0/1 renders all of them in one run; not with "
     "--time-budget"},
    {"--size", NULL, "WxH", VB_SCENE,
     "the image size in pixels, 1..16384 each (default: the script's size, else 512x512)"},
    {"--set", NULL, "NAME=VALUE", VB_SCENE,
     "a scene parameter, read by the script with c.param(NAME, default); repeatable"},
    {"--timings", NULL, NULL, VB_RENDER, "print each pass's GPU and CPU time"},
    {"--aov", NULL, "PASS.OUTPUT", VB_RENDER | VB_RECORD,
     "one more layer of an .exr output, e.g. shade.depth (repeatable, at most 8); `holdout`: the image over "
     "nothing (colour times coverage, the environment left out, alpha the coverage) for a compositor's plate"},
    {"--half", NULL, NULL, VB_RENDER | VB_RECORD,
     "an .exr output's R, G, B, A as 16-bit half floats, as compositors take a beauty pass (its layers, depth and "
     "objectId stay 32-bit); default 32-bit float"},
    {"--aov", NULL, "tir|exit", VB_REFERENCE,
     "a debug image instead of radiance: where light is trapped by total internal reflection, or leaves the "
     "glass"},
    {"--screenshot", NULL, "OUT.png", VB_RUN, "save the last frame shown"},
    {"--keys", NULL, "K,K,...", VB_RUN, "keys pressed on the first frame (space, left, right, s, r)"},
    {"--update-refs", NULL, NULL, VB_TEST, "write the reference images the tests compare with"},
    {"--filter", NULL, "TEXT", VB_TEST, "run only the cases whose name contains TEXT"},
    {"--report", NULL, "OUT.html", VB_TEST,
     "also write one self-contained page: every case, and each failed comparison's images (rendered, compared "
     "with, difference) side by side with a flip view"},
    {"--junit", NULL, "OUT.xml", VB_TEST, "also write the results as JUnit XML (what CI servers read)"},
    {"--report", NULL, NULL, VB_REFERENCE, "print the noise estimate of each iteration"},
    {"--no-render", NULL, NULL, VB_INFO, "describe the graph without rendering a frame"},
    {"--photons", NULL, "N", VB_REFERENCE, "photons per iteration (default 200000; >= 0)"},
    {"--spp", NULL, "N", VB_REFERENCE,
     "iterations of progressive photon mapping (default 16; >= 1; with --time-budget, the most)"},
    {"--time-budget", NULL, "S", VB_REFERENCE,
     "stop after S seconds (> 0; default no budget)"},
    {"--seed", NULL, "S", VB_REFERENCE, "the random seed (default 1; >= 0)"},
    {"--radius", NULL, "R", VB_REFERENCE,
     "the initial gather radius in scene units (> 0; default from the scene's size)"},
    {"--antialias", NULL, NULL, VB_REFERENCE, "pixel means instead of pixel centres"},
    {"--tessellated", NULL, NULL, VB_REFERENCE,
     "trace the triangles of the spheres the script made (c.mesh.sphere), as the GPU draws them (default: the "
     "spheres themselves)"},
    {"--mask", NULL, "M", VB_COMPARE, "compare only where the mask image (.png, .pfm, .hdr, .exr) is non-zero"},
    {"--exposure", NULL, "E", VB_CONVERT, "multiply the colour by E before writing (> 0; default 1)"},
    {"--tonemap", NULL, "clamp|reinhard|aces", VB_CONVERT,
     "to a .png through the same tone mapping as render -o x.png with the script's tonemap (default: a plain "
     "clamp, without the renderer)"},
    {"--sweep", NULL, "KEY=V1,V2,...", VB_BENCH,
     "the values of one parameter to try (a scene parameter, or pass.param); technique=all|NAME,... tries the "
     "techniques the scene's `techniques` table declares; repeatable, at most 16"},
    {"--ref-photons", NULL, "N", VB_BENCH | VB_CHOOSE,
     "photons per iteration of the ground truth (default 100000)"},
    {"--truth", NULL, "FILE", VB_BENCH,
     "the ground truth from FILE (reference -o, or caustica merge's: .pfm, .hdr, .exr, its caustic region from the "
     "EXR's `caustic` layer) instead of rendering one: one scene (sweep pass parameters or techniques) and one "
     "error frame; a FILE.part's frame and size are checked"},
    {"--ref-spp", NULL, "N", VB_BENCH | VB_CHOOSE,
     "the longest reference run of the error-time curve, in iterations (default 8; >= 8); the ground truth "
     "runs 16 x N iterations unless --truth-spp says"},
    {"--truth-spp", NULL, "N", VB_BENCH | VB_CHOOSE,
     "the ground truth's iterations (default 16 x --ref-spp, 128; >= --ref-spp): fewer is faster and noisier, "
     "and bench reports the truth's own error beside the table"},
    {"--ref-antialias", NULL, NULL, VB_BENCH | VB_CHOOSE,
     "judge against a truth of pixel means (default: pixel centres)"},
    {"--ref-tessellated", NULL, NULL, VB_BENCH | VB_CHOOSE,
     "judge against a truth of the spheres' triangles, as the GPU draws them (default: the spheres themselves)"},
    {"--error-frames", NULL, "K", VB_BENCH | VB_CHOOSE,
     "the error is the mean over K frames spread over the animation (1..16; default 1, or 3 with a technique "
     "sweep)"},
    {"--error", NULL, "E", VB_CHOOSE, "the largest relative error accepted (> 0, e.g. 0.1)"},
    {"--time", NULL, "MS", VB_CHOOSE, "the milliseconds a frame may take (> 0)"},
    {"--flicker", NULL, "F", VB_CHOOSE,
     "the largest flicker accepted (> 0): the error of the frame-to-frame change, as bench measures it "
     "(docs/TEMPORAL.md)"},
    {"--cached", NULL, NULL, VB_CHOOSE, "read the bench cache only, never run the sweep"},
    {"--threads", NULL, "N", VB_REFERENCE | VB_BENCH | VB_CHOOSE | VB_TEST,
     "worker threads of the CPU reference, 1..1024 (default: the CPUs this process may use: its affinity "
     "mask, e.g. taskset or a Slurm cpuset, and its cgroup's CPU quota)"},
    {"--backend", NULL, "osmesa|egl", VB_ALL,
     "the GL context: osmesa (default; Mesa on the CPU) or egl (headless, a GPU where there is one)"},
    {"--trusted", NULL, NULL, VB_ALL,
     "run the script without the sandbox (it may then read and write anywhere)"},
    {"--verbose", "-v", NULL, VB_ALL, "log each step, and Lua tracebacks"},
    {"--quiet", "-q", NULL, VB_ALL, "no progress lines and no \"wrote ...\" (errors and warnings still)"},
    {"--script-timeout", NULL, "S", VB_ALL,
     "seconds one call into the script may take (default 30; 0 = no limit)"},
    {"--script-memory", NULL, "MB", VB_ALL,
     "the Lua heap's limit (default 4096; 0 = no limit)"},
    {"--allow-read", NULL, "DIR", VB_ALL,
     "a folder a sandboxed script may also read (repeatable, at most 8)"},
    {"--allow-write", NULL, "DIR", VB_ALL, "a folder a sandboxed script may also write"},
    {"--asset-path", NULL, "DIR", VB_ALL,
     "a folder c.asset searches before the project's assets (repeatable, at most 8; also CAUSTICA_ASSET_PATH, "
     "folders separated by ':')"},
};
#define CLI_OPTION_COUNT (sizeof cli_options / sizeof cli_options[0])
#define CLI_VERB_COUNT (sizeof cli_verbs / sizeof cli_verbs[0])

static const struct cli_verb *verb_find(const char *name)
{
    for (size_t i = 0; i < CLI_VERB_COUNT; i++)
        if (name && strcmp(cli_verbs[i].name, name) == 0)
            return &cli_verbs[i];
    return NULL;
}

bool cli_is_verb(const char *name) { return verb_find(name) != NULL; }

const char *cli_suggest_verb(const char *word)
{
    const char *names[CLI_VERB_COUNT + 1];
    for (size_t i = 0; i < CLI_VERB_COUNT; i++)
        names[i] = cli_verbs[i].name;
    names[CLI_VERB_COUNT] = "help";
    return suggest_nearest(word, names, CLI_VERB_COUNT + 1);
}

void cli_usage(FILE *out)
{
    fputs("usage: caustica VERB ARGUMENTS [options]   (caustica VERB --help: its options, defaults and limits)\n\n",
          out);
    for (size_t i = 0; i < CLI_VERB_COUNT; i++)
        fprintf(out, "  caustica %s %s\n      %s\n", cli_verbs[i].name, cli_verbs[i].synopsis, cli_verbs[i].summary);
    fputs("  caustica help [passes | PASS] [--markdown]\n      the passes and their parameters\n"
          "  caustica --version   (or -V, or version)\n", out);
}

/* Prints `text` wrapped at 100 columns, each line indented by `indent`. */
static void print_wrapped(FILE *out, const char *text, int indent, int first_column)
{
    int column = first_column;
    const char *p = text;
    while (*p) {
        const char *space = strchr(p, ' ');
        int word = space ? (int)(space - p) : (int)strlen(p);
        if (column > indent && column + 1 + word > 100) {
            fprintf(out, "\n%*s", indent, "");
            column = indent;
        } else if (column > indent) {
            fputc(' ', out);
            column++;
        }
        fwrite(p, 1, (size_t)word, out);
        column += word;
        p += word;
        while (*p == ' ')
            p++;
    }
    fputc('\n', out);
}

void cli_usage_verb(FILE *out, const char *verb)
{
    const struct cli_verb *v = verb_find(verb);
    if (!v)
        return;
    fprintf(out, "usage:\n  caustica %s %s\n\n%s.\n\noptions:\n", v->name, v->synopsis, v->summary);
    for (size_t i = 0; i < CLI_OPTION_COUNT; i++) {
        const struct cli_option *o = &cli_options[i];
        if (!(o->verbs & v->bit))
            continue;
        char head[96];
        int n = snprintf(head, sizeof head, "  %s%s%s%s%s", o->alias ? o->alias : "", o->alias ? ", " : "", o->name,
                         o->value ? " " : "", o->value ? o->value : "");
        fputs(head, out);
        if (n < 30) {
            fprintf(out, "%*s", 30 - n, "");
            n = 30;
        } else {
            fprintf(out, "\n%30s", "");
            n = 30;
        }
        print_wrapped(out, o->help, 30, n);
    }
}

void cli_print_error(const struct error *err) { fprintf(stderr, "caustica: %s\n", err->message); }

int cli_check_radiance_output(const struct cli *cli, const char *what)
{
    if (!image_path_is_pfm(cli->output) && !image_path_is_hdr(cli->output) && !image_path_is_exr(cli->output)) {
        fprintf(stderr, "caustica: -o %s: %s is linear radiance, write it as .pfm, .hdr or .exr\n", cli->output, what);
        return EXIT_USAGE;
    }
    struct error err;
    if (!path_check_writable_dir(cli->output, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}

void cli_usage_hint(const char *verb)
{
    if (verb && verb_find(verb))
        fprintf(stderr, "see `caustica %s --help`\n", verb);
    else
        fprintf(stderr, "see `caustica --help`\n");
}

static bool parse_int(const char *s, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < -1000000000L || v > 1000000000L)
        return false;
    *out = (int)v;
    return true;
}

/* "A<sep>B" as two ints, each through parse_int (overflow checked). */
static bool parse_int_pair(const char *s, char sep, int *a, int *b)
{
    const char *at = strchr(s, sep);
    char first[64];
    if (!at || (size_t)(at - s) >= sizeof first)
        return false;
    snprintf(first, sizeof first, "%.*s", (int)(at - s), s);
    return parse_int(first, a) && parse_int(at + 1, b);
}

static const char *usage_verb; /* the verb being parsed, for the hint */

static bool usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "caustica: ");
    fprintf(stderr, fmt, arg);
    fputc('\n', stderr);
    cli_usage_hint(usage_verb);
    return false;
}

/* The option `name` stands for (its long name or short alias), as the verb
 * takes it; another verb's entry when this verb does not; NULL when unknown. */
static const struct cli_option *option_find(const char *name, size_t len, unsigned verb_bit)
{
    const struct cli_option *other = NULL;
    for (size_t i = 0; i < CLI_OPTION_COUNT; i++) {
        const struct cli_option *o = &cli_options[i];
        if ((strlen(o->name) == len && strncmp(o->name, name, len) == 0) ||
            (o->alias && strlen(o->alias) == len && strncmp(o->alias, name, len) == 0)) {
            if (o->verbs & verb_bit)
                return o;
            other = o;
        }
    }
    return other;
}

/* An unknown option, and the nearest of those the verb takes. */
static bool unknown_option(const char *arg, size_t len, unsigned verb_bit)
{
    char name[128];
    snprintf(name, sizeof name, "%.*s", (int)(len < 120 ? len : 120), arg);
    const char *names[CLI_OPTION_COUNT];
    size_t count = 0;
    for (size_t i = 0; i < CLI_OPTION_COUNT; i++)
        if (cli_options[i].verbs & verb_bit)
            names[count++] = cli_options[i].name;
    const char *near = suggest_nearest(name, names, count);
    fprintf(stderr, "caustica: unknown option '%s'", name);
    if (near)
        fprintf(stderr, " (did you mean %s?)", near);
    fputc('\n', stderr);
    cli_usage_hint(usage_verb);
    return false;
}

static int usage_fail(const char *fmt, const char *arg)
{
    usage_error(fmt, arg);
    return -1;
}

/* The options of what is rendered and where it goes: 1 taken, 0 not one of them, -1 refused (said). */
static int output_file_option(const char *a, const char *next, struct app *app, struct cli *cli)
{
    if (strcmp(a, "--output") == 0) {
        cli->output = next;
    } else if (strcmp(a, "--frame") == 0) {
        if (!parse_int(next, &cli->frame) || cli->frame < 0)
            return usage_fail("--frame needs a frame number >= 0, got '%s'", next);
    } else if (strcmp(a, "--frames") == 0) {
        char message[300];
        if (!frame_set_parse(next, &cli->frame_set, message, sizeof message))
            return usage_fail("%s", message);
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
        cli->video = next;
    } else if (strcmp(a, "--overwrite") == 0) {
        cli->overwrite = true;
    } else if (strcmp(a, "--script") == 0) {
        cli->script = true;
    } else if (strcmp(a, "--shard") == 0) {
        /* 0/99999999999 is refused, not wrapped */
        if (!parse_int_pair(next, '/', &cli->shard_index, &cli->shard_count) || cli->shard_count < 1 || cli->shard_index < 0 || cli->shard_index >= cli->shard_count)
            return usage_fail("--shard needs i/n with 0 <= i < n (e.g. $SLURM_ARRAY_TASK_ID/4), got '%s'", next);
    } else if (strcmp(a, "--size") == 0) {
        if (!parse_int_pair(next, 'x', &cli->width, &cli->height) || cli->width < 1 || cli->height < 1 ||
            cli->width > 16384 || cli->height > 16384)
            return usage_fail("--size needs WxH (1..16384), got '%s'", next);
    } else if (strcmp(a, "--backend") == 0) {
        if (!gl_backend_parse(next, &app->backend) || app->backend == GL_BACKEND_GLFW)
            return usage_fail("--backend must be osmesa or egl, got '%s'", next);
    } else if (strcmp(a, "--set") == 0) {
        struct error err;
        if (!lua_params_add(&cli->params, next, &err))
            return usage_fail("%s", err.message);
    } else if (strcmp(a, "--screenshot") == 0) {
        cli->screenshot = next;
    } else if (strcmp(a, "--keys") == 0) {
        cli->keys = next;
    } else if (strcmp(a, "--mask") == 0) {
        cli->mask = next;
    } else if (strcmp(a, "--filter") == 0) {
        cli->filter = next;
    } else {
        return 0;
    }
    return 1;
}

/* The reference's and the images' options: 1 taken, 0 not one of them, -1 refused (said). */
static int reference_option(const char *a, const char *next, struct app *app, struct cli *cli)
{
    (void)app;
    if (strcmp(a, "--photons") == 0) {
        char *end;
        cli->photons = strtol(next, &end, 10);
        if (end == next || *end || cli->photons < 0 || cli->photons > 2000000000L)
            return usage_fail("--photons needs a count >= 0, got '%s'", next);
    } else if (strcmp(a, "--spp") == 0) {
        if (!parse_int(next, &cli->spp) || cli->spp < 1)
            return usage_fail("--spp needs a count >= 1, got '%s'", next);
    } else if (strcmp(a, "--exposure") == 0) {
        char *end;
        cli->exposure = strtod(next, &end);
        if (end == next || *end || !(cli->exposure > 0))
            return usage_fail("--exposure needs a positive number, got '%s'", next);
    } else if (strcmp(a, "--time-budget") == 0 || strcmp(a, "--radius") == 0) {
        char *end;
        double value = strtod(next, &end);
        if (end == next || *end || !(value > 0) || value > 1e9)
            return usage_fail("this option needs a positive number, got '%s'", next);
        if (a[2] == 't')
            cli->time_budget = value;
        else
            cli->radius = value;
    } else if (strcmp(a, "--aov") == 0) {
        /* `reference --aov tir|exit`: a debug output; `render/record --aov pass.output`: an EXR layer */
        if (strcmp(next, "tir") == 0)
            cli->aov = 1;
        else if (strcmp(next, "exit") == 0)
            cli->aov = 2;
        else if ((strchr(next, '.') || strcmp(next, "holdout") == 0) && cli->aov_count < 8)
            cli->aovs[cli->aov_count++] = next;
        else
            return usage_fail("--aov needs tir or exit (reference) or pass.output or holdout (render, record to "
                               ".exr), at most 8, got '%s'", next);
    } else if (strcmp(a, "--antialias") == 0 || strcmp(a, "--ref-antialias") == 0) {
        cli->antialias = true;
    } else if (strcmp(a, "--tessellated") == 0 || strcmp(a, "--ref-tessellated") == 0) {
        cli->tessellated = true;
    } else if (strcmp(a, "--report") == 0) {
        if (next)
            cli->report_html = next;
        else
            cli->report = true;
    } else if (strcmp(a, "--seed") == 0) {
        char *end;
        cli->seed = strtoll(next, &end, 10);
        if (end == next || *end || cli->seed < 0)
            return usage_fail("--seed needs an integer >= 0, got '%s'", next);
    } else {
        return 0;
    }
    return 1;
}

/* bench's, choose's and test's options: 1 taken, 0 not one of them, -1 refused (said). */
static int bench_option(const char *a, const char *next, struct app *app, struct cli *cli)
{
    (void)app;
    if (strcmp(a, "--sweep") == 0) {
        if (cli->nsweeps >= 16 || !strchr(next, '=') || next[0] == '=')
            return usage_fail("--sweep needs key=v1,v2,... (at most 16 sweeps), got '%s'", next);
        cli->sweeps[cli->nsweeps++] = next;
    } else if (strcmp(a, "--ref-photons") == 0) {
        char *end;
        cli->ref_photons = strtol(next, &end, 10);
        if (end == next || *end || cli->ref_photons < 0)
            return usage_fail("--ref-photons needs a count >= 0, got '%s'", next);
    } else if (strcmp(a, "--truth") == 0) {
        cli->truth = next;
    } else if (strcmp(a, "--ref-spp") == 0) {
        if (!parse_int(next, &cli->ref_spp) || cli->ref_spp < 8)
            return usage_fail("--ref-spp needs a count >= 8, got '%s'", next);
    } else if (strcmp(a, "--truth-spp") == 0) {
        if (!parse_int(next, &cli->truth_spp) || cli->truth_spp < 8 || cli->truth_spp > 1000000)
            return usage_fail("--truth-spp needs a count from 8 to 1000000, got '%s'", next);
    } else if (strcmp(a, "--error-frames") == 0) {
        if (!parse_int(next, &cli->error_frames) || cli->error_frames < 1 || cli->error_frames > 16)
            return usage_fail("--error-frames needs a count in 1..16, got '%s'", next);
    } else if (strcmp(a, "--error") == 0 || strcmp(a, "--time") == 0 || strcmp(a, "--flicker") == 0) {
        char *end;
        double value = strtod(next, &end);
        if (end == next || *end || !(value > 0) || value > 1e12)
            return usage_fail(strcmp(a, "--error") == 0 ? "--error needs a relative error > 0 (e.g. 0.1), got '%s'"
                               : strcmp(a, "--flicker") == 0 ? "--flicker needs a relative flicker > 0 (e.g. 0.05), got '%s'"
                                                             : "--time needs milliseconds a frame > 0, got '%s'", next);
        if (strcmp(a, "--error") == 0)
            cli->max_error = value;
        else if (strcmp(a, "--flicker") == 0)
            cli->max_flicker = value;
        else
            cli->max_time_ms = value;
    } else if (strcmp(a, "--timings") == 0) {
        cli->timings = true;
    } else if (strcmp(a, "--update-refs") == 0) {
        cli->update_refs = true;
    } else if (strcmp(a, "--cached") == 0) {
        cli->cached_only = true;
    } else if (strcmp(a, "--no-render") == 0) {
        cli->no_render = true;
    } else {
        return 0;
    }
    return 1;
}

/* The session's options (the sandbox, the log, video, threads): 1 taken, 0 not one of them, -1 refused (said). */
static int app_option(const char *a, const char *next, struct app *app, struct cli *cli)
{
    if (strcmp(a, "--script-timeout") == 0 || strcmp(a, "--script-memory") == 0) {
        char *end;
        double value = strtod(next, &end);
        if (end == next || *end || !(value >= 0) || value > 1e9)
            return usage_fail("this option needs a number >= 0 (0 = no limit), got '%s'", next);
        if (strcmp(a, "--script-timeout") == 0)
            app->script_timeout = value;
        else
            app->script_memory = value * 1024.0 * 1024.0;
    } else if (strcmp(a, "--allow-read") == 0) {
        if (app->allow_read_count >= (int)(sizeof app->allow_read / sizeof app->allow_read[0]))
            return usage_fail("at most 8 --allow-read folders (%s)", next);
        app->allow_read[app->allow_read_count++] = next;
    } else if (strcmp(a, "--allow-write") == 0) {
        app->allow_write = next;
    } else if (strcmp(a, "--half") == 0) {
        cli->half = true;
    } else if (strcmp(a, "--trusted") == 0) {
        app->trusted = true;
    } else if (strcmp(a, "--verbose") == 0) {
        log_set_verbose(true);
    } else if (strcmp(a, "--quiet") == 0) {
        log_set_quiet(true);
    } else if (strcmp(a, "--crf") == 0) {
        if (!parse_int(next, &cli->crf) || cli->crf < 0 || cli->crf > 51)
            return usage_fail("--crf needs a quality in 0..51, got '%s'", next);
    } else if (strcmp(a, "--tonemap") == 0) {
        cli->tonemap = next;
    } else if (strcmp(a, "--fps") == 0) {
        char *end;
        cli->fps = strtod(next, &end);
        if (*next == '\0' || *end != '\0' || !(cli->fps >= 0.01 && cli->fps <= 1e4))
            return usage_fail("--fps needs frames a second in 0.01..10000, got '%s'", next);
    } else if (strcmp(a, "--frame-count") == 0) {
        if (!parse_int(next, &cli->frame_count) || cli->frame_count < 1 || cli->frame_count > 10000000)
            return usage_fail("--frame-count needs a count in 1..10000000, got '%s'", next);
    } else if (strcmp(a, "--junit") == 0) {
        cli->junit = next;
    } else if (strcmp(a, "--threads") == 0) {
        if (!parse_int(next, &app->threads) || app->threads < 1 || app->threads > 1024)
            return usage_fail("--threads needs a count in 1..1024, got '%s'", next);
    } else if (strcmp(a, "--asset-path") == 0) {
        if (app->asset_path_count >= 8)
            return usage_fail("at most 8 --asset-path folders (%s)", next);
        app->asset_path[app->asset_path_count++] = next;

    } else {
        return 0;
    }
    return 1;
}

bool cli_parse(const char *verb, int argc, char **argv, struct app *app, struct cli *cli)
{
    memset(cli, 0, sizeof *cli);
    cli->verb = verb;
    usage_verb = verb;
    const struct cli_verb *known = verb_find(verb);
    unsigned verb_bit = known ? known->bit : VB_ALL;
    cli->frames_from = cli->frames_to = -1;
    cli->photons = -1; /* (unset: the reference's default; 0 is a count, no photons) */
    cli->max_error = cli->max_time_ms = cli->max_flicker = -1.0;
    cli->crf = 18;
    bool options_end = false;
    for (int i = 0; i < argc; i++) {
        const char *arg = argv[i];
        if (options_end || arg[0] != '-' || !arg[1]) {
            if (cli->npositional >= 64)
                return usage_error("too many arguments (%s)", arg);
            cli->positional[cli->npositional++] = arg;
            continue;
        }
        if (strcmp(arg, "--") == 0) {
            options_end = true;
            continue;
        }
        /* --name=value or --name value */
        const char *eq = arg[1] == '-' ? strchr(arg, '=') : NULL;
        size_t len = eq ? (size_t)(eq - arg) : strlen(arg);
        const struct cli_option *o = option_find(arg, len, verb_bit);
        if (!o)
            return unknown_option(arg, len, verb_bit);
        const char *a = o->name;
        if (!(o->verbs & verb_bit)) {
            char message[200];
            snprintf(message, sizeof message, "%s does not take %%s", verb);
            return usage_error(message, a);
        }
        const char *next = NULL;
        if (!o->value) {
            if (eq)
                return usage_error("%s takes no value", a);
        } else if (eq) {
            next = eq + 1;
        } else {
            if (i + 1 >= argc)
                return usage_error("%s needs a value", a);
            next = argv[++i];
        }
        int taken = output_file_option(a, next, app, cli);
        if (taken == 0)
            taken = reference_option(a, next, app, cli);
        if (taken == 0)
            taken = bench_option(a, next, app, cli);
        if (taken == 0)
            taken = app_option(a, next, app, cli);
        if (taken < 0)
            return false;
    }
    return true;
}
