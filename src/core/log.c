#define _POSIX_C_SOURCE 200809L
#include "core/log.h"

#include <stdarg.h>
#include <stdio.h>
#include <time.h>

static bool verbose_enabled;

void log_set_verbose(bool verbose) { verbose_enabled = verbose; }
bool log_verbose(void) { return verbose_enabled; }

static bool quiet_enabled;
void log_set_quiet(bool quiet) { quiet_enabled = quiet; }
bool log_quiet(void) { return quiet_enabled; }

void log_info(const char *fmt, ...)
{
    if (!verbose_enabled)
        return;
    va_list ap;
    va_start(ap, fmt);
    fputs("caustica: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

void log_warn(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("caustica: warning: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

double log_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}
