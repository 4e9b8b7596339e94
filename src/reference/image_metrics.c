#include "reference/image_metrics.h"

#include <math.h>
#include <string.h>

#include "core/vecmath.h"

static double luminance(const float *px)
{
    return 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2];
}

static bool in_mask(const struct image *mask, size_t i)
{
    return !mask || luminance(mask->rgba + i * 4) > 0.0;
}

/* SSIM (Wang et al. 2004) on luminance over non-overlapping 8x8 windows,
 * with the usual constants for a dynamic range of 1. */
static double ssim_luminance(const struct image *a, const struct image *b, const struct image *mask)
{
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double total = 0.0;
    long windows = 0;
    for (int wy = 0; wy + 8 <= a->height; wy += 8)
        for (int wx = 0; wx + 8 <= a->width; wx += 8) {
            double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
            int n = 0;
            for (int y = wy; y < wy + 8; y++)
                for (int x = wx; x < wx + 8; x++) {
                    size_t i = (size_t)y * (size_t)a->width + (size_t)x;
                    if (!in_mask(mask, i))
                        continue;
                    double la = luminance(a->rgba + i * 4), lb = luminance(b->rgba + i * 4);
                    if (!isfinite(la) || !isfinite(lb))
                        continue;
                    sa += la;
                    sb += lb;
                    saa += la * la;
                    sbb += lb * lb;
                    sab += la * lb;
                    n++;
                }
            if (n < 2)
                continue;
            double ma = sa / n, mb = sb / n;
            double va = saa / n - ma * ma, vb = sbb / n - mb * mb, cov = sab / n - ma * mb;
            total += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            windows++;
        }
    return windows > 0 ? total / (double)windows : 1.0;
}

bool image_metrics_compute(const struct image *a, const struct image *b, const struct image *mask,
                           struct image_metrics *out, struct error *err)
{
    memset(out, 0, sizeof *out);
    if (a->width != b->width || a->height != b->height)
        return error_set(err, "images differ in size: %dx%d and %dx%d", a->width, a->height, b->width,
                         b->height);
    if (mask && (mask->width != a->width || mask->height != a->height))
        return error_set(err, "the mask is %dx%d, the images %dx%d", mask->width, mask->height, a->width,
                         a->height);
    size_t n = (size_t)a->width * (size_t)a->height;
    double sum_sq = 0.0, ref_sq = 0.0, max = 0.0, log_sq = 0.0;
    long count = 0, nan = 0;
    for (size_t i = 0; i < n; i++) {
        if (!in_mask(mask, i))
            continue;
        count++;
        for (int c = 0; c < 3; c++) {
            double va = a->rgba[i * 4 + (size_t)c], vb = b->rgba[i * 4 + (size_t)c];
            if (!isfinite(va) || !isfinite(vb)) {
                nan++;
                continue;
            }
            double d = va - vb;
            sum_sq += d * d;
            /* log(1 + x): HDR-friendly, a spike 100x too bright counts ~4.6, not 100 */
            double dl = log1p(fmax(va, 0.0)) - log1p(fmax(vb, 0.0));
            log_sq += dl * dl;
            ref_sq += vb * vb;
            if (fabs(d) > max)
                max = fabs(d);
        }
    }
    double samples = (double)count * 3.0;
    out->pixels = count;
    out->nan = nan;
    out->max = max;
    out->rmse = sqrt(math_safe_div_d(sum_sq, samples, 0.0));
    out->log_rmse = sqrt(math_safe_div_d(log_sq, samples, 0.0));
    double ref_rms = sqrt(math_safe_div_d(ref_sq, samples, 0.0));
    out->rel_rmse = math_safe_div_d(out->rmse, ref_rms, out->rmse > 0 ? INFINITY : 0.0);
    out->psnr = out->rmse > 0 ? 20.0 * log10(1.0 / out->rmse) : 999.0;
    out->ssim = ssim_luminance(a, b, mask);
    return true;
}

/* Issue 32's flicker: the error of a frame-to-frame change (the temporal
 * metrics of video restoration and denoising, e.g. TecoGAN's tOF and tLP,
 * Chu et al. 2020: the distance between the output's and the ground
 * truth's change from one frame to the next, here per pixel since the
 * truth is exact). Halved in square so that on a still scene, where the
 * truth does not change, it is the per-pixel standard deviation over frames
 * of independent noise; relative to the RMS of the truth's mean frame, as
 * rel_rmse is to the truth's. */
bool image_flicker_compute(const struct image *a0, const struct image *a1, const struct image *b0,
                           const struct image *b1, const struct image *mask, double *flicker, struct error *err)
{
    *flicker = 0.0;
    const struct image *all[4] = {a0, a1, b0, b1};
    for (int k = 1; k < 4; k++)
        if (all[k]->width != a0->width || all[k]->height != a0->height)
            return error_set(err, "frames differ in size: %dx%d and %dx%d", a0->width, a0->height, all[k]->width,
                             all[k]->height);
    if (mask && (mask->width != a0->width || mask->height != a0->height))
        return error_set(err, "the mask is %dx%d, the frames %dx%d", mask->width, mask->height, a0->width,
                         a0->height);
    size_t n = (size_t)a0->width * (size_t)a0->height;
    double change_sq = 0.0, ref_sq = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (!in_mask(mask, i))
            continue;
        for (size_t c = 0; c < 3; c++) {
            size_t j = i * 4 + c;
            double v[4] = {a0->rgba[j], a1->rgba[j], b0->rgba[j], b1->rgba[j]};
            if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2]) || !isfinite(v[3]))
                continue; /* counted by image_metrics_compute */
            double d = (v[1] - v[0]) - (v[3] - v[2]), mean = 0.5 * (v[2] + v[3]);
            change_sq += 0.5 * d * d;
            ref_sq += mean * mean;
        }
    }
    *flicker = sqrt(math_safe_div_d(change_sq, ref_sq, change_sq > 0 ? INFINITY : 0.0));
    return true;
}
