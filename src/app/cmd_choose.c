/* `caustica choose SCENE --error E [--time T] [--flicker F]`: the cheapest
 * technique and settings of a comparison scene whose error is at most E (or
 * the most accurate within T milliseconds a frame), whose flicker (the error
 * of its frame-to-frame change, issue 32) is at most F where given, from the
 * scene's technique sweep
 * — read from `bench`'s cache when it was measured with the same options,
 * run otherwise — with the graph lines to paste into the script. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "app/bench.h"
#include "app/bench_cache.h"
#include "core/fileio.h"
#include "app/cli.h"
#include "app/techniques.h"
#include "graph/graph.h"
#include "graph/graph_lint.h"
#include "scene/scene.h"

/* One pass's constructor as a script writes it: the parameters the script
 * (or the chosen settings) set. Lights and objects by their index in the
 * scene, since the script's variable names are not known here. */
static void print_pass(const struct pass *p, const struct scene *scene)
{
    printf("  g:add(\"%s\", c.pass.%s {", p->name, p->desc->name);
    int printed = 0;
    for (int i = 0; i < p->desc->param_count; i++) {
        const struct pass_param_desc *d = &p->desc->params[i];
        const struct pass_value *v = &p->values[i];
        if (!v->set)
            continue;
        char text[512] = "";
        switch (d->type) {
        case PASS_PARAM_NUMBER:
            snprintf(text, sizeof text, "%g", v->number);
            break;
        case PASS_PARAM_INTEGER:
            snprintf(text, sizeof text, "%.0f", v->number);
            break;
        case PASS_PARAM_BOOLEAN:
            snprintf(text, sizeof text, "%s", v->number != 0 ? "true" : "false");
            break;
        case PASS_PARAM_STRING:
        case PASS_PARAM_INPUT:
            snprintf(text, sizeof text, "\"%s\"", v->string ? v->string : "");
            break;
        case PASS_PARAM_ENUM: {
            const char *c = d->choices;
            for (int k = 0; k < (int)v->number && c; k++) {
                c = strchr(c, '|');
                c = c ? c + 1 : NULL;
            }
            if (c)
                snprintf(text, sizeof text, "\"%.*s\"", (int)strcspn(c, "|"), c);
            break;
        }
        case PASS_PARAM_LIGHT:
            for (int k = 0; k < scene->light_count; k++)
                if (scene->lights[k] == v->light)
                    snprintf(text, sizeof text, "LIGHT%d", k + 1);
            break;
        case PASS_PARAM_OBJECT:
            for (int k = 0; k < scene->object_count; k++)
                if (scene->objects[k] == v->object)
                    snprintf(text, sizeof text, "OBJECT%d", k + 1);
            break;
        case PASS_PARAM_INPUT_LIST: {
            size_t used = 0;
            used += (size_t)snprintf(text, sizeof text, "{");
            for (int k = 0; k < v->list_count && used < sizeof text; k++)
                used += (size_t)snprintf(text + used, sizeof text - used, "%s\"%s\"", k ? ", " : " ", v->list[k]);
            if (used < sizeof text)
                snprintf(text + used, sizeof text - used, " }");
            break;
        }
        case PASS_PARAM_COLOR:
            snprintf(text, sizeof text, "{%g, %g, %g}", v->color[0], v->color[1], v->color[2]);
            break;
        default:
            snprintf(text, sizeof text, "...");
            break;
        }
        if (!text[0])
            continue;
        printf("%s %s = %s", printed++ ? "," : "", d->name, text);
    }
    printf(" })\n");
}

/* Whether the technique's graph leaves out something of the scene (a pass's
 * descriptor says so: graph_lint's "leaves out" warnings): `why` gets the
 * first such warning. A technique that renders part of the scene dark
 * without saying so in its error must not be recommended for it (issue 27);
 * its error on this scene may even be small where what it leaves out is
 * small here. False with `err` set when the script cannot be opened. */
