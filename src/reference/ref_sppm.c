/* The reference estimator: eye paths traced exactly through specular
 * chains (Fresnel, Snell, total internal reflection, Beer-Lambert), direct
 * light by shadow rays at the first diffuse vertex, and caustics
 * (light -> specular+ -> diffuse) by stochastic progressive photon mapping
 * (Hachisuka & Jensen, SIGGRAPH Asia 2009): each iteration traces one eye
 * path per pixel to a visible point and a batch of photons, and shrinks
 * every pixel's gather radius by R' = R sqrt((N + a M) / (N + M)) with
 * a = 2/3, so bias and variance both go to zero as iterations grow
 * (docs/REFERENCE.md). The transport is the one caustica's scenes define:
 * lights are the emitters, the environment is seen directly and through
 * specular chains, diffuse surfaces get direct light, caustics and the
 * scene's ambient term, and there is no diffuse interreflection. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/cpus.h"
#include "core/log.h"
#include "core/vecmath.h"
#include "core/optics.h"
#include "reference/ref_emit.h"
#include "reference/ref_media.h"
#include "reference/ref_photon_map.h"
#include "reference/ref_rng.h"
#include "reference/ref_microfacet.h"
#include "reference/ref_scene.h"
#include "reference/reference.h"

#define MAX_DEPTH 32       /* specular bounces: every loop has a cap */
#define MAX_MEDIA 8
#define SPPM_ALPHA (2.0 / 3.0)
#define PHOTON_CHUNKS 64
#define RADIUS_PIXELS 2.0  /* initial gather radius, in pixel footprints */
#define STRUCTURE_SUMS 3  /* the structure test's sums (structure_sums) */
#define GLOSSY_SAMPLES 4  /* directions drawn from a glTF surface's glossy lobes per eye path */
#define MAX_SEGMENTS 4     /* camera path segments through the medium kept for the volume gather */
#define VOLUME_SAMPLES 8   /* stratified points per segment where volume photons are gathered */   /* fixed, so the result does not depend on the thread count */

void ref_options_default(struct ref_options *o)
{
    memset(o, 0, sizeof *o);
    o->width = o->height = 256;
    o->photons = 200000;
    o->iterations = 16;
    o->seed = 1;
}

/* ---- optics ------------------------------------------------------------ */

/* The material's reflectance (core/optics.h): Fresnel's, or for an ideal
 * interface (fresnel = false) 0, and 1 where refraction is impossible (the
 * shaders' fresnel_of). */
static double fresnel_of(const struct material *m, double cos_i, double eta)
{
    return optics_fresnel_of(cos_i, eta, m->ideal);
}

/* The media a path is inside: a small stack of object indices. */
struct media {
    int objects[MAX_MEDIA];
    int count;
};

static dvec3 medium_sigma(const struct ref_scene *rs, const struct media *m)
{
    if (m->count == 0)
        return dv(0, 0, 0);
    vec3 a = rs->objects[m->objects[m->count - 1]].material.absorption;
    return dv(a.x, a.y, a.z);
}

static void media_toggle(struct media *m, int object, bool entering)
{
    if (entering) {
        if (m->count < MAX_MEDIA)
            m->objects[m->count++] = object;
        return;
    }
    for (int i = m->count - 1; i >= 0; i--)
        if (m->objects[i] == object) {
            memmove(m->objects + i, m->objects + i + 1, (size_t)(m->count - i - 1) * sizeof m->objects[0]);
            m->count--;
            return;
        }
}

/* Is the scene's participating medium present where a path is? Outside
 * every dielectric; and in water, whose one-interface surfaces bound the
 * water below them (murky water is a medium box under a water surface),
 * but not inside glass, which keeps its own absorption. */
static bool scene_medium_here(const struct ref_scene *rs, const struct media *m)
{
    return m->count == 0 || rs->objects[m->objects[m->count - 1]].material.kind == MATERIAL_WATER;
}

/* Beer-Lambert over distance t in the current medium. */
static dvec3 attenuate(dvec3 beta, dvec3 sigma, double t)
{
    return dv(beta.x * exp(-sigma.x * t), beta.y * exp(-sigma.y * t), beta.z * exp(-sigma.z * t));
}

/* Which dielectrics contain point p: walk a ray upwards and note, for each
 * object, whether its first crossing leaves it. */
static void media_at(const struct ref_scene *rs, dvec3 p, struct media *m)
{
    m->count = 0;
    int seen[64];
    int nseen = 0;
    dvec3 dir = dv(0.0001, 1.0, 0.0002);
    dir = dv_normalize_or(dir, dv(0, 1, 0));
    dvec3 o = p;
    for (int step = 0; step < 64; step++) {
        struct ref_hit h;
        if (!ref_scene_intersect(rs, o, dir, INFINITY, &h))
            break;
        bool known = false;
        for (int i = 0; i < nseen; i++)
            known = known || seen[i] == h.object;
        if (!known && nseen < 64) {
            seen[nseen++] = h.object;
            if (ref_is_dielectric(&rs->objects[h.object].material) && dv_dot(dir, h.geometric_normal) > 0.0)
                media_toggle(m, h.object, true);
        }
        o = dv_add(h.position, dv_scale(dir, rs->epsilon * 4));
    }
}

/* Is this hit diffuse for this path? A diffuse material always; glass or
 * water of transmission t < 1 with probability 1 - t: the surface is t
 * glass and 1 - t diffuse of its colour (glTF's transmissionFactor), and
 * picking one per path by those odds estimates the mix without a weight. */
static bool hit_is_diffuse(const struct ref_scene *rs, const struct ref_hit *h, struct ref_rng *rng)
{
    const struct ref_object *o = &rs->objects[h->object];
    const struct material *m = &o->material;
    if (m->kind == MATERIAL_DIFFUSE)
        return true;
    if ((m->kind != MATERIAL_GLASS && m->kind != MATERIAL_WATER) ||
        (m->transmission >= 1.0f && !m->transmission_map.texture))
        return false;
    return ref_rng_uniform(rng) >= ref_object_transmission(o, h);
}

/* One step through a specular surface: picks reflection or refraction by
 * Fresnel (the weight cancels), updates the media, returns the new
 * direction and origin. False when the path went on as it was (through a
 * thin-walled pane): no bounce, the light's own way (a photon that only
 * crossed panes is direct light, which the shadow rays see through them). */
static bool specular_step(const struct ref_scene *rs, const struct ref_hit *h, struct media *media, dvec3 *dir,
                          dvec3 *origin, dvec3 *beta, struct ref_rng *rng)
{
    const struct ref_object *o = &rs->objects[h->object];
    const struct material *m = &o->material;
    dvec3 ng = h->geometric_normal, n = h->shading_normal;
    bool entering = dv_dot(*dir, ng) < 0.0;
    dvec3 nn = entering ? n : dv_scale(n, -1.0);
    dvec3 ngo = entering ? ng : dv_scale(ng, -1.0);
    if (m->kind == MATERIAL_MIRROR) {
        double alpha = (double)m->roughness * (double)m->roughness;
        dvec3 mn = nn;
        double w = 1.0;
        if (alpha > 0.0) {
            /* a rough mirror: reflect about a GGX microfacet normal, weighted
             * as rough glass's reflection (Walter et al. 2007, eq. 41) */
            double u1 = ref_rng_uniform(rng), u2 = ref_rng_uniform(rng);
            mn = ref_ggx_sample_normal(nn, alpha, u1, u2);
            double cos_i = -dv_dot(*dir, mn);
            dvec3 out = ref_reflect(*dir, mn);
            if (!(cos_i > 0.0) || dv_dot(out, ngo) <= 0.0) {
                *beta = dv(0, 0, 0);
                return true;
            }
            dvec3 in = dv_scale(*dir, -1.0);
            w = cos_i * ref_ggx_g1(in, mn, nn, alpha) * ref_ggx_g1(out, mn, nn, alpha) /
                fmax(-dv_dot(*dir, nn) * dv_dot(mn, nn), 1e-12);
        }
        *dir = dv_normalize_or(ref_reflect(*dir, mn), ref_reflect(*dir, ngo));
        *beta = dv_scale(dv_mul(*beta, dv(m->color.x, m->color.y, m->color.z)), w);
        *origin = dv_add(h->position, dv_scale(ngo, rs->epsilon));
        return true;
    }
    if (m->thin) {
        /* Thin-walled glass (glTF's glass without a volume): reflect F
         * about the shading normal, else go on undeviated, x the tint
         * (shade/thin_glass.frag). No random number where F is 0 (an
         * ideal pane: the eye path stays fixed). */
        dvec3 normal, tint;
        double f = ref_thin_surface(o, h, *dir, nn, &normal, &tint);
        if (f > 0.0 && (f >= 1.0 || ref_rng_uniform(rng) < f)) {
            *dir = dv_normalize_or(ref_reflect(*dir, normal), ref_reflect(*dir, ngo));
            *origin = dv_add(h->position, dv_scale(ngo, rs->epsilon));
            return true;
        }
        *beta = dv_mul(*beta, tint);
        *origin = dv_sub(h->position, dv_scale(ngo, rs->epsilon));
        return false;
    }
    double eta = entering ? 1.0 / m->ior : m->ior;
    /* Rough glass: reflect or refract about a microfacet normal drawn from
     * GGX's D(m)|m.n| (Walter et al. 2007 §5.3), the path weighted by
     * |i.m| G(i, o, m) / (|i.n| |m.n|) (their eq. 41; Fresnel's weight
     * cancels against the choice by it). A direction that leaves on the
     * wrong side of the surface ends the path, as the single-scattering
     * model loses that light. */
    double alpha = (double)m->roughness * (double)m->roughness;
    dvec3 mn = nn;
    if (alpha > 0.0) {
        double u1 = ref_rng_uniform(rng), u2 = ref_rng_uniform(rng);
        mn = ref_ggx_sample_normal(nn, alpha, u1, u2);
        if (dv_dot(*dir, mn) >= 0.0) { /* the ray meets the microfacet's back */
            *beta = dv(0, 0, 0);
            return true;
        }
    }
    double cos_i = -dv_dot(*dir, mn);
    double f = fresnel_of(m, cos_i, eta);
    dvec3 t;
    bool can_refract = ref_refract(*dir, mn, eta, &t);
    bool reflected = !can_refract || ref_rng_uniform(rng) < f;
    dvec3 out = reflected ? dv_normalize_or(ref_reflect(*dir, mn), ref_reflect(*dir, ngo)) : t;
    if (alpha > 0.0) {
        dvec3 in = dv_scale(*dir, -1.0);
        bool wrong_side = reflected ? dv_dot(out, ngo) <= 0.0 : dv_dot(out, ngo) >= 0.0;
        double g = ref_ggx_g1(in, mn, nn, alpha) * ref_ggx_g1(out, mn, nn, alpha); /* eq. 23, chi+ both ways */
        double w = wrong_side ? 0.0 : cos_i * g / fmax(-dv_dot(*dir, nn) * dv_dot(mn, nn), 1e-12);
        *beta = dv_scale(*beta, w);
    }
    if (reflected) {
        *dir = out;
        *origin = dv_add(h->position, dv_scale(ngo, rs->epsilon));
    } else {
        *dir = out;
        *origin = dv_sub(h->position, dv_scale(ngo, rs->epsilon));
        media_toggle(media, h->object, entering);
        if (entering) /* glTF's transmission tint (x baseColorTexture), once per way through */
            *beta = dv_mul(*beta, ref_glass_tint(o, h));
    }
    return true;
}

/* An eye path's next surface: ref_scene_intersect, through the back faces
 * of single-sided surfaces (glTF's doubleSided false, which shade discards;
 * they still cast shadows and meet photons), h->t from `origin`. */
static bool eye_intersect(const struct ref_scene *rs, dvec3 origin, dvec3 dir, struct ref_hit *h)
{
    double skipped = 0.0;
    for (int k = 0; k < 64; k++) {
        if (!ref_scene_intersect(rs, origin, dir, INFINITY, h))
            return false;
        const struct material *m = &rs->objects[h->object].material;
        if (!(m->single_sided && material_is_textured_surface(m) && dv_dot(dir, h->geometric_normal) > 0.0)) {
            h->t += skipped;
            return true;
        }
        dvec3 next = dv_add(h->position, dv_scale(dir, rs->epsilon));
        skipped += dv_dot(dv_sub(next, origin), dir);
        origin = next;
    }
    return false;
}

/* ---- per-pixel state ---------------------------------------------------- */

struct visible_point {
    bool valid;
    dvec3 position, normal; /* normal faces the eye */
    dvec3 weight;           /* path throughput x albedo / pi */
};

