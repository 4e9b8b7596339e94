/* Growable arrays: the one doubling rule the scene and the mesh cache use. */
#ifndef CAUSTICA_ARRAY_H
#define CAUSTICA_ARRAY_H

#include <stdbool.h>
#include <stddef.h>

#include "core/error.h"

/* Makes room for one more element: doubles *capacity (from 16) when
 * `count` has reached it. False with "out of memory", *items unchanged. */
bool array_grow(void **items, int *capacity, int count, size_t elem, struct error *err);

#endif
