/* libFuzzer harness for the test reports `caustica test --junit` and
 * `--report` write (src/app/test_report.c) from what test files say: the
 * input is cut at its NUL bytes into results of five fields (file, name,
 * message, ok, an image path), fields missing or empty as a test file may
 * leave them. Both reports are written and read back; every byte must be
 * well-formed UTF-8 that XML 1.0 allows as a character (no control
 * characters but tab, newline and return), whatever the input held. */
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/test_report.h"
#include "fuzz_files.h"

static char junit[320], html[320];

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    char dir[256];
    if (!fuzz_private_dir("report", dir, sizeof dir))
        return 1;
    snprintf(junit, sizeof junit, "%s/junit.xml", dir);
    snprintf(html, sizeof html, "%s/report.html", dir);
    return 0;
}

/* Aborts unless the file is UTF-8 text that XML allows. */
static void check_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        abort();
    static unsigned char bytes[1 << 20];
    size_t n = fread(bytes, 1, sizeof bytes - 4, f);
    fclose(f);
    memset(bytes + n, 0, 4);
    for (size_t i = 0; i < n;) {
        unsigned c = bytes[i];
        if (c < 0x80) {
            if (c < 0x20 && c != '\t' && c != '\n' && c != '\r')
                abort();
            i++;
            continue;
        }
        size_t len = c >= 0xf0 ? 4 : c >= 0xe0 ? 3 : c >= 0xc2 ? 2 : 0;
        if (len == 0 || c > 0xf4 || i + len > n)
            abort();
        unsigned cp = c & (0x3fu >> (len - 1));
        for (size_t k = 1; k < len; k++) {
            if ((bytes[i + k] & 0xc0) != 0x80)
                abort();
            cp = cp << 6 | (bytes[i + k] & 0x3fu);
        }
        static const unsigned least[5] = {0, 0, 0x80, 0x800, 0x10000};
        if (cp < least[len] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff) || cp == 0xfffe || cp == 0xffff)
            abort();
        i += len;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    struct test_report report = {0};
    char *field[5] = {0};
    int used = 0;
    for (size_t at = 0; at <= size; at += strlen(text + at) + 1) {
        field[used++] = text + at;
        if (used == 5 || at + strlen(text + at) >= size) {
            /* an empty field stands for one the test file left out */
            struct test_case_result r = {.file = field[0] && field[0][0] ? field[0] : NULL,
                                         .name = field[1] && field[1][0] ? field[1] : NULL,
                                         .message = field[2] && field[2][0] ? field[2] : NULL,
                                         .ok = field[3] && field[3][0] == '1',
                                         .seconds = 0.25};
            r.images[0] = field[4] && field[4][0] ? field[4] : NULL;
            test_report_add(&report, &r);
            memset(field, 0, sizeof field);
            used = 0;
        }
    }
    struct error err;
    if (test_report_write_junit(&report, junit, &err))
        check_text(junit);
    if (test_report_write(&report, html, &err))
        check_text(html);
    test_report_release(&report);
    free(text);
    return 0;
}
