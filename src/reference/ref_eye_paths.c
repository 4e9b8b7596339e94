/* The reference's eye paths (ref_sppm.c runs them): traced exactly through
 * specular chains (Fresnel, Snell, total internal reflection, Beer-Lambert)
 * and the media, with direct light, single scattering and the glossy lobes
 * at the first diffuse vertex, to a visible point per pixel and iteration
 * where the photons are gathered. */
#define _POSIX_C_SOURCE 200809L
#include "reference/ref_footprint.h"
#include "reference/ref_sppm_internal.h"

/* The material's reflectance (core/optics.h): Fresnel's, or for an ideal
 * interface (fresnel = false) 0, and 1 where refraction is impossible (the
 * shaders' fresnel_of). */
static double fresnel_of(const struct material *m, double cos_i, double eta)
{
    return optics_fresnel_of(cos_i, eta, m->ideal);
}


dvec3 sppm_medium_sigma(const struct ref_scene *rs, const struct media *m)
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
bool sppm_scene_medium_here(const struct ref_scene *rs, const struct media *m)
{
    return m->count == 0 || rs->objects[m->objects[m->count - 1]].material.kind == MATERIAL_WATER;
}

/* Beer-Lambert over distance t in the current medium. */
dvec3 sppm_attenuate(dvec3 beta, dvec3 sigma, double t)
{
    return dv(beta.x * exp(-sigma.x * t), beta.y * exp(-sigma.y * t), beta.z * exp(-sigma.z * t));
}

/* Which dielectrics contain point p: walk a ray upwards and note, for each
 * object, whether its first crossing leaves it. */
