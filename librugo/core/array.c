/* The growable array (core/array.h). */
#include "core/array.h"

#include "core/internal.h"

rugo_status rugo__array_reserve(rugo__array* a, const rugo_allocator* al, size_t need, size_t elem,
                                size_t first) {
    if (need <= a->capacity) return RUGO_OK;
    if (elem == 0) return RUGO_ERR_OUT_OF_MEMORY;
    size_t n = a->capacity > first ? a->capacity : (first > 0 ? first : 1);
    while (n < need) {
        if (n > ((size_t)-1) / 4 / elem) return RUGO_ERR_OUT_OF_MEMORY;
        n *= 2;
    }
    void* p = rugo__alloc_array(al, n, elem);
    if (p == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    if (a->data != NULL) {
        memcpy(p, a->data, a->capacity * elem);
        rugo__free(al, a->data);
    }
    a->data = p;
    a->capacity = n;
    return RUGO_OK;
}

void rugo__array_free(rugo__array* a, const rugo_allocator* al) {
    rugo__free(al, a->data);
    a->data = NULL;
    a->capacity = 0;
}
