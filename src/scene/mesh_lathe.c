/* Surfaces of revolution: a profile of (radius, height) points turned about
 * the y axis, and the cylinder and cone made that way. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

/* Two profile segments meeting at more than this turn get their own
 * normals (a crease, like a cylinder's rim); below it the surface is smooth. */
#define LATHE_CREASE_COS 0.82f /* about 35 degrees */

/* The outward normal of the profile segment a -> b in the (r, y) plane,
 * for a profile that runs counter-clockwise (bottom to top on the outside). */
static void segment_normal(const float *a, const float *b, float *nr, float *ny)
{
    float dr = b[0] - a[0], dy = b[1] - a[1];
    float len = sqrtf(dr * dr + dy * dy);
    *nr = dy / len;
    *ny = -dr / len;
}

/* Each profile segment has its own two rings of segments + 1 vertices. */
void mesh_lathe_counts(int points, int segments, size_t *vertices, size_t *indices)
{
    size_t profile_segments = points > 1 ? (size_t)points - 1 : 0, around = segments > 0 ? (size_t)segments : 0;
    *vertices = profile_segments * 2 * (around + 1);
    *indices = profile_segments * around * 6;
}

/* The profile checked and cleaned: points that repeat the previous one
 * make no surface and are dropped; either order is accepted, the profile
 * closed along the axis turned to run counter-clockwise in (r, y) so that
 * the normals face out (shoelace). Its point count in *out_count; NULL
 * (said) where it is not a profile. */
static float *lathe_profile(const char *name, const float *profile_in, int count, int *out_count, struct error *err)
{
    float *profile = malloc((size_t)count * 2 * sizeof(float));
    if (!profile) {
        error_set(err, "%s: out of memory", name);
        return NULL;
    }
    int n = 0;
    bool off_axis = false;
    for (int i = 0; i < count; i++) {
        float r = profile_in[i * 2], y = profile_in[i * 2 + 1];
        if (!isfinite(r) || !isfinite(y) || r < 0.0f || r > 1e18f || fabsf(y) > 1e18f) {
            free(profile);
            error_set(err, "%s: profile point %d must be finite with radius >= 0 (got {%g, %g})", name, i + 1, (double)r, (double)y);
            return NULL;
        }
        off_axis |= r > 0.0f;
        if (n > 0 && profile[(n - 1) * 2] == r && profile[(n - 1) * 2 + 1] == y)
            continue;
        profile[n * 2] = r;
        profile[n * 2 + 1] = y;
        n++;
    }
    if (n < 2 || !off_axis) {
        free(profile);
        error_set(err, "%s: the profile needs two distinct points, one off the axis", name);
        return NULL;
    }
    double area = 0.0;
    for (int i = 0; i < n; i++) {
        const float *a = profile + i * 2, *b = profile + ((i + 1) % n) * 2;
        area += (double)a[0] * b[1] - (double)b[0] * a[1];
    }
    if (area < 0.0)
        for (int i = 0; i < n / 2; i++)
            for (int k = 0; k < 2; k++) {
                float t = profile[i * 2 + k];
                profile[i * 2 + k] = profile[(n - 1 - i) * 2 + k];
                profile[(n - 1 - i) * 2 + k] = t;
            }
    *out_count = n;
    return profile;
}

