/* Graph mistakes that render without an error (see graph_lint.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "graph/graph_lint.h"
#include "graph/pass.h"

static bool kept(const struct graph_entry *e) { return e->state == GRAPH_PASS_KEPT; }

static struct light *light_of(const struct pass *p)
{
    int k = pass_param_index(p->desc, "light");
    return k >= 0 && p->desc->params[k].type == PASS_PARAM_LIGHT ? pass_light_at(p, k) : NULL;
}

/* The kept pass that makes resource `source` ("pass.output"). */
static const struct pass *producer(const struct graph *g, const char *source)
{
    const char *dot = strchr(source, '.');
    size_t n = dot ? (size_t)(dot - source) : strlen(source);
    for (int i = 0; i < g->count; i++)
        if (strlen(g->entries[i].pass->name) == n && strncmp(g->entries[i].pass->name, source, n) == 0)
            return g->entries[i].pass;
    return NULL;
}

/* The checks share where they write: messages[count++] while count < max. */
struct lint {
    const struct graph *g;
    const struct scene *scene;
    char (*messages)[400];
    int count, max;
};

/* Whether a kept pass of the graph draws volume caustics. */
static bool lint_volume_caustics(const struct graph *g)
{
    bool volume = false;
    for (int i = 0; i < g->count; i++)
        volume = volume || (kept(&g->entries[i]) && g->entries[i].pass->desc->volume_caustics);
    return volume;
}

/* Who draws glass, water and mirrors: each descriptor says (shade {
 * specular = true }: one interface of each; the refraction passes;
 * water_surface its water; a user's pass may draw anything: no warning
 * then). */
static void lint_undrawn(struct lint *l, const mat4 *view_proj)
{
    const struct graph *g = l->g;
    const struct scene *scene = l->scene;
    unsigned drawn_by = 0;
    for (int i = 0; i < g->count; i++)
        if (kept(&g->entries[i]) && g->entries[i].pass->desc->draws)
            drawn_by |= g->entries[i].pass->desc->draws(g->entries[i].pass);
    bool custom = drawn_by & PASS_DRAWS_ANYTHING;
    for (int i = 0; i < scene->object_count && !custom && l->count < l->max; i++) {
        const struct object *o = scene->objects[i];
        unsigned role = object_role(o);
        if (!(role & (OBJECT_ROLE_SPECULAR | OBJECT_ROLE_THIN)) || (view_proj && !object_in_view(o, *view_proj)))
            continue; /* receivers: shade's */
        if (role == OBJECT_ROLE_THIN && !(role & drawn_by))
            snprintf(l->messages[l->count++], 400,
                     "object %d (thin glass) is drawn by no pass the output needs (shade draws it), so it shows "
                     "what is behind it", i + 1);
        else if (!(role & drawn_by))
            snprintf(l->messages[l->count++], 400,
                     "object %d (%s) is drawn by no pass the output needs (shade draws it unless specular = false; "
                     "else refraction, layered_refraction or sliced_refraction%s), so it shows what is behind it",
                     i + 1, object_role_name(role), role == OBJECT_ROLE_WATER ? ", water_surface" : "");
    }
}

/* A refractor drawn twice: a pass that looks its "color" input up
 * behind the glass or water it draws (the descriptor says), over an
 * image in which the pass that made it already drew them (shade {
 * specular = true } before layered_refraction): the refracted image
 * shows the glass inside itself (rel 0.066 on issue 29's scene). */
/* The pass that made p's `color` input (NULL: none, or one that may draw
 * anything), its resource's name and the roles it draws: for the lints of a
 * pass that draws objects over an image already showing them. */
static const struct pass *color_maker(const struct graph *g, const struct pass *p, const char **source,
                                      unsigned *theirs)
{
    for (int k = 0; k < p->input_count; k++) {
        if (strcmp(p->inputs[k].name, "color") != 0)
            continue;
        const struct pass *maker = producer(g, p->inputs[k].source);
        *theirs = maker && maker->desc->draws ? maker->desc->draws(maker) : 0;
        *source = p->inputs[k].source;
        return *theirs & PASS_DRAWS_ANYTHING ? NULL : maker;
    }
    return NULL;
}

