/* Progress and diagnostics on stderr; quiet unless asked. */
#ifndef CAUSTICA_LOG_H
#define CAUSTICA_LOG_H

#include <stdbool.h>

void log_set_verbose(bool verbose);
bool log_verbose(void);
/* --quiet: no progress lines and no "wrote ..." (errors and warnings still). */
void log_set_quiet(bool quiet);
bool log_quiet(void);
void log_info(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void log_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* Seconds on a monotonic clock. */
double log_now(void);

#endif
