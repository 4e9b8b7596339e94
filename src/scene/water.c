/* The water height field. Time integration: symplectic Euler (a kick,
 * then a drift: leapfrog) on the 2D wave equation with the 5-point graph
 * Laplacian (spacings dx along x and dz along z), substepped so that every
 * substep satisfies the CFL condition c dt sqrt(1/dx^2 + 1/dz^2) <= 1 (we
 * keep half of it: c dt / dx <= 0.5 on a square grid): any time step a
 * script uses stays stable. Damping is applied implicitly (v /= 1 + damping dt), which can
 * only remove energy. Boundaries: fixed (h = 0) or reflective (zero normal
 * slope: a border node's missing neighbour is itself), both of which keep
 * the Laplacian symmetric, so leapfrog conserves the discrete energy
 *   E = 1/2 v_old . v_new + 1/2 c^2 sum over grid edges (dh / dx)^2
 * exactly when damping is 0 (it tends to the physical energy as dt -> 0). */
#include "scene/water.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CFL_SAFETY 0.5
#define MAX_SUBSTEPS 100000 /* a cap on one call; dt beyond that is clamped */

void water_grid_counts(int resolution, float size_x, float size_z, int *nx, int *nz)
{
    double longer = fmax(size_x, size_z), shorter = fmin(size_x, size_z);
    long other = lround(shorter / longer * (resolution - 1)) + 1;
    int short_count = (int)(other < 2 ? 2 : other > resolution ? resolution : other);
    *nx = size_x >= size_z ? resolution : short_count;
    *nz = size_x >= size_z ? short_count : resolution;
}

bool water_create(struct water *w, int resolution, float size_x, float size_z, float depth, float wave_speed,
                  float damping, bool fixed_boundary, struct error *err)
{
    memset(w, 0, sizeof *w);
    if (resolution < 2 || resolution > 2048)
        return error_set(err, "water: resolution must be 2..2048, got %d", resolution);
    if (!(size_x > 0) || !(size_z > 0) || !(depth > 0) || !(wave_speed > 0) || !(damping >= 0) ||
        !isfinite(size_x) || !isfinite(size_z) || !isfinite(depth) || !isfinite(wave_speed) || !isfinite(damping))
        return error_set(err, "water: size, depth and wave speed must be > 0 and damping >= 0");
    if (fmax(size_x, size_z) / fmin(size_x, size_z) > 1000.0)
        return error_set(err, "water: the sides %g and %g differ by more than 1000 times", (double)size_x,
                         (double)size_z);
    water_grid_counts(resolution, size_x, size_z, &w->nx, &w->nz);
    size_t n = (size_t)w->nx * (size_t)w->nz;
    w->height = calloc(n, sizeof *w->height);
    w->velocity = calloc(n, sizeof *w->velocity);
    if (!w->height || !w->velocity) {
        water_release(w);
        return error_set(err, "water: out of memory for a %dx%d grid", w->nx, w->nz);
    }
    w->size_x = size_x;
    w->size_z = size_z;
    w->depth = depth;
    w->wave_speed = wave_speed;
    w->damping = damping;
    w->fixed_boundary = fixed_boundary;
    w->dirty = true;
    return true;
}

void water_release(struct water *w)
{
    free(w->height);
    free(w->velocity);
    w->height = w->velocity = NULL;
}

static double spacing_x(const struct water *w) { return (double)w->size_x / (double)(w->nx - 1); }
static double spacing_z(const struct water *w) { return (double)w->size_z / (double)(w->nz - 1); }
static size_t node(const struct water *w, int i, int j) { return (size_t)j * (size_t)w->nx + (size_t)i; }

void water_drop(struct water *w, float x, float z, float radius, float strength)
{
    if (!(radius > 0) || !isfinite(strength))
        return;
    double dx = spacing_x(w), dz = spacing_z(w), half_x = 0.5 * w->size_x, half_z = 0.5 * w->size_z;
    for (int j = 0; j < w->nz; j++)
        for (int i = 0; i < w->nx; i++) {
            double px = -half_x + i * dx, pz = -half_z + j * dz;
            double r = sqrt((px - x) * (px - x) + (pz - z) * (pz - z));
            if (r < radius)
                w->height[node(w, i, j)] += strength * 0.5 * (cos(MATH_PI * r / radius) + 1.0);
        }
    w->dirty = true;
    w->dirty_energy = true;
}

double water_stable_step(const struct water *w)
{
    /* CFL: c dt sqrt(1/dx^2 + 1/dz^2) <= 1, halved (sqrt(2) x 0.5 dx / c on a square grid) */
    double dx = spacing_x(w), dz = spacing_z(w);
    return CFL_SAFETY * sqrt(2.0) / (w->wave_speed * sqrt(1.0 / (dx * dx) + 1.0 / (dz * dz)));
}

static double at(const struct water *w, int i, int j)
{
    if (i < 0 || j < 0 || i >= w->nx || j >= w->nz) {
        if (w->fixed_boundary)
            return 0.0;
        /* reflective: the missing neighbour is the node itself (zero flux) */
        i = i < 0 ? 0 : i >= w->nx ? w->nx - 1 : i;
        j = j < 0 ? 0 : j >= w->nz ? w->nz - 1 : j;
    }
    return w->height[node(w, i, j)];
}

