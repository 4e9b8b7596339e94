/* Error between two images: what `caustica compare`, `c.image.compare` and
 * the regression tests report. All on linear RGB values. */
#ifndef CAUSTICA_IMAGE_METRICS_H
#define CAUSTICA_IMAGE_METRICS_H

#include <stdbool.h>

#include "core/error.h"
#include "io/image.h"

struct image_metrics {
    double rmse;     /* root mean square difference over RGB */
    double rel_rmse; /* rmse divided by the RMS of the reference (b) */
    double log_rmse; /* the robust one: RMS difference of log(1 + value), so that one caustic
                      * spike does not swamp the rest (rel_rmse 3.47 from a single hot pixel) */
    double psnr;     /* dB, peak 1.0; +inf written as 999 for identical images */
    double ssim;     /* mean SSIM of luminance, 8x8 windows */
    double max;      /* largest absolute channel difference */
    long nan;        /* non-finite values in a or b */
    long pixels;     /* pixels compared (inside the mask) */
};

/* `mask` (may be NULL) restricts to pixels whose mask luminance is > 0. */
bool image_metrics_compute(const struct image *a, const struct image *b, const struct image *mask,
                           struct image_metrics *out, struct error *err);

/* The flicker of two consecutive frames a0, a1 of a technique against the
 * truth's b0, b1 (issue 32; docs/TEMPORAL.md): sqrt(sum |(a1 - a0) - (b1 -
 * b0)|^2 / 2) / sqrt(sum |(b0 + b1) / 2|^2) over RGB in the mask (NULL: all).
 * On a still scene it is the per-pixel standard deviation over frames,
 * relative to the truth's RMS. */
bool image_flicker_compute(const struct image *a0, const struct image *a1, const struct image *b0,
                           const struct image *b1, const struct image *mask, double *flicker, struct error *err);

#endif
