/* The HTML test report (see test_report.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/test_report.h"
#include "core/fileio.h"
#include "io/image.h"

#define REPORT_IMAGE_MAX_BYTES (64u << 20)

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
    /* the writers compare and print these: never NULL */
    r->file = copy(result->file ? result->file : "(no file)");
    r->name = copy(result->name ? result->name : "(no name)");
    r->message = copy(result->message ? result->message : "");
    if (!r->file || !r->name || !r->message) {
        free(r->file);
        free(r->name);
        free(r->message);
        report->count--;
        return false;
    }
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

/* The length of the well-formed UTF-8 sequence at s (RFC 3629: no
 * overlong forms, no surrogates, nothing past U+10FFFF) whose code point
 * XML 1.0 allows as a character, or 0. */
static int xml_char_length(const unsigned char *s)
{
    unsigned c = s[0];
    if (c < 0x80)
        return c >= 0x20 || c == '\t' || c == '\n' || c == '\r' ? 1 : 0;
    int n = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 ? 2 : 0;
    if (n == 0 || c > 0xf4)
        return 0;
    unsigned cp = c & (0x3fu >> (n - 1));
    for (int i = 1; i < n; i++) {
        if ((s[i] & 0xc0) != 0x80) /* the NUL at the end fails here too */
            return 0;
        cp = cp << 6 | (s[i] & 0x3fu);
    }
    static const unsigned least[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < least[n] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff) || cp == 0xfffe || cp == 0xffff)
        return 0;
    return n;
}

/* Text with &, <, > and " escaped, valid in XML and HTML whatever the
 * bytes: a control character or a byte that is not part of well-formed
 * UTF-8 is written as the text \xNN (a test's message may quote any
 * bytes; none of them may make the report unreadable). */
static void put_text(FILE *f, const char *text)
{
    const unsigned char *s = (const unsigned char *)text;
    while (s && *s) {
        int n = xml_char_length(s);
        if (n == 0) {
            fprintf(f, "\\x%02X", *s);
            s++;
            continue;
        }
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fwrite(s, 1, (size_t)n, f);
        }
        s += n;
    }
}

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* A PNG as a data: URI, so that the page stands alone (uploaded as a CI
 * artifact, mailed); a file that cannot be read becomes an empty image. */
static void put_data_uri(FILE *f, const char *path)
{
    static const char table[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    fputs("data:image/png;base64,", f);
    /* a regular file only (a test may name any path: /dev/zero would
     * never end), and no more than a large PNG's worth */
    struct error ignored;
    FILE *in = file_open_read(path, false, &ignored);
    if (!in)
        return;
    unsigned char b[3];
    size_t n, total = 0;
    while (total < REPORT_IMAGE_MAX_BYTES && (n = fread(b, 1, 3, in)) > 0) {
        total += n;
        unsigned v = (unsigned)b[0] << 16 | (n > 1 ? (unsigned)b[1] << 8 : 0u) | (n > 2 ? b[2] : 0u);
        fputc(table[v >> 18 & 63], f);
        fputc(table[v >> 12 & 63], f);
        fputc(n > 1 ? table[v >> 6 & 63] : '=', f);
        fputc(n > 2 ? table[v & 63] : '=', f);
        if (n < 3)
            break;
    }
    fclose(in);
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
               ".ok{color:#070}.fail{color:#b00}.row{display:flex;flex-wrap:wrap;gap:1em}figure{margin:0}"
               "img{image-rendering:pixelated;width:256px;border:1px solid #999}"
               ".flip{position:relative}.flip .b{position:absolute;left:0;top:0;opacity:0}"
               ".flip:hover .b{opacity:1}img.thumb{width:64px}</style></head><body>\n",
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
        static const char *const captions[3] = {"rendered", "compared with", "difference (scaled)"};
        fputs("<div class=\"row\">", f);
        for (int k = 0; k < 3; k++) {
            if (!r->images[k])
                continue;
            fputs("<figure><img src=\"", f);
            put_data_uri(f, r->images[k]);
            fprintf(f, "\"><figcaption>%s<br><code>", captions[k]);
            put_text(f, base_name(r->images[k]));
            fputs("</code></figcaption></figure>\n", f);
        }
        if (r->images[0] && r->images[1]) {
            /* flip: the rendered image, the other one while the pointer is over it */
            fputs("<figure class=\"flip\"><img class=\"a\" src=\"", f);
            put_data_uri(f, r->images[0]);
            fputs("\"><img class=\"b\" src=\"", f);
            put_data_uri(f, r->images[1]);
            fputs("\"><figcaption>flip: rendered; hover: compared with</figcaption></figure>", f);
        }
        fputs("</div>\n", f);
    }
    fputs("<h2>All cases</h2>\n<table><tr><th>file</th><th>case</th><th>result</th><th>s</th><th>image</th></tr>\n", f);
    for (int i = 0; i < report->count; i++) {
        const struct test_case_result *r = &report->cases[i];
        fputs("<tr><td>", f);
        put_text(f, r->file);
        fputs("</td><td>", f);
        put_text(f, r->name);
        fprintf(f, "</td><td class=\"%s\">%s</td><td>%.2f</td><td>", r->ok ? "ok" : "fail", r->ok ? "ok" : "FAIL",
                r->seconds);
        if (r->images[0]) {
            /* a thumbnail of what the case rendered (a passing one too) */
            fputs("<img class=\"thumb\" src=\"", f);
            put_data_uri(f, r->images[0]);
            fputs("\">", f);
        }
        fputs("</td></tr>\n", f);
    }
    fputs("</table>\n</body></html>\n", f);
    bool ok = !ferror(f);
    if (fclose(f) != 0 || !ok)
        return error_set(err, "--report %s: write failed", path);
    return true;
}

