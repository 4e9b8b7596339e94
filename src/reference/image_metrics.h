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

#endif
