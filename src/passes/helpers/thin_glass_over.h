/* Thin-walled glass in front of what a view technique draws (issue 50).
 * shade draws the panes over its image (common/thin_glass.frag); a view
 * technique after it (refraction, layered_refraction, sliced_refraction,
 * water_surface) draws its glass or water over shade's image, and looks up
 * what lies behind them in that image. So a pane in front of a visible
 * glass, water or mirror surface is left out of shade's image (where it
 * would be drawn over, and would tint what the technique looks up behind
 * the glass), and drawn by the technique over the surface it drew, the
 * same way. */
#ifndef CAUSTICA_THIN_GLASS_OVER_H
#define CAUSTICA_THIN_GLASS_OVER_H

#include <stdbool.h>

#include "core/error.h"
#include "gl/gl_texture.h"
#include "graph/pass.h"
#include "scene/scene.h"

/* Owned by the pass that draws with it, released by it. */
struct thin_glass_over {
    struct gl_texture surface; /* r32f: the nearest visible surface's window depth, 1 where none */
    struct gl_framebuffer surface_fb, color_fb;
};

enum thin_glass_panes {
    THIN_GLASS_ALL,            /* every pane */
    THIN_GLASS_BEHIND_SURFACES,/* shade: all but those in front of a visible surface of `roles` */
    THIN_GLASS_OVER_SURFACES,  /* a view technique: those alone */
};

/* Whether the scene has visible thin glass (nothing to do otherwise). */
bool thin_glass_in_scene(const struct scene *scene);

/* Draws the panes of `which` back to front, blended (dual-source) into
 * `color`, or where it is NULL into `framebuffer`'s first draw buffer (as
 * its owner set its draw buffers), depth
 * tested against `scene_depth` where it is not NULL. The surfaces are the
 * visible objects of `roles` (OBJECT_ROLE_*), or `only` alone where it is
 * not NULL, where they lie in front of `scene_depth`. */
bool thin_glass_draw(struct thin_glass_over *s, struct pass *p, struct pass_frame *f, enum thin_glass_panes which,
                     GLuint framebuffer, const struct gl_texture *color, const struct gl_texture *scene_depth, unsigned roles,
                     struct object *only, struct error *err);
void thin_glass_over_release(struct thin_glass_over *s);

#endif
