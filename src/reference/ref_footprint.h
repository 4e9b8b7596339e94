/* A pixel's footprint along an eye path, for the textures' mip level:
 * ray differentials (Igehy 1999, "Tracing Ray Differentials") carried as
 * the rays of the next pixel across and the next one down, each kept on
 * the surfaces the path itself meets (the plane of the path's triangle,
 * the normal interpolated at its own barycentrics), so that a curved
 * mirror or lens spreads or narrows the footprint as it does the pixel's
 * light. The rasterizer's texture derivatives are these differences at
 * the first surface; the reference with them reads a minified texture
 * through the same mip levels (texture_sample_grad) rather than point-
 * sampling level 0, which aliased a distant texture's detail (issue 50's
 * DamagedHelmet). */
#ifndef CAUSTICA_REF_FOOTPRINT_H
#define CAUSTICA_REF_FOOTPRINT_H

#include "reference/ref_scene.h"

struct ref_footprint {
    bool valid;
    dvec3 origin[2], dir[2]; /* the neighbours' rays: across, down */
    dvec3 point[2];          /* where they met the last hit's plane */
    double bary[2][2];       /* and their barycentrics on its triangle */
};

/* The neighbours of the primary ray through image point (px, py). */
void ref_footprint_camera(const struct ref_scene *rs, double px, double py, int width, int height,
                          struct ref_footprint *f);
/* The path met h: the neighbours meet h's triangle's plane; h->footprint
 * and h->dbary say how far their barycentrics lie from h's. */
void ref_footprint_hit(const struct ref_scene *rs, struct ref_footprint *f, struct ref_hit *h);
/* The path left h's surface from direction `in` along `out` (reflected,
 * refracted, or on through a thin pane): the neighbours do the same at
 * their own points. A rough surface's random microfacet ends the
 * footprint (the textures beyond are read at level 0). */
void ref_footprint_bounce(const struct ref_scene *rs, struct ref_footprint *f, const struct ref_hit *h, dvec3 in,
                          dvec3 out);

#endif
