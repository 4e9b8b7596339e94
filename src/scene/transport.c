/* The light transport table (Iwasaki et al. §3, [12]): traced with Embree. */
#define _POSIX_C_SOURCE 200809L
#include "scene/transport.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <time.h>

#include <embree3/rtcore.h>

#include "core/fileio.h"
#include "core/optics.h"
#include "core/hash.h"
#include "scene/mesh_embree.h"

/* Octahedral map of the sphere onto [0, 1]^2 (Praun & Hoppe 2003): even
 * sampling, no poles, a direction's cell found in constant time. */
static void octahedral_encode(vec3 d, double *u, double *v)
{
    double s = fabs(d.x) + fabs(d.y) + fabs(d.z);
    s = s > 1e-30 ? s : 1.0;
    double x = d.x / s, y = d.y / s;
    if (d.z < 0.0) {
        double ox = x;
        x = (1.0 - fabs(y)) * (ox >= 0.0 ? 1.0 : -1.0);
        y = (1.0 - fabs(ox)) * (y >= 0.0 ? 1.0 : -1.0);
    }
    *u = x * 0.5 + 0.5;
    *v = y * 0.5 + 0.5;
}

static vec3 octahedral_decode(double u, double v)
{
    double x = u * 2.0 - 1.0, y = v * 2.0 - 1.0, z = 1.0 - fabs(x) - fabs(y);
    if (z < 0.0) {
        double ox = x;
        x = (1.0 - fabs(y)) * (ox >= 0.0 ? 1.0 : -1.0);
        y = (1.0 - fabs(ox)) * (y >= 0.0 ? 1.0 : -1.0);
    }
    return vec3_normalize_or(vec3_make((float)x, (float)y, (float)z), vec3_make(0, 0, 1));
}

vec3 transport_direction(int resolution, double i, double j)
{
    return octahedral_decode((i + 0.5) / resolution, (j + 0.5) / resolution);
}

void transport_cell(int resolution, vec3 d, double *i, double *j)
{
    double u, v;
    octahedral_encode(d, &u, &v);
    *i = u * resolution - 0.5;
    *j = v * resolution - 0.5;
}

void transport_table_release(struct transport_table *t)
{
    free(t->entries);
    memset(t, 0, sizeof *t);
}

bool transport_table_matches(const struct transport_table *t, const struct mesh *m, const struct material *mat,
                             int resolution, enum transport_internal internal)
{
    return t->entries && t->mesh_serial == m->serial && t->ior == mat->ior && t->ideal == mat->ideal &&
           t->absorption.x == mat->absorption.x && t->absorption.y == mat->absorption.y &&
           t->absorption.z == mat->absorption.z && t->resolution == resolution && t->internal == internal;
}

/* Refraction of unit d about unit n facing against it (core/optics.h); false under TIR. */
static bool refract3(vec3 d, vec3 n, double eta, vec3 *t)
{
    const double dd[3] = {d.x, d.y, d.z}, nn[3] = {n.x, n.y, n.z};
    double tt[3];
    if (!optics_refract(dd, nn, eta, tt))
        return false;
    *t = vec3_make((float)tt[0], (float)tt[1], (float)tt[2]);
    return true;
}

struct tracer {
    RTCScene scene;
    const struct mesh *m;
    float eps;
};

/* The next surface from o along d inside the mesh: its point and the
 * interpolated normal; false when the ray leaves through a hole. */
