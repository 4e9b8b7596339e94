/* What a caustics pass left dark under glass (issue 52): the receiver
 * pixels the camera sees in the refractors' shadow from the pass's light
 * (their depth from that light, a texel's margin inside the outline) that
 * got none of its light. Exact light reaches almost all of a glass object's
 * shadow, thinly where it grazes the rim; a pass whose photons, beams or
 * volumes land too far apart leaves black pixels between them. Measured
 * once, on the first frame a pass instance makes with refractors in view,
 * and said in one warning that names the pass, the object and the count
 * where a third of the shadow or more is dark (glass does keep smaller
 * parts dark: a tilted cube of IOR 2.42, a quarter). */
#ifndef CAUSTICA_CAUSTIC_COVERAGE_H
#define CAUSTICA_CAUSTIC_COVERAGE_H

#include <stdbool.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "gl/gl_texture.h"

struct pass;
struct pass_frame;
struct frame_light;

struct caustic_coverage {
    bool checked;               /* measured already (once a pass instance) */
    struct gl_texture depth;    /* the refractors' depth from the light, where the pass has none */
    struct gl_framebuffer fb;
    GLuint counters;            /* ssbo: shadow, dark */
};

/* Where the refractors lie as the pass's light sees them, from what the pass
 * already made (no draw): the layers' first depths (eye depths, a 2D array,
 * with their per-texel count), or a window depth of the nearest specular
 * surface with its normals (w < 0: a mirror, left out). Neither (depth 0):
 * the refractors are drawn once from the light, through the layers' fit. */
struct caustic_coverage_view {
    bool layers;
    GLuint depth, info, normal;
    mat4 view, proj;
};

void caustic_coverage_init(struct caustic_coverage *c);
void caustic_coverage_release(struct caustic_coverage *c);
/* Measures `irradiance` (the pass's output at the frame's size) over the
 * receivers (`receiver_depth`, window depths at the frame's size;
 * `receiver_normal` their world normals, or 0 where the pass has none) lit by
 * `light`, and warns once where 30% of the shadow or more, and 16 pixels or
 * more, is dark; `remedy` ends the warning (what to raise). Does nothing
 * after the first measure. */
bool caustic_coverage_check(struct caustic_coverage *c, struct pass *p, struct pass_frame *f,
                            const struct frame_light *light, const struct caustic_coverage_view *view,
                            GLuint receiver_depth, GLuint receiver_normal, const struct gl_texture *irradiance,
                            const char *remedy, struct error *err);

#endif