/* 1/2 c^2 sum over edges of (dh/dx)^2 (times the cell area): the potential energy. */
static double potential(const struct water *w)
{
    double dx = spacing_x(w), dz = spacing_z(w), c2 = (double)w->wave_speed * w->wave_speed, e = 0.0;
    for (int j = 0; j < w->nz; j++)
        for (int i = 0; i < w->nx; i++) {
            double h = at(w, i, j);
            double gx = (at(w, i + 1, j) - h) / dx, gz = (at(w, i, j + 1) - h) / dz;
            if (!w->fixed_boundary) {
                /* edges to the outside carry no energy (zero slope) */
                if (i == w->nx - 1)
                    gx = 0.0;
                if (j == w->nz - 1)
                    gz = 0.0;
            }
            e += 0.5 * c2 * (gx * gx + gz * gz);
        }
    return e * dx * dz;
}

static void substep(struct water *w, double dt)
{
    int nx = w->nx, nz = w->nz;
    double c2 = (double)w->wave_speed * w->wave_speed;
    double inv_dx2 = 1.0 / (spacing_x(w) * spacing_x(w)), inv_dz2 = 1.0 / (spacing_z(w) * spacing_z(w));
    double kinetic = 0.0;
    /* v += dt c^2 lap(h); v /= 1 + damping dt; h += dt v (symplectic Euler) */
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nx; i++) {
            size_t k = node(w, i, j);
            if (w->fixed_boundary && (i == 0 || j == 0 || i == nx - 1 || j == nz - 1)) {
                w->velocity[k] = 0.0;
                continue;
            }
            double h = w->height[k];
            double lap = (at(w, i - 1, j) + at(w, i + 1, j) - 2.0 * h) * inv_dx2 +
                         (at(w, i, j - 1) + at(w, i, j + 1) - 2.0 * h) * inv_dz2;
            double v_old = w->velocity[k];
            w->velocity[k] = (v_old + dt * c2 * lap) / (1.0 + w->damping * dt);
            kinetic += 0.5 * v_old * w->velocity[k];
        }
    w->energy = kinetic * spacing_x(w) * spacing_z(w) + potential(w); /* at the kick: leapfrog's conserved energy */
    for (size_t k = 0; k < (size_t)nx * (size_t)nz; k++)
        w->height[k] += dt * w->velocity[k];
    if (w->fixed_boundary) {
        for (int i = 0; i < nx; i++)
            w->height[node(w, i, 0)] = w->height[node(w, i, nz - 1)] = 0.0;
        for (int j = 0; j < nz; j++)
            w->height[node(w, 0, j)] = w->height[node(w, nx - 1, j)] = 0.0;
    }
}

void water_step(struct water *w, double dt)
{
    if (!(dt > 0) || !isfinite(dt))
        return;
    double limit = water_stable_step(w);
    long steps = (long)ceil(dt / limit);
    if (steps > MAX_SUBSTEPS)
        steps = MAX_SUBSTEPS; /* dt larger than that is clamped: time slows, nothing blows up */
    double h = fmin(dt / (double)steps, limit);
    for (long s = 0; s < steps; s++)
        substep(w, h);
    w->time += h * (double)steps;
    w->substeps += steps;
    w->dirty = true;
    w->dirty_energy = false;
}

double water_energy(const struct water *w)
{
    if (w->substeps > 0 && !w->dirty_energy)
        return w->energy;
    /* before any step (or after drops and set_heights): 1/2 |v|^2 + potential */
    double kinetic = 0.0;
    for (size_t k = 0; k < (size_t)w->nx * (size_t)w->nz; k++)
        kinetic += 0.5 * w->velocity[k] * w->velocity[k];
    return kinetic * spacing_x(w) * spacing_z(w) + potential(w);
}

void water_fill_vertices(const struct water *w, float *positions, float *normals)
{
    int nx = w->nx, nz = w->nz;
    double dx = spacing_x(w), dz = spacing_z(w), half_x = 0.5 * w->size_x, half_z = 0.5 * w->size_z;
    for (int j = 0; j < nz; j++)
        for (int i = 0; i < nx; i++) {
            size_t k = node(w, i, j);
            positions[k * 3] = (float)(-half_x + i * dx);
            positions[k * 3 + 1] = (float)w->height[k];
            positions[k * 3 + 2] = (float)(-half_z + j * dz);
            /* central differences (one-sided at the border) */
            int i0 = i > 0 ? i - 1 : i, i1 = i < nx - 1 ? i + 1 : i, j0 = j > 0 ? j - 1 : j, j1 = j < nz - 1 ? j + 1 : j;
            double sx = (w->height[node(w, i1, j)] - w->height[node(w, i0, j)]) / ((i1 - i0) * dx);
            double sz = (w->height[node(w, i, j1)] - w->height[node(w, i, j0)]) / ((j1 - j0) * dz);
            double len = sqrt(sx * sx + 1.0 + sz * sz);
            normals[k * 3] = (float)(-sx / len);
            normals[k * 3 + 1] = (float)(1.0 / len);
            normals[k * 3 + 2] = (float)(-sz / len);
        }
}

double water_max_height(const struct water *w)
{
    double hmax = 0.0;
    for (size_t i = 0; i < (size_t)w->nx * (size_t)w->nz; i++)
        hmax = fmax(hmax, fabs(w->height[i]));
    return hmax;
}

bool water_set_heights(struct water *w, double (*height)(void *user, double x, double z), void *user,
                       struct error *err)
{
    double dx = spacing_x(w), dz = spacing_z(w), half_x = 0.5 * w->size_x, half_z = 0.5 * w->size_z;
    for (int j = 0; j < w->nz; j++)
        for (int i = 0; i < w->nx; i++) {
            double x = -half_x + i * dx, z = -half_z + j * dz;
            double h = height(user, x, z);
            if (!isfinite(h))
                return error_set(err, "set_heights: the function returned a non-finite height at (%g, %g)", x, z);
            w->height[node(w, i, j)] = h;
            w->velocity[node(w, i, j)] = 0.0;
        }
    w->dirty = true;
    w->dirty_energy = true;
    return true;
}
