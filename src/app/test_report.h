/* `caustica test --report out.html`: one self-contained HTML page (images
 * embedded) with a summary of every case and, for each failed image
 * comparison, the rendered image, the image it was compared with and their
 * difference side by side, and a flip view of the first two.
 * `--junit out.xml`: the same results as JUnit XML. */
#ifndef CAUSTICA_TEST_REPORT_H
#define CAUSTICA_TEST_REPORT_H

#include <stdbool.h>

#include "core/error.h"

struct test_case_result {
    char *file, *name, *message;
    bool ok;
    double seconds;
    char *images[3]; /* new, ref, diff: absolute paths, or NULL */
};

struct test_report {
    struct test_case_result *cases;
    int count, capacity;
};

/* Adds a copy of the result (false when out of memory). */
bool test_report_add(struct test_report *report, const struct test_case_result *result);
bool test_report_write(const struct test_report *report, const char *path, struct error *err);
/* <testsuites> of one <testsuite> per test file, a <testcase> per case
 * (classname: the file, time in seconds) with a <failure message> where it
 * failed: the subset of the JUnit format CI servers read (tests/data/junit.xsd). */
bool test_report_write_junit(const struct test_report *report, const char *path, struct error *err);
void test_report_release(struct test_report *report);

#endif
