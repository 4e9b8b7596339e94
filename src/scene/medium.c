/* Participating media: coefficients, phase asymmetry and density. */
#include <math.h>
#include <stdlib.h>

#include "scene/scene.h"

struct medium *medium_create(void)
{
    struct medium *m = calloc(1, sizeof *m);
    if (m)
        m->references = 1;
    if (!m)
        return NULL;
    m->sigma_s = vec3_make(0.1f, 0.1f, 0.1f);
    m->box_min = vec3_make(-1, -1, -1);
    m->box_max = vec3_make(1, 1, 1);
    m->density = 1.0f;
    m->max_density = 1.0f;
    m->version = 1;
    return m;
}

void medium_retain(struct medium *m)
{
    if (m)
        m->references++;
}

void medium_destroy(struct medium *m)
{
    if (m && --m->references > 0)
        return;
    if (!m)
        return;
    free(m->grid);
    free(m);
}

float medium_density(const struct medium *m, vec3 p)
{
    vec3 lo = m->box_min, hi = m->box_max;
    if (p.x < lo.x || p.y < lo.y || p.z < lo.z || p.x > hi.x || p.y > hi.y || p.z > hi.z)
        return 0.0f;
    if (!m->grid)
        return m->density;
    /* grid values sit on the corners of (n-1)^3 cells spanning the box */
    float fx = math_safe_div(p.x - lo.x, hi.x - lo.x, 0.0f) * (float)(m->nx - 1);
    float fy = math_safe_div(p.y - lo.y, hi.y - lo.y, 0.0f) * (float)(m->ny - 1);
    float fz = math_safe_div(p.z - lo.z, hi.z - lo.z, 0.0f) * (float)(m->nz - 1);
    int x0 = (int)fminf(floorf(fx), (float)(m->nx - 2 > 0 ? m->nx - 2 : 0));
    int y0 = (int)fminf(floorf(fy), (float)(m->ny - 2 > 0 ? m->ny - 2 : 0));
    int z0 = (int)fminf(floorf(fz), (float)(m->nz - 2 > 0 ? m->nz - 2 : 0));
    float tx = fx - (float)x0, ty = fy - (float)y0, tz = fz - (float)z0;
    int x1 = x0 + (m->nx > 1), y1 = y0 + (m->ny > 1), z1 = z0 + (m->nz > 1);
#define G(x, y, z) m->grid[((size_t)(z) * (size_t)m->ny + (size_t)(y)) * (size_t)m->nx + (size_t)(x)]
    float c00 = G(x0, y0, z0) * (1 - tx) + G(x1, y0, z0) * tx;
    float c10 = G(x0, y1, z0) * (1 - tx) + G(x1, y1, z0) * tx;
    float c01 = G(x0, y0, z1) * (1 - tx) + G(x1, y0, z1) * tx;
    float c11 = G(x0, y1, z1) * (1 - tx) + G(x1, y1, z1) * tx;
#undef G
    float c0 = c00 * (1 - ty) + c10 * ty, c1 = c01 * (1 - ty) + c11 * ty;
    return c0 * (1 - tz) + c1 * tz;
}

bool medium_sample_grid(struct medium *m, int nx, int ny, int nz, double (*density)(void *user, vec3 p), void *user,
                        struct error *err)
{
    if (nx < 2 || ny < 2 || nz < 2 || nx > 256 || ny > 256 || nz > 256)
        return error_set(err, "bad argument 'resolution' to 'medium' (2..256 per axis expected)");
    free(m->grid);
    m->grid = malloc((size_t)nx * (size_t)ny * (size_t)nz * sizeof(float));
    if (!m->grid)
        return error_set(err, "out of memory for a %dx%dx%d density grid", nx, ny, nz);
    m->nx = nx;
    m->ny = ny;
    m->nz = nz;
    m->max_density = 0;
    for (int z = 0; z < nz; z++)
        for (int y = 0; y < ny; y++)
            for (int x = 0; x < nx; x++) {
                vec3 p = {m->box_min.x + (m->box_max.x - m->box_min.x) * (float)x / (float)(nx - 1),
                          m->box_min.y + (m->box_max.y - m->box_min.y) * (float)y / (float)(ny - 1),
                          m->box_min.z + (m->box_max.z - m->box_min.z) * (float)z / (float)(nz - 1)};
                float d = (float)density(user, p);
                if (!(d >= 0) || !isfinite(d))
                    return error_set(err, "medium density function returned %f at (%f, %f, %f): non-negative finite "
                                          "values expected", (double)d, (double)p.x, (double)p.y, (double)p.z);
                m->grid[((size_t)z * (size_t)ny + (size_t)y) * (size_t)nx + (size_t)x] = d;
                if (d > m->max_density)
                    m->max_density = d;
            }
    return true;
}