static bool technique_leaves_out(struct app *app, const struct cli *cli, const char *script,
                                 const struct technique *tech, bool *leaves, char *why, size_t whylen,
                                 struct error *err)
{
    *leaves = false;
    struct session_options so = {.script = script, .params = cli->params, .width = cli->width, .height = cli->height,
                                 .past_last_frame = true};
    bool ok = true;
    for (int k = 0; ok && k < tech->set_count; k++) {
        char assignment[200];
        snprintf(assignment, sizeof assignment, "%s=%s", tech->set_keys[k], tech->set_values[k]);
        ok = lua_params_add(&so.params, assignment, err);
    }
    struct session *s = NULL;
    ok = ok && session_open(app, &so, &s, err) && graph_check(s->graph, err);
    if (ok) {
        char messages[GRAPH_LINT_MAX][400];
        int n = graph_lint(s->graph, s->scene, NULL, messages, GRAPH_LINT_MAX);
        for (int i = 0; i < n && !*leaves; i++)
            if (graph_lint_is_omission(messages[i])) {
                *leaves = true;
                size_t len = strnlen(messages[i], sizeof messages[i] - 1);
                len = len < whylen ? len : whylen - 1;
                memcpy(why, messages[i], len);
                why[len] = '\0';
            }
    }
    if (s)
        session_close(s);
    return ok;
}

/* The sweep `choose` picks from: its cache entry's path in `cached`, run
 * by bench first where the cache has none (not with --cached). 0, or the
 * exit status. */