static bool hit(const struct tracer *tr, vec3 o, vec3 d, float *t_hit, vec3 *p, vec3 *n)
{
    struct RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    struct RTCRayHit rh;
    memset(&rh, 0, sizeof rh);
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = tr->eps;
    rh.ray.tfar = 1e30f;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(tr->scene, &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return false;
    const uint32_t *tri = tr->m->indices + (size_t)rh.hit.primID * 3;
    float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
    const float *n0 = tr->m->normals + tri[0] * 3, *n1 = tr->m->normals + tri[1] * 3, *n2 = tr->m->normals + tri[2] * 3;
    vec3 ng = vec3_normalize_or(vec3_make(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z), vec3_scale(d, -1.0f));
    vec3 ns = vec3_make(w * n0[0] + u * n1[0] + v * n2[0], w * n0[1] + u * n1[1] + v * n2[1], w * n0[2] + u * n1[2] + v * n2[2]);
    ns = vec3_normalize_or(ns, ng);
    *t_hit = rh.ray.tfar;
    *p = vec3_add(o, vec3_scale(d, rh.ray.tfar));
    *n = ns;
    return true;
}

/* The path of light along d entering at point p of normal n: entry,
 * inside, exit; out[3..5] stay 0 where no light leaves. */
static void trace_path(const struct tracer *tr, const struct material *mat, enum transport_internal internal, vec3 p,
                       vec3 n, vec3 d, float *out)
{
    memset(out, 0, TRANSPORT_FLOATS * sizeof(float));
    double ior = mat->ior;
    if (vec3_dot(d, n) >= 0.0f)
        return; /* light from behind the point: it does not enter here */
    vec3 t;
    if (!refract3(d, n, 1.0 / ior, &t))
        return; /* IOR < 1: totally reflected on the outside */
    double transmit = 1.0 - optics_fresnel_of(-vec3_dot(d, n), 1.0 / ior, mat->ideal), length = 0.0;
    vec3 o = p, dir = t;
    int reflections = internal == TRANSPORT_INTERNAL_FIRST ? 1 : 0;
    for (int bounce = 0; bounce <= reflections; bounce++) {
        float th;
        vec3 q, nq;
        if (!hit(tr, o, dir, &th, &q, &nq))
            return;
        length += th;
        vec3 inward = vec3_dot(nq, dir) > 0.0f ? vec3_scale(nq, -1.0f) : nq; /* facing against dir */
        vec3 out_dir;
        if (refract3(dir, inward, ior, &out_dir)) {
            transmit *= 1.0 - optics_fresnel_of(-vec3_dot(dir, inward), ior, mat->ideal);
            vec3 a = mat->absorption;
            out[0] = q.x;
            out[1] = q.y;
            out[2] = q.z;
            out[3] = out_dir.x;
            out[4] = out_dir.y;
            out[5] = out_dir.z;
            out[6] = (float)(transmit * exp(-a.x * length));
            out[7] = (float)(transmit * exp(-a.y * length));
            out[8] = (float)(transmit * exp(-a.z * length));
            return;
        }
        /* total internal reflection: followed once with `first`, else the path ends */
        o = q;
        dir = vec3_normalize_or(vec3_sub(dir, vec3_scale(inward, 2.0f * vec3_dot(dir, inward))), dir);
    }
}

static void trace_vertex(const struct tracer *tr, const struct material *mat, enum transport_internal internal,
                         size_t vi, vec3 d, float *out)
{
    const struct mesh *m = tr->m;
    vec3 p = vec3_make(m->positions[vi * 3], m->positions[vi * 3 + 1], m->positions[vi * 3 + 2]);
    vec3 n = vec3_make(m->normals[vi * 3], m->normals[vi * 3 + 1], m->normals[vi * 3 + 2]);
    trace_path(tr, mat, internal, p, n, d, out);
}

struct transport_tracer {
    RTCDevice device;
    struct tracer tr;
    struct material material;
    enum transport_internal internal;
};

bool transport_tracer_create(struct transport_tracer **out, const struct mesh *m, const struct material *mat,
                             enum transport_internal internal, struct error *err)
{
    *out = NULL;
    struct transport_tracer *t = calloc(1, sizeof *t);
    if (!t)
        return error_set(err, "%s: out of memory for its tracer", m->name);
    RTCScene scene;
    if (!mesh_embree_create(m, &t->device, &scene, err)) {
        free(t);
        return false;
    }
    t->tr = (struct tracer){scene, m, 1e-5f * fmaxf(vec3_length(vec3_sub(m->bounds_max, m->bounds_min)), 1e-6f)};
    t->material = *mat;
    t->internal = internal;
    *out = t;
    return true;
}

void transport_tracer_destroy(struct transport_tracer *t)
{
    if (!t)
        return;
    mesh_embree_release(t->device, t->tr.scene);
    free(t);
}

bool transport_trace(const struct transport_tracer *t, vec3 p, vec3 n, vec3 dir, vec3 *position, vec3 *direction,
                     vec3 *transmittance)
{
    float e[TRANSPORT_FLOATS];
    trace_path(&t->tr, &t->material, t->internal, p, vec3_normalize_or(n, vec3_scale(dir, -1.0f)),
               vec3_normalize_or(dir, vec3_make(0, -1, 0)), e);
    if (e[3] == 0.0f && e[4] == 0.0f && e[5] == 0.0f)
        return false;
    *position = vec3_make(e[0], e[1], e[2]);
    *direction = vec3_make(e[3], e[4], e[5]);
    *transmittance = vec3_make(e[6], e[7], e[8]);
    return true;
}

/* The tracer's version: bumped whenever the tables it makes change, so that
 * a table cached by an older build is traced again (2: refraction from
 * core/optics.c, in double). */
#define TRANSPORT_TRACER_VERSION 2

/* Everything the table depends on. */
static uint64_t table_hash(const struct mesh *m, const struct material *mat, int resolution,
                           enum transport_internal internal)
{
    uint64_t h = HASH_FNV1A_BASIS;
    h = hash_fnv1a(h, m->positions, m->vertex_count * 3 * sizeof(float));
    h = hash_fnv1a(h, m->normals, m->vertex_count * 3 * sizeof(float));
    h = hash_fnv1a(h, m->indices, m->index_count * sizeof(uint32_t));
    float values[5] = {mat->ior, mat->ideal ? 1.0f : 0.0f, mat->absorption.x, mat->absorption.y, mat->absorption.z};
    h = hash_fnv1a(h, values, sizeof values);
    int settings[4] = {resolution, (int)internal, TRANSPORT_FLOATS, TRANSPORT_TRACER_VERSION};
    return hash_fnv1a(h, settings, sizeof settings);
}

/* The cache file for `hash`, creating its folders; false where there is
 * no usable cache folder. */
static bool cache_path(uint64_t hash, char *out, size_t outlen)
{
    char dir[3072];
    const char *env = getenv("CAUSTICA_CACHE"), *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (env && *env)
        snprintf(dir, sizeof dir, "%s", env);
    else if (xdg && *xdg)
        snprintf(dir, sizeof dir, "%s/caustica", xdg);
    else if (home && *home)
        snprintf(dir, sizeof dir, "%s/.cache/caustica", home);
    else
        return false;
    struct error ignore;
    char sub[3200];
    snprintf(sub, sizeof sub, "%s/transport", dir);
    if (!dir_ensure(dir, &ignore) || !dir_ensure(sub, &ignore))
        return false;
    snprintf(out, outlen, "%s/%016llx.table", sub, (unsigned long long)hash);
    return true;
}

struct cache_header {
    char magic[8];          /* "CAUSTTB1" */
    uint64_t hash;
    uint64_t vertex_count;
    int32_t resolution, floats;
    uint64_t checksum;      /* FNV-1a of the entries: a damaged file is traced again */
};

static bool cache_read(const char *path, uint64_t hash, size_t vertex_count, int resolution, float *entries,
                       size_t count)
{
    struct error ignored; /* a missing, linked or odd entry is traced again (not read through a link, not a FIFO) */
    FILE *f = file_open_read(path, true, &ignored);
    if (!f)
        return false;
    struct cache_header h;
    bool ok = fread(&h, sizeof h, 1, f) == 1 && memcmp(h.magic, "CAUSTTB1", 8) == 0 && h.hash == hash &&
              h.vertex_count == vertex_count && h.resolution == resolution && h.floats == TRANSPORT_FLOATS &&
              fread(entries, sizeof(float), count, f) == count;
    fclose(f);
    return ok && hash_fnv1a(HASH_FNV1A_BASIS, entries, count * sizeof(float)) == h.checksum;
}

static void cache_write(const char *path, uint64_t hash, size_t vertex_count, int resolution, const float *entries,
                        size_t count)
{
    char tmp[4200];
    struct error ignored;
    int fd = path_temporary_create(path, tmp, sizeof tmp, &ignored); /* never through a planted link */
    FILE *f = fd >= 0 ? fdopen(fd, "wb") : NULL;
    if (!f) {
        if (fd >= 0) {
            close(fd);
            remove(tmp);
        }
        return;
    }
    struct cache_header h = {{'C', 'A', 'U', 'S', 'T', 'T', 'B', '1'}, hash, vertex_count, resolution, TRANSPORT_FLOATS,
                             hash_fnv1a(HASH_FNV1A_BASIS, entries, count * sizeof(float))};
    bool ok = fwrite(&h, sizeof h, 1, f) == 1 && fwrite(entries, sizeof(float), count, f) == count;
    ok = fclose(f) == 0 && ok;
    if (!ok || rename(tmp, path) != 0)
        remove(tmp); /* the whole file or none */
}

int transport_fit_resolution(size_t vertex_count, int wanted)
{
    for (int r = wanted; r >= 2; r--) {
        size_t cells = (size_t)r * (size_t)r;
        if (vertex_count <= TRANSPORT_MAX_BYTES / sizeof(float) / TRANSPORT_FLOATS / cells)
            return r;
    }
    return 0;
}

bool transport_table_ensure(struct transport_table *t, const struct mesh *m, const struct material *mat, int wanted,
                            enum transport_internal internal, int object, char *report, size_t reportlen,
                            struct error *err)
{
    int fitted = transport_fit_resolution(m->vertex_count, wanted);
    if (fitted == 0)
        return error_set(err, "%s: %zu vertices: too many for any transport table (at most %zu MB); use a coarser mesh",
                         m->name, m->vertex_count, (size_t)TRANSPORT_MAX_BYTES >> 20);
    if (fitted < wanted)
        snprintf(report, reportlen, "object %d's transport table has %d x %d directions, not %d x %d, to fit %zu MB "
                 "(%zu vertices)", object, fitted, fitted, wanted, wanted, (size_t)TRANSPORT_MAX_BYTES >> 20,
                 m->vertex_count);
    return transport_table_matches(t, m, mat, fitted, internal) ||
           transport_table_build(t, m, mat, fitted, internal, err);
}

bool transport_table_build(struct transport_table *t, const struct mesh *m, const struct material *mat,
                           int resolution, enum transport_internal internal, struct error *err)
{
    transport_table_release(t);
    if (resolution < 2 || resolution > 64)
        return error_set(err, "transport table: resolution must be in 2..64 (got %d)", resolution);
    size_t cells = (size_t)resolution * (size_t)resolution;
    size_t count = m->vertex_count * cells * TRANSPORT_FLOATS;
    if (m->vertex_count == 0 || count / TRANSPORT_FLOATS / cells != m->vertex_count ||
        count > TRANSPORT_MAX_BYTES / sizeof(float))
        return error_set(err, "%s: a transport table of %zu vertices x %zu directions would take %zu MB (at most %zu): "
                              "use a smaller `table` or a coarser mesh",
                         m->name, m->vertex_count, cells, (count * sizeof(float)) >> 20, TRANSPORT_MAX_BYTES >> 20);
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    float *entries = malloc(count * sizeof(float));
    if (!entries)
        return error_set(err, "%s: out of memory for a transport table of %zu MB", m->name, (count * 4) >> 20);
    uint64_t hash = table_hash(m, mat, resolution, internal);
    char path[4096];
    bool cached = cache_path(hash, path, sizeof path);
    if (cached && cache_read(path, hash, m->vertex_count, resolution, entries, count)) {
        clock_gettime(CLOCK_MONOTONIC, &t1);
        t->from_cache = true;
        goto done;
    }
    RTCDevice device;
    RTCScene scene;
    if (!mesh_embree_create(m, &device, &scene, err)) {
        free(entries);
        return false;
    }
    struct tracer tr = {scene, m, 1e-5f * fmaxf(vec3_length(vec3_sub(m->bounds_max, m->bounds_min)), 1e-6f)};
    for (size_t c = 0; c < cells; c++) {
        vec3 d = transport_direction(resolution, (double)(c % (size_t)resolution), (double)(c / (size_t)resolution));
        for (size_t v = 0; v < m->vertex_count; v++)
            trace_vertex(&tr, mat, internal, v, d, entries + (v * cells + c) * TRANSPORT_FLOATS);
    }
    mesh_embree_release(device, scene);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (cached)
        cache_write(path, hash, m->vertex_count, resolution, entries, count);
done:
    t->mesh_serial = m->serial;
    t->ior = mat->ior;
    t->ideal = mat->ideal;
    t->absorption = mat->absorption;
    t->resolution = resolution;
    t->internal = internal;
    t->vertex_count = m->vertex_count;
    t->entries = entries;
    t->bytes = count * sizeof(float);
    t->build_seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    return true;
}

bool transport_lookup(const struct transport_table *t, size_t vertex, vec3 dir, vec3 *position, vec3 *direction,
                      vec3 *transmittance)
{
    return transport_lookup_smooth(t, vertex, dir, position, direction, transmittance, NULL);
}

bool transport_lookup_smooth(const struct transport_table *t, size_t vertex, vec3 dir, vec3 *position,
                             vec3 *direction, vec3 *transmittance, bool *smooth)
{
    if (smooth)
        *smooth = true;
    float least_cos = 1.0f;
    bool missing = false;
    vec3 first_dir = {0, 0, 0};
    if (!t->entries || vertex >= t->vertex_count)
        return false;
    int r = t->resolution;
    double ci, cj;
    transport_cell(r, vec3_normalize_or(dir, vec3_make(0, -1, 0)), &ci, &cj);
    double fi = floor(ci), fj = floor(cj);
    double ai = ci - fi, aj = cj - fj;
    vec3 p = {0, 0, 0}, d = {0, 0, 0}, tr = {0, 0, 0};
    double wsum = 0.0;
    const float *base = t->entries + vertex * (size_t)r * (size_t)r * TRANSPORT_FLOATS;
    for (int dj = 0; dj < 2; dj++)
        for (int di = 0; di < 2; di++) {
            /* cells past the map's edge are clamped (the octahedral seam is
             * approximated by its nearest cell) */
            int i = (int)fi + di, j = (int)fj + dj;
            i = i < 0 ? 0 : i >= r ? r - 1 : i;
            j = j < 0 ? 0 : j >= r ? r - 1 : j;
            double w = (di ? ai : 1.0 - ai) * (dj ? aj : 1.0 - aj);
            const float *e = base + ((size_t)j * (size_t)r + (size_t)i) * TRANSPORT_FLOATS;
            if (w <= 0.0)
                continue;
            if (e[3] == 0.0f && e[4] == 0.0f && e[5] == 0.0f) {
                missing = true;
                continue;
            }
            vec3 ed = vec3_make(e[3], e[4], e[5]);
            if (wsum > 0.0)
                least_cos = fminf(least_cos, vec3_dot(ed, first_dir));
            else
                first_dir = ed;
            p = vec3_add(p, vec3_scale(vec3_make(e[0], e[1], e[2]), (float)w));
            d = vec3_add(d, vec3_scale(vec3_make(e[3], e[4], e[5]), (float)w));
            tr = vec3_add(tr, vec3_scale(vec3_make(e[6], e[7], e[8]), (float)w));
            wsum += w;
        }
    if (smooth)
        *smooth = !missing && least_cos >= TRANSPORT_SMOOTH_COS;
    if (wsum < 1e-6)
        return false;
    float inv = (float)(1.0 / wsum);
    *position = vec3_scale(p, inv);
    *direction = vec3_normalize_or(d, vec3_make(0, -1, 0));
    *transmittance = vec3_scale(tr, inv);
    return true;
}