/* The file's cases, counted. */
static void suite_counts(const struct test_report *report, const char *file, int *tests, int *failures, double *time)
{
    *tests = *failures = 0;
    *time = 0.0;
    for (int i = 0; i < report->count; i++)
        if (strcmp(report->cases[i].file, file) == 0) {
            (*tests)++;
            *failures += !report->cases[i].ok;
            *time += report->cases[i].seconds;
        }
}

bool test_report_write_junit(const struct test_report *report, const char *path, struct error *err)
{
    char tmp[4200];
    FILE *f = image_file_begin(path, tmp, sizeof tmp, err);
    if (!f)
        return error_prefix(err, "--junit");
    int failed = 0;
    double total = 0.0;
    for (int i = 0; i < report->count; i++) {
        failed += !report->cases[i].ok;
        total += report->cases[i].seconds;
    }
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"caustica\" tests=\"%d\" "
               "failures=\"%d\" errors=\"0\" time=\"%.3f\">\n", report->count, failed, total);
    for (int i = 0; i < report->count; i++) {
        const char *file = report->cases[i].file;
        bool first = true;
        for (int k = 0; k < i; k++)
            first = first && strcmp(report->cases[k].file, file) != 0;
        if (!first)
            continue; /* one suite per file, at its first case */
        int tests, failures;
        double time;
        suite_counts(report, file, &tests, &failures, &time);
        fputs("  <testsuite name=\"", f);
        put_text(f, file);
        fprintf(f, "\" tests=\"%d\" failures=\"%d\" errors=\"0\" skipped=\"0\" time=\"%.3f\">\n", tests, failures,
                time);
        for (int k = i; k < report->count; k++) {
            const struct test_case_result *r = &report->cases[k];
            if (strcmp(r->file, file) != 0)
                continue;
            fputs("    <testcase classname=\"", f);
            put_text(f, file);
            fputs("\" name=\"", f);
            put_text(f, r->name);
            fprintf(f, "\" time=\"%.3f\"", r->seconds);
            if (r->ok) {
                fputs("/>\n", f);
                continue;
            }
            fputs(">\n      <failure message=\"", f);
            put_text(f, r->message);
            fputs("\" type=\"failure\">", f);
            put_text(f, r->message);
            fputs("</failure>\n    </testcase>\n", f);
        }
        fputs("  </testsuite>\n", f);
    }
    fputs("</testsuites>\n", f);
    return image_file_finish(f, tmp, path, !ferror(f), err);
}
