#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

bool error_set(struct error *err, const char *fmt, ...)
{
    if (!err)
        return false;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    return false;
}

bool error_prefix(struct error *err, const char *fmt, ...)
{
    if (!err)
        return false;
    char prefix[ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(prefix, sizeof prefix, fmt, ap);
    va_end(ap);
    char joined[ERROR_MESSAGE_MAX * 2 + 2];
    snprintf(joined, sizeof joined, "%s: %s", prefix, err->message);
    joined[ERROR_MESSAGE_MAX - 1] = '\0';
    memcpy(err->message, joined, ERROR_MESSAGE_MAX);
    return false;
}