static void lint_drawn_twice(struct lint *l)
{
    const struct graph *g = l->g;
    for (int i = 0; i < g->count && l->count < l->max; i++) {
        const struct pass *p = g->entries[i].pass;
        unsigned mine = kept(&g->entries[i]) && p->desc->draws ? p->desc->draws(p) : 0, theirs = 0;
        if (!p->desc->color_behind_refractors || !(mine & OBJECT_ROLE_REFRACTOR) || (mine & PASS_DRAWS_ANYTHING))
            continue;
        const char *source = NULL;
        const struct pass *maker = color_maker(g, p, &source, &theirs);
        unsigned both = mine & theirs & OBJECT_ROLE_REFRACTOR;
        if (maker && both)
            snprintf(l->messages[l->count++], 400,
                     "pass '%s' (%s) draws the %s over '%s', in which pass '%s' (%s) already drew %s: it shows "
                     "twice, refracted through itself (shade { specular = false } leaves glass and water to a "
                     "later pass)",
                     p->name, p->desc->name, object_role_name(both & OBJECT_ROLE_GLASS ? OBJECT_ROLE_GLASS : both),
                     source, maker->name, maker->desc->name, both & OBJECT_ROLE_GLASS ? "it" : "them");
    }
}

/* A glass or mirror of glTF's alphaMode MASK or BLEND drawn by the pass
 * that made the image a later pass draws it over (shade { specular = true }
 * before refraction): its holes, or its uncovered share, show shade's
 * drawing of it, not what lies behind it (tests/scenes/cut_specular.lua's
 * glass with holes: 0.197 from the reference so, 0.130 without). */
static void lint_cut_drawn_twice(struct lint *l)
{
    const struct graph *g = l->g;
    for (int i = 0; i < g->count && l->count < l->max; i++) {
        const struct pass *p = g->entries[i].pass;
        unsigned mine = kept(&g->entries[i]) && p->desc->draws ? p->desc->draws(p) : 0, theirs = 0;
        if (!(mine & OBJECT_ROLE_SPECULAR) || (mine & PASS_DRAWS_ANYTHING))
            continue;
        const char *source = NULL;
        const struct pass *maker = color_maker(g, p, &source, &theirs);
        for (int o = 0; maker && o < l->scene->object_count && l->count < l->max; o++) {
            const struct object *ob = l->scene->objects[o];
            bool blend = ob->material.alpha_blend, mask = ob->material.alpha_cutoff > 0.0f;
            if ((blend || mask) && (object_role(ob) & mine & theirs & OBJECT_ROLE_SPECULAR))
                snprintf(l->messages[l->count++], 400,
                         "object %d (%s, alphaMode %s) is drawn by pass '%s' (%s) into '%s', over which pass "
                         "'%s' (%s) draws it: %s shows it again, not what lies behind it (shade { specular = "
                         "false } leaves it to the later pass)",
                         o + 1, object_role_name(object_role(ob) & OBJECT_ROLE_SPECULAR), blend ? "BLEND" : "MASK",
                         maker->name, maker->desc->name, source, p->name, p->desc->name,
                         blend ? "its uncovered share" : "each of its holes");
        }
    }
}

/* A pass whose light is not in the scene makes nothing (the graph skips it). */
static void lint_absent_lights(struct lint *l)
{
    const struct graph *g = l->g;
    const struct scene *scene = l->scene;
    for (int i = 0; i < g->count && l->count < l->max; i++) {
        const struct pass *p = g->entries[i].pass;
        for (int k = 0; kept(&g->entries[i]) && k < p->desc->param_count && l->count < l->max; k++)
            if (p->desc->params[k].type == PASS_PARAM_LIGHT && p->values[k].light &&
                scene_light_index(scene, p->values[k].light) < 0)
                snprintf(l->messages[l->count++], 400,
                         "pass '%s' (%s): its %s is not among the scene's lights, so it makes nothing (add it with "
                         "scene:add(light))", p->name, p->desc->name, p->desc->params[k].name);
    }
}

/* Objects a kept pass leaves out (its descriptor says which and why). */
static void lint_left_out(struct lint *l)
{
    const struct graph *g = l->g;
    const struct scene *scene = l->scene;
    for (int i = 0; i < g->count && l->count < l->max; i++) {
        const struct graph_entry *e = &g->entries[i];
        const struct pass *p = e->pass;
        if (!kept(e) || !p->desc->leaves_out)
            continue;
        for (int k = 0; k < scene->object_count && l->count < l->max; k++) {
            const struct object *o = scene->objects[k];
            if (!object_is(o, OBJECT_ROLE_SPECULAR | OBJECT_ROLE_THIN))
                continue;
            const char *why = p->desc->leaves_out(p, scene, o);
            if (why)
                snprintf(l->messages[l->count++], 400, "pass '%s' (%s) leaves out object %d (%s): %s", p->name,
                         p->desc->name, k + 1, object_role_name(object_role(o)), why);
        }
    }
}

