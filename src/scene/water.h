/* A water surface: a height field on a regular xz grid (square or
 * rectangular: nx by nz vertices over size_x by size_z) with waves that
 * propagate by the 2D wave equation, drops, damping, reflective or fixed
 * boundaries, and per-vertex normals. Its mesh is an ordinary scene object
 * (material water) whose vertex buffers the simulation fills each frame. */
#ifndef CAUSTICA_WATER_H
#define CAUSTICA_WATER_H

#include <stdbool.h>

#include "core/error.h"
#include "scene/scene.h"

struct water {
    int nx, nz;          /* vertices along x and along z */
    float size_x, size_z; /* the extent along x and z (scene units), centred on the object's origin */
    float depth;         /* from the mean surface down to the pool floor */
    float wave_speed;    /* c in h_tt = c^2 lap(h) - damping h_t */
    float damping;
    bool fixed_boundary; /* h = 0 at the border; else reflective (zero slope) */
    double *height, *velocity; /* nx * nz each (x fastest), owned */
    double time;
    long substeps;       /* total substeps taken (for tests and progress) */
    bool dirty;          /* heights changed since the GPU buffers were written */
    double energy;       /* the discrete energy at the last substep's kick */
    bool dirty_energy;   /* heights were set since: recompute it */
};

/* `resolution` vertices along the longer side; the shorter side gets the
 * count that keeps the cells nearest to square (at least 2). */
bool water_create(struct water *w, int resolution, float size_x, float size_z, float depth, float wave_speed,
                  float damping, bool fixed_boundary, struct error *err);
/* The vertices along each side water_create would choose. */
void water_grid_counts(int resolution, float size_x, float size_z, int *nx, int *nz);
void water_release(struct water *w);
/* A smooth bump: strength * (cos(pi r / radius) + 1) / 2 inside radius. */
void water_drop(struct water *w, float x, float z, float radius, float strength);
/* Advances by dt, substepping to the stability limit. */
void water_step(struct water *w, double dt);
/* The largest stable substep (CFL for the 2D explicit scheme, with margin). */
double water_stable_step(const struct water *w);
/* The discrete energy leapfrog conserves (see water.c), times the cell area. */
double water_energy(const struct water *w);
/* Fills vertex positions (object space, grid centred at the origin) and normals. */
void water_fill_vertices(const struct water *w, float *positions, float *normals);
/* The largest |height| of the surface. */
double water_max_height(const struct water *w);
/* Sets every height from height(user, x, z) (velocities to 0); false with a
 * message naming the point when it returns a non-finite height. */
bool water_set_heights(struct water *w, double (*height)(void *user, double x, double z), void *user,
                       struct error *err);

#endif
