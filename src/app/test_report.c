/* The HTML test report (see test_report.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/test_report.h"
#include "core/fileio.h"

static char *copy(const char *s)
{
    if (!s)
        return NULL;
    size_t n = strlen(s) + 1;
    char *c = malloc(n);
    if (c)
        memcpy(c, s, n);
    return c;
}

bool test_report_add(struct test_report *report, const struct test_case_result *result)
{
    if (report->count == report->capacity) {
        int cap = report->capacity ? report->capacity * 2 : 64;
        struct test_case_result *c = realloc(report->cases, (size_t)cap * sizeof *c);
        if (!c)
            return false;
        report->cases = c;
        report->capacity = cap;
    }
    struct test_case_result *r = &report->cases[report->count++];
    *r = *result;
    r->file = copy(result->file);
    r->name = copy(result->name);
    r->message = copy(result->message);
    for (int k = 0; k < 3; k++)
        r->images[k] = copy(result->images[k]);
    return true;
}

void test_report_release(struct test_report *report)
{
    for (int i = 0; i < report->count; i++) {
        struct test_case_result *r = &report->cases[i];
        free(r->file);
        free(r->name);
        free(r->message);
        for (int k = 0; k < 3; k++)
            free(r->images[k]);
    }
    free(report->cases);
    memset(report, 0, sizeof *report);
}

/* Text with &, <, > and " escaped. */
static void put_text(FILE *f, const char *s)
{
    for (; s && *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
    }
}

bool test_report_write(const struct test_report *report, const char *path, struct error *err)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return error_set(err, "--report %s: cannot write: %s", path, strerror(errno));
    int failed = 0;
    for (int i = 0; i < report->count; i++)
        failed += !report->cases[i].ok;
    fprintf(f, "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>caustica test: %d passed, %d failed"
               "</title>\n<style>body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}"
               "td,th{border:1px solid #ccc;padding:4px 8px;text-align:left;vertical-align:top}"
               ".ok{color:#070}.fail{color:#b00}figure{display:inline-block;margin:0 1em 1em 0}"
               "img{image-rendering:pixelated;width:256px;border:1px solid #999}</style></head><body>\n",
            report->count - failed, failed);
    fprintf(f, "<h1>caustica test: %d passed, %d failed</h1>\n", report->count - failed, failed);
    for (int i = 0; i < report->count; i++) {
        const struct test_case_result *r = &report->cases[i];
        if (r->ok)
            continue;
        fprintf(f, "<h2 class=\"fail\">");
        put_text(f, r->file);
        fputs(": ", f);
        put_text(f, r->name);
        fputs("</h2>\n<p>", f);
        put_text(f, r->message);
        fputs("</p>\n", f);
        static const char *const captions[3] = {"rendered", "compared with (golden)", "difference"};
        for (int k = 0; k < 3; k++) {
            if (!r->images[k])
                continue;
            fputs("<figure><img src=\"file://", f);
            put_text(f, r->images[k]);
            fprintf(f, "\"><figcaption>%s<br><code>", captions[k]);
            put_text(f, r->images[k]);
            fputs("</code></figcaption></figure>\n", f);
        }
    }
    fputs("<h2>All cases</h2>\n<table><tr><th>file</th><th>case</th><th>result</th><th>s</th></tr>\n", f);
    for (int i = 0; i < report->count; i++) {
        const struct test_case_result *r = &report->cases[i];
        fputs("<tr><td>", f);
        put_text(f, r->file);
        fputs("</td><td>", f);
        put_text(f, r->name);
        fprintf(f, "</td><td class=\"%s\">%s</td><td>%.2f</td></tr>\n", r->ok ? "ok" : "fail", r->ok ? "ok" : "FAIL",
                r->seconds);
    }
    fputs("</table>\n</body></html>\n", f);
    bool ok = !ferror(f);
    if (fclose(f) != 0 || !ok)
        return error_set(err, "--report %s: write failed", path);
    return true;
}
