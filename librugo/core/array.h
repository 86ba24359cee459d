/* The one growable array of librugo: elements of one size in memory from the owner's allocator.
 * Not installed. May include: core.
 *
 * The owner keeps the allocator (every owned array is freed through the allocator that made it) and,
 * where it tracks them, the elements in use; the array itself only knows its room. Growth doubles from
 * a first capacity each owner chooses (its usual size), so an owner that reserves once in advance never
 * allocates afterwards. */
#ifndef RUGO_CORE_ARRAY_H
#define RUGO_CORE_ARRAY_H

#include "rugo/base.h"

#include <stddef.h>

typedef struct rugo__array {
    void* data;      /* capacity elements; NULL before the first reserve */
    size_t capacity; /* elements allocated */
} rugo__array;

/* Room for at least `need` elements of `elem` bytes: the capacity doubles from max(capacity, first)
 * until it holds `need`, and the old elements are copied over. RUGO_OK (also when there was room), or
 * RUGO_ERR_OUT_OF_MEMORY when the size overflows or the allocator fails; the array is then unchanged. */
rugo_status rugo__array_reserve(rugo__array* a, const rugo_allocator* al, size_t need, size_t elem,
                                size_t first);

/* Frees the elements (through the allocator that reserved them) and empties the array. */
void rugo__array_free(rugo__array* a, const rugo_allocator* al);

#endif
