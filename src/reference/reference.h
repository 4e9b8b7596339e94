/* The ground truth: an exact CPU renderer of the same scene snapshot the
 * GPU draws (geometry read back after morphs and deformers), built on
 * Embree. Estimator: see docs/REFERENCE.md. */
#ifndef CAUSTICA_REFERENCE_H
#define CAUSTICA_REFERENCE_H

#include <stdbool.h>
#include <stdint.h>

#include "core/error.h"
#include "io/image.h"

struct renderer;
struct scene;

/* What `reference` computes: the image, or a debug output traced exactly
 * through the same two interfaces the refraction pass models
 * (src/reference/ref_aov.c): `tir` (r = total internal reflections met, 0
 * to 2; a = 1 on a refractor or mirror) or `exit` (rgb = the direction the
 * path leaves in), to hold the pass's outputs of the same names against. */
enum ref_aov { REF_AOV_NONE, REF_AOV_TIR, REF_AOV_EXIT };

struct ref_options {
    int width, height;
    long photons;        /* photons emitted per iteration */
    int iterations;      /* SPPM iterations (one camera sample per pixel each) */
    double time_budget;  /* seconds; > 0 stops early when spent (and may run past `iterations`? no) */
    uint64_t seed;
    double initial_radius; /* 0: from the scene size */
    double volume_radius;  /* initial volume gather radius; 0: 1% of the medium box diagonal */
    bool progress;       /* print progress with time left on stderr */
    bool report;         /* print the noise estimate after every iteration on stderr */
    int threads;         /* 0: the CPUs this process may use (core/cpus.h) */
    enum ref_aov aov;    /* REF_AOV_NONE: the image */
    bool antialias;      /* each iteration's camera ray through a random point of its pixel (the pixel's
                          * mean, SPPM's stochastic visible points), not its centre (what the
                          * rasterizer samples) */
    /* Independent passes (probabilistic progressive photon mapping, Knaus
     * & Zwicker 2011) when shard_count > 0: pass p (0 <= p < iterations)
     * has its own eye paths, photons and a gather radius fixed by p alone,
     * so passes share no state and any set of them can be rendered apart
     * and averaged (caustica merge). This run renders the passes p with
     * p % shard_count == shard_index. 0: SPPM (Hachisuka & Jensen 2009). */
    int shard_index, shard_count;
    /* Trace the triangles of spheres the script made (c.mesh.sphere), as
     * the GPU draws them, instead of the spheres (ref_scene.c) */
    bool tessellated;
};

struct ref_stats {
    int iterations;        /* iterations done */
    long long photons;     /* photons emitted in all */
    long long caustic_photons; /* photons that reached a diffuse surface after a specular one */
    double caustic_power[3]; /* W reaching diffuse surfaces by light-specular+-diffuse paths */
    double seconds;
    int threads;           /* worker threads it ran on */
    int passes;            /* independent passes rendered (shard_count > 0), else 0 */
    /* Relative noise of the image: half the RMS difference of the means of
     * the even and the odd iterations' own estimates, over the RMS of the
     * image (the standard error of the mean; it measures variance, not the
     * kernel's bias, which shrinks with the radius). 0 with one iteration. */
    double noise;
};

void ref_options_default(struct ref_options *o);
/* Renders the scene as set up by renderer_begin_frame for this frame (the
 * deformed vertex buffers are read back from the GPU), also returning the
 * caustic part of the image on its own (light -> specular+ -> diffuse, and
 * light -> specular+ -> medium; `caustic` may be NULL). */
/* The debug output `aov` of the frame (ref_aov.c). */
bool ref_render_aov(struct renderer *r, struct scene *scene, const struct ref_options *options, struct image *out,
                    struct error *err);
bool ref_render_parts(struct renderer *r, struct scene *scene, const struct ref_options *options, struct image *out,
                      struct image *caustic, struct ref_stats *stats, struct error *err);

#endif
