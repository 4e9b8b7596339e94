/* The water height field. Time integration: symplectic Euler (a kick,
 * then a drift: leapfrog) on the 2D wave equation with the 5-point graph
 * Laplacian, substepped so that every substep satisfies the CFL condition
 * c dt / dx <= 1/sqrt(2) (we keep 0.5): any time step a script uses stays
 * stable. Damping is applied implicitly (v /= 1 + damping dt), which can
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

bool water_create(struct water *w, int resolution, float size, float depth, float wave_speed, float damping,
                  bool fixed_boundary, struct error *err)
{
    memset(w, 0, sizeof *w);
    if (resolution < 2 || resolution > 2048)
        return error_set(err, "water: resolution must be 2..2048, got %d", resolution);
    if (!(size > 0) || !(depth > 0) || !(wave_speed > 0) || !(damping >= 0) || !isfinite(size) || !isfinite(depth) ||
        !isfinite(wave_speed) || !isfinite(damping))
        return error_set(err, "water: size, depth and wave speed must be > 0 and damping >= 0");
    size_t n = (size_t)resolution * (size_t)resolution;
    w->height = calloc(n, sizeof *w->height);
    w->velocity = calloc(n, sizeof *w->velocity);
    if (!w->height || !w->velocity) {
        water_release(w);
        return error_set(err, "water: out of memory for a %dx%d grid", resolution, resolution);
    }
    w->resolution = resolution;
    w->size = size;
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

static double spacing(const struct water *w) { return (double)w->size / (double)(w->resolution - 1); }

void water_drop(struct water *w, float x, float z, float radius, float strength)
{
    if (!(radius > 0) || !isfinite(strength))
        return;
    int n = w->resolution;
    double dx = spacing(w), half = 0.5 * w->size;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double px = -half + i * dx, pz = -half + j * dx;
            double r = sqrt((px - x) * (px - x) + (pz - z) * (pz - z));
            if (r < radius)
                w->height[(size_t)j * (size_t)n + (size_t)i] += strength * 0.5 * (cos(MATH_PI * r / radius) + 1.0);
        }
    w->dirty = true;
    w->dirty_energy = true;
}

double water_stable_step(const struct water *w) { return CFL_SAFETY * spacing(w) / w->wave_speed; }

static double at(const struct water *w, int i, int j)
{
    int n = w->resolution;
    if (i < 0 || j < 0 || i >= n || j >= n) {
        if (w->fixed_boundary)
            return 0.0;
        /* reflective: the missing neighbour is the node itself (zero flux) */
        i = i < 0 ? 0 : i >= n ? n - 1 : i;
        j = j < 0 ? 0 : j >= n ? n - 1 : j;
    }
    return w->height[(size_t)j * (size_t)n + (size_t)i];
}

/* 1/2 c^2 sum over edges of (dh/dx)^2 (times the cell area): the potential energy. */
static double potential(const struct water *w)
{
    int n = w->resolution;
    double dx = spacing(w), c2 = (double)w->wave_speed * w->wave_speed, e = 0.0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double h = at(w, i, j);
            double gx = (at(w, i + 1, j) - h) / dx, gz = (at(w, i, j + 1) - h) / dx;
            if (!w->fixed_boundary) {
                /* edges to the outside carry no energy (zero slope) */
                if (i == n - 1)
                    gx = 0.0;
                if (j == n - 1)
                    gz = 0.0;
            }
            e += 0.5 * c2 * (gx * gx + gz * gz);
        }
    return e * dx * dx;
}

static void substep(struct water *w, double dt)
{
    int n = w->resolution;
    double c2 = (double)w->wave_speed * w->wave_speed, inv_dx2 = 1.0 / (spacing(w) * spacing(w));
    double kinetic = 0.0;
    /* v += dt c^2 lap(h); v /= 1 + damping dt; h += dt v (symplectic Euler) */
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            size_t k = (size_t)j * (size_t)n + (size_t)i;
            if (w->fixed_boundary && (i == 0 || j == 0 || i == n - 1 || j == n - 1)) {
                w->velocity[k] = 0.0;
                continue;
            }
            double lap = (at(w, i - 1, j) + at(w, i + 1, j) + at(w, i, j - 1) + at(w, i, j + 1) - 4.0 * w->height[k]) * inv_dx2;
            double v_old = w->velocity[k];
            w->velocity[k] = (v_old + dt * c2 * lap) / (1.0 + w->damping * dt);
            kinetic += 0.5 * v_old * w->velocity[k];
        }
    double dx = spacing(w);
    w->energy = kinetic * dx * dx + potential(w); /* at the kick: leapfrog's conserved energy */
    for (size_t k = 0; k < (size_t)n * (size_t)n; k++)
        w->height[k] += dt * w->velocity[k];
    if (w->fixed_boundary)
        for (int i = 0; i < n; i++) {
            w->height[i] = w->height[(size_t)(n - 1) * (size_t)n + (size_t)i] = 0.0;
            w->height[(size_t)i * (size_t)n] = w->height[(size_t)i * (size_t)n + (size_t)(n - 1)] = 0.0;
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
    double dx = spacing(w), kinetic = 0.0;
    for (size_t k = 0; k < (size_t)w->resolution * (size_t)w->resolution; k++)
        kinetic += 0.5 * w->velocity[k] * w->velocity[k];
    return kinetic * dx * dx + potential(w);
}

void water_fill_vertices(const struct water *w, float *positions, float *normals)
{
    int n = w->resolution;
    double dx = spacing(w), half = 0.5 * w->size;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            size_t k = (size_t)j * (size_t)n + (size_t)i;
            positions[k * 3] = (float)(-half + i * dx);
            positions[k * 3 + 1] = (float)w->height[k];
            positions[k * 3 + 2] = (float)(-half + j * dx);
            /* central differences (one-sided at the border) */
            int i0 = i > 0 ? i - 1 : i, i1 = i < n - 1 ? i + 1 : i, j0 = j > 0 ? j - 1 : j, j1 = j < n - 1 ? j + 1 : j;
            double sx = (w->height[(size_t)j * (size_t)n + (size_t)i1] - w->height[(size_t)j * (size_t)n + (size_t)i0]) / ((i1 - i0) * dx);
            double sz = (w->height[(size_t)j1 * (size_t)n + (size_t)i] - w->height[(size_t)j0 * (size_t)n + (size_t)i]) / ((j1 - j0) * dx);
            double len = sqrt(sx * sx + 1.0 + sz * sz);
            normals[k * 3] = (float)(-sx / len);
            normals[k * 3 + 1] = (float)(1.0 / len);
            normals[k * 3 + 2] = (float)(-sz / len);
        }
}

double water_max_height(const struct water *w)
{
    double hmax = 0.0;
    for (size_t i = 0; i < (size_t)w->resolution * (size_t)w->resolution; i++)
        hmax = fmax(hmax, fabs(w->height[i]));
    return hmax;
}

bool water_set_heights(struct water *w, double (*height)(void *user, double x, double z), void *user,
                       struct error *err)
{
    int n = w->resolution;
    double dx = (double)w->size / (n - 1), half = 0.5 * w->size;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double x = -half + i * dx, z = -half + j * dx;
            double h = height(user, x, z);
            if (!isfinite(h))
                return error_set(err, "set_heights: the function returned a non-finite height at (%g, %g)", x, z);
            w->height[(size_t)j * (size_t)n + (size_t)i] = h;
            w->velocity[(size_t)j * (size_t)n + (size_t)i] = 0.0;
        }
    w->dirty = true;
    w->dirty_energy = true;
    return true;
}