struct pixel {
    dvec3 direct;           /* sum over iterations of what the eye path gathered */
    int samples;            /* eye paths traced (an iteration cut short by the budget leaves some pixels one ahead) */
    /* an eye path that draws no random number is the same every iteration:
     * its radiance, traced once (trace_eye) */
    bool eye_fixed;
    dvec3 eye_once;
    dvec3 volume;           /* sum of the volume caustic estimates */
    double volume_samples;  /* the gathers' weights: their passes' fractions */
    /* the noise estimate: sums of the even and the odd iterations' own
     * estimates (eye path + volume + this iteration's photons / pi R^2) */
    dvec3 direct_seen, volume_seen, half[2];
    dvec3 half_photons[2];  /* the photon estimates, each weighted by its pass's fraction (a cut-short pass counts less) */
    dvec3 tau;              /* SPPM flux */
    double radius, n;
    /* the structure test, iteration by iteration (structure_restart): the
     * least radius (0: not tested), its sums (structure_sums) and their
     * variances since the radius was last halved, and the photon passes
     * before that (tau counts those after) */
    double radius_floor, structure[STRUCTURE_SUMS], structure_var[STRUCTURE_SUMS], passes_before;
    double passes_missed;   /* passes since then whose gather the budget stopped before this pixel's row */
    dvec3 phi_inner;        /* this iteration's photons within half the radius, and their count */
    long m_inner;
    double r1;              /* independent passes: the first pass's radius (the pilot's), 0: none found */
    dvec3 pppm;             /* independent passes: the sum of their photon estimates */
    struct visible_point vp;
    dvec3 phi;              /* this iteration's photons */
    long m;
    /* this iteration's eye-path segments through the medium */
    struct {
        dvec3 origin, dir, beta;
        double t0, t1;
    } segments[MAX_SEGMENTS];
    int segment_count;
};

/* Light arriving at p from light l, unshadowed: the irradiance a surface
 * facing it would get, the unit direction towards it and its distance. */
static bool light_arrival(const struct ref_light *l, dvec3 p, dvec3 *e, dvec3 *wi, double *dist)
{
    /* the GPU's light_arrival (common/lighting.glsl), through its C twin */
    double at[3] = {p.x, p.y, p.z}, ev[3], to[3];
    bool lit = shading_light_arrival(&l->shading, at, ev, to, dist);
    *e = dv(ev[0], ev[1], ev[2]);
    *wi = dv(to[0], to[1], to[2]);
    return lit;
}

/* Radiance the lights scatter at medium point x towards -view (phase
 * function included, sigma_s not), shadowed and attenuated. */
static dvec3 inscatter(const struct ref_scene *rs, const struct ref_medium *rm, struct ref_rng *rng, dvec3 x,
                       dvec3 view)
{
    dvec3 sum = dv(0, 0, 0);
    for (int i = 0; i < rs->light_count; i++) {
        dvec3 e, wi;
        double dist;
        if (!light_arrival(&rs->lights[i], x, &e, &wi, &dist))
            continue;
        double tmax = isfinite(dist) ? dist * (1.0 - 1e-6) : INFINITY;
        dvec3 through = ref_scene_transmittance(rs, x, wi, tmax);
        if (!(dv_dot(through, through) > 0.0))
            continue;
        e = dv_mul(e, through);
        /* cos between the light's travel direction (-wi) and the direction to the eye (-view) */
        double p = ref_phase_hg(rm->g, dv_dot(wi, view));
        sum = dv_add(sum, dv_scale(dv_mul(e, ref_medium_transmittance(rm, x, wi, tmax, rng)), p));
    }
    return sum;
}

/* The lights' light at p, normal n, shadowed and attenuated: with brdf
 * NULL their irradiance (a Lambert surface's caller weighs it by albedo /
 * pi); with a glTF surface's BRDF, the radiance it sends towards v, sum of
 * f(v, wi) E_i (common/surface_light.glsl's surface_light_gltf). */
static dvec3 direct_light(const struct ref_scene *rs, const struct ref_medium *rm, struct ref_rng *rng, dvec3 p,
                          dvec3 n, const struct brdf_material *brdf, dvec3 v)
{
    dvec3 e = dv(0, 0, 0);
    dvec3 origin = dv_add(p, dv_scale(n, rs->epsilon));
    for (int i = 0; i < rs->light_count; i++) {
        dvec3 el, wi;
        double dist;
        if (!light_arrival(&rs->lights[i], p, &el, &wi, &dist))
            continue;
        double c = dv_dot(n, wi);
        double tmax = isfinite(dist) ? dist * (1.0 - 1e-6) - rs->epsilon : INFINITY;
        /* (a clearcoat's own normal may face a light the base does not) */
        if (c <= 0.0 && !(brdf && brdf->clearcoat > 0.0 &&
                          brdf->clearcoat_normal[0] * wi.x + brdf->clearcoat_normal[1] * wi.y +
                                  brdf->clearcoat_normal[2] * wi.z > 0.0))
            continue;
        dvec3 through = ref_scene_transmittance(rs, origin, wi, tmax); /* (through thin-walled panes) */
        if (!(dv_dot(through, through) > 0.0))
            continue;
        el = dv_mul(el, through);
        /* with a medium, attenuated along the shadow ray */
        if (rm->present)
            el = dv_mul(el, ref_medium_transmittance(rm, origin, wi, tmax, rng));
        if (brdf) { /* f cos, the coat's by its own normal (core/brdf.h) */
            double nn[3] = {n.x, n.y, n.z}, vv[3] = {v.x, v.y, v.z}, ll[3] = {wi.x, wi.y, wi.z}, f[3];
            brdf_gltf_cos(nn, vv, ll, brdf, f);
            e = dv_add(e, dv_mul(el, dv(f[0], f[1], f[2])));
        } else {
            e = dv_add(e, dv_scale(el, c));
        }
    }
    return e;
}

/* The radiance arriving at `origin` from direction `dir` for a glTF
 * surface's glossy lobes (docs/GLTF.md): the environment where the ray
 * leaves the scene; through glass and mirrors by their specular steps;
 * at the first diffuse surface, its own light as an eye path draws it
 * (the lights, the ambient sky, its emission; a glTF surface there reflects
 * the environment in its mirror direction, unoccluded), without its
 * caustics and without a second glossy bounce. Absorbed by the media it
 * crosses (not the scene's participating medium). */
static dvec3 glossy_radiance(const struct ref_scene *rs, const struct ref_medium *rm, struct ref_rng *rng,
                             dvec3 origin, dvec3 dir, struct media media)
{
    dvec3 beta = dv(1, 1, 1);
    for (int depth = 0; depth < MAX_DEPTH; depth++) {
        struct ref_hit h;
        if (!ref_scene_intersect(rs, origin, dir, INFINITY, &h))
            return dv_mul(beta, ref_scene_environment(rs, dir));
        beta = attenuate(beta, medium_sigma(rs, &media), h.t);
        if (hit_is_diffuse(rs, &h, rng)) {
            dvec3 n = dv_dot(h.shading_normal, dir) < 0 ? h.shading_normal : dv_scale(h.shading_normal, -1.0);
            struct ref_surface surface;
            ref_surface_diffuse(rs, &h, n, &surface);
            n = surface.normal;
            dvec3 v = dv_scale(dir, -1.0);
            if (surface.pbr) {
                double nn[3] = {n.x, n.y, n.z}, vv[3] = {v.x, v.y, v.z}, amb[3], diff[3];
                brdf_ambient_albedo(nn, vv, &surface.brdf, amb);
                brdf_diffuse_albedo(nn, vv, &surface.brdf, diff);
                dvec3 lit = direct_light(rs, rm, rng, h.position, n, &surface.brdf, v);
                dvec3 mirror = dv_sub(dv_scale(n, 2.0 * dv_dot(n, v)), v);
                dvec3 env = ref_scene_environment(rs, mirror);
                dvec3 sky = dv_add(dv_mul(rs->ambient, dv(diff[0], diff[1], diff[2])),
                                   dv_mul(env, dv(amb[0] - diff[0], amb[1] - diff[1], amb[2] - diff[2])));
                return dv_mul(beta, dv_add(dv_add(lit, dv_scale(sky, surface.occlusion)), surface.emission));
            }
            dvec3 e = direct_light(rs, rm, rng, h.position, n, NULL, dv(0, 0, 0));
            double a[3] = {surface.albedo.x, surface.albedo.y, surface.albedo.z}, ev[3] = {e.x, e.y, e.z};
            double am[3] = {rs->ambient.x, rs->ambient.y, rs->ambient.z};
            double em[3] = {surface.emission.x, surface.emission.y, surface.emission.z}, out[3];
            shading_diffuse_radiance(a, ev, am, em, out);
            return dv_mul(beta, dv(out[0], out[1], out[2]));
        }
        specular_step(rs, &h, &media, &dir, &origin, &beta, rng);
        if (dv_dot(beta, beta) < 1e-30)
            break;
    }
    return dv(0, 0, 0);
}

/* What the threads of one render share: the clock they all stop by. */
struct budget {
    double deadline;        /* log_now() time; 0: none */
    double photon_deadline; /* when photons stop: the deadline less what the gathers after them need */
    atomic_int cut;         /* set when an eye or gather pass stopped early for the deadline */
    atomic_int photons_cut; /* set when the photon pass did */
    long chunk_reached[PHOTON_CHUNKS]; /* where each chunk's photons stopped (its end, unless cut) */
    double start, last_print;
    bool tty;
    bool log_lines;         /* progress asked for, off a terminal: one line an iteration */
    int iteration;
    long long emitted_before;
    int line_length;        /* of the progress line on the terminal, to blank what a shorter one leaves */
    double last_line;       /* when the last whole progress line went to the log */
    bool map_warned;        /* the photon map's out-of-memory warning was given */
    double gather_share;    /* of a photon stage's time, what the surface gather after the tracing took, last time */
    bool gather_seen;       /* an iteration's gather has set gather_share (before it, the pilot's rates predict it) */
    double seconds_per_traced, seconds_per_mapped, seconds_per_gathered; /* the pilot's rates: a photon traced, put
                                                                          * in the map, taken by a visible point */
};

/* A photon stage that must end by `until` (0: no budget) stops tracing
 * early enough for the surface gather after it, as long as the last one
 * took (the first guess, before any was measured, is a quarter). */
static double photon_deadline_before_gather(const struct budget *b, double until)
{
    if (until <= 0.0)
        return 0.0;
    double now = log_now();
    return now + fmax(until - now, 0.0) * (1.0 - b->gather_share);
}

static void gather_share_measured(struct budget *b, double trace_seconds, double gather_seconds)
{
    if (trace_seconds + gather_seconds > 0.0)
        b->gather_share = fmin(gather_seconds / (trace_seconds + gather_seconds), 0.9);
}

/* The one progress writer: on a terminal, the line rewritten in place
 * (padded over the longer line before it); off one, nothing here (the
 * iteration lines are whole lines). */