static int choose_sweep(struct app *app, const struct cli *cli, struct cli *sweep, const char *dir, char *cached,
                        size_t cached_size)
{
    const char *script = cli->positional[0];
    struct error err;
    if (!bench_sweep_cache_path(sweep, dir, cached, cached_size, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    struct stat st;
    bool present = lstat(cached, &st) == 0;
    FILE *probe = present ? file_open_read(cached, true, &err) : NULL;
    if (present && !probe) {
        cli_print_error(&err); /* a link or a FIFO where the cache entry should be: never read, never replaced */
        return EXIT_SCENE_ERROR;
    }
    if (probe) {
        fclose(probe);
        fprintf(stderr, "caustica: choose: the sweep from the bench cache %s\n", cached);
    } else if (cli->cached_only) {
        fprintf(stderr, "caustica: choose: --cached: no sweep of %s with these options in %s/cache (%s); run `caustica "
                        "bench %s --sweep %s -o %s` with the same --size, --frames, --error-frames and --ref-* options, "
                        "or leave out --cached\n", script, dir, cached, script, sweep->sweeps[0], dir);
        return EXIT_SCENE_ERROR;
    } else {
        fprintf(stderr, "caustica: choose: no sweep of %s with these options in %s/cache: running `caustica bench %s "
                        "--sweep %s -o %s` ...\n", script, dir, script, sweep->sweeps[0], dir);
        return cmd_bench(app, sweep);
    }
    return 0;
}

/* Times measured on another renderer (a cache from an llvmpipe node read
 * on a GPU node) do not hold here: said once. Techniques that leave out
 * part of the scene are not considered (one line each says which and why;
 * their rows marked excluded). The script's techniques, read once. */
static bool choose_exclude(struct app *app, const struct cli *cli, struct bench_row *rows, int n, struct error *err)
{
    const char *script = cli->positional[0];
    if (app_ensure_gl(app, err)) {
        char here[256];
        bench_renderer_label(app->gl->renderer, here, sizeof here);
        if (!rows[0].renderer[0])
            fprintf(stderr, "caustica: choose: warning: the cached sweep does not say which renderer measured it; "
                            "its times may not be this machine's (%s)\n", here);
        else if (strcmp(rows[0].renderer, here) != 0)
            fprintf(stderr, "caustica: choose: warning: the cached sweep was measured on %s, this machine renders "
                            "with %s: its frame times do not hold here (run bench again on this machine, or keep "
                            "another -o DIR per machine)\n", rows[0].renderer, here);
    }
    struct technique_list *all = calloc(1, sizeof *all);
    struct session_options base = {.script = script, .params = cli->params, .width = cli->width,
                                   .height = cli->height, .past_last_frame = true};
    struct session *s0 = NULL;
    bool read = all && session_open(app, &base, &s0, err) && techniques_read(s0, all, err);
    if (s0)
        session_close(s0);
    if (!read) {
        free(all);
        return false;
    }
    for (int i = 0; i < n; i++) {
        bool seen = false;
        for (int j = 0; j < i && !seen; j++)
            seen = strcmp(rows[j].technique, rows[i].technique) == 0;
        const struct technique *tech = NULL;
        for (int j = 0; j < all->count && !tech; j++)
            if (strcmp(all->items[j].name, rows[i].technique) == 0)
                tech = &all->items[j];
        if (seen || !tech) /* a cached row of a technique the script no longer declares: judged as it was */
            continue;
        bool leaves;
        char why[400];
        if (!technique_leaves_out(app, cli, script, tech, &leaves, why, sizeof why, err)) {
            free(all);
            return false;
        }
        if (!leaves)
            continue;
        fprintf(stderr, "caustica: choose: %s is not considered: %s\n", rows[i].technique, why);
        for (int j = i; j < n; j++)
            if (strcmp(rows[j].technique, rows[i].technique) == 0)
                rows[j].excluded = true;
    }
    free(all);
    return true;
}

/* No row within the bounds: what the sweep's most accurate, fastest (and
 * steadiest) reach instead. */
static void choose_report_none(const struct cli *cli, const struct bench_row *rows, int n)
{
    const char *script = cli->positional[0];
    int accurate = -1, fastest = -1;
    for (int i = 0; i < n; i++) {
        if (rows[i].excluded)
            continue;
        if (accurate < 0 || rows[i].error < rows[accurate].error)
            accurate = i;
        if (fastest < 0 || rows[i].ms < rows[fastest].ms)
            fastest = i;
    }
    if (accurate < 0) {
        fprintf(stderr, "caustica: choose: every technique of %s leaves out part of the scene (above)\n", script);
        return;
    }
    fprintf(stderr, "caustica: choose: no technique of %s reaches", script);
    if (cli->max_error >= 0)
        fprintf(stderr, " error %g", cli->max_error);
    if (cli->max_time_ms >= 0)
        fprintf(stderr, "%s %g ms a frame", cli->max_error >= 0 ? " within" : "", cli->max_time_ms);
    if (cli->max_flicker >= 0)
        fprintf(stderr, "%s flicker %g", cli->max_error >= 0 || cli->max_time_ms >= 0 ? " with" : "",
                cli->max_flicker);
    fprintf(stderr, " on this machine; the most accurate is %s (%s): %.4g in %.1f ms, the fastest %s (%s): "
                    "%.4g in %.1f ms", rows[accurate].technique, rows[accurate].settings, rows[accurate].error,
            rows[accurate].ms, rows[fastest].technique, rows[fastest].settings, rows[fastest].error,
            rows[fastest].ms);
    if (cli->max_flicker >= 0) {
        int steady = -1;
        for (int i = 0; i < n; i++)
            if (!rows[i].excluded && rows[i].flicker >= 0 && (steady < 0 || rows[i].flicker < rows[steady].flicker))
                steady = i;
        if (steady >= 0)
            fprintf(stderr, ", the steadiest %s (%s): flicker %.4g", rows[steady].technique,
                    rows[steady].settings, rows[steady].flicker);
        else
            fprintf(stderr, "; the sweep has no flicker (measured before bench measured it: run bench again)");
    }
    fprintf(stderr, "\n");
}

/* With --error: the cheapest row within the error (and the time); with
 * --time only: the most accurate within the time. -1: none. */
static int choose_best(const struct cli *cli, const struct bench_row *rows, int n)
{
    int best = -1;
    for (int i = 0; i < n; i++) {
        if (rows[i].excluded)
            continue;
        /* a row without a flicker (a cache from before it was measured) fits no flicker bound */
        bool fits = (cli->max_error < 0 || rows[i].error <= cli->max_error) &&
                    (cli->max_time_ms < 0 || rows[i].ms <= cli->max_time_ms) &&
                    (cli->max_flicker < 0 || (rows[i].flicker >= 0 && rows[i].flicker <= cli->max_flicker));
        if (!fits)
            continue;
        bool better = best < 0 || (cli->max_error >= 0 ? rows[i].ms < rows[best].ms : rows[i].error < rows[best].error);
        if (better)
            best = i;
    }
    return best;
}

int cmd_choose(struct app *app, struct cli *cli)
{
    if (cli->npositional != 1 || (cli->max_error < 0 && cli->max_time_ms < 0 && cli->max_flicker < 0)) {
        fprintf(stderr, "caustica: choose needs one scene script and --error E (the largest error accepted), --time "
                        "MS (the milliseconds a frame may take) or --flicker F (the largest flicker accepted), or "
                        "several\n");
        cli_usage_hint("choose");
        return EXIT_USAGE;
    }
    const char *script = cli->positional[0];
    const char *dir = cli->output ? cli->output : "bench";
    /* the sweep `bench --sweep technique=all` runs, with the same options */
    struct cli sweep = *cli;
    if (sweep.nsweeps == 0) {
        sweep.sweeps[0] = "technique=all";
        sweep.nsweeps = 1;
    }
    struct error err;
    char cached[4400];
    int rc = choose_sweep(app, cli, &sweep, dir, cached, sizeof cached);
    if (rc != 0)
        return rc;
    struct bench_row *rows = calloc(BENCH_CACHE_MAX_ROWS, sizeof *rows);
    int n = 0;
    if (!rows || !bench_cache_read(cached, rows, &n, &err)) {
        free(rows);
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    if (!choose_exclude(app, cli, rows, n, &err)) {
        free(rows);
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    int best = choose_best(cli, rows, n);
    if (best < 0) {
        choose_report_none(cli, rows, n);
        free(rows);
        return EXIT_SCENE_ERROR;
    }
    struct bench_row chosen = rows[best];
    free(rows);
    /* the chosen technique's graph: the script opened with its selecting
     * parameters and settings */
    struct session_options so = {.script = script, .params = cli->params, .width = cli->width, .height = cli->height,
                                 .past_last_frame = true};
    struct session *s = NULL;
    struct technique_list *list = calloc(1, sizeof *list);
    bool ok = list && session_open(app, &so, &s, &err) && techniques_read(s, list, &err) &&
              techniques_select(list, chosen.technique, &err);
    const struct technique *tech = ok ? &list->items[0] : NULL;
    const char *metric = ok && list->metric == TECHNIQUE_METRIC_IMAGE ? "error (rel_rmse of the image)"
                                                                      : "caustic-region error (rel_rmse)";
    char set_text[600] = "";
    for (int k = 0; ok && k < tech->set_count; k++) {
        char assignment[200];
        snprintf(assignment, sizeof assignment, "%s=%s", tech->set_keys[k], tech->set_values[k]);
        snprintf(set_text + strlen(set_text), sizeof set_text - strlen(set_text), " --set %s", assignment);
        ok = lua_params_add(&so.params, assignment, &err);
    }
    /* the settings: "pass.param=value" overrides, "param=value" scene parameters */
    struct technique_point point;
    if (ok && !technique_point_parse(chosen.settings, &point))
        ok = error_set(&err, "%s: the cached settings '%s' are not pass.param=value ...", cached, chosen.settings);
    for (int k = 0; ok && k < point.count; k++) {
        char assignment[200];
        snprintf(assignment, sizeof assignment, "%s=%s", point.keys[k], point.values[k]);
        if (!technique_key_is_pass(point.keys[k])) {
            ok = lua_params_add(&so.params, assignment, &err);
            snprintf(set_text + strlen(set_text), sizeof set_text - strlen(set_text), " --set %s", assignment);
        }
    }
    if (s)
        session_close(s);
    s = NULL;
    ok = ok && session_open(app, &so, &s, &err);
    for (int k = 0; ok && k < point.count; k++)
        if (technique_key_is_pass(point.keys[k]))
            ok = session_set_pass_param(s, point.keys[k], point.values[k], &err);
    if (ok) {
        printf("%s: %s (%s): %.1f ms a frame, %s %.4g", script, chosen.technique, chosen.settings, chosen.ms, metric,
               chosen.error);
        if (chosen.flicker >= 0)
            printf(", flicker %.4g", chosen.flicker);
        printf("\n");
        printf("measured by the sweep in %s\n", cached);
        printf("the graph (paste into the script; LIGHTn is the scene's n-th light, OBJECTn its n-th object):\n");
        for (int i = 0; i < s->graph->count; i++)
            print_pass(s->graph->entries[i].pass, s->scene);
        printf("  g:output(\"%s\")\n", s->graph->output);
        printf("or keep the script as it is and run it with:%s\n", set_text);
    }
    if (s)
        session_close(s);
    free(list);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