/* A medium in the scene and caustics on surfaces only: no pass draws
 * the light the refractors bend scattered on its way (issue 52: a
 * glass ball in fog under photon_caustics showed no shaft, and no
 * line said why). One line a pass, naming its refractors. */
static void lint_no_volume_caustics(struct lint *l)
{
    const struct graph *g = l->g;
    const struct scene *scene = l->scene;
    bool volume = lint_volume_caustics(g);
    for (int i = 0; i < g->count && scene->medium && !volume && l->count < l->max; i++) {
        const struct pass *p = g->entries[i].pass;
        if (!kept(&g->entries[i]) || !p->desc->surface_caustics_only)
            continue;
        char names[160] = "";
        int listed = 0, refractors = 0;
        for (int k = 0; k < scene->object_count; k++) {
            if (!object_is(scene->objects[k], OBJECT_ROLE_REFRACTOR))
                continue;
            refractors++;
            if (listed < 4) {
                size_t used = strlen(names);
                snprintf(names + used, sizeof names - used, "%s%d (%s)", listed ? ", " : "", k + 1,
                         object_role_name(object_role(scene->objects[k])));
                listed++;
            }
        }
        if (refractors > 0)
            snprintf(l->messages[l->count++], 400,
                     "pass '%s' (%s) makes caustics on surfaces only: none of the light that object%s %s%s bend%s is "
                     "drawn where the scene's medium scatters it (no volume caustic: add beam_caustics, whose "
                     "inscatter volume_light adds)",
                     p->name, p->desc->name, refractors > 1 ? "s" : "", names, refractors > listed ? ", ..." : "",
                     refractors > 1 ? "" : "s");
    }
}

/* The camera inside a refractor that a view technique draws, in a graph
 * that makes caustics: what it sees through the glass is lit by that
 * pass's own lookups, without them (issue 52: the camera in a glass
 * ball over a floor saw no caustic, where the reference's floor shows
 * the ball's focus in its shadow). */
static void lint_camera_in_glass(struct lint *l, bool volume)
{
    const struct graph *g = l->g;
    const struct scene *scene = l->scene;
    bool caustics = volume;
    for (int i = 0; i < g->count; i++)
        caustics = caustics || (kept(&g->entries[i]) && g->entries[i].pass->desc->surface_caustics_only);
    for (int i = 0; i < g->count && caustics && l->count < l->max; i++) {
        const struct pass *p = g->entries[i].pass;
        unsigned mine = kept(&g->entries[i]) && p->desc->draws ? p->desc->draws(p) : 0;
        if (!p->desc->behind_glass_without_caustics || !(mine & OBJECT_ROLE_REFRACTOR))
            continue;
        /* what its input shows behind the glass: nothing, where the pass
         * that made it drew the glass itself */
        unsigned theirs = 0;
        for (int k = 0; k < p->input_count; k++) {
            const struct pass *maker = strcmp(p->inputs[k].name, "color") == 0 ? producer(g, p->inputs[k].source) : NULL;
            theirs |= maker && maker->desc->draws ? maker->desc->draws(maker) : 0;
        }
        for (int k = 0; k < scene->object_count && l->count < l->max; k++) {
            const struct object *o = scene->objects[k];
            unsigned role = object_role(o);
            if (object_is(o, OBJECT_ROLE_REFRACTOR) && (mine & role) && (theirs & (role | PASS_DRAWS_ANYTHING)) &&
                object_contains_point(o, scene->camera.eye))
                snprintf(l->messages[l->count++], 400,
                         "pass '%s' (%s): the camera is inside object %d (%s), which its input shows, so what it sees "
                         "through it is its own lookups' view, lit without caustics (the caustics passes' images are "
                         "of the surfaces the camera sees directly): shade { specular = false } leaves them in the input",
                         p->name, p->desc->name, k + 1, object_role_name(role));
        }
    }
}

/* A depth range the 24 bits of the depth buffers cannot resolve at the
 * scene: perspective depth steps grow as distance^2 / near, an
 * orthographic camera's are (far - near) / 2^24 everywhere. Surfaces
 * closer than a step are confused (a silhouette's pixels take the wrong
 * side); the frame still renders, so this is said, not refused. */
