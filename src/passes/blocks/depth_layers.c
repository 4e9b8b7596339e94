/* depth_layers: the refractors' depth layers seen from a light or from the
 * camera, a building block (issue 26). Chaudhari 2008 §3.3-3.5 (passes/helpers/layers.c builds them:
 * bounds, voxelization, peeling, per-layer normals): from the light they
 * are Liktor & Dachsbacher's light-space G-buffer (§4.1), through which
 * beam_caustics traces its grid, and the photons of layered_caustics
 * (Chaudhari §4.1); from the camera, the layers layered_refraction traces
 * its rays through (§3.6-3.8). The graph adds one per light and configuration when a
 * script names none, so two techniques for one light build its layers
 * once. The output `layers` is a bundle (a `layer_set` record: five
 * textures, two buffers, the view) that readers bind with layers_bind. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "graph/frame.h"
#include "graph/pass.h"
#include "graph/renderer.h"
#include "passes/helpers/layers.h"

struct depth_layers_state {
    struct layer_set layers;
};

enum depth_layers_param {
    DL_VIEW,
    DL_LIGHT,
    DL_BUFFER,
    DL_LAYERS,
    DL_VOXELS,
    DL_DEPTHS,
};
enum { VIEW_LIGHT, VIEW_CAMERA };
enum { DEPTHS_EXACT, DEPTHS_VOXEL };

static const struct pass_param_desc params[] = {
    [DL_VIEW] = {.name = "view", .type = PASS_PARAM_ENUM, .default_string = "light", .choices = "light|camera",
     .help = "whose view of the refractors (glass and water): `light`'s, or the camera's at the frame's size"},
    [DL_LIGHT] = {.name = "light", .type = PASS_PARAM_LIGHT, .help = "the light, for view = \"light\""},
    [DL_BUFFER] = LAYERS_PARAM_BUFFER("the light's view, buffer x buffer texels"),
    [DL_LAYERS] = LAYERS_PARAM_LAYERS(8, "depth layers per texel"),
    [DL_VOXELS] = LAYERS_PARAM_VOXELS("slices per texel, a multiple of 128"),
    [DL_DEPTHS] = LAYERS_PARAM_DEPTHS("each layer's depth: the surface's own, or its slice's centre (§3.4.2)"),
};

static bool depth_layers_declare(struct pass *p, struct error *err)
{
    if (pass_choice(p, DL_VIEW) == VIEW_LIGHT && !pass_light_at(p, DL_LIGHT))
        return error_set(err, "bad argument 'light' to 'depth_layers' (a light expected for view = \"light\", got no "
                              "value)");
    return pass_declare_bundle(p, "layers", &LAYER_SET_RECORD, err);
}

static bool depth_layers_create(struct pass *p, struct renderer *r, struct error *err)
{
    (void)r;
    struct depth_layers_state *s = calloc(1, sizeof *s);
    if (!s)
        return error_set(err, "out of memory");
    layers_init(&s->layers);
    p->state = s;
    return true;
}

static void depth_layers_destroy(struct pass *p)
{
    struct depth_layers_state *s = p->state;
    if (!s)
        return;
    layers_release(&s->layers);
    free(s);
    p->state = NULL;
}

static bool depth_layers_execute(struct pass *p, struct pass_frame *f, struct error *err)
{
    struct depth_layers_state *s = p->state;
    pass_frame_output(p, f, "layers")->record = &s->layers;
    s->layers.built = false;
    struct renderer *r = f->renderer;
    vec3 lo, hi;
    mat4 view, proj;
    int width, height;
    /* the refractors only (glass and water: what the layers hold; a mirror
     * widened the light's view and took its texels) */
    struct light_view lv = {0};
    int slot = -1;
    if (pass_choice(p, DL_VIEW) == VIEW_CAMERA) {
        if (!scene_role_bounds(f->scene, OBJECT_ROLE_REFRACTOR, &lo, &hi) ||
            !scene_specular_in_view(f->scene, f->snapshot->view_proj))
            return true; /* no glass or water in the camera's view: the readers pass the image through */
        view = f->snapshot->view;
        proj = f->snapshot->proj;
        width = f->width;
        height = f->height;
    } else {
        slot = renderer_light_slot(r, f->scene, pass_light_at(p, DL_LIGHT));
        if (slot < 0 || !scene_role_bounds(f->scene, OBJECT_ROLE_REFRACTOR, &lo, &hi))
            return true; /* the light is not in the scene, or nothing refracts: the readers draw nothing */
        if (!layers_light_view(&f->snapshot->lights[slot], lo, hi, &lv, "depth_layers", err))
            return false;
        view = lv.view;
        proj = lv.proj;
        width = height = pass_int(p, DL_BUFFER);
    }
    pass_stage_begin(p);
    if (!layers_build(&s->layers, r, f->scene, view, proj, width, height, pass_int(p, DL_VOXELS),
                      pass_int(p, DL_LAYERS), pass_choice(p, DL_DEPTHS) == DEPTHS_EXACT, p, err))
        return false;
    s->layers.light_slot = slot;
    s->layers.lo = lo;
    s->layers.hi = hi;
    s->layers.light_view = lv;
    s->layers.radius = fmaxf(0.5f * vec3_length(vec3_sub(hi, lo)), 1e-4f) * LAYERS_RADIUS_SCALE;
    snprintf(p->report, sizeof p->report, "%d refractor draws, %ld triangles", s->layers.draws, s->layers.triangles);
    return true;
}

/* Made again only when the geometry, the light (a LIGHT parameter's
 * version is always in the key) or, from the camera, the camera changed. */
static unsigned depth_layers_depends(const struct pass *p)
{
    return PASS_DEPENDS_GEOMETRY | (pass_choice(p, DL_VIEW) == VIEW_CAMERA ? PASS_DEPENDS_CAMERA : 0u);
}

const struct pass_desc depth_layers_pass = {
    .depends = depth_layers_depends,
    .name = "depth_layers",
    .summary = "building block: the refractors' depth layers from a light or the camera (Chaudhari 2008 §3.3-3.5), "
               "shared by beam_caustics and layered_caustics",
    .params = params,
    .param_count = sizeof params / sizeof params[0],
    .declare = depth_layers_declare,
    .create = depth_layers_create,
    .execute = depth_layers_execute,
    .destroy = depth_layers_destroy,
};