static void progress_line(struct budget *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void progress_line(struct budget *b, const char *fmt, ...)
{
    if (!b->tty)
        return;
    char text[256];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    if (n > (int)sizeof text - 1)
        n = (int)sizeof text - 1;
    fprintf(stderr, "\r%s%*s", text, b->line_length > n ? b->line_length - n : 0, "");
    b->line_length = n;
    fflush(stderr);
}

static bool budget_photons_spent(struct budget *b)
{
    if (b->photon_deadline > 0 && log_now() >= b->photon_deadline) {
        atomic_store(&b->photons_cut, 1);
        return true;
    }
    return atomic_load(&b->photons_cut) != 0;
}

static bool budget_spent(struct budget *b)
{
    if (b->deadline > 0 && log_now() >= b->deadline) {
        atomic_store(&b->cut, 1);
        return true;
    }
    return atomic_load(&b->cut) != 0;
}

struct job {
    const struct ref_scene *rs;
    const struct ref_options *o;
    struct pixel *pixels;
    int iteration;
    int thread, threads;
    const struct media *camera_media;
    const struct ref_medium *medium;
    double pixel_angle; /* radians a pixel spans at the image centre */
    double pixel_size;  /* an orthographic camera's pixel, in scene units */
    /* volume photons */
    struct volume_photons *volume_chunks;
    struct volume_grid *volume_grid;
    int volume_rows;    /* which rows a volume gather does: VOLUME_ROWS_* */
    int volume_samples; /* stratified points per segment (VOLUME_SAMPLES but in a budget's first gather) */
    atomic_int volume_rows_left; /* rows a first gather under a budget could not reach */
    struct budget *budget;
    /* photons: light l emits photons_of[l] of them, photon k of the
     * iteration belongs to the light whose range [first_of[l], first_of[l] +
     * photons_of[l]) holds it */
    struct ref_emitter *emitters;
    struct aim_log *aims;     /* PHOTON_CHUNKS of them */
    double pass_fraction;     /* of the photons of the pass just traced (1 unless the budget cut it) */
    double gather_until;      /* when an iteration's surface gather stops (0: no budget) */
    bool independent;         /* passes that share no state (ref_options.shard_count > 0) */
    bool pilot_done;          /* the pilot ran before the passes (independent passes) */
    double emit_shift[SCENE_MAX_GPU_LIGHTS][3]; /* each light's random rotation of its emission sequence */
    long photons_of[SCENE_MAX_GPU_LIGHTS], first_of[SCENE_MAX_GPU_LIGHTS];
    long photons_total;
    struct ref_photon_map *photon_map; /* the iterations' map, its arrays kept between them */
    const double *light_scale;         /* the gather's scale of each light's photons */
    bool gather_counts_only;           /* the pilot's gather: photons per pixel into m, no flux */
    struct radius_search *radius_search; /* the pilot's radius passes: per pixel */
    bool radius_search_knn;              /* their kind: k nearest neighbours, or the structure test */
    double radius_search_until;          /* their deadline (0: none), checked every row */
    struct ref_surface_photons *chunks;
    long long caustic_photons[PHOTON_CHUNKS];
    double caustic_power[PHOTON_CHUNKS][3]; /* flux the photons brought to diffuse surfaces */
};

/* One eye path of pixel (x, y): its visible point, its segments through
 * the medium and its first radius into the pixel; returns the radiance it
 * gathered on the way (the lights seen directly, single scattering, the
 * environment, emission). */
static dvec3 trace_eye_path(struct job *j, struct pixel *px, int x, int y, struct ref_rng *rngp)
{
    const struct ref_scene *rs = j->rs;
    struct ref_rng rng = *rngp;
    dvec3 seen = dv(0, 0, 0);
    dvec3 origin, dir;
    /* Pixel centres, as the rasterizer samples: a point-sampled reference;
     * with `antialias` a point spread over the pixel each iteration, so that
     * the iterations average the pixel's area (a caustic whose focus is a few
     * pixels wide is then the light falling in each pixel, not at its
     * centre: issue 8's glass_sphere). */
    double sx = 0.5, sy = 0.5;
    if (j->o->antialias) {
        sx = ref_rng_uniform(&rng);
        sy = ref_rng_uniform(&rng);
    }
    ref_scene_camera_ray(rs, x + sx, y + sy, j->o->width, j->o->height, &origin, &dir);
    struct media media = *j->camera_media;
    /* The ray starts on the near plane (what the rasterizer clips), but the
     * camera sits at the eye: the medium around it absorbs from there. */
    double from_eye = rs->ortho ? rs->znear /* from the eye's plane */
                                : sqrt(dv_dot(dv_sub(origin, rs->eye), dv_sub(origin, rs->eye)));
    dvec3 beta = attenuate(dv(1, 1, 1), medium_sigma(rs, &media), from_eye);
    px->vp.valid = false;
    px->segment_count = 0;
    const struct ref_medium *rm = j->medium;
    for (int depth = 0; depth < MAX_DEPTH; depth++) {
        struct ref_hit h;
        bool hit = eye_intersect(rs, origin, dir, &h);
        double t0, t1;
        if (scene_medium_here(rs, &media) && ref_medium_clip(rm, origin, dir, hit ? h.t : INFINITY, &t0, &t1)) {
            /* Single scattering of the lights along the segment: one
             * uniformly placed sample per iteration (unbiased; the
             * iterations average it). */
            double sdist = t0 + (t1 - t0) * ref_rng_uniform(&rng);
            dvec3 at = dv_add(origin, dv_scale(dir, sdist));
            double rho = ref_medium_density(rm, at);
            if (rho > 0.0) {
                dvec3 tr = ref_medium_transmittance(rm, origin, dir, sdist, &rng);
                dvec3 ls = inscatter(rs, rm, &rng, at, dir);
                dvec3 c = dv_mul(dv_mul(beta, tr), dv_mul(dv_scale(rm->sigma_s, rho * (t1 - t0)), ls));
                seen = dv_add(seen, c);
            }
            if (px->segment_count < MAX_SEGMENTS) {
                int k = px->segment_count++;
                px->segments[k].origin = origin;
                px->segments[k].dir = dir;
                px->segments[k].beta = beta;
                px->segments[k].t0 = t0;
                px->segments[k].t1 = t1;
            }
            beta = dv_mul(beta, ref_medium_transmittance(rm, origin, dir, hit ? h.t : INFINITY, &rng));
        }
        if (!hit) {
            seen = dv_add(seen, dv_mul(beta, ref_scene_environment(rs, dir)));
            break;
        }
        beta = attenuate(beta, medium_sigma(rs, &media), h.t);
        if (hit_is_diffuse(rs, &h, &rng)) {
            dvec3 n = dv_dot(h.shading_normal, dir) < 0 ? h.shading_normal : dv_scale(h.shading_normal, -1.0);
            struct ref_surface surface;
            ref_surface_diffuse(rs, &h, n, &surface);
            n = surface.normal;
            dvec3 albedo = surface.albedo;
            dvec3 f;
            if (surface.pbr) {
                /* surface_light_gltf (common/surface_light.glsl) by its C
                 * twins: the lights through the BRDF, the ambient sky by the
                 * BRDF's directional albedo and the occlusion; photons (the
                 * caustics) by the diffuse lobe's albedo, as the GPU weighs
                 * caustic irradiance */
                dvec3 v = dv_scale(dir, -1.0);
                double nn[3] = {n.x, n.y, n.z}, vv[3] = {v.x, v.y, v.z}, diff[3];
                dvec3 lit = direct_light(rs, rm, &rng, h.position, n, &surface.brdf, v);
                brdf_diffuse_albedo(nn, vv, &surface.brdf, diff);
                /* the ambient sky on the diffuse lobe; the specular lobes
                 * reflect the environment and the scene, GLOSSY_SAMPLES
                 * directions drawn from them per iteration (docs/GLTF.md) */
                dvec3 sky = dv_mul(rs->ambient, dv(diff[0], diff[1], diff[2]));
                for (int s = 0; s < GLOSSY_SAMPLES; s++) {
                    double l[3], pdf, fs[3];
                    if (!brdf_sample_specular(nn, vv, &surface.brdf, ref_rng_uniform(&rng), ref_rng_uniform(&rng),
                                              ref_rng_uniform(&rng), l, &pdf))
                        continue;
                    dvec3 ld = dv(l[0], l[1], l[2]);
                    /* (a mapped normal may send l under the triangle: it meets the surface itself, nothing) */
                    double side = dv_dot(h.geometric_normal, dir) < 0 ? 1.0 : -1.0;
                    if (!(side * dv_dot(ld, h.geometric_normal) > 0.0))
                        continue;
                    brdf_gltf_specular_cos(nn, vv, l, &surface.brdf, fs);
                    dvec3 w = dv(fs[0] / (pdf * GLOSSY_SAMPLES), fs[1] / (pdf * GLOSSY_SAMPLES),
                                 fs[2] / (pdf * GLOSSY_SAMPLES));
                    dvec3 from = dv_add(h.position, dv_scale(h.geometric_normal, side * rs->epsilon));
                    sky = dv_add(sky, dv_mul(w, glossy_radiance(rs, rm, &rng, from, ld, media)));
                }
                sky = dv_scale(sky, surface.occlusion);
                seen = dv_add(seen, dv_mul(beta, dv_add(dv_add(lit, sky), surface.emission)));
                f = dv_scale(dv_mul(beta, dv(diff[0], diff[1], diff[2])), 1.0 / MATH_PI);
            } else {
                dvec3 e = direct_light(rs, rm, &rng, h.position, n, NULL, dv(0, 0, 0));
                f = dv_scale(dv_mul(beta, albedo), 1.0 / MATH_PI);
                /* the GPU's surface_diffuse_radiance (common/surface_light.glsl),
                 * through its C twin; its own emission seen along the path
                 * (emissive surfaces light nothing: no interreflection) */
                double a[3] = {albedo.x, albedo.y, albedo.z}, ev[3] = {e.x, e.y, e.z};
                double amb[3] = {rs->ambient.x, rs->ambient.y, rs->ambient.z};
                double em[3] = {surface.emission.x, surface.emission.y, surface.emission.z}, out[3];
                shading_diffuse_radiance(a, ev, amb, em, out);
                seen = dv_add(seen, dv_mul(beta, dv(out[0], out[1], out[2])));
            }
            if (px->radius <= 0.0) {
                /* First visible point: start the gather radius at a few
                 * pixel footprints at this distance (then SPPM shrinks it). */
                dvec3 eye_to = dv_sub(h.position, rs->eye);
                double footprint = rs->ortho ? j->pixel_size : sqrt(dv_dot(eye_to, eye_to)) * j->pixel_angle;
                px->radius = j->o->initial_radius > 0 ? j->o->initial_radius : fmax(RADIUS_PIXELS * footprint, 1e-6);
            }
            px->vp.valid = true;
            px->vp.position = h.position;
            px->vp.normal = n;
            px->vp.weight = f;
            break;
        }
        specular_step(rs, &h, &media, &dir, &origin, &beta, &rng);
        if (dv_dot(beta, beta) < 1e-30)
            break;
    }
    *rngp = rng;
    return seen;
}

/* Pixel (x, y)'s eye path of this iteration. A path that drew no random
 * number (a pixel centre, no choice between Fresnel's branches, no medium,
 * lights sampled without one: the rng's state as seeded) and met no
 * blended surface, with its shadow rays too (their coins: ref_scene.c) is the same path
 * every iteration: its radiance is kept and added again, its visible point
 * and first radius stand, and it is not traced again (at 512^2 the eye
 * pass was a tenth of each iteration of the ball lens; issue 28). */
static void trace_eye(struct job *j, int x, int y)
{
    struct pixel *px = &j->pixels[(size_t)y * (size_t)j->o->width + (size_t)x];
    px->samples++;
    if (px->eye_fixed) {
        px->direct = dv_add(px->direct, px->eye_once);
        return;
    }
    struct ref_rng rng = ref_rng_seed(j->o->seed, 1000003u * (uint64_t)j->iteration + 1u,
                                      (uint64_t)y * (uint64_t)j->o->width + (uint64_t)x);
    uint64_t seeded = rng.state;
    ref_scene_blend_begin(seeded); /* a new coin each iteration for the blended surfaces it meets */
    dvec3 seen = trace_eye_path(j, px, x, y, &rng);
    px->direct = dv_add(px->direct, seen);
    if (rng.state == seeded && !ref_scene_blend_met()) {
        px->eye_fixed = true;
        px->eye_once = seen;
    }
}

/* Rows interleaved over the threads. After the first iteration the clock
 * is checked per row: an eye pass cut short leaves the pixels it reached
 * one sample ahead (each pixel averages its own samples) and no photon
 * pass follows it. */
static void *camera_thread(void *arg)
{
    struct job *j = arg;
    for (int y = j->thread; y < j->o->height; y += j->threads) {
        if (j->iteration > 0 && budget_spent(j->budget))
            return NULL;
        for (int x = 0; x < j->o->width; x++)
            trace_eye(j, x, y);
    }
    return NULL;
}

/* ---- photons ------------------------------------------------------------ */

/* Volume caustic photons: where light that went through specular
 * surfaces scattered in the medium (flux already weighted by sigma_s). */
struct volume_photon {
    float position[3], dir[3], flux[3];
    int light;
};

struct volume_photons {
    struct volume_photon *items;
    size_t count, capacity;
};

static void volume_push(struct volume_photons *v, dvec3 p, dvec3 d, dvec3 flux, int light)
{
    if (v->count == v->capacity) {
        size_t cap = v->capacity ? v->capacity * 2 : 1024;
        struct volume_photon *q = realloc(v->items, cap * sizeof *q);
        if (!q)
            return;
        v->items = q;
        v->capacity = cap;
    }
    v->items[v->count++] = (struct volume_photon){{(float)p.x, (float)p.y, (float)p.z},
                                                  {(float)d.x, (float)d.y, (float)d.z},
                                                  {(float)flux.x, (float)flux.y, (float)flux.z}, light};
}

/* A hash grid over volume photons, cell = the gather radius. */
struct volume_grid {
    double radius, cell;
    size_t size;
    size_t *start;
    struct volume_photon *items; /* sorted by cell */
};

static size_t volume_hash(const struct volume_grid *g, long x, long y, long z)
{
    uint64_t h = ((uint64_t)x * 73856093u) ^ ((uint64_t)y * 19349663u) ^ ((uint64_t)z * 83492791u);
    return (size_t)(h % g->size);
}

static void volume_grid_build(struct volume_grid *g, const struct volume_photons *chunks, int nchunks, double radius)
{
    size_t n = 0;
    for (int c = 0; c < nchunks; c++)
        n += chunks[c].count;
    g->radius = radius;
    g->cell = radius;
    g->size = n > 0 ? n * 2 : 1;
    g->start = calloc(g->size + 1, sizeof *g->start);
    g->items = malloc((n + 1) * sizeof *g->items);
    if (!g->start || !g->items) {
        g->size = 0;
        return;
    }
    for (int c = 0; c < nchunks; c++)
        for (size_t k = 0; k < chunks[c].count; k++) {
            const float *p = chunks[c].items[k].position;
            g->start[volume_hash(g, (long)floor(p[0] / g->cell), (long)floor(p[1] / g->cell), (long)floor(p[2] / g->cell)) + 1]++;
        }
    for (size_t s = 0; s < g->size; s++)
        g->start[s + 1] += g->start[s];
    size_t *fill = malloc((g->size + 1) * sizeof *fill);
    if (!fill) {
        g->size = 0;
        return;
    }
    memcpy(fill, g->start, (g->size + 1) * sizeof *fill);
    for (int c = 0; c < nchunks; c++)
        for (size_t k = 0; k < chunks[c].count; k++) {
            const float *p = chunks[c].items[k].position;
            size_t h = volume_hash(g, (long)floor(p[0] / g->cell), (long)floor(p[1] / g->cell), (long)floor(p[2] / g->cell));
            g->items[fill[h]++] = chunks[c].items[k];
        }
    free(fill);
}

static void volume_grid_release(struct volume_grid *g)
{
    free(g->start);
    free(g->items);
    memset(g, 0, sizeof *g);
}

/* In-scattered radiance of the volume photons at x towards -view: the
 * volume radiance estimate sum(flux * phase) / (4/3 pi r^3) (Jensen &
 * Christensen 1998). */
static dvec3 volume_estimate(const struct volume_grid *g, double phase_g, dvec3 x, dvec3 view)
{
    dvec3 sum = dv(0, 0, 0);
    if (g->size == 0)
        return sum;
    long cx = (long)floor(x.x / g->cell), cy = (long)floor(x.y / g->cell), cz = (long)floor(x.z / g->cell);
    double r2 = g->radius * g->radius;
    /* two of the 27 cells may hash to one slot: each slot is read once, or
     * its photons would count twice */
    size_t seen[27];
    int nseen = 0;
    for (long z = cz - 1; z <= cz + 1; z++)
        for (long y = cy - 1; y <= cy + 1; y++)
            for (long xx = cx - 1; xx <= cx + 1; xx++) {
                size_t h = volume_hash(g, xx, y, z);
                if (!ref_slot_first(seen, &nseen, h))
                    continue;
                for (size_t k = g->start[h]; k < g->start[h + 1]; k++) {
                    const struct volume_photon *p = &g->items[k];
                    dvec3 d = dv(p->position[0] - x.x, p->position[1] - x.y, p->position[2] - x.z);
                    if (dv_dot(d, d) > r2)
                        continue;
                    /* hash collisions bring photons of far cells: the distance test rejects them */
                    double ph = ref_phase_hg(phase_g, -(p->dir[0] * view.x + p->dir[1] * view.y + p->dir[2] * view.z));
                    sum = dv_add(sum, dv_scale(dv(p->flux[0], p->flux[1], p->flux[2]), ph));
                }
            }
    return dv_scale(sum, 1.0 / (4.0 / 3.0 * MATH_PI * g->radius * g->radius * g->radius));
}

/* The volume caustic seen along a pixel's medium segments. */
static void gather_volume(struct job *j, int x, int y)
{
    struct pixel *px = &j->pixels[(size_t)y * (size_t)j->o->width + (size_t)x];
    px->volume_samples += j->pass_fraction;
    if (px->segment_count == 0)
        return;
    struct ref_rng rng = ref_rng_seed(j->o->seed, 1000003u * (uint64_t)j->iteration + 3u,
                                      (uint64_t)y * (uint64_t)j->o->width + (uint64_t)x);
    const struct ref_medium *rm = j->medium;
    for (int k = 0; k < px->segment_count; k++) {
        int samples = j->volume_samples > 0 ? j->volume_samples : VOLUME_SAMPLES;
        double t0 = px->segments[k].t0, t1 = px->segments[k].t1, step = (t1 - t0) / samples;
        dvec3 o = px->segments[k].origin, d = px->segments[k].dir;
        dvec3 sum = dv(0, 0, 0);
        for (int s = 0; s < samples; s++) {
            double t = t0 + step * (s + ref_rng_uniform(&rng));
            dvec3 p = dv_add(o, dv_scale(d, t));
            dvec3 l = volume_estimate(j->volume_grid, rm->g, p, d);
            if (l.x + l.y + l.z <= 0.0)
                continue;
            sum = dv_add(sum, dv_mul(ref_medium_transmittance(rm, o, d, t, &rng), l));
        }
        px->volume = dv_add(px->volume, dv_mul(px->segments[k].beta, dv_scale(sum, step)));
    }
}

/* The rows a volume gather does: all, or (the first gather under a time
 * budget) every VOLUME_PROBE_STRIDE-th row first at VOLUME_PROBE_SAMPLES
 * points a ray, timed (1/128 of the whole gather's cost), then the rest. */
enum { VOLUME_ROWS_ALL, VOLUME_ROWS_PROBE, VOLUME_ROWS_REST };
#define VOLUME_PROBE_STRIDE 32
#define VOLUME_PROBE_SAMPLES 2

static void *volume_thread(void *arg)
{
    struct job *j = arg;
    for (int y = j->thread; y < j->o->height; y += j->threads) {
        bool probe_row = y % VOLUME_PROBE_STRIDE == 0;
        if ((j->volume_rows == VOLUME_ROWS_PROBE && !probe_row) || (j->volume_rows == VOLUME_ROWS_REST && probe_row))
            continue;
        if (j->iteration > 0 && budget_spent(j->budget))
            return NULL;
        if (j->volume_rows == VOLUME_ROWS_REST && budget_spent(j->budget)) {
            /* the last resort of a first gather the probe misjudged: the
             * row keeps no medium light, and the warning counts it */
            atomic_fetch_add(&j->volume_rows_left, 1);
            continue;
        }
        for (int x = 0; x < j->o->width; x++)
            gather_volume(j, x, y);
    }
    return NULL;
}

/* What each chunk's photons were aimed at, and whether they reached a
 * visible point: (light << 40) | (entry << 1) | useful, for the adaptive
 * emission (ref_emitter_adapt). */
struct aim_log {
    uint64_t *items;
    size_t count, capacity;
};

static void aim_push(struct aim_log *log, int light, size_t entry, bool useful)
{
    if (log->count == log->capacity) {
        size_t cap = log->capacity ? log->capacity * 2 : 4096;
        uint64_t *p = realloc(log->items, cap * sizeof *p);
        if (!p)
            return; /* the adaptation sees one photon fewer: it stays valid */
        log->items = p;
        log->capacity = cap;
    }
    log->items[log->count++] = ((uint64_t)light << 40) | ((uint64_t)entry << 1) | (useful ? 1u : 0u);
}

static void trace_photon_path(struct job *j, int light, struct ref_rng *rng_in, dvec3 origin, dvec3 dir, dvec3 flux,
                              int target_object, unsigned target_primitive, struct ref_surface_photons *hits,
                              long long *caustic, double *power, struct volume_photons *volume, uint32_t aim);

static void trace_photon(struct job *j, int light, long index, struct ref_surface_photons *hits, long long *caustic,
                         double *power, struct volume_photons *volume, struct aim_log *aims)
{
    const struct ref_scene *rs = j->rs;
    struct ref_rng rng = ref_rng_seed(j->o->seed, 7919u * (uint64_t)j->iteration + 2u + (uint64_t)light * 104729u,
                                      (uint64_t)index);
    dvec3 origin, dir, flux;
    int target_object;
    unsigned target_primitive;
    size_t entry;
    /* Photon `index` of this iteration is point (iteration x photons +
     * index) of the light's sequence: each iteration takes the next stretch
     * of it (the pilot one far beyond the rest). */
    uint64_t sequence = j->iteration < 0 ? ((uint64_t)-j->iteration << 40) + (uint64_t)index
                                         : (uint64_t)j->iteration * (uint64_t)j->photons_of[light] + (uint64_t)index;
    double point[3];
    ref_emit_point(sequence, j->emit_shift[light], point);
    if (!ref_emitter_sample(&j->emitters[light], rs, &rs->lights[light], j->photons_of[light], point, &origin, &dir,
                            &flux, &target_object, &target_primitive, &entry))
        return;
    size_t volume_before = volume->count;
    /* a surface photon is marked useful by the gather (gather_surface_photons),
     * a volume photon now: it is gathered wherever it lies */
    trace_photon_path(j, light, &rng, origin, dir, flux, target_object, target_primitive, hits, caustic, power, volume,
                      (uint32_t)aims->count);
    aim_push(aims, light, entry, volume->count > volume_before);
}

static void trace_photon_path(struct job *j, int light, struct ref_rng *rng_in, dvec3 origin, dvec3 dir, dvec3 flux,
                              int target_object, unsigned target_primitive, struct ref_surface_photons *hits,
                              long long *caustic, double *power, struct volume_photons *volume, uint32_t aim)
{
    const struct ref_scene *rs = j->rs;
    struct ref_rng rng = *rng_in;
    struct media media = {.count = 0}; /* lights are outside every dielectric */
    int specular = 0;
    for (int depth = 0; depth < MAX_DEPTH; depth++) {
        struct ref_hit h;
        bool hit = ref_scene_intersect(rs, origin, dir, INFINITY, &h);
        /* Aimed at one triangle: if another surface comes first, this
         * direction belongs to that surface's own photons (or to direct
         * light, for an opaque one) and this photon carries nothing. */
        if (depth == 0 && (!hit || h.object != target_object || h.primitive != target_primitive))
            return;
        if (scene_medium_here(rs, &media) && j->medium->present) {
            double ts = 0;
            dvec3 w = dv(1, 1, 1);
            enum ref_medium_event ev = ref_medium_track(j->medium, origin, dir, hit ? h.t : INFINITY, &rng, &ts, &w);
            if (ev == REF_MEDIUM_ABSORB)
                return;
            if (ev == REF_MEDIUM_SCATTER) {
                /* Light -> specular+ -> medium: a volume caustic photon. One
                 * that scatters before any specular surface is direct
                 * single scattering, which the eye paths estimate. */
                if (specular > 0)
                    volume_push(volume, dv_add(origin, dv_scale(dir, ts)), dir, dv_mul(flux, w), light);
                return;
            }
            flux = dv_mul(flux, w);
        }
        if (!hit)
            return;
        flux = attenuate(flux, medium_sigma(rs, &media), h.t);
        if (hit_is_diffuse(rs, &h, &rng)) {
            if (specular > 0) {
                (*caustic)++;
                power[0] += flux.x;
                power[1] += flux.y;
                power[2] += flux.z;
                struct ref_surface_photon ph = {
                    {(float)h.position.x, (float)h.position.y, (float)h.position.z},
                    {(float)dir.x, (float)dir.y, (float)dir.z},
                    {(float)h.geometric_normal.x, (float)h.geometric_normal.y, (float)h.geometric_normal.z},
                    {(float)flux.x, (float)flux.y, (float)flux.z}, light, aim};
                ref_surface_photons_push(hits, &ph); /* out of memory: the photon is lost, the estimate stays finite */
            }
            return; /* L D paths are direct light, gathered by shadow rays */
        }
        if (specular_step(rs, &h, &media, &dir, &origin, &flux, &rng))
            specular++;
        if (dv_dot(flux, flux) < 1e-40)
            return;
    }
}

static void chunk_range(const struct job *j, int c, long *begin, long *end)
{
    *begin = (long)((long long)j->photons_total * c / PHOTON_CHUNKS);
    *end = (long)((long long)j->photons_total * (c + 1) / PHOTON_CHUNKS);
}

/* Progress while photons are traced (thread 0 only), at most 4 times a
 * second: with millions of photons an iteration can take many seconds. */
static void photon_progress(const struct job *j, int chunks_done)
{
    struct budget *b = j->budget;
    double now = log_now();
    if (!b->tty || now - b->last_print < 0.25)
        return;
    b->last_print = now;
    if (b->deadline > 0)
        progress_line(b, "reference: iteration %d (%d%% of its photons), %.1f s of %.1f s", b->iteration + 1,
                      100 * chunks_done / PHOTON_CHUNKS, now - b->start, b->deadline - b->start);
    else
        progress_line(b, "reference: iteration %d/%d (%d%% of its photons), %.1f s", b->iteration + 1,
                      j->o->iterations, 100 * chunks_done / PHOTON_CHUNKS, now - b->start);
}

/* Photons in 64 fixed chunks (so the sums do not depend on the thread
 * count). The clock is checked every PHOTON_BATCH photons, after each
 * thread's first batch: a budget ends within a batch's time whatever the
 * photon count, and the photons traced are counted per light. */
#define PHOTON_BATCH 64 /* a few ms of photons even on a loaded machine: the budget ends within that */
static void *photon_thread(void *arg)
{
    struct job *j = arg;
    int done = 0;
    bool first = true;
    for (int c = j->thread; c < PHOTON_CHUNKS; c += j->threads) {
        long begin, end;
        chunk_range(j, c, &begin, &end);
        j->budget->chunk_reached[c] = begin;
        int light = 0;
        for (long k = begin; k < end; k++) {
            if ((k - begin) % PHOTON_BATCH == 0) {
                if (!first && budget_photons_spent(j->budget))
                    return NULL;
                j->budget->chunk_reached[c] = k;
                if (j->thread == 0)
                    photon_progress(j, done);
            }
            first = false;
            while (light + 1 < j->rs->light_count && k >= j->first_of[light + 1])
                light++;
            trace_photon(j, light, k - j->first_of[light], &j->chunks[c], &j->caustic_photons[c],
                         j->caustic_power[c], &j->volume_chunks[c], &j->aims[c]);
            j->budget->chunk_reached[c] = k + 1;
        }
        done += j->threads;
    }
    return NULL;
}

static void run_threads(struct job *base, int threads, void *(*fn)(void *))
{
    struct job jobs[64];
    pthread_t ids[64];
    if (threads > 64)
        threads = 64;
    for (int t = 0; t < threads; t++) {
        jobs[t] = *base;
        jobs[t].thread = t;
        jobs[t].threads = threads;
        memset(jobs[t].caustic_photons, 0, sizeof jobs[t].caustic_photons);
        memset(jobs[t].caustic_power, 0, sizeof jobs[t].caustic_power);
    }
    int started = 0;
    for (int t = 1; t < threads; t++)
        if (pthread_create(&ids[t], NULL, fn, &jobs[t]) == 0)
            started = t;
        else
            break;
    /* the calling thread takes slot 0, and the slots of threads that did not start */
    for (int t = 0; t < threads; t++)
        if (t == 0 || t > started)
            fn(&jobs[t]);
    for (int t = 1; t <= started; t++)
        pthread_join(ids[t], NULL);
    for (int t = 0; t < threads; t++)
        for (int c = 0; c < PHOTON_CHUNKS; c++) {
            base->caustic_photons[c] += jobs[t].caustic_photons[c];
            for (int k = 0; k < 3; k++)
                base->caustic_power[c][k] += jobs[t].caustic_power[c][k];
        }
}

/* Adapts each light's emission to where its photons were useful (what
 * the chunks logged, in chunk order: deterministic). */
/* Returns the fraction of the logged photons that were useful. */
static double adapt_emission(struct aim_log *aims, struct ref_emitter *emitters, int light_count)
{
    double logged = 0.0, useful = 0.0;
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        for (size_t k = 0; k < aims[c].count; k++) {
            uint64_t a = aims[c].items[k];
            logged += 1.0;
            useful += (double)(a & 1u);
            struct ref_emitter *e = &emitters[a >> 40];
            size_t entry = (size_t)((a >> 1) & ((1ull << 39) - 1));
            e->sampled[entry] += 1.0;
            e->useful[entry] += (double)(a & 1u);
        }
        aims[c].count = 0;
    }
    for (int l = 0; l < light_count; l++)
        ref_emitter_adapt(&emitters[l]);
    return logged > 0.0 ? useful / logged : 0.0;
}