static void lint_depth_range(struct lint *l)
{
    const struct scene *scene = l->scene;
    vec3 lo, hi;
    const struct camera *cam = &scene->camera;
    if (l->count < l->max && scene_bounds(scene, &lo, &hi)) {
        float size = vec3_length(vec3_sub(hi, lo));
        float far_corner = 0.0f;
        for (int k = 0; k < 8; k++) {
            vec3 corner = {k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z};
            far_corner = fmaxf(far_corner, vec3_length(vec3_sub(corner, cam->eye)));
        }
        float d = fminf(far_corner, cam->zfar);
        double step = cam->ortho_width > 0.0f ? ((double)cam->zfar - cam->znear) / 16777216.0
                                              : (double)d * d / fmax(cam->znear, 1e-30) / 16777216.0;
        if (size > 0.0f && step > 1e-3 * size)
            snprintf(l->messages[l->count++], 400,
                     "the camera's near and far planes (%g, %g) resolve depth only to %.3g at the scene (%.2g%% of its "
                     "size): surfaces closer than that are confused, at silhouettes first; raise near or lower far",
                     (double)cam->znear, (double)cam->zfar, step, 100.0 * step / size);
    }
}

/* The camera inside an opaque closed object: the frame shows its inside
 * faces (culled or black) instead of the scene, and nothing says why.
 * (Inside glass or water is a view the refraction passes handle.) */
static void lint_camera_in_opaque(struct lint *l)
{
    const struct scene *scene = l->scene;
    const struct camera *cam = &scene->camera;
    for (int i = 0; i < scene->object_count && l->count < l->max; i++) {
        const struct object *o = scene->objects[i];
        if (!o->visible || object_is(o, OBJECT_ROLE_SPECULAR) || !object_encloses_point(o, cam->eye))
            continue;
        snprintf(l->messages[l->count++], 400,
                 "the camera (eye at %g, %g, %g) is inside object %d (%s, '%.60s'), a closed opaque surface: the "
                 "frame shows its inside, not the scene; move the eye out of it, or hide the object",
                 (double)cam->eye.x, (double)cam->eye.y, (double)cam->eye.z, i + 1, object_role_name(object_role(o)),
                 o->mesh ? o->mesh->name : "?");
    }
}

/* Caustics added for a light that the same pass does not shadow (shade's
 * `caustics` and `shadow` inputs). */
static void lint_unshadowed_caustics(struct lint *l)
{
    const struct graph *g = l->g;
    for (int i = 0; i < g->count && l->count < l->max; i++) {
        const struct graph_entry *e = &g->entries[i];
        const struct pass *shade = e->pass;
        if (!kept(e))
            continue;
        for (int k = 0; k < shade->input_count && l->count < l->max; k++) {
            if (strncmp(shade->inputs[k].name, "caustics", 8) != 0)
                continue;
            const struct pass *maker = producer(g, shade->inputs[k].source);
            struct light *light = maker ? light_of(maker) : NULL;
            if (!light)
                continue;
            bool shadowed = false;
            for (int m = 0; m < shade->input_count; m++) {
                if (strncmp(shade->inputs[m].name, "shadow", 6) != 0)
                    continue;
                const struct pass *map = producer(g, shade->inputs[m].source);
                shadowed = shadowed || (map && light_of(map) == light);
            }
            if (!shadowed)
                snprintf(l->messages[l->count++], 400,
                         "pass '%s' adds the caustics of '%s' for a light it does not shadow (no shadow map of that "
                         "light in its shadow list): the surfaces under the glass get that light twice, directly "
                         "and as caustics; add the light's shadow_map to shade's shadow",
                         shade->name, maker->name);
        }
    }
}

int graph_lint(const struct graph *g, const struct scene *scene, const mat4 *view_proj, char messages[][400], int max)
{
    struct lint l = {.g = g, .scene = scene, .messages = messages, .max = max};
    lint_undrawn(&l, view_proj);
    lint_drawn_twice(&l);
    lint_cut_drawn_twice(&l);
    lint_absent_lights(&l);
    lint_left_out(&l);
    lint_no_volume_caustics(&l);
    lint_camera_in_glass(&l, lint_volume_caustics(g));
    lint_depth_range(&l);
    lint_camera_in_opaque(&l);
    lint_unshadowed_caustics(&l);
    return l.count;
}

/* The phrases of the sentences above that say something is not drawn. */
static const char *const omissions[] = {" leaves out object ", " makes caustics on surfaces only: ",
                                        " lit without caustics "};

bool graph_lint_is_omission(const char *message)
{
    for (size_t i = 0; i < sizeof omissions / sizeof omissions[0]; i++)
        if (strstr(message, omissions[i]))
            return true;
    return false;
}
