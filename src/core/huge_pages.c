/* Transparent huge pages on request (huge_pages.h). */
#define _DEFAULT_SOURCE
#include "core/huge_pages.h"

#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

#define HUGE_PAGE_BYTES ((size_t)2 << 20)

void huge_pages_advise(void *memory, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    if (!memory || bytes < 2 * HUGE_PAGE_BYTES)
        return; /* too small to hold a whole aligned huge page worth asking for */
    long page = sysconf(_SC_PAGESIZE);
    if (page <= 0)
        return;
    /* madvise wants a page-aligned start: the whole pages inside the block */
    uintptr_t start = ((uintptr_t)memory + (uintptr_t)page - 1) & ~((uintptr_t)page - 1);
    uintptr_t end = ((uintptr_t)memory + bytes) & ~((uintptr_t)page - 1);
    if (end > start)
        (void)madvise((void *)start, end - start, MADV_HUGEPAGE); /* advice: a refusal leaves small pages */
#else
    (void)memory;
    (void)bytes;
#endif
}

void *huge_pages_calloc(size_t count, size_t size)
{
    if (size && count > SIZE_MAX / size)
        return NULL;
    /* glibc serves a block this large by a fresh anonymous mapping, zeroed
     * and untouched, so the advice comes before any page is faulted in */
    void *memory = calloc(count, size);
    huge_pages_advise(memory, count * size);
    return memory;
}
