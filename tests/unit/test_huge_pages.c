/* core/huge_pages.c: zeroed memory of the size asked, NULL on overflow,
 * and, where the system gives transparent huge pages on request (its
 * policy "madvise" or "always"), a large block advised for them
 * (/proc/self/smaps' VmFlags "hg"). The advice, not the pages: whether the
 * kernel finds free 2 MiB pages depends on how fragmented the machine's
 * memory is. */
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

/* Whether the mapping that holds `p` is advised for huge pages: smaps'
 * VmFlags line lists "hg" (MADV_HUGEPAGE). -1: no such line found. */
static int advised_at(const void *p)
{
    FILE *f = fopen("/proc/self/smaps", "r");
    if (!f)
        return -1;
    char line[1024];
    bool inside = false;
    int advised = -1;
    uintptr_t at = (uintptr_t)p;
    while (fgets(line, sizeof line, f)) {
        unsigned long lo, hi;
        if (sscanf(line, "%lx-%lx ", &lo, &hi) == 2) {
            inside = at >= lo && at < hi;
            continue;
        }
        if (inside && strncmp(line, "VmFlags:", 8) == 0) {
            advised = strstr(line, " hg") != NULL;
            break;
        }
    }
    fclose(f);
    return advised;
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
        if (huge_pages_on_request())
            CHECK(advised_at(big + (count * size) / 2) == 1);
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
