/* libFuzzer target: the baked-shape loader on arbitrary bytes; a shape it accepts is queried and
 * baked again (which must give the same bytes: nothing is lost or invented on load). Random bytes
 * almost never carry a valid checksum, so each input is also loaded with its checksum field rewritten
 * to match (docs/baked.md: u64 at bytes 24..31, the word-wise checksum of the file with those bytes
 * taken as zero): that is what reaches the field checks behind the checksum. */
#include "fuzz_common.h"

#include <stdint.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

/* The checksum of docs/baked.md, written from the document (word by word, zero-padded). */
static uint64_t ck_round(uint64_t acc, uint64_t w) {
    acc += w * UINT64_C(0xC2B2AE3D27D4EB4F);
    acc = (acc << 31) | (acc >> 33);
    return acc * UINT64_C(0x9E3779B185EBCA87);
}
static uint64_t baked_checksum(const uint8_t* p, size_t n) {
    uint64_t lane[4] = {UINT64_C(0x9E3779B185EBCA87), UINT64_C(0xC2B2AE3D27D4EB4F),
                        UINT64_C(0x165667B19E3779F9), UINT64_C(0x85EBCA77C2B2AE63)};
    for (size_t i = 0; 8 * i < n; ++i) {
        uint64_t w = 0;
        for (size_t k = 0; k < 8; ++k) {
            const size_t at = 8 * i + k;
            w |= (uint64_t)(at < n && (at < 24 || at >= 32) ? p[at] : 0) << (8 * k);
        }
        lane[i % 4] = ck_round(lane[i % 4], w);
    }
    uint64_t h = (uint64_t)n;
    for (int l = 0; l < 4; ++l)
        h = ck_round(h, lane[l]);
    h ^= h >> 33;
    h *= UINT64_C(0xC2B2AE3D27D4EB4F);
    h ^= h >> 29;
    h *= UINT64_C(0x165667B19E3779F9);
    h ^= h >> 32;
    return h;
}

static void load_one(const uint8_t* data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    load_one(data, size);
    if (size >= 32) {
        uint8_t* fixed = (uint8_t*)malloc(size);
        if (fixed == NULL) return 0;
        memcpy(fixed, data, size);
        const uint64_t ck = baked_checksum(fixed, size);
        for (int i = 0; i < 8; ++i)
            fixed[24 + i] = (uint8_t)(ck >> (8 * i));
        load_one(fixed, size);
        free(fixed);
    }
    return 0;
}

static void load_one(const uint8_t* data, size_t size) {
    rugo_shape* shape = NULL;
    rugo_baked_error err;
    rugo_status st = rugo_shape_load_baked(data, size, NULL, &shape, &err);
    FUZZ_CHECK(memchr(err.field, '\0', sizeof err.field) != NULL);
    FUZZ_CHECK(memchr(err.message, '\0', sizeof err.message) != NULL);
    if (st != RUGO_OK) {
        FUZZ_CHECK(shape == NULL);
        FUZZ_CHECK(err.offset <= size || st == RUGO_ERR_TOO_LARGE);
        return;
    }
    size_t need = 0;
    FUZZ_CHECK(rugo_shape_bake_size(shape, &need) == RUGO_OK && need == size);
    unsigned char* again = (unsigned char*)malloc(need);
    size_t written = 0;
    if (again != NULL) {
        FUZZ_CHECK(rugo_shape_bake(shape, again, need, &written) == RUGO_OK);
        FUZZ_CHECK(memcmp(again, data, size) == 0);
        free(again);
    }
    fuzz_query_shape(shape, shape, rugo_identity_transform(), rugo_make_transform(0.05, -0.02, 0.7));
    rugo_shape_destroy(shape);
}
