/* The reference's clock and progress (struct budget, shared by every
 * thread of a render): whether the time budget is spent, when a photon
 * stage must stop to leave its gather time, how many photons the first
 * gather can afford, and the progress line. */
#define _POSIX_C_SOURCE 200809L
#include "reference/ref_sppm_internal.h"

#include <unistd.h>

/* The render's clock from `start`: the deadline --time-budget sets, the
 * cut counters at 0, progress on a terminal or as log lines. */
void sppm_budget_start(struct budget *budget, const struct ref_options *o, double start)
{
    atomic_init(&budget->cut, 0);
    atomic_init(&budget->photons_cut, 0);
    for (int k = 0; k < 3; k++)
        atomic_init(&budget->paths_cut[k], 0);
    atomic_init(&budget->knn_pixels, 0);
    atomic_init(&budget->knn_counted, 0);
    budget->knn_seconds = 0.0;
    budget->start = start;
    budget->gather_share = 0.25;
    budget->deadline = o->time_budget > 0 ? start + o->time_budget : 0.0;
    budget->tty = o->progress && isatty(STDERR_FILENO) && !log_quiet();
    budget->log_lines = o->progress && !budget->tty && !log_quiet();
}

/* A photon stage that must end by `until` (0: no budget) stops tracing
 * early enough for the surface gather after it, as long as the last one
 * took (the first guess, before any was measured, is a quarter). */
double sppm_photon_deadline(const struct budget *b, double until)
{
    if (until <= 0.0)
        return 0.0;
    double now = log_now();
    return now + fmax(until - now, 0.0) * (1.0 - b->gather_share);
}

void sppm_gather_share_measured(struct budget *b, double trace_seconds, double gather_seconds)
{
    if (trace_seconds + gather_seconds > 0.0)
        b->gather_share = fmin(gather_seconds / (trace_seconds + gather_seconds), 0.9);
}

/* The one progress writer: on a terminal, the line rewritten in place
 * (padded over the longer line before it); off one, nothing here (the
 * iteration lines are whole lines). */
void sppm_progress_line(struct budget *b, const char *fmt, ...)
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

bool sppm_budget_photons_spent(struct budget *b)
{
    if (b->photon_deadline > 0 && log_now() >= b->photon_deadline) {
        atomic_store(&b->photons_cut, 1);
        return true;
    }
    return atomic_load(&b->photons_cut) != 0;
}

bool sppm_budget_spent(struct budget *b)
{
    if (b->deadline > 0 && log_now() >= b->deadline) {
        atomic_store(&b->cut, 1);
        return true;
    }
    return atomic_load(&b->cut) != 0;
}

/* Under a budget, how many photons the first radii hold: GATHER_PHOTONS,
 * or where the first gather of that many would take more than
 * FIRST_GATHER_SHARE of the time left, fewer in proportion, down to
 * GATHER_PHOTONS_MIN, the radii shrunk to hold them (as sqrt(k'/k): the
 * density within a radius is about even, or the radius would have been
 * halved). The first gather is predicted from the first k-nearest-neighbour
 * pass, which counted the pilot's last round (a quarter of an iteration's
 * photons) within radii about as wide: its time, per photon counted, times
 * the photons the gather will take, twice (the flux and the structure
 * sums). More photons a gather cost fewer iterations, which the photons'
 * stratification repays, but not where the first gather itself no longer
 * fits: at 512^2 and 2 s the TIR cube's stopped short of its last rows
 * (26% of error, against 5.3% with 200 a gather). The pilot's counting
 * rates at its small radius, and the time the eye pass and the pilot took,
 * were tried as the measure and missed by 3 to 4 times, differently per
 * scene. */
double sppm_budget_gather_photons(const struct budget *budget, struct pixel *pixels, size_t npix)
{
    if (!(budget->deadline > 0))
        return GATHER_PHOTONS;
    long long counted = atomic_load(&budget->knn_counted), served = atomic_load(&budget->knn_pixels);
    double rest = budget->deadline - log_now(), gather;
    if (counted > 0 && served > 0 && budget->knn_seconds > 0.0) {
        gather = 2.0 * budget->knn_seconds * GATHER_PHOTONS * (double)served / (double)counted;
    } else {
        /* no pass before the pilot's deadline (a short budget): the
         * pilot's counting rate, which says too much, is the safer side */
        gather = 2.0 * budget->seconds_per_gathered * GATHER_PHOTONS * (double)sppm_gathering_points(pixels, npix);
        if (!(gather > 0.0))
            return GATHER_PHOTONS;
    }
    if (gather <= FIRST_GATHER_SHARE * rest)
        return GATHER_PHOTONS;
    double k = fmax(GATHER_PHOTONS * FIRST_GATHER_SHARE * fmax(rest, 0.0) / gather, GATHER_PHOTONS_MIN);
    double shrink = sqrt(k / GATHER_PHOTONS);
    for (size_t i = 0; i < npix; i++)
        if (pixels[i].radius > 0.0)
            pixels[i].radius = fmax(pixels[i].radius * shrink, pixels[i].radius_floor);
    return k;
}

size_t sppm_gathering_points(const struct pixel *pixels, size_t npix)
{
    size_t points = 0;
    for (size_t i = 0; i < npix; i++)
        points += pixels[i].vp.valid && pixels[i].radius > 0.0;
    return points;
}