static void structure_sums(const struct ref_photon_rings *g, double area, double sum[STRUCTURE_SUMS],
                           double var[STRUCTURE_SUMS]);

/* ---- the surface gather --------------------------------------------------- */

/* Rows interleaved over the threads; each pixel sums the photons within
 * its radius (ref_photon_map.h: the gather from the pixels' side). */
static void *surface_gather_thread(void *arg)
{
    struct job *j = arg;
    bool stopped = false;
    for (int y = j->thread; y < j->o->height; y += j->threads) {
        /* Under a budget the gather stops at the deadline, row by row: a
         * pixel whose row it did not reach leaves this pass out of its
         * estimate (passes_missed), as if its photons had not been traced. */
        if (!stopped && j->gather_until > 0.0 && !j->gather_counts_only && log_now() >= j->gather_until) {
            stopped = true;
            atomic_store(&j->budget->cut, 1);
        }
        for (int x = 0; x < j->o->width; x++) {
            struct pixel *px = &j->pixels[(size_t)y * (size_t)j->o->width + (size_t)x];
            if (stopped) {
                px->passes_missed += j->pass_fraction;
                continue;
            }
            if (!px->vp.valid || !(px->radius > 0.0))
                continue;
            dvec3 flux;
            struct ref_photon_rings rings;
            bool test = !j->gather_counts_only && !j->independent && px->radius_floor > 0.0;
            long m = ref_photon_map_gather(j->photon_map, px->vp.position, px->vp.normal, px->radius, j->light_scale,
                                           &flux, test ? &rings : NULL);
            px->m += m;
            if (m > 0 && !j->gather_counts_only)
                px->phi = dv_add(px->phi, dv_mul(px->vp.weight, flux));
            if (m > 0 && test) {
                /* the structure test's sums, in flux densities */
                double sum[STRUCTURE_SUMS], var[STRUCTURE_SUMS];
                structure_sums(&rings, 0.25 * MATH_PI * px->radius * px->radius, sum, var);
                for (int k = 0; k < STRUCTURE_SUMS; k++) {
                    px->structure[k] += sum[k];
                    px->structure_var[k] += var[k];
                }
                px->phi_inner = dv_add(px->phi_inner, dv_mul(px->vp.weight, dv(rings.inner_flux[0], rings.inner_flux[1],
                                                                            rings.inner_flux[2])));
                px->m_inner += rings.inner_count;
            }
        }
    }
    return NULL;
}