struct mesh *mesh_create_lathe(const char *name, const float *profile_in, int count, int segments,
                               struct error *err)
{
    if (count < 2 || count > 4096 || segments < 3 || segments > 4096) {
        error_set(err, "%s: 2..4096 profile points and 3..4096 segments expected (got %d, %d)", name, count, segments);
        return NULL;
    }
    int n = 0;
    float *profile = lathe_profile(name, profile_in, count, &n, err);
    if (!profile)
        return NULL;
    /* Each profile segment has its own two rings of vertices, so that a
     * crease keeps its two normals; smooth joints share the mean normal. */
    int nseg = n - 1;
    size_t ring = (size_t)segments + 1;
    size_t nv, ni;
    mesh_lathe_counts(n, segments, &nv, &ni);
    float *p = malloc(nv * 3 * sizeof(float)), *nn = malloc(nv * 3 * sizeof(float));
    float *uv = malloc(nv * 2 * sizeof(float));
    uint32_t *idx = malloc(ni * sizeof(uint32_t));
    float *length = malloc((size_t)n * sizeof(float)); /* arc length to each point, for v */
    if (!p || !nn || !uv || !idx || !length) {
        free(profile), free(p), free(nn), free(uv), free(idx), free(length);
        error_set(err, "%s: out of memory", name);
        return NULL;
    }
    length[0] = 0.0f;
    for (int i = 1; i < n; i++)
        length[i] = length[i - 1] + hypotf(profile[i * 2] - profile[(i - 1) * 2],
                                           profile[i * 2 + 1] - profile[(i - 1) * 2 + 1]);
    size_t k = 0;
    for (int s = 0; s < nseg; s++) {
        const float *a = profile + s * 2, *b = a + 2;
        float snr, sny;
        segment_normal(a, b, &snr, &sny);
        for (int end = 0; end < 2; end++) {
            int pi = s + end;
            float nr = snr, ny = sny;
            int other = end ? s + 1 : s - 1; /* the neighbouring segment at this end */
            if (other >= 0 && other < nseg) {
                float onr, ony;
                segment_normal(profile + other * 2, profile + other * 2 + 2, &onr, &ony);
                if (snr * onr + sny * ony > LATHE_CREASE_COS) {
                    float len = hypotf(snr + onr, sny + ony);
                    nr = (snr + onr) / len;
                    ny = (sny + ony) / len;
                }
            }
            float r = profile[pi * 2], y = profile[pi * 2 + 1];
            for (int j = 0; j <= segments; j++) {
                /* as the sphere: x = cos(phi), z = -sin(phi), u from +x towards -z */
                float phi = 2.0f * (float)MATH_PI * (float)j / (float)segments;
                float c = cosf(phi), sn = -sinf(phi);
                size_t v = ((size_t)s * 2 + (size_t)end) * ring + (size_t)j;
                p[v * 3] = r * c;
                p[v * 3 + 1] = y;
                p[v * 3 + 2] = r * sn;
                nn[v * 3] = nr * c;
                nn[v * 3 + 1] = ny;
                nn[v * 3 + 2] = nr * sn;
                uv[v * 2] = (float)j / (float)segments;
                uv[v * 2 + 1] = length[n - 1] > 0.0f ? 1.0f - length[pi] / length[n - 1] : 0.0f;
            }
        }
        for (int j = 0; j < segments; j++) {
            uint32_t lo = (uint32_t)(((size_t)s * 2) * ring + (size_t)j), hi = lo + (uint32_t)ring;
            /* counter-clockwise seen from outside; a ring on the axis makes
             * one triangle of the quad, not a zero-area one */
            if (b[0] > 0.0f) {
                idx[k++] = hi; idx[k++] = lo; idx[k++] = hi + 1;
            }
            if (a[0] > 0.0f) {
                idx[k++] = hi + 1; idx[k++] = lo; idx[k++] = lo + 1;
            }
        }
    }
    free(profile);
    free(length);
    struct mesh *m = mesh_create_from_arrays(name, p, nn, nv, idx, k, err);
    if (!m) {
        free(uv);
        return NULL;
    }
    m->texcoords[0] = uv;
    return m;
}

struct mesh *mesh_create_cylinder(float radius, float height, int segments, struct error *err)
{
    if (!(radius > 0.0f) || !(height > 0.0f) || !isfinite(radius) || !isfinite(height)) {
        error_set(err, "cylinder: radius and height must be finite and > 0 (got %g, %g)", (double)radius, (double)height);
        return NULL;
    }
    float h = 0.5f * height;
    const float profile[8] = {0.0f, -h, radius, -h, radius, h, 0.0f, h};
    return mesh_create_lathe("cylinder", profile, 4, segments, err);
}

struct mesh *mesh_create_cone(float radius, float height, int segments, struct error *err)
{
    if (!(radius > 0.0f) || !(height > 0.0f) || !isfinite(radius) || !isfinite(height)) {
        error_set(err, "cone: radius and height must be finite and > 0 (got %g, %g)", (double)radius, (double)height);
        return NULL;
    }
    float h = 0.5f * height;
    const float profile[6] = {0.0f, -h, radius, -h, 0.0f, h};
    return mesh_create_lathe("cone", profile, 3, segments, err);
}
