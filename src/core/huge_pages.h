/* Large arrays that the reference fills from scratch every run (the
 * pixels' records and their medium segments) are touched first page by page: with
 * 4 KiB pages a 512 x 512 image's pixel records (about 230 MiB) took some
 * 60,000 page faults in the first eye pass, a fifth of a 2 s budget's CPU
 * time (perf, docs/REFERENCE.md). Transparent huge pages cut that count
 * by 512 where the system allows them on request (madvise mode). */
#ifndef CAUSTICA_HUGE_PAGES_H
#define CAUSTICA_HUGE_PAGES_H

#include <stddef.h>

/* Zeroed memory for `count` items of `size` bytes, asked to be backed by
 * transparent huge pages when it is large (advice only: where the system
 * refuses, ordinary pages). Released with free(). NULL when out of memory
 * or when count * size overflows. */
void *huge_pages_calloc(size_t count, size_t size);

/* The same advice for memory already allocated and not yet touched. */
void huge_pages_advise(void *memory, size_t bytes);

#endif