/* The pilot's radius passes: each pass, every pixel still searching
 * (search[i].floor > 0) reads the map (the pilot's last round, aimed as
 * the estimate will be) at its radius and moves it. */
struct radius_search {
    double floor, ceiling; /* the radius stays within these; floor 0: settled */
};

/* The pixels a gather serves: those with a visible point and a radius
 * (with `search`, only those still searching). */
static bool gathers(const struct pixel *px, const struct radius_search *search, size_t i)
{
    return px->vp.valid && px->radius > 0.0 && (!search || search[i].floor > 0.0);
}

/* Sets the map's levels for the radii of the pixels that gather, and
 * counts how many read each level (for ref_photon_map_build); false when
 * none gathers. */
static bool map_levels_for(struct job *job, const struct radius_search *search,
                           size_t per_level[REF_PHOTON_MAP_LEVELS])
{
    size_t npix = (size_t)job->o->width * (size_t)job->o->height;
    double rmax = 0.0;
    for (size_t i = 0; i < npix; i++)
        if (gathers(&job->pixels[i], search, i))
            rmax = fmax(rmax, job->pixels[i].radius);
    if (!(rmax > 0.0))
        return false;
    ref_photon_map_prepare(job->photon_map, rmax);
    memset(per_level, 0, REF_PHOTON_MAP_LEVELS * sizeof *per_level);
    for (size_t i = 0; i < npix; i++)
        if (gathers(&job->pixels[i], search, i))
            per_level[ref_photon_map_level_of(job->photon_map, job->pixels[i].radius)]++;
    return true;
}

/* Gathers the traced surface photons into the visible points (their flux
 * into phi and their count into m, or for the pilot only the count), each
 * light's photons scaled by light_scale, tells each chunk's aim log which
 * of its photons a visible point took (the adaptive emission's "useful"),
 * and empties the chunks. */
static void gather_surface_photons(struct job *job, int threads, const double *light_scale, bool counts_only)
{
    struct ref_photon_map *map = job->photon_map;
    size_t npix = (size_t)job->o->width * (size_t)job->o->height;
    size_t per_level[REF_PHOTON_MAP_LEVELS];
    if (map_levels_for(job, NULL, per_level)) {
        double build_start = log_now();
        bool built = ref_photon_map_build(map, job->chunks, PHOTON_CHUNKS, per_level, threads);
        if (counts_only && map->count > 0)
            job->budget->seconds_per_mapped = (log_now() - build_start) / (double)map->count;
        if (!built) {
            if (!job->budget->map_warned)
                log_warn("reference: out of memory for the photon map: an iteration's caustic photons are lost "
                         "(fewer --photons would fit)");
            job->budget->map_warned = true;
            map->count = 0;
        }
        if (map->count > 0) {
            job->light_scale = light_scale;
            job->gather_counts_only = counts_only;
            double scan_start = log_now();
            run_threads(job, threads, surface_gather_thread);
            if (counts_only) {
                long long taken = 0;
                for (size_t i = 0; i < npix; i++)
                    taken += job->pixels[i].m;
                if (taken > 0)
                    job->budget->seconds_per_gathered = (log_now() - scan_start) / (double)taken;
            }
        }
        size_t i = 0;
        for (int c = 0; c < PHOTON_CHUNKS && map->count > 0; c++)
            for (size_t k = 0; k < job->chunks[c].count; k++, i++)
                if (ref_photon_map_was_used(map, i) &&
                    job->chunks[c].items[k].aim < job->aims[c].count)
                    job->aims[c].items[job->chunks[c].items[k].aim] |= 1u;
    }
    for (int c = 0; c < PHOTON_CHUNKS; c++)
        job->chunks[c].count = 0;
}

/* The first radius (docs/REFERENCE.md, "Against POV-Ray, per pixel at
 * 512^2": chosen there on the ball lens at its focus and beyond it, flat
 * water and the TIR cube, at 2 s and 4 s, two seeds each). 200 photons a
 * gather: 40 left flat water's per-pixel noise at 6.7% in 2 s, 800 blurred
 * the ball's focus; a radius up to 32 pixel footprints lets an even,
 * sparsely lit floor gather as widely as POV-Ray's photon counts do (up to
 * 8 left flat water at 3.3%, 64 let a dim pixel beside a bright band
 * reach across it before the tests below could stop it). */
#define PILOT_RADIUS 2.0     /* the pilot counts photons within this many first radii */
#define GATHER_PHOTONS 200.0 /* photons a first radius is chosen to hold, about, per iteration */
#define RADIUS_MIN 0.0625    /* the first radius stays within these multiples of two pixel footprints */
#define RADIUS_MAX 16.0

/* ---- the structure test ------------------------------------------------- */

/* A wide radius is cheap noise reduction where the light is even and a
 * blur where it is not: a focus, a fold, the edge of a shadow or of a
 * caustic band. After Kaplanyan & Dachsbacher ("Adaptive progressive
 * photon mapping", TOG 2013: the radius that balances a kernel's bias
 * against its noise), but tested instead of estimated: the pilot's last
 * round, aimed as the estimate will be, is gathered at each pixel's first
 * radius in two parts, the disc of half the radius and the ring around it.
 * On even light their flux densities agree; where they differ by more than
 * STRUCTURE_Z standard deviations of the difference (the flux's own noise,
 * from the sum of the squared fluxes) the disc's bias is above its noise,
 * and the radius is halved and tested again, down to its floor. A dim
 * region with few photons cannot show a difference and keeps its wide
 * radius, which is right: its noise is the larger error there. */
#define STRUCTURE_Z 3.0
#define RESTART_Z 5.0 /* stricter: the test is repeated every iteration */
#define STRUCTURE_HALVINGS 6
#define KNN_PASSES 4

/* Whether sums show structure: a difference (a sum whose mean is 0 on
 * even light) above STRUCTURE_Z of its standard deviation. */
static bool structure_significant(double sum, double var, double z)
{
    return var > 0.0 && sum * sum > z * z * var;
}

/* Two kinds of structure: curvature (a focus, a ridge), where the inner
 * disc's flux density (over pi r^2 / 4) differs from the ring's (over
 * 3 pi r^2 / 4), inner vs ring / 3; and an edge or a slope, where the flux
 * leans to one side (a step through the centre: the disc and the ring are
 * cut alike, and only the moments see it). Each as a sum whose mean is 0
 * on even light, with its variance, per `area` (pi r^2 / 4 for densities). */
static void structure_sums(const struct ref_photon_rings *g, double area, double sum[STRUCTURE_SUMS],
                           double var[STRUCTURE_SUMS])
{
    sum[0] = (g->inner - g->ring / 3.0) / area;
    var[0] = (g->inner_sq + g->ring_sq / 9.0) / (area * area);
    for (int k = 0; k < 2; k++) {
        sum[1 + k] = g->moment[k] / (4.0 * area);
        var[1 + k] = g->moment_sq[k] / (16.0 * area * area);
    }
}

static bool structure_any(const double sum[STRUCTURE_SUMS], const double var[STRUCTURE_SUMS], double z)
{
    for (int k = 0; k < STRUCTURE_SUMS; k++)
        if (structure_significant(sum[k], var[k], z))
            return true;
    return false;
}

static bool structure_shows(const struct ref_photon_rings *g)
{
    double sum[STRUCTURE_SUMS], var[STRUCTURE_SUMS];
    structure_sums(g, 1.0, sum, var);
    return structure_any(sum, var, STRUCTURE_Z);
}

/* The same test iteration by iteration, on the sums of every iteration's
 * gather since the radius was last halved (the estimate's own photons:
 * the differences average over iterations, so ever smaller biases show as
 * the noise they would hide in falls). Where it shows, the pixel's photon
 * estimate starts again at half the radius: what it gathered so far holds
 * the bias, and SPPM's own shrinking would keep it (Kaplanyan & Dachsbacher
 * 2013 adapt the radius in the same spirit from an estimated Laplacian).
 * Sequential passes only: independent passes share no state. */
static bool structure_restart(struct pixel *px, double passes_now)
{
    if (!(px->radius_floor > 0.0) || 0.5 * px->radius < px->radius_floor)
        return false;
    if (!structure_any(px->structure, px->structure_var, RESTART_Z))
        return false;
    px->radius *= 0.5;
    px->tau = dv(0, 0, 0);
    px->n = 0.0;
    px->passes_before = passes_now;
    px->passes_missed = 0.0;
    memset(px->structure, 0, sizeof px->structure);
    memset(px->structure_var, 0, sizeof px->structure_var);
    return true;
}


