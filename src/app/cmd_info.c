/* `caustica info`: the compiled graph, every pass kept or left out, why. */
#define _DEFAULT_SOURCE /* realpath */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/cli.h"
#include "app/session.h"
#include "core/fileio.h"
#include "graph/graph.h"
#include "graph/graph_lint.h"

/* The base name of a path, for short lines. */
static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* Every object whose material came from a file (a glTF primitive's): which
 * material, what it is drawn as, and what of it is not drawn. */
static void print_file_materials(const struct scene *scene)
{
    bool header = false;
    for (int i = 0; i < scene->object_count; i++) {
        const struct object *o = scene->objects[i];
        const struct material *m = &o->material;
        if (!o->mesh->material_name[0])
            continue;
        if (!header)
            printf("materials from files (object number as in the warnings: mesh, the file's material, drawn as):\n");
        header = true;
        char drawn[224];
        const char *thick = m->thickness_map.texture ? ", thickness x thicknessTexture" : "";
        if ((m->kind == MATERIAL_GLASS || m->kind == MATERIAL_WATER) && m->roughness > 0.0f)
            snprintf(drawn, sizeof drawn, "%s, ior %g, roughness %.2g%s", material_kind_name(m->kind), m->ior,
                     m->roughness, thick);
        else if (m->kind == MATERIAL_GLASS && m->thin)
            snprintf(drawn, sizeof drawn, "thin-walled glass, ior %g%s", m->ior,
                     m->base_color.texture ? " (tinted by baseColorTexture)" : "");
        else if (m->kind == MATERIAL_GLASS || m->kind == MATERIAL_WATER)
            snprintf(drawn, sizeof drawn, "%s, ior %g%s", material_kind_name(m->kind), m->ior, thick);
        else if (m->pbr) {
            char specular[64] = "";
            if (m->specular != 1.0f || m->specular_color.x != 1.0f || m->specular_color.y != 1.0f ||
                m->specular_color.z != 1.0f)
                snprintf(specular, sizeof specular, ", specular %.2g x (%.2g %.2g %.2g)", m->specular,
                         m->specular_color.x, m->specular_color.y, m->specular_color.z);
            char coat[96] = "";
            if (m->clearcoat > 0.0f)
                snprintf(coat, sizeof coat, ", clearcoat %.2g%s (roughness %.2g%s)%s", m->clearcoat,
                         m->clearcoat_map.texture ? " x texture" : "", m->clearcoat_roughness,
                         m->clearcoat_roughness_map.texture ? " x texture" : "",
                         m->clearcoat_normal.texture ? " with its normal map" : "");
            snprintf(drawn, sizeof drawn, "glTF BRDF, metallic %.2g, roughness %.2g%s, ior %g%s%s%s", m->metallic,
                     m->roughness, m->metallic_roughness.texture ? " (x metallicRoughnessTexture)" : "", m->ior,
                     specular, m->occlusion.texture ? ", occlusion" : "", coat);
        }
        else if (m->kind == MATERIAL_MIRROR && m->roughness > 0.0f)
            snprintf(drawn, sizeof drawn, "mirror, roughness %.2g", m->roughness);
        else
            snprintf(drawn, sizeof drawn, "%s", material_kind_name(m->kind));
        const char *name = o->mesh->material_name;
        bool replaced = strcmp(m->source, name) != 0; /* the script set another material */
        printf("  %3d  %s '%s': %s%s%s%s\n", i + 1, base_name(o->group ? o->group->mesh->name : o->mesh->name), name,
               drawn, replaced ? " (the script's)" : "", !replaced && m->ignored[0] ? "; ignored: " : "",
               !replaced ? m->ignored : "");
    }
}

/* `info FILE.glb --script`: lua/caustica/gltf_scene.lua, the script the
 * file is rendered with, made to stand alone: the file named by its full
 * path on the lines marked "info --script". */
static bool print_gltf_script(const struct app *app, const char *gltf, struct error *err)
{
    char builtin[4200], full[PATH_MAX];
    snprintf(builtin, sizeof builtin, "%s/lua/caustica/gltf_scene.lua", app->root);
    if (!realpath(gltf, full))
        return error_set(err, "%s: %s", gltf, strerror(errno));
    size_t n;
    char *text;
    if (!file_read_all(builtin, &text, &n, err))
        return false;
    printf("-- Written by `caustica info %s --script`: the scene caustica renders for the\n"
           "-- file with no script. Save it, edit it, render it as any script.\n", full);
    for (char *line = text, *next; line && *line; line = next) {
        next = strchr(line, '\n');
        if (next)
            *next++ = '\0';
        if (strstr(line, "-- info --script: the file"))
            printf("local path = \"%s\"\n", full);
        else if (strstr(line, "-- info --script: by its path"))
            printf("local ok, file = pcall(c.gltf.load, path,\n");
        else
            printf("%s\n", line);
    }
    free(text);
    return true;
}

int cmd_info(struct app *app, struct cli *cli)
{
    if (cli->npositional != 1) {
        fprintf(stderr, "caustica: info needs one scene script\n");
        return EXIT_USAGE;
    }
    if (cli->script && !session_is_gltf(cli->positional[0])) {
        fprintf(stderr, "caustica: info --script writes the script of a glTF file (.gltf, .glb); %s is a script "
                        "already\n", cli->positional[0]);
        return EXIT_USAGE;
    }
    struct session_options o = {.script = cli->positional[0], .params = cli->params, .width = cli->width,
                                .height = cli->height, .fps = cli->fps};
    struct session *s;
    struct error err;
    if (!session_open(app, &o, &s, &err)) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    if (cli->script) {
        bool written = print_gltf_script(app, s->script, &err);
        session_close(s);
        if (!written) {
            cli_print_error(&err);
            return EXIT_SCENE_ERROR;
        }
        return EXIT_SUCCESS;
    }
    bool ok = graph_check(s->graph, &err);
    /* Two frames show what the graph reuses from one frame to the next (a
     * still has one: what its frame does). */
    bool still = s->frames <= 1;
    int shown = still ? 0 : 1;
    bool rendered = ok && !cli->no_render && session_render(s, 0, &err) && (still || session_render(s, 1, &err));
    if (ok && !cli->no_render && !rendered)
        ok = false;
    if (ok) {
        printf("%s: %d objects, %d lights, %dx%d, %d frame%s at %g fps, output '%s'\n", s->script,
               s->scene->object_count, s->scene->light_count, s->width, s->height, s->frames, s->frames == 1 ? "" : "s",
               s->fps, s->graph->output);
        print_file_materials(s->scene);
        for (int i = 0; i < s->graph->count; i++) {
            const struct graph_entry *e = &s->graph->entries[i];
            const struct pass *p = e->pass;
            const char *runs = still ? "runs once (a still)" : "runs every frame";
            printf("%2d  %-16s %-16s ", i + 1, p->name, p->desc->name);
            if (e->state != GRAPH_PASS_KEPT) {
                printf("left out: %s\n", e->reason);
            } else if (rendered && e->last_need == PASS_SKIP) {
                const char *why = e->last_why;
                if (strncmp(why, "left out: ", 10) == 0)
                    why += 10;
                printf("kept, but does nothing on frame %d: %s\n", shown, why);
            } else if (rendered && e->last_need == PASS_REUSE && !still) {
                printf("kept; on frame %d %s\n", shown, e->last_why);
            } else if (rendered && e->last_why[0]) {
                printf("kept; %s: %s\n", runs, e->last_why);
            } else {
                printf("kept; %s\n", runs);
            }
            if (p->implicit)
                printf("      %s: a building block, shared by every pass that reads it\n", p->origin);
            if (rendered && e->state == GRAPH_PASS_KEPT && e->last_need == PASS_RUN && p->report[0])
                printf("      on frame %d: %s\n", shown, p->report);
            for (int k = 0; k < p->input_count; k++)
                printf("      in  %-12s <- %s\n", p->inputs[k].name, p->inputs[k].source);
            for (int k = 0; k < p->output_count; k++)
                printf("      out %s.%s (%s)\n", p->name, p->outputs[k].name,
                       p->outputs[k].kind == RESOURCE_RECORD ? p->outputs[k].record->name
                                                             : gl_format_name(p->outputs[k].format));
        }
    }
    if (ok) {
        char messages[GRAPH_LINT_MAX][400];
        int n = graph_lint(s->graph, s->scene, rendered ? &app->renderer.frame.view_proj : NULL, messages,
                           GRAPH_LINT_MAX);
        for (int i = 0; i < n; i++)
            printf("warning: %s\n", messages[i]);
    }
    session_close(s);
    if (!ok) {
        cli_print_error(&err);
        return EXIT_SCENE_ERROR;
    }
    return 0;
}
