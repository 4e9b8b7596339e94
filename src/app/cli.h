/* Command-line options shared by the verbs. */
#ifndef CAUSTICA_CLI_H
#define CAUSTICA_CLI_H

#include <stdbool.h>
#include <stdio.h>

#include "app/app.h"
#include "app/frame_set.h"
#include "app/session.h"

#define EXIT_SCENE_ERROR 1
#define EXIT_USAGE 2

struct cli {
    const char *verb;
    const char *positional[64];
    int npositional;
    const char *output;      /* -o */
    int frame;               /* --frame */
    int frames_from, frames_to; /* --frames: the set's first and last frame (N: 0..N-1) */
    bool frames_set;
    int frame_count;         /* --frame-count N (render, record, run): the animation's length instead of the script's */
    double fps;              /* --fps N (render, record, run): frames a second instead of the script's (0: its) */
    struct frame_set frame_set; /* --frames as given (record renders exactly these) */
    bool overwrite;          /* --overwrite (record): render frames whose file exists */
    bool script;             /* --script (info): a glTF file's scene written as the Lua script it runs */
    const char *aovs[8];     /* --aov pass.output (render, record to .exr): extra layers */
    int aov_count;
    bool half;               /* --half: an EXR's beauty channels as 16-bit half floats */
    const char *video;       /* --video OUT.mp4|OUT.gif (record): the frames encoded by ffmpeg */
    int crf;                 /* --crf (record --video): x264's quality, default 18 */
    int shard_index, shard_count; /* --shard i/n (record): every n-th frame of the set from the i-th */
    int width, height;       /* --size */
    const char *screenshot;
    const char *keys;        /* --keys space,right,s (run): keys pressed on the first frame, for tests */
    const char *mask;
    bool timings, update_refs, no_render;
    bool cached_only;        /* --cached (choose): read the bench cache only, never run the sweep */
    bool report;             /* --report: the reference's noise estimate per iteration */
    bool antialias;          /* --antialias (reference), --ref-antialias (bench, choose): pixel means */
    bool tessellated;        /* --tessellated (reference), --ref-tessellated (bench, choose): spheres' triangles */
    const char *report_html; /* --report OUT.html (test): the HTML report */
    const char *junit;       /* --junit OUT.xml (test): JUnit XML for CI servers */
    int aov;                 /* --aov tir|exit: enum ref_aov (reference) */
    const char *filter;
    long photons;            /* --photons (reference); -1 where not given */
    int spp;                 /* --spp: SPPM iterations (reference) */
    double time_budget;      /* --time-budget seconds (reference) */
    long long seed;          /* --seed (reference) */
    double radius;           /* --radius: initial SPPM radius (reference) */
    const char *sweeps[16];  /* --sweep key=v1,v2,... (bench) */
    int nsweeps;
    long ref_photons;        /* --ref-photons (bench) */
    int ref_spp;             /* --ref-spp: the longest reference run of the curve (bench) */
    int truth_spp;           /* --truth-spp: the ground truth's iterations (0: 16 x ref_spp) */
    const char *truth;       /* --truth: bench's ground truth from a file (a merged reference) */
    int error_frames;        /* --error-frames K (bench, choose): errors averaged over K frames spread over the
                                animation (0: 1 frame, or 3 with --sweep technique=...) */
    double max_error;        /* --error E (choose): the largest error accepted (< 0: not given) */
    double max_flicker;      /* --flicker F (choose): the largest flicker accepted (< 0: not given) */
    double max_time_ms;      /* --time T (choose): milliseconds a frame may take (< 0: not given) */
    double exposure;         /* --exposure (convert) */
    const char *tonemap;     /* --tonemap clamp|reinhard|aces (convert to .png): render's tone mapping */
    struct lua_params params;
};

/* Parses argv after `verb` (GNU style: --opt value, --opt=value, -- ends
 * the options); an option the verb does not take, an unknown one (with the
 * nearest name) or a bad value prints one line and the hint, and returns false. */
bool cli_parse(const char *verb, int argc, char **argv, struct app *app, struct cli *cli);
/* Every verb's synopsis and summary. */
void cli_usage(FILE *out);
/* "see `caustica VERB --help`" on stderr, after a usage error's line. */
void cli_usage_hint(const char *verb);
bool cli_is_verb(const char *name);
/* The verb nearest a misspelt one, or NULL. */
const char *cli_suggest_verb(const char *word);
void cli_print_error(const struct error *err);
/* -o as linear radiance (.pfm, .hdr or .exr) in a folder that exists and
 * is writable: 0, or the exit status after one line saying what is wrong
 * (`what`: "the reference", "a merged reference"). */
int cli_check_radiance_output(const struct cli *cli, const char *what);

int cmd_render(struct app *app, struct cli *cli);
int cmd_record(struct app *app, struct cli *cli);
int cmd_run(struct app *app, struct cli *cli);
int cmd_test(struct app *app, struct cli *cli);
int cmd_info(struct app *app, struct cli *cli);
int cmd_compare(struct app *app, struct cli *cli);
int cmd_reference(struct app *app, struct cli *cli);
int cmd_bench(struct app *app, struct cli *cli);
int cmd_choose(struct app *app, struct cli *cli);
int cmd_convert(struct app *app, struct cli *cli);
int cmd_merge(struct app *app, struct cli *cli);
/* One verb's synopsis, and every option it takes with its meaning, default and limits. */
void cli_usage_verb(FILE *out, const char *verb);
/* `caustica help [passes | PASS] [--markdown]`: the pass reference from the descriptors. */
int cmd_help(int argc, char **argv);

#endif