/* A k-nearest-neighbour radius (after the pilot's first guess from the
 * count within R_c): the radius that holds the GATHER_PHOTONS an
 * iteration would put there (a quarter of them in the pilot's round),
 * found by counting at the radius and moving it, within a factor 2 of the
 * count. A count at R_c only sees the density around the pixel: a dim
 * pixel beside a bright caustic would reach far into it. */
static void knn_step(const struct job *j, struct pixel *px, struct radius_search *s)
{
    double want = GATHER_PHOTONS / 4.0;
    long c = ref_photon_map_count(j->photon_map, px->vp.position, px->vp.normal, px->radius, (long)(8.0 * want));
    double r = px->radius;
    if ((double)c > 2.0 * want)
        r *= fmax(sqrt(want / (double)c), 0.25);
    else if ((double)c < 0.5 * want)
        r *= c > 0 ? fmin(sqrt(want / (double)c), 2.0) : 2.0;
    r = fmin(fmax(r, s->floor), s->ceiling);
    if (r == px->radius)
        s->floor = 0.0; /* settled */
    px->radius = r;
}

static void structure_step(const struct job *j, struct pixel *px, struct radius_search *s)
{
    struct ref_photon_rings g;
    ref_photon_map_rings(j->photon_map, px->vp.position, px->vp.normal, px->radius, &g);
    if (structure_shows(&g) && 0.5 * px->radius >= s->floor)
        px->radius *= 0.5;
    else
        s->floor = 0.0; /* settled */
}

static void *radius_search_thread(void *arg)
{
    struct job *j = arg;
    for (int y = j->thread; y < j->o->height; y += j->threads) {
        if (j->radius_search_until > 0.0 && log_now() >= j->radius_search_until)
            return NULL; /* the rows left keep the radii they have */
        for (int x = 0; x < j->o->width; x++) {
            size_t i = (size_t)y * (size_t)j->o->width + (size_t)x;
            struct pixel *px = &j->pixels[i];
            struct radius_search *s = &j->radius_search[i];
            if (!(s->floor > 0.0) || !px->vp.valid)
                continue;
            if (j->radius_search_knn)
                knn_step(j, px, s);
            else
                structure_step(j, px, s);
        }
    }
    return NULL;
}

/* Up to `passes` passes of k-nearest-neighbour steps (knn) or structure
 * steps over the pixels `search` marks, each with the map's levels built
 * for the radii of that pass; stops at `until` (0: no deadline). The
 * search marks are spent (every pixel settled) when it returns. */
static void radius_search(struct job *job, int threads, struct radius_search *search, bool knn, int passes,
                          double until)
{
    struct ref_photon_map *map = job->photon_map;
    job->radius_search = search;
    job->radius_search_knn = knn;
    job->radius_search_until = until;
    for (int pass = 0; pass < passes && map->count > 0; pass++) {
        if (until > 0.0 && log_now() >= until)
            break;
        size_t per_level[REF_PHOTON_MAP_LEVELS];
        if (!map_levels_for(job, search, per_level))
            break; /* every pixel settled */
        if (!ref_photon_map_build_levels(map, per_level, threads))
            break; /* out of memory: the radii stand */
        run_threads(job, threads, radius_search_thread);
    }
    job->radius_search = NULL;
}


/* The pilot: before the first photon pass, rounds of a quarter of its
 * photons each are traced only to learn where photons are useful and how
 * dense they fall (their light is thrown away), so that no iteration of
 * the estimate is spent on the first, unadapted pdf: where few photons
 * reach what the camera sees (a pool seen close up), that iteration's
 * noise would dominate the average. Rounds go on, each aimed by the last,
 * until a fifth of a round's photons are useful (at most PILOT_ROUNDS). */
#define PILOT_ROUNDS 4
#define PILOT_USEFUL 0.2
static long share_photons(struct job *job, const struct ref_scene *rs, const struct ref_emitter *emitters, long photons);
static long photons_traced(const struct job *j, const struct budget *b, int l);

static void pilot_photons(struct job *job, int threads, struct budget *budget, struct volume_photons *volume_chunks,
                          long photons, struct pixel *pixels, size_t npix)
{
    int light_count = job->rs->light_count;
    long pilot = photons / 4 > 1 ? photons / 4 : 1;
    share_photons(job, job->rs, job->emitters, pilot);
    /* The pilot counts photons within PILOT_RADIUS times each pixel's
     * first radius (the last round's, the best aimed). */
    for (size_t i = 0; i < npix; i++)
        pixels[i].radius *= PILOT_RADIUS;
    /* the pilot only aims: under a budget it may take a quarter of what is
     * left, so that the estimate's own photons get the rest */
    double pilot_deadline = budget->deadline;
    if (budget->deadline > 0)
        pilot_deadline = log_now() + 0.25 * fmax(budget->deadline - log_now(), 0.0);
    /* The counts that set the radii must come from photons aimed as the
     * estimate's will be: once the aim has settled (or the rounds are
     * used up), one more round counts on the final pdf and is not adapted
     * after. Counting on the round before the last adaptation undercounted
     * wherever that adaptation moved photons into view (flat water seen
     * close up: two photons where 40 were meant, and the radius pinned at
     * its largest). */
    bool settled = false;
    for (int round = 0; round <= PILOT_ROUNDS; round++) {
        for (size_t i = 0; i < npix; i++)
            pixels[i].m = 0;
        job->iteration = -1 - round;
        budget->photon_deadline = photon_deadline_before_gather(budget, pilot_deadline);
        double trace_start = log_now();
        run_threads(job, threads, photon_thread);
        double gather_start = log_now();
        gather_surface_photons(job, threads, NULL, true);
        gather_share_measured(budget, gather_start - trace_start, log_now() - gather_start);
        long long traced = 0;
        for (int l = 0; l < job->rs->light_count; l++)
            traced += photons_traced(job, budget, l);
        if (traced > 0)
            budget->seconds_per_traced = (gather_start - trace_start) / (double)traced;
        for (int c = 0; c < PHOTON_CHUNKS; c++)
            volume_chunks[c].count = 0;
        bool pilot_spent = atomic_load(&budget->photons_cut) != 0;
        atomic_store(&budget->photons_cut, 0);
        if (settled || pilot_spent || budget_spent(budget))
            break; /* the aims this round logged feed the first iteration's adaptation */
        settled = adapt_emission(job->aims, job->emitters, light_count) >= PILOT_USEFUL || round + 1 == PILOT_ROUNDS;
    }
    /* A first radius for the photon density (Issue 15, "a gather that
     * adapts", a k-nearest-neighbour choice): where the last round's m
     * photons fell within R_c = PILOT_RADIUS x R0, an iteration's photons
     * (4 times as many) put about GATHER_PHOTONS within
     * R_c sqrt(GATHER_PHOTONS / 4m). Kept within [RADIUS_MIN R0,
     * RADIUS_MAX R0] (R0: two pixel footprints): a bright caustic is
     * gathered tightly, a dim or even region widely (little noise). Then
     * counting passes correct the guess (knn_step) and the structure test
     * halves it where it would blur (structure_step). SPPM accepts any
     * starting radius and shrinks it from there. Each radius's bounds go to
     * those passes (no passes if out of memory: the first guesses stand). */
    struct radius_search *search = job->o->initial_radius > 0.0 ? NULL : malloc(npix * sizeof *search);
    for (size_t i = 0; i < npix; i++) {
        struct pixel *px = &pixels[i];
        if (search)
            search[i] = (struct radius_search){0.0, 0.0};
        if (job->o->initial_radius > 0.0) {
            px->radius /= PILOT_RADIUS; /* the user's radius (--radius) stands */
            px->m = 0;
            continue;
        }
        if (px->radius <= 0.0)
            continue;
        double r0 = px->radius / PILOT_RADIUS, r = RADIUS_MAX * r0;
        if (px->m > 0)
            r = PILOT_RADIUS * r0 * sqrt(GATHER_PHOTONS / (4.0 * (double)px->m));
        px->radius = fmin(fmax(r, RADIUS_MIN * r0), RADIUS_MAX * r0);
        if (search)
            search[i] = (struct radius_search){RADIUS_MIN * r0, RADIUS_MAX * r0};
        px->radius_floor = RADIUS_MIN * r0;
        px->m = 0;
    }
    if (search) {
        /* the searches take at most what is left of the pilot's share */
        radius_search(job, threads, search, true, KNN_PASSES, pilot_deadline);
        for (size_t i = 0; i < npix; i++)
            search[i].floor = pixels[i].radius_floor;
        radius_search(job, threads, search, false, STRUCTURE_HALVINGS, pilot_deadline);
    }
    free(search);
    share_photons(job, job->rs, job->emitters, photons);
    job->iteration = 0;
    memset(job->caustic_photons, 0, sizeof job->caustic_photons);
    memset(job->caustic_power, 0, sizeof job->caustic_power);
}

/* Shares the iteration's photons between the lights in proportion to the
 * power each sends towards its specular targets (every light that has
 * targets gets at least one). */
static long share_photons(struct job *job, const struct ref_scene *rs, const struct ref_emitter *emitters, long photons)
{
    double power = 0.0;
    for (int l = 0; l < rs->light_count; l++)
        power += emitters[l].power;
    long total = 0;
    for (int l = 0; l < rs->light_count; l++) {
        long n = 0;
        if (emitters[l].power > 0.0 && power > 0.0)
            n = (long)fmax(1.0, floor((double)photons * emitters[l].power / power + 0.5));
        job->first_of[l] = total;
        job->photons_of[l] = n;
        total += n;
    }
    job->photons_total = total;
    return total;
}

/* How many of light l's photons the finished chunks traced. */
static long photons_traced(const struct job *j, const struct budget *b, int l)
{
    long n = 0;
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        long begin, end;
        chunk_range(j, c, &begin, &end);
        end = b->chunk_reached[c];
        long lo = begin > j->first_of[l] ? begin : j->first_of[l];
        long hi = end < j->first_of[l] + j->photons_of[l] ? end : j->first_of[l] + j->photons_of[l];
        if (hi > lo)
            n += hi - lo;
    }
    return n;
}

/* Half the RMS difference of the even and odd iterations' means over the
 * RMS of the image, in grey (struct ref_stats.noise). */
static double noise_estimate(const struct pixel *pixels, size_t npix, int iterations, const double fraction[2])
{
    int n_even = (iterations + 1) / 2, n_odd = iterations / 2;
    if (n_odd == 0)
        return 0.0;
    double diff = 0.0, level = 0.0;
    for (size_t i = 0; i < npix; i++) {
        const struct pixel *px = &pixels[i];
        double a = (px->half[0].x + px->half[0].y + px->half[0].z) / (3.0 * n_even);
        double b = (px->half[1].x + px->half[1].y + px->half[1].z) / (3.0 * n_odd);
        if (fraction[0] > 0.0 && fraction[1] > 0.0) {
            a += (px->half_photons[0].x + px->half_photons[0].y + px->half_photons[0].z) / (3.0 * fraction[0]);
            b += (px->half_photons[1].x + px->half_photons[1].y + px->half_photons[1].z) / (3.0 * fraction[1]);
        }
        diff += (a - b) * (a - b);
        level += 0.25 * (a + b) * (a + b);
    }
    return level > 0.0 ? 0.5 * sqrt(diff / level) : 0.0;
}

/* What a render adds up over its iterations. */
struct sppm_totals {
    long long emitted, caustic_total;
    double caustic_power[3];
    double photon_passes;                  /* iterations whose photons were traced, a cut-short one counting as its fraction */
    double half_fraction[2];               /* the same, of the even and of the odd iterations (the noise estimate) */
    double gather_seconds, gather_photons; /* the last volume gather's cost */
    double volume_radius;
    double volume_radius_first; /* independent passes: pass 0's, the others' shrink from it */
    int independent_passes;     /* independent passes done (0: SPPM) */
    /* seconds spent in each stage so far (--report): the eye pass, the
     * pilot, photon tracing, the volume gather, the per-pixel update */
    double stage_eye, stage_pilot, stage_photons, stage_photon_gather, stage_gather, stage_update;
    double gather_kept;   /* the share of the first gather's volume photons kept for the budget (1: all) */
    int gather_samples;   /* the points per ray segment it used (0: VOLUME_SAMPLES) */
    int gather_rows_left; /* rows it could not reach at all */
};

/* Independent passes: pass p's gather area (surface: r^2; volume: r^3)
 * over pass 0's, prod_{i=1..p} (i + alpha) / (i + 1) (Knaus & Zwicker
 * 2011, eq. 15 with alpha = 2/3): fixed by p alone, so a pass needs no
 * other to know its radius. */
static double pass_shrink(int p)
{
    double f = 1.0;
    for (int i = 1; i <= p; i++)
        f *= (i + SPPM_ALPHA) / (i + 1.0);
    return f;
}

