/* `caustica info`: the compiled graph, every pass kept or left out, why. */
#include <stdio.h>
#include <string.h>

#include "app/cli.h"
#include "graph/graph.h"

int cmd_info(struct app *app, struct cli *cli)
{
    if (cli->npositional != 1) {
        fprintf(stderr, "caustica: info needs one scene script\n");
        return EXIT_USAGE;
    }
    struct session_options o = {.script = cli->positional[0], .params = cli->params, .width = cli->width,
                                .height = cli->height};
    struct session *s;
    struct error err;
    if (!session_open(app, &o, &s, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    bool ok = graph_check(s->graph, &err);
    /* Two frames show what the graph reuses from one frame to the next. */
    bool rendered = ok && !cli->no_render && session_render(s, 0, &err) && session_render(s, 1 % s->frames, &err);
    if (ok && !cli->no_render && !rendered)
        ok = false;
    if (ok) {
        printf("%s: %d objects, %d lights, %dx%d, %d frames at %g fps, output '%s'\n", s->script,
               s->scene->object_count, s->scene->light_count, s->width, s->height, s->frames, s->fps, s->graph->output);
        for (int i = 0; i < s->graph->count; i++) {
            const struct graph_entry *e = &s->graph->entries[i];
            const struct pass *p = e->pass;
            printf("%2d  %-16s %-16s ", i + 1, p->name, p->desc->name);
            if (e->state != GRAPH_PASS_KEPT)
                printf("left out: %s\n", e->reason);
            else if (rendered && e->last_need != PASS_RUN)
                printf("kept; on frame %d %s\n", 1 % s->frames, e->last_why);
            else if (rendered && e->last_why[0])
                printf("kept; runs every frame: %s\n", e->last_why);
            else
                printf("kept; runs every frame\n");
            for (int k = 0; k < p->input_count; k++)
                printf("      in  %-12s <- %s\n", p->inputs[k].name, p->inputs[k].source);
            for (int k = 0; k < p->output_count; k++)
                printf("      out %s.%s (%s)\n", p->name, p->outputs[k].name, gl_format_name(p->outputs[k].format));
        }
    }
    session_close(s);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
