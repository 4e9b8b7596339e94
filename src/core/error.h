/* The project's one error type: a message naming the input (script, asset,
 * shader) and, where there is one, its line. Fallible functions take it as
 * their last parameter and return false after filling it. */
#ifndef CAUSTICA_ERROR_H
#define CAUSTICA_ERROR_H

#include <stdbool.h>

#define ERROR_MESSAGE_MAX 2048

#ifdef __cplusplus
extern "C" {
#endif

struct error {
    char message[ERROR_MESSAGE_MAX];
};

/* Sets the message (printf-style) and returns false, so that a failing
 * function can `return error_set(err, ...)`. `err` may be NULL. */
bool error_set(struct error *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Prepends "prefix: " to an existing message (adds context on the way up). */
bool error_prefix(struct error *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));


#ifdef __cplusplus
}
#endif

#endif