/* Keeps each volume photon with probability `keep` (a hash of its place
 * and the seed, so a run is repeatable for the photons it traced), its
 * flux divided by `keep`: an unbiased thinning (Russian roulette). */
static void volume_photons_thin(struct volume_photons *chunks, double keep, uint64_t seed)
{
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        size_t kept = 0;
        for (size_t k = 0; k < chunks[c].count; k++) {
            struct ref_rng rng = ref_rng_seed(seed, 7000003u + (uint64_t)c, (uint64_t)k);
            if (ref_rng_uniform(&rng) >= keep)
                continue;
            struct volume_photon vp = chunks[c].items[k];
            for (int q = 0; q < 3; q++)
                vp.flux[q] = (float)(vp.flux[q] / keep);
            chunks[c].items[kept++] = vp;
        }
        chunks[c].count = kept;
    }
}

/* One iteration's photons (Hachisuka & Jensen 2009): traced into the
 * visible points' grid (the first iteration after a pilot that aims the
 * lights), reduced in chunk order, the volume photons gathered, and each
 * visible point's radius and flux updated. */
static void photon_iteration(struct job *job, int it, int threads, size_t npix, struct sppm_totals *t)
{
    const struct ref_scene *rs = job->rs;
    struct budget *budget = job->budget;
    struct pixel *pixels = job->pixels;
    struct volume_photons *volume_chunks = job->volume_chunks;
    double stage_start = log_now();
    if (it == 0 && !job->pilot_done)
        pilot_photons(job, threads, budget, volume_chunks, job->o->photons, pixels, npix);
    t->stage_pilot += log_now() - stage_start;
    stage_start = log_now();
    /* With a medium, the volume gather after the photons must fit in the
     * budget too: reserve what the last one cost per photon for this
     * iteration's photons (the first iteration, with nothing to go by,
     * gives photons half of what is left). */
    /* the work after the photons (the per-pixel update, the estimates, the
     * file) gets 3% of the budget, so the whole stays inside it */
    budget->photon_deadline = budget->deadline > 0 ? budget->deadline - 0.03 * job->o->time_budget : 0.0;
    atomic_store(&budget->photons_cut, 0);
    if (budget->deadline > 0 && job->medium->present) {
        double now = log_now(), left = budget->deadline - now;
        double reserve = t->gather_photons > 0 ? t->gather_seconds * (double)job->photons_total / t->gather_photons
                                               : 0.5 * left;
        budget->photon_deadline = fmin(budget->photon_deadline, now + fmax(left - reserve, 0.1 * left));
    }
    if (!budget->gather_seen && budget->seconds_per_traced > 0.0 && budget->seconds_per_gathered > 0.0) {
        /* The first iteration's gather, from the pilot's rates: every
         * photon goes into the map, and each visible point takes about
         * GATHER_PHOTONS at twice the cost of the pilot's counting gather
         * (the flux and the structure sums). The pilot's own gathers, at
         * its small counting radius, cost far less than this one, and
         * photons traced by their share overran a 1 s budget by a third at
         * 512^2. */
        size_t points = 0;
        for (size_t i = 0; i < npix; i++)
            points += pixels[i].vp.valid && pixels[i].radius > 0.0;
        double gather = budget->seconds_per_mapped * (double)job->photons_total +
                        2.0 * budget->seconds_per_gathered * GATHER_PHOTONS * (double)points;
        double trace = budget->seconds_per_traced * (double)job->photons_total;
        budget->gather_share = fmin(gather / (gather + trace), 0.9);
    }
    budget->photon_deadline = photon_deadline_before_gather(budget, budget->photon_deadline);
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        long begin, end;
        chunk_range(job, c, &begin, &end);
        budget->chunk_reached[c] = begin; /* a chunk no thread reached traced nothing */
    }
    run_threads(job, threads, photon_thread);
    double gather_start = log_now();
    t->stage_photons += gather_start - stage_start;
    /* An iteration cut short by the budget traced a fraction f of its
     * photons: it counts as f of an iteration (the estimate divides the flux
     * by the photons traced, as a photon map does), rather than being scaled
     * up to a whole one, which would give its few photons a weight they
     * cannot carry. Each light's photons are scaled by f x (its photons) /
     * (those traced), 1 unless the cut left the lights unevenly traced;
     * without a budget every scale is 1 and f = 1. */
    long traced_of[SCENE_MAX_GPU_LIGHTS];
    long long traced = 0;
    for (int l = 0; l < rs->light_count; l++) {
        traced_of[l] = photons_traced(job, budget, l);
        traced += traced_of[l];
    }
    double pass_fraction = job->photons_total > 0 ? (double)traced / (double)job->photons_total : 0.0;
    double scale[SCENE_MAX_GPU_LIGHTS];
    for (int l = 0; l < rs->light_count; l++)
        scale[l] = traced_of[l] > 0 ? pass_fraction * (double)job->photons_of[l] / (double)traced_of[l] : 0.0;
    /* Each pixel sums its photons in the map's order: the same sums
     * whatever the thread count. */
    job->pass_fraction = pass_fraction;
    job->gather_until = budget->deadline > 0 ? budget->deadline - 0.03 * job->o->time_budget : 0.0;
    gather_surface_photons(job, threads, scale, false);
    gather_share_measured(budget, gather_start - stage_start, log_now() - gather_start);
    budget->gather_seen = true;
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        t->caustic_total += job->caustic_photons[c];
        /* (the power statistic is scaled for the whole pass, exact unless
         * several lights share a pass the budget cut short) */
        for (int k = 0; k < 3; k++)
            t->caustic_power[k] += job->caustic_power[c][k];
    }
    if (!job->independent) /* independent passes keep the pilot's aim: no pass may depend on another */
        adapt_emission(job->aims, job->emitters, rs->light_count);
    t->stage_photon_gather += log_now() - gather_start;
    t->emitted += traced;
    t->photon_passes += pass_fraction;
    t->half_fraction[it % 2] += pass_fraction;
    job->pass_fraction = pass_fraction;
    if (job->medium->present) {
        for (int c = 0; c < PHOTON_CHUNKS; c++)
            for (size_t k = 0; k < volume_chunks[c].count; k++) {
                struct volume_photon *vp = &volume_chunks[c].items[k];
                for (int q = 0; q < 3; q++)
                    vp->flux[q] = (float)(vp->flux[q] * scale[vp->light]);
            }
        /* Volume caustics: gather this iteration's volume photons with the
         * current radius, which shrinks as r^3 ~ i^(alpha - 1) (Knaus &
         * Zwicker 2011), so the average over iterations converges. */
        if (job->independent)
            t->volume_radius = t->volume_radius_first * cbrt(pass_shrink(job->iteration));
        struct volume_grid vgrid;
        volume_grid_build(&vgrid, volume_chunks, PHOTON_CHUNKS, t->volume_radius);
        job->volume_grid = &vgrid;
        double volume_start = log_now();
        if (it == 0 && budget->deadline > 0) {
            /* The first gather under a budget has no earlier one to go by:
             * every 16th row first, timed, and if the rest would pass the
             * deadline the volume photons are thinned for it (each kept
             * with probability f, its flux divided by f: the same
             * expectation, more noise), so the budget holds however the
             * machine is loaded. */
            job->volume_rows = VOLUME_ROWS_PROBE;
            job->volume_samples = VOLUME_PROBE_SAMPLES;
            run_threads(job, threads, volume_thread);
            job->volume_samples = VOLUME_SAMPLES;
            /* the rest at full samples: the cost is about linear in them */
            double rest = (log_now() - volume_start) * (VOLUME_PROBE_STRIDE - 1) * VOLUME_SAMPLES / VOLUME_PROBE_SAMPLES;
            double left = budget->deadline - log_now();
            if (rest > 0.9 * left) {
                /* fewer points along each ray first (the march is most of
                 * the cost, photons or not), then fewer photons */
                double fit = fmax(0.9 * left / rest, 0.0);
                int samples = (int)floor(VOLUME_SAMPLES * fit);
                job->volume_samples = samples < 1 ? 1 : samples;
                t->gather_samples = job->volume_samples;
                double still = rest * job->volume_samples / VOLUME_SAMPLES;
                if (still > 0.9 * left) {
                    double keep = fmax(0.9 * left / still, 1e-3);
                    volume_photons_thin(volume_chunks, keep, job->o->seed);
                    volume_grid_release(&vgrid);
                    volume_grid_build(&vgrid, volume_chunks, PHOTON_CHUNKS, t->volume_radius);
                    t->gather_kept = keep;
                }
            }
            job->volume_rows = VOLUME_ROWS_REST;
            atomic_store(&job->volume_rows_left, 0);
        }
        run_threads(job, threads, volume_thread);
        if (job->volume_rows == VOLUME_ROWS_REST)
            t->gather_rows_left = atomic_load(&job->volume_rows_left);
        job->volume_rows = VOLUME_ROWS_ALL;
        job->volume_samples = VOLUME_SAMPLES;
        t->gather_seconds = log_now() - volume_start;
        t->stage_gather += t->gather_seconds;
        t->gather_photons = (double)traced;
        volume_grid_release(&vgrid);
        for (int c = 0; c < PHOTON_CHUNKS; c++)
            volume_chunks[c].count = 0;
        if (!job->independent)
            t->volume_radius *= cbrt((it + 1 + SPPM_ALPHA) / (it + 2.0));
    }
    /* SPPM radius and flux update (Hachisuka & Jensen 2009, eq. 6-7). */
    stage_start = log_now();
    for (size_t i = 0; i < npix; i++) {
        struct pixel *px = &pixels[i];
        if (px->m > 0 && px->radius > 0 && pass_fraction > 0) {
            dvec3 e = dv_scale(px->phi, 1.0 / (pass_fraction * MATH_PI * px->radius * px->radius));
            px->half_photons[it % 2] = dv_add(px->half_photons[it % 2], dv_scale(e, pass_fraction));
            if (job->independent)
                px->pppm = dv_add(px->pppm, e);
        }
        /* (never on an iteration the budget cut short: the estimate would
         * start again from a fraction of an iteration's photons) */
        if (px->m > 0 && !job->independent && pass_fraction >= 1.0 &&
            structure_restart(px, t->photon_passes - pass_fraction)) {
            /* the estimate starts again with this iteration's photons
             * within the new radius */
            px->phi = px->phi_inner;
            px->m = px->m_inner;
        }
        if (px->m > 0 && !job->independent) {
            double n_new = px->n + SPPM_ALPHA * (double)px->m;
            double r_new = px->radius * sqrt(n_new / (px->n + (double)px->m));
            double shrink = (r_new * r_new) / (px->radius * px->radius);
            px->tau = dv_scale(dv_add(px->tau, px->phi), shrink);
            px->n = n_new;
            px->radius = r_new;
        }
        px->phi = px->phi_inner = dv(0, 0, 0);
        px->m = px->m_inner = 0;
    }
    t->stage_update += log_now() - stage_start;

}

/* After iteration `it`: the eye-path and volume estimates into the noise
 * halves, the report line and the progress line. */
static void iteration_report(const struct job *job, int it, size_t npix, double start, const struct sppm_totals *t)
{
    const struct ref_options *o = job->o;
    struct pixel *pixels = job->pixels;
    for (size_t i = 0; i < npix; i++) {
        struct pixel *px = &pixels[i];
        dvec3 d = dv_add(dv_sub(px->direct, px->direct_seen), dv_sub(px->volume, px->volume_seen));
        px->half[it % 2] = dv_add(px->half[it % 2], d);
        px->direct_seen = px->direct;
        px->volume_seen = px->volume;
    }
    bool tty = job->budget->tty;
    if (o->report) {
        double noise = noise_estimate(pixels, npix, it + 1, t->half_fraction);
        if (tty) {
            fputc('\n', stderr);
            job->budget->line_length = 0;
        }
        if (it == 0)
            fprintf(stderr, "reference: iteration 1: %lld photons, %.2f s (the noise estimate starts at 2)",
                    t->emitted, log_now() - start);
        else
            fprintf(stderr, "reference: iteration %d: %lld photons, %.2f s, noise ~%.3g%% (even vs odd iterations)",
                    it + 1, t->emitted, log_now() - start, 100.0 * noise);
        fprintf(stderr,
                "; so far: eye %.2f s, pilot %.2f s, photons %.2f s, photon gather %.2f s, volume gather %.2f s, "
                "update %.2f s\n",
                t->stage_eye, t->stage_pilot, t->stage_photons, t->stage_photon_gather, t->stage_gather,
                t->stage_update);
    }
    double elapsed = log_now() - start;
    /* Under a time budget the iteration count is open-ended: show the
     * clock against the budget instead of a count that will never be
     * reached. */
    if (tty && o->time_budget > 0)
        progress_line(job->budget, "reference: iteration %d, %lld photons, %.1f s of %.1f s", it + 1, t->emitted,
                      elapsed, o->time_budget);
    else if (tty)
        progress_line(job->budget, "reference: iteration %d/%d, %lld photons, %.0f s left", it + 1, o->iterations,
                      t->emitted, elapsed / (it + 1) * (o->iterations - it - 1));
    else if (job->budget->log_lines && !o->report &&
             (it == 0 || it + 1 == o->iterations || log_now() - job->budget->last_line >= 5.0)) {
        /* a farm's log: whole lines, the first and last iteration and one every 5 s between */
        job->budget->last_line = log_now();
        if (o->time_budget > 0)
            fprintf(stderr, "reference: iteration %d, %lld photons, %.1f s of %.1f s\n", it + 1, t->emitted, elapsed,
                    o->time_budget);
        else
            fprintf(stderr, "reference: iteration %d/%d, %lld photons, %.1f s\n", it + 1, o->iterations, t->emitted,
                    elapsed);
        fflush(stderr);
    }
}

