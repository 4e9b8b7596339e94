/* Shadow map inputs of a pass (shade, volume_light, refraction): the slots
 * shadow0..3 of an input list parameter `shadow` (declared from the
 * descriptor, .max = SHADOW_INPUTS_MAX), bound with the uniforms of
 * shaders/common/shadows.glsl. */
#ifndef CAUSTICA_SHADOW_INPUTS_H
#define CAUSTICA_SHADOW_INPUTS_H

#include <stdbool.h>

#include "core/error.h"
#include "gl/gl_program.h"
#include "graph/pass.h"

#define SHADOW_INPUTS_MAX 4 /* the sampler arrays u_shadow_2d[4] and u_shadow_cubes[4] */

/* What a shadow map's depth texture carries for its readers: the
 * resource's record, of SHADOW_MAP_RECORD's type (graph/pass.h), owned by
 * the shadow_map pass, NULL on a frame it made nothing. */
extern const struct record_type SHADOW_MAP_RECORD;
struct shadow_record {
    mat4 matrix;     /* the light's view-projection (2D), or its translation to the origin (cube) */
    int light_index; /* the light's first entry in the frame's GPU light list */
    int kind;        /* enum light_kind */
    float range;     /* far plane, or the cube's distance range */
    float bias;
    GLuint filter;   /* 2D maps: what thin-walled glass lets through (RGB) and its depth (A), or 0 */
};

/* A caustics pass's `shadow` parameter: the light's shadow map, whose pane
 * filter dims and tints the light where it meets the glass (issue 50;
 * pane_filter in common/shadows.glsl). `what`: the pass's light carrier. */
#define SHADOW_PARAM_PANES(what)                                                                                 \
    {.name = "shadow", .type = PASS_PARAM_INPUT_LIST, .max = SHADOW_INPUTS_MAX, .record = &SHADOW_MAP_RECORD,     \
     .help = "the light's shadow map (its `depth`): " what " that crossed thin-walled panes on its way to the glass " \
             "carries what they let through, (1 - F) x tint, as the map's pane filter has it; without it panes are " \
             "not seen"}

/* What a caustics pass leaves out of pane `o` (thin-walled glass), or NULL:
 * a pass with a `shadow` parameter (SHADOW_PARAM_PANES) sees panes between
 * the light and the glass when it is given the light's shadow map; one
 * without does not see them; and no pass dims a caustic by a pane that lies
 * beyond glass, water or a mirror as its light sees them (between them and
 * the receivers). */
const char *shadow_inputs_pane_left_out(const struct pass *p, const struct scene *scene, const struct object *o);

/* Gives `block` (a building block with a `shadow` list) the shadow maps of
 * `reader`'s parameter `reader_shadow` (-1: none): what lights the reader's
 * own surfaces lights the block it asks the graph for (its distance map, its
 * impostors). */
bool shadow_inputs_give(struct pass *block, const struct pass *reader, int reader_shadow, struct error *err);

/* Binds the shadow maps and sets the uniforms on `program`. */
void shadow_inputs_bind(struct pass *p, struct pass_frame *f, const struct gl_program *program);

#endif
