/* A tiny assert header: failures print "file:line: expected ... got ..."
 * and the test executable exits non-zero at the end. */
#ifndef CAUSTICA_CHECK_H
#define CAUSTICA_CHECK_H

#include <math.h>
#include <stdio.h>
#include <string.h>

static int check_failures;
static int check_count;

#define CHECK(cond)                                                                    \
    do {                                                                               \
        check_count++;                                                                 \
        if (!(cond)) {                                                                 \
            fprintf(stderr, "%s:%d: expected %s\n", __FILE__, __LINE__, #cond);         \
            check_failures++;                                                          \
        }                                                                              \
    } while (0)

#define CHECK_NEAR(got, want, tol)                                                     \
    do {                                                                               \
        check_count++;                                                                 \
        double g_ = (double)(got), w_ = (double)(want);                                \
        if (!(fabs(g_ - w_) <= (tol))) {                                               \
            fprintf(stderr, "%s:%d: expected %s = %.9g (within %g), got %.9g\n", __FILE__, \
                    __LINE__, #got, w_, (double)(tol), g_);                            \
            check_failures++;                                                          \
        }                                                                              \
    } while (0)

#define CHECK_CONTAINS(text, part)                                                     \
    do {                                                                               \
        check_count++;                                                                 \
        if (!strstr((text), (part))) {                                                 \
            fprintf(stderr, "%s:%d: expected \"%s\" to contain \"%s\"\n", __FILE__, __LINE__, \
                    (text), (part));                                                   \
            check_failures++;                                                          \
        }                                                                              \
    } while (0)

static int check_finish(const char *name)
{
    printf("%s: %d checks, %d failed\n", name, check_count, check_failures);
    return check_failures ? 1 : 0;
}

#endif