/* The estimates into the image (and the caustic part into caustic_out):
 * direct and volume radiance averaged over their samples, plus the photon
 * estimate L = tau / (passes pi R^2) (each pass carries the lights' power
 * between its photons, flux per photon = power / photons). */
static void write_estimates(const struct pixel *pixels, size_t npix, const struct sppm_totals *t, struct image *out,
                            struct image *caustic_out)
{
    double passes = t->photon_passes > 0 ? t->photon_passes : 1;
    for (size_t i = 0; i < npix; i++) {
        const struct pixel *px = &pixels[i];
        dvec3 l = px->samples > 0 ? dv_scale(px->direct, 1.0 / px->samples) : dv(0, 0, 0);
        /* (volume_samples sums the gathers' pass fractions) */
        dvec3 volume = px->volume_samples > 0 ? dv_scale(px->volume, 1.0 / px->volume_samples) : dv(0, 0, 0);
        l = dv_add(l, volume);
        dvec3 lc = dv(0, 0, 0);
        if (t->independent_passes > 0)
            lc = dv_scale(px->pppm, 1.0 / t->independent_passes); /* the passes' mean */
        else if (t->emitted > 0 && px->radius > 0 && px->n > 0 && passes - px->passes_before - px->passes_missed > 0)
            lc = dv_scale(px->tau, 1.0 / ((passes - px->passes_before - px->passes_missed) * MATH_PI * px->radius *
                                          px->radius));
        l = dv_add(l, lc);
        if (caustic_out) {
            /* the caustic part: surface caustics and volume caustics */
            float *cd = caustic_out->rgba + i * 4;
            cd[0] = (float)(lc.x + volume.x);
            cd[1] = (float)(lc.y + volume.y);
            cd[2] = (float)(lc.z + volume.z);
            cd[3] = 1.0f;
        }
        float *dst = out->rgba + i * 4;
        dst[0] = (float)l.x;
        dst[1] = (float)l.y;
        dst[2] = (float)l.z;
        dst[3] = 1.0f;
    }
}

/* The render's buffers: per pixel, per photon chunk, the budget. */
struct sppm_buffers {
    struct pixel *pixels;
    struct ref_surface_photons *chunks;
    struct volume_photons *volume_chunks;
    struct aim_log *aims;
    struct budget *budget;
};

static void sppm_buffers_release(struct sppm_buffers *b)
{
    for (int c = 0; c < PHOTON_CHUNKS; c++) {
        if (b->chunks)
            ref_surface_photons_release(&b->chunks[c]);
        if (b->volume_chunks)
            free(b->volume_chunks[c].items);
        if (b->aims)
            free(b->aims[c].items);
    }
    free(b->aims);
    free(b->budget);
    free(b->volume_chunks);
    free(b->chunks);
    free(b->pixels);
}

static bool sppm_buffers_create(struct sppm_buffers *b, size_t npix)
{
    memset(b, 0, sizeof *b);
    b->pixels = calloc(npix, sizeof *b->pixels);
    b->chunks = calloc(PHOTON_CHUNKS, sizeof *b->chunks);
    b->volume_chunks = calloc(PHOTON_CHUNKS, sizeof *b->volume_chunks);
    b->aims = calloc(PHOTON_CHUNKS, sizeof *b->aims);
    b->budget = calloc(1, sizeof *b->budget);
    return b->pixels && b->chunks && b->volume_chunks && b->aims && b->budget;
}

bool ref_render_parts(struct renderer *r, struct scene *scene, const struct ref_options *o, struct image *out,
                      struct image *caustic_out, struct ref_stats *stats, struct error *err)
{
    if (o->aov != REF_AOV_NONE) {
        if (caustic_out)
            memset(caustic_out, 0, sizeof *caustic_out);
        if (stats)
            memset(stats, 0, sizeof *stats);
        return ref_render_aov(r, scene, o, out, err);
    }
    double start = log_now();
    struct ref_scene rs;
    if (!ref_scene_build(&rs, r, scene, err))
        return false;
    struct ref_emitter emitters[SCENE_MAX_GPU_LIGHTS];
    memset(emitters, 0, sizeof emitters);
    bool caustics = rs.has_specular_bounds && rs.light_count > 0 && o->photons > 0;
    for (int l = 0; caustics && l < rs.light_count; l++)
        if (!ref_emitter_build(&emitters[l], &rs, &rs.lights[l], err)) {
            for (int k = 0; k < l; k++)
                ref_emitter_release(&emitters[k]);
            ref_scene_release(&rs);
            return false;
        }
    size_t npix = (size_t)o->width * (size_t)o->height;
    struct sppm_buffers buf;
    if (!sppm_buffers_create(&buf, npix) || !image_create(out, o->width, o->height, err) ||
        (caustic_out && !image_create(caustic_out, o->width, o->height, err))) {
        image_destroy(out);
        sppm_buffers_release(&buf);
        for (int l = 0; l < rs.light_count; l++)
            ref_emitter_release(&emitters[l]);
        ref_scene_release(&rs);
        return err && err->message[0] ? false : error_set(err, "reference: out of memory");
    }
    double fov = (double)scene->camera.fov * MATH_PI / 180.0;
    double pixel_angle = 2.0 * tan(0.5 * fov) / o->height;
    double pixel_size = (double)scene->camera.ortho_width / (double)o->width;
    int threads = o->threads > 0 ? o->threads : cpus_available();
    if (threads < 1)
        threads = 1;
    struct ref_medium medium;
    ref_medium_init(&medium, scene->medium);
    struct sppm_totals totals = {.gather_kept = 1.0};
    if (medium.present) {
        dvec3 ext = dv_sub(medium.hi, medium.lo);
        totals.volume_radius = o->volume_radius > 0 ? o->volume_radius : 0.01 * sqrt(dv_dot(ext, ext));
    }
    struct media camera_media;
    dvec3 cam_origin, cam_dir;
    ref_scene_camera_ray(&rs, o->width * 0.5, o->height * 0.5, o->width, o->height, &cam_origin, &cam_dir);
    media_at(&rs, cam_origin, &camera_media);

    struct budget *budget = buf.budget;
    atomic_init(&budget->cut, 0);
    atomic_init(&budget->photons_cut, 0);
    budget->start = start;
    budget->gather_share = 0.25;
    budget->deadline = o->time_budget > 0 ? start + o->time_budget : 0.0;
    budget->tty = o->progress && isatty(STDERR_FILENO) && !log_quiet();
    budget->log_lines = o->progress && !budget->tty && !log_quiet();
    struct ref_photon_map photon_map = {0};
    struct job job = {.rs = &rs, .o = o, .pixels = buf.pixels, .camera_media = &camera_media, .medium = &medium,
                      .volume_chunks = buf.volume_chunks, .pixel_angle = pixel_angle, .pixel_size = pixel_size,
                      .chunks = buf.chunks, .budget = budget, .emitters = emitters, .aims = buf.aims,
                      .photon_map = &photon_map};
    if (caustics && share_photons(&job, &rs, emitters, o->photons) == 0)
        caustics = false;
    for (int l = 0; l < rs.light_count; l++) {
        struct ref_rng shift_rng = ref_rng_seed(o->seed, 11u, (uint64_t)l);
        for (int k = 0; k < 3; k++)
            job.emit_shift[l][k] = ref_rng_uniform(&shift_rng);
    }
    totals.volume_radius_first = totals.volume_radius;
    job.independent = o->shard_count > 0;
    if (job.independent) {
        /* The pilot, the same in every shard (it depends on the seed
         * alone): pass 0's eye paths aim the lights and give each pixel its
         * first radius; what they gathered is not kept, since a shard
         * without pass 0 renders none of it. */
        double eye_start = log_now();
        job.iteration = 0;
        run_threads(&job, threads, camera_thread);
        totals.stage_eye += log_now() - eye_start;
        if (caustics) {
            double pilot_start = log_now();
            pilot_photons(&job, threads, budget, buf.volume_chunks, o->photons, buf.pixels, npix);
            totals.stage_pilot += log_now() - pilot_start;
            job.pilot_done = true;
        }
        for (size_t i = 0; i < npix; i++) {
            struct pixel *px = &buf.pixels[i];
            double r1 = px->radius;
            memset(px, 0, sizeof *px);
            px->r1 = r1;
        }
    }
    int it = 0;
    int pass = job.independent ? o->shard_index : 0, pass_stride = job.independent ? o->shard_count : 1;
    for (; pass < o->iterations; it++, pass += pass_stride) {
        job.iteration = job.independent ? pass : it;
        budget->iteration = it;
        memset(job.caustic_photons, 0, sizeof job.caustic_photons);
        memset(job.caustic_power, 0, sizeof job.caustic_power);
        /* independent passes: pass p's radius from its index alone */
        double shrink = job.independent ? sqrt(pass_shrink(pass)) : 1.0;
        for (size_t i = 0; job.independent && i < npix; i++)
            buf.pixels[i].radius = buf.pixels[i].r1 * shrink;
        double eye_start = log_now();
        run_threads(&job, threads, camera_thread);
        totals.stage_eye += log_now() - eye_start;
        if (atomic_load(&budget->cut))
            break; /* the eye pass ran out of time: no photons for a half-traced set of visible points */
        for (size_t i = 0; job.independent && i < npix; i++)
            if (buf.pixels[i].r1 <= 0.0) /* no visible point in pass 0: this pass's own first radius */
                buf.pixels[i].radius *= shrink;
        if (caustics)
            photon_iteration(&job, it, threads, npix, &totals);
        if (job.independent)
            totals.independent_passes++;
        iteration_report(&job, it, npix, start, &totals);
        /* (photons stopped early only to leave the gather its time do not
         * end the render: the next iteration may still fit) */
        double elapsed = log_now() - start;
        if (atomic_load(&budget->cut) || (o->time_budget > 0 && elapsed >= o->time_budget)) {
            it++;
            break;
        }
    }
    if (budget->tty)
        fputc('\n', stderr);
    /* A budget that did not buy one whole iteration says so: the image is
     * an unbiased estimate, but a noisier one than a single iteration at
     * the scene's settings, which a user of --time-budget would not guess. */
    if (o->time_budget > 0) {
        char parts[5][96];
        int n = 0;
        double elapsed = log_now() - start;
        if (totals.stage_eye > o->time_budget)
            snprintf(parts[n++], sizeof parts[0], "the first eye pass alone took %.1f s", totals.stage_eye);
        if (caustics && totals.photon_passes < 0.999)
            snprintf(parts[n++], sizeof parts[0], "%.2g%% of one iteration's photons",
                     100.0 * totals.photon_passes);
        if (totals.gather_samples > 0)
            snprintf(parts[n++], sizeof parts[0], "the medium's gather at %d of %d points a ray",
                     totals.gather_samples, VOLUME_SAMPLES);
        if (totals.gather_kept < 1.0)
            snprintf(parts[n++], sizeof parts[0], "with %.2g%% of its photons", 100.0 * totals.gather_kept);
        if (totals.gather_rows_left > 0)
            snprintf(parts[n++], sizeof parts[0], "%d rows left without the medium's light", totals.gather_rows_left);
        char list[512] = "";
        for (int i = 0; i < n; i++)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", parts[i]);
        if (n > 0)
            log_warn("reference: --time-budget %g s bought less than one full iteration (%s; %.2f s in all): the image "
                     "is %s than one iteration would make it; raise --time-budget",
                     o->time_budget, list, elapsed, totals.gather_rows_left > 0 ? "incomplete, and noisier" : "noisier");
    }
    write_estimates(buf.pixels, npix, &totals, out, caustic_out);
    if (stats) {
        double passes = totals.photon_passes > 0 ? totals.photon_passes : 1;
        stats->noise = noise_estimate(buf.pixels, npix, it > 0 ? it : 1, totals.half_fraction);
        stats->iterations = it > 0 ? it : 1;
        stats->photons = totals.emitted;
        stats->caustic_photons = totals.caustic_total;
        stats->seconds = log_now() - start;
        stats->threads = threads < 64 ? threads : 64; /* run_threads' cap */
        stats->passes = totals.independent_passes;
        for (int k = 0; k < 3; k++)
            stats->caustic_power[k] = totals.caustic_power[k] / passes;
    }
    ref_photon_map_release(&photon_map);
    sppm_buffers_release(&buf);
    for (int l = 0; l < rs.light_count; l++)
        ref_emitter_release(&emitters[l]);
    ref_scene_release(&rs);
    return true;
}
