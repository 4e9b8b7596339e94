/* FNV-1a hashing of bytes: the keys of caches (bench's ground truths, the
 * transport tables on disk, what a pass's textures were made from). */
#ifndef CAUSTICA_HASH_H
#define CAUSTICA_HASH_H

#include <stddef.h>
#include <stdint.h>

#define HASH_FNV1A_BASIS 14695981039346656037ULL

/* h folded with n bytes of data (start from HASH_FNV1A_BASIS). */
uint64_t hash_fnv1a(uint64_t h, const void *data, size_t n);

#endif