void sppm_media_at(const struct ref_scene *rs, dvec3 p, struct media *m)
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
bool sppm_hit_is_diffuse(const struct ref_scene *rs, const struct ref_hit *h, struct ref_rng *rng)
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
bool sppm_specular_step(const struct ref_scene *rs, const struct ref_hit *h, struct media *media, dvec3 *dir,
                        dvec3 *origin, dvec3 *beta, struct ref_rng *rng, struct specular_branch *branch)
{
    if (branch)
        branch->taken = false;
    const struct ref_object *o = &rs->objects[h->object];
    const struct material *m = &o->material;
    double offset = ref_scene_offset(rs, h);
    dvec3 ng = h->geometric_normal, n = h->shading_normal;
    if (!m->thin) { /* a normal map on glass or a mirror (the pane maps its own below) */
        dvec3 mapped = ref_interface_normal(o, h, n);
        if (dv_dot(mapped, h->geometric_normal) > 0.0) /* (one turned past the triangle: the triangle's side) */
            n = mapped;
    }
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
        *origin = dv_add(h->position, dv_scale(ngo, offset));
        return true;
    }
    if (m->thin) {
        /* Thin-walled glass (glTF's glass without a volume): reflect F
         * about the shading normal, else go on undeviated, x the tint
         * (common/thin_glass.frag). No random number where F is 0 (an
         * ideal pane: the eye path stays fixed). */
        dvec3 normal, tint;
        double f = ref_thin_surface(o, h, *dir, nn, &normal, &tint);
        if (f > 0.0 && (f >= 1.0 || ref_rng_uniform(rng) < f)) {
            *dir = dv_normalize_or(ref_reflect(*dir, normal), ref_reflect(*dir, ngo));
            *origin = dv_add(h->position, dv_scale(ngo, offset));
            return true;
        }
        *beta = dv_mul(*beta, tint);
        *origin = dv_sub(h->position, dv_scale(ngo, offset));
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
    /* A photon at a smooth interface takes the refracted way always, with
     * 1 - f of its flux, and the reflected way as a branch with
     * probability f, with all of it: the same expectation as one way by
     * Fresnel's odds, but the refracted photons, most of a caustic, carry
     * no coin. That coin thinned a stratified set of photons at random
     * (per pixel, a variance of F (1 - F) per photon where a jittered
     * grid's is near 0): one iteration's noise at a fixed radius beyond the
     * ball lens's focus 2.65% -> 1.77%, as low as an ideal interface's
     * without any coin, 1.79% (issue 53). Splitting both ways with weights f and 1 - f
     * did as well on the refracted photons but filled the maps with faint
     * reflected ones, which made far emission cells look useful. */
    bool split = branch && alpha == 0.0 && can_refract && f > 0.0 && f < 1.0;
    if (split) {
        branch->taken = ref_rng_uniform(rng) < f;
        if (branch->taken) {
            branch->dir = dv_normalize_or(ref_reflect(*dir, mn), ref_reflect(*dir, ngo));
            branch->origin = dv_add(h->position, dv_scale(ngo, offset));
            branch->beta = *beta;
            branch->media = *media;
        }
        *beta = dv_scale(*beta, 1.0 - f);
    }
    bool reflected = !can_refract || (!split && ref_rng_uniform(rng) < f);
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
        *origin = dv_add(h->position, dv_scale(ngo, offset));
    } else {
        *dir = out;
        *origin = dv_sub(h->position, dv_scale(ngo, offset));
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
static dvec3 glossy_radiance(const struct job *j, struct ref_rng *rng, dvec3 origin, dvec3 dir, struct media media)
{
    const struct ref_scene *rs = j->rs;
    const struct ref_medium *rm = j->medium;
    dvec3 beta = dv(1, 1, 1);
    int depth;
    for (depth = 0; depth < MAX_DEPTH; depth++) {
        struct ref_hit h;
        if (!ref_scene_intersect(rs, origin, dir, INFINITY, &h))
            return dv_mul(beta, ref_scene_environment(rs, dir));
        beta = sppm_attenuate(beta, sppm_medium_sigma(rs, &media), h.t);
        if (sppm_hit_is_diffuse(rs, &h, rng)) {
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
        sppm_specular_step(rs, &h, &media, &dir, &origin, &beta, rng, NULL);
        if (dv_dot(beta, beta) < 1e-30)
            break;
    }
    if (depth == MAX_DEPTH)
        atomic_fetch_add(&j->budget->paths_cut[1], 1);
    return dv(0, 0, 0);
}

/* One eye path of pixel (x, y): its visible point, its segments through
 * the medium and its first radius into the pixel; returns the radiance it
 * gathered on the way (the lights seen directly, single scattering, the
 * environment, emission). */
/* surface_light_gltf (common/surface_light.glsl) by its C twins: the
 * lights through the BRDF, the ambient sky by the BRDF's directional
 * albedo and the occlusion, the specular lobes reflecting the environment
 * and the scene (GLOSSY_SAMPLES directions drawn from them per iteration,
 * docs/GLTF.md), and the emission: the radiance the eye path sees there.
 * *diffuse: the diffuse lobe's albedo, by which photons (the caustics) are
 * weighed, as the GPU weighs caustic irradiance. */
static dvec3 gltf_surface_radiance(struct job *j, struct ref_rng *rng, const struct ref_hit *h, dvec3 dir, dvec3 n,
                                   const struct ref_surface *surface, struct media media, dvec3 *diffuse)
{
    const struct ref_scene *rs = j->rs;
    dvec3 v = dv_scale(dir, -1.0);
    double nn[3] = {n.x, n.y, n.z}, vv[3] = {v.x, v.y, v.z}, diff[3];
    dvec3 lit = direct_light(rs, j->medium, rng, h->position, n, &surface->brdf, v);
    brdf_diffuse_albedo(nn, vv, &surface->brdf, diff);
    dvec3 sky = dv_mul(rs->ambient, dv(diff[0], diff[1], diff[2]));
    for (int s = 0; s < GLOSSY_SAMPLES; s++) {
        double l[3], pdf, fs[3];
        if (!brdf_sample_specular(nn, vv, &surface->brdf, ref_rng_uniform(rng), ref_rng_uniform(rng),
                                  ref_rng_uniform(rng), l, &pdf))
            continue;
        dvec3 ld = dv(l[0], l[1], l[2]);
        /* (a mapped normal may send l under the triangle: it meets the surface itself, nothing) */
        double side = dv_dot(h->geometric_normal, dir) < 0 ? 1.0 : -1.0;
        if (!(side * dv_dot(ld, h->geometric_normal) > 0.0))
            continue;
        brdf_gltf_specular_cos(nn, vv, l, &surface->brdf, fs);
        dvec3 w = dv(fs[0] / (pdf * GLOSSY_SAMPLES), fs[1] / (pdf * GLOSSY_SAMPLES), fs[2] / (pdf * GLOSSY_SAMPLES));
        dvec3 from = dv_add(h->position, dv_scale(h->geometric_normal, side * rs->epsilon));
        sky = dv_add(sky, dv_mul(w, glossy_radiance(j, rng, from, ld, media)));
    }
    sky = dv_scale(sky, surface->occlusion);
    *diffuse = dv(diff[0], diff[1], diff[2]);
    return dv_add(dv_add(lit, sky), surface->emission);
}

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
    /* The pixel's footprint, for the textures' mip levels, where the
     * pixel is point-sampled as the rasterizer samples it; spread over the
     * pixel, the iterations filter the textures themselves. */
    struct ref_footprint footprint = {.valid = false};
    if (!j->o->antialias)
        ref_footprint_camera(rs, x + sx, y + sy, j->o->width, j->o->height, &footprint);
    struct media media = *j->camera_media;
    /* The ray starts on the near plane (what the rasterizer clips), but the
     * camera sits at the eye: the medium around it absorbs from there. */
    double from_eye = rs->ortho ? rs->znear /* from the eye's plane */
                                : sqrt(dv_dot(dv_sub(origin, rs->eye), dv_sub(origin, rs->eye)));
    dvec3 beta = sppm_attenuate(dv(1, 1, 1), sppm_medium_sigma(rs, &media), from_eye);
    px->vp.valid = false;
    struct pixel_segments *kept = j->segments ? &j->segments[(size_t)y * (size_t)j->o->width + (size_t)x] : NULL;
    if (kept)
        kept->count = 0;
    const struct ref_medium *rm = j->medium;
    int depth;
    for (depth = 0; depth < MAX_DEPTH; depth++) {
        struct ref_hit h;
        bool hit = eye_intersect(rs, origin, dir, &h);
        double t0, t1;
        if (sppm_scene_medium_here(rs, &media) && ref_medium_clip(rm, origin, dir, hit ? h.t : INFINITY, &t0, &t1)) {
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
            if (kept && kept->count < MAX_SEGMENTS) {
                int k = kept->count++;
                kept->segments[k].origin = origin;
                kept->segments[k].dir = dir;
                kept->segments[k].beta = beta;
                kept->segments[k].t0 = t0;
                kept->segments[k].t1 = t1;
            }
            beta = dv_mul(beta, ref_medium_transmittance(rm, origin, dir, hit ? h.t : INFINITY, &rng));
        }
        if (!hit) {
            seen = dv_add(seen, dv_mul(beta, ref_scene_environment(rs, dir)));
            break;
        }
        beta = sppm_attenuate(beta, sppm_medium_sigma(rs, &media), h.t);
        ref_footprint_hit(rs, &footprint, &h);
        if (sppm_hit_is_diffuse(rs, &h, &rng)) {
            dvec3 n = dv_dot(h.shading_normal, dir) < 0 ? h.shading_normal : dv_scale(h.shading_normal, -1.0);
            struct ref_surface surface;
            ref_surface_diffuse(rs, &h, n, &surface);
            n = surface.normal;
            dvec3 albedo = surface.albedo;
            dvec3 f;
            if (surface.pbr) {
                dvec3 diff;
                seen = dv_add(seen, dv_mul(beta, gltf_surface_radiance(j, &rng, &h, dir, n, &surface, media, &diff)));
                f = dv_scale(dv_mul(beta, diff), 1.0 / MATH_PI);
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
                double width = rs->ortho ? j->pixel_size : sqrt(dv_dot(eye_to, eye_to)) * j->pixel_angle;
                px->radius = j->o->initial_radius > 0 ? j->o->initial_radius : fmax(RADIUS_PIXELS * width, 1e-6);
            }
            px->vp.valid = true;
            px->vp.position = h.position;
            px->vp.normal = n;
            px->vp.weight = f;
            break;
        }
        dvec3 in = dir;
        sppm_specular_step(rs, &h, &media, &dir, &origin, &beta, &rng, NULL);
        ref_footprint_bounce(rs, &footprint, &h, in, dir);
        if (dv_dot(beta, beta) < 1e-30)
            break;
    }
    if (depth == MAX_DEPTH)
        atomic_fetch_add(&j->budget->paths_cut[0], 1);
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
void *sppm_camera_thread(void *arg)
{
    struct job *j = arg;
    for (int y = j->thread; y < j->o->height; y += j->threads) {
        if (j->iteration > 0 && sppm_budget_spent(j->budget))
            return NULL;
        for (int x = 0; x < j->o->width; x++)
            trace_eye(j, x, y);
    }
    return NULL;
}
