#include "core/array.h"

#include <stdlib.h>

bool array_grow(void **items, int *capacity, int count, size_t elem, struct error *err)
{
    if (count < *capacity)
        return true;
    int cap = *capacity ? *capacity * 2 : 16;
    void *p = realloc(*items, (size_t)cap * elem);
    if (!p)
        return error_set(err, "out of memory");
    *items = p;
    *capacity = cap;
    return true;
}
