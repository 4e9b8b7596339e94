/* core/huge_pages.c: zeroed memory of the size asked, NULL on overflow,
 * and, where the system gives transparent huge pages on request (its
 * policy "madvise" or "always"), a large block actually backed by them
 * once touched (/proc/self/smaps' AnonHugePages). */
#define _DEFAULT_SOURCE
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/huge_pages.h"

/* The kernel's policy, as /sys shows it: "[madvise]" marks the one in force. */
static bool huge_pages_on_request(void)
{
    FILE *f = fopen("/sys/kernel/mm/transparent_hugepage/enabled", "r");
    if (!f)
        return false;
    char line[256] = {0};
    bool on = fgets(line, sizeof line, f) && (strstr(line, "[madvise]") || strstr(line, "[always]"));
    fclose(f);
    return on;
}

/* kB of huge pages backing the mapping that holds `p` (smaps). */
static long huge_kb_at(const void *p)
{
    FILE *f = fopen("/proc/self/smaps", "r");
    if (!f)
        return -1;
    char line[512];
    bool inside = false;
    long kb = -1;
    uintptr_t at = (uintptr_t)p;
    while (fgets(line, sizeof line, f)) {
        unsigned long lo, hi;
        if (sscanf(line, "%lx-%lx ", &lo, &hi) == 2) {
            inside = at >= lo && at < hi;
            continue;
        }
        long v;
        if (inside && sscanf(line, "AnonHugePages: %ld kB", &v) == 1) {
            kb = v;
            break;
        }
    }
    fclose(f);
    return kb;
}

int main(void)
{
    /* a large block: zeroed, every byte writable */
    size_t count = 8u << 20, size = 8; /* 64 MiB */
    unsigned char *big = huge_pages_calloc(count, size);
    CHECK(big != NULL);
    if (big) {
        bool zero = true;
        for (size_t i = 0; i < count * size; i += 4093)
            zero = zero && big[i] == 0;
        CHECK(zero && big[count * size - 1] == 0);
        memset(big, 0xab, count * size);
        CHECK(big[0] == 0xab && big[count * size - 1] == 0xab);
        if (huge_pages_on_request()) {
            long kb = huge_kb_at(big + (count * size) / 2);
            CHECK(kb >= 2048); /* at least one 2 MiB page of the 64 MiB */
        }
        free(big);
    }
    /* small blocks are ordinary calloc */
    int *small = huge_pages_calloc(10, sizeof *small);
    CHECK(small != NULL && small[0] == 0 && small[9] == 0);
    free(small);
    /* a size that overflows is refused, not wrapped */
    CHECK(huge_pages_calloc(SIZE_MAX / 2, 4) == NULL);
    free(huge_pages_calloc(0, 16)); /* calloc(0): NULL or a block, no crash */
    huge_pages_advise(NULL, 1u << 30); /* no memory: nothing to advise */
    return check_finish("huge_pages");
}
