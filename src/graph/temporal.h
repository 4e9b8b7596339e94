/* Temporal accumulation of a caustics pass's screen-space irradiance
 * (issue 32): a pass that samples the light (a photon grid) moves its
 * samples by a sub-texel jitter every frame (temporal_jitter) and blends
 * each frame's irradiance into a history (temporal_accumulate), as TAA does
 * for a frame's pixels (Karis, "High-quality temporal supersampling",
 * SIGGRAPH 2014 course; Yang et al., "A survey of temporal antialiasing
 * techniques", 2020):
 *
 * - the history is reprojected to this frame's pixels by their depth (the
 *   camera may move) and dropped where the surface it saw is not the one
 *   seen now (a disocclusion: more than 1% of the distance apart);
 * - while the light and the geometry are unchanged (the pass's key without
 *   the camera, and no mesh animates: pass_frame_reusable), a pixel averages its last `frames` frames with equal
 *   weights: a still scene converges to the mean over the jitter's 16
 *   offsets, the light of a photon grid 4 x 4 times as dense;
 * - when they changed, the history is clipped to the mean +- 1.5 standard
 *   deviations of this frame's 3 x 3 neighbourhood (variance clipping,
 *   Salvi 2016) before the blend, so a caustic that moved far leaves no
 *   ghost, and a pixel averages at most its last frames / 2 (at least 2):
 *   the crawl of a moving light is averaged over fewer frames;
 * - where the pass says how its light moved on screen (photon_caustics:
 *   the same light-view texel's photon last frame and now, motion.comp),
 *   the history is read from where the light was, by a Catmull-Rom
 *   resampling (a caustic that moves a third of a pixel a frame otherwise
 *   lags, or blurs under a bilinear fetch); where it does not (the thin
 *   spread light), the caustic lags a little (docs/TEMPORAL.md has the
 *   measurements).
 *
 * One owner per history (the pass's state); temporal_release frees it. */
#ifndef CAUSTICA_TEMPORAL_H
#define CAUSTICA_TEMPORAL_H

#include <stdbool.h>
#include <stdint.h>

#include "core/error.h"
#include "core/vecmath.h"
#include "gl/gl_texture.h"

struct renderer;
struct frame;

struct temporal_history {
    struct gl_texture color[2]; /* rgb: the accumulated irradiance; a: the frames it holds */
    struct gl_texture depth[2]; /* r32f: the window depth each pixel was seen at */
    struct gl_texture current;  /* this frame's irradiance, copied (read while the output is written) */
    int newest;                 /* which of color/depth holds the latest history */
    int width, height;
    bool valid;
    long sequence;   /* frames rendered with accumulation: the jitter's index */
    mat4 view_proj, inv_view_proj; /* the camera the history was seen with */
    int still;       /* frames the light and the geometry have stood still */
};

/* The sub-texel offset of this frame's sample grid, in texels within
 * (-0.5, 0.5): a 4 x 4 stratified pattern in ordered-dither order, so any
 * 4 consecutive frames cover the texel's quarters and 16 all its
 * sixteenths. */
void temporal_jitter(const struct temporal_history *h, float *dx, float *dy);

/* Blends `irradiance` (this frame's, RGBA32F, alpha kept) with the history
 * and writes the result back into it. `depth` holds the window depth of the
 * surfaces the irradiance lies on (1 where none); `still` says the light
 * and the geometry are as they were the last frame (the camera may have
 * moved); `motion` (may be NULL) where the light moved on screen since the
 * last frame, an R32I array of 3 layers (x and y in 1/64 pixels and the
 * samples that said so, summed per pixel: photon_caustics/motion.comp):
 * while things move the history is taken from where the light was;
 * `frames` the most frames averaged (>= 1; 1 keeps no history).
 * Fills `*held` (may be NULL) with how many frames the history held before
 * this one (0 after a reset). */
bool temporal_accumulate(struct temporal_history *h, struct renderer *r, const struct frame *frame,
                         const struct gl_texture *irradiance, const struct gl_texture *depth,
                         const struct gl_texture *motion, bool still, int frames, int *held, struct error *err);

/* Forgets the history (the next frame starts afresh). */
void temporal_reset(struct temporal_history *h);
void temporal_release(struct temporal_history *h);

#endif
