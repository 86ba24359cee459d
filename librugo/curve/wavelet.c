/* Biorthogonal cubic B-spline wavelets CDF(4, m~) on periodic control polygons (SPEC 2.1-2.2).
 *
 * Every coefficient below is an exact dyadic rational (numerator < 2^53, power-of-two denominator),
 * so the tables hold the exact filter values, not the 6-digit ones printed in the thesis.
 *
 * The transform is the periodisation of the infinite one: every index is taken modulo the level's
 * size and every term of the sums is kept, so a filter longer than the level wraps around and its
 * taps on the same sample add up. Synthesis after analysis is the identity for any period because
 * the infinite identity is a finite polynomial identity in the shift operator that commutes with
 * periodisation; perfect reconstruction therefore holds down to 4 fine points (half = 2) for every
 * filter, and the tests check it there. Single steps accept any half >= 2 (not only powers of two).
 *
 * The transform does not inspect values: a NaN or infinity in the input propagates to the output
 * (callers that need finite results validate first, as the pyramid does). */
#include "rugo/wavelet.h"

#include "core/internal.h"

#include <stdint.h>
#include <string.h>

/* ---- Filter tables (SPEC 2.1). Half-filters, index 0 = centre. ------------------------------- */

/* a: analysis scaling (Aa). */
static const rugo_real A2[] = {5.0 / 4.0, 5.0 / 32.0, -3.0 / 8.0, 3.0 / 32.0};
static const rugo_real A4[] = {35.0 / 32.0, 35.0 / 128.0, -3.0 / 8.0, -1.0 / 256.0, 5.0 / 64.0, -5.0 / 256.0};
static const rugo_real A6[] = {525.0 / 512.0,  2625.0 / 8192.0, -733.0 / 2048.0, -557.0 / 8192.0,
                               115.0 / 1024.0, -55.0 / 8192.0,  -35.0 / 2048.0,  35.0 / 8192.0};
static const rugo_real A8[] = {8085.0 / 8192.0, 11319.0 / 32768.0, -1403.0 / 4096.0, -1807.0 / 16384.0,
                               523.0 / 4096.0,  205.0 / 16384.0,   -133.0 / 4096.0,  217.0 / 65536.0,
                               63.0 / 16384.0,  -63.0 / 65536.0};
static const rugo_real A12[] = {495495.0 / 524288.0,    778635.0 / 2097152.0, -5249.0 / 16384.0,
                                -1354283.0 / 8388608.0, 288995.0 / 2097152.0, 401465.0 / 8388608.0,
                                -3415.0 / 65536.0,      -32543.0 / 4194304.0, 15153.0 / 1048576.0,
                                -1095.0 / 4194304.0,    -165.0 / 65536.0,     3135.0 / 8388608.0,
                                429.0 / 2097152.0,      -429.0 / 8388608.0};

/* q = 2 Qq, Qq_i = (-1)^i Aa_i. Doubling a double is exact, so these equal the exact values. */
#define Q2(i, v) ((((i) % 2) ? -2.0 : 2.0) * (v))
static const rugo_real Q2_[] = {Q2(0, 5.0 / 4.0), Q2(1, 5.0 / 32.0), Q2(2, -3.0 / 8.0), Q2(3, 3.0 / 32.0)};
static const rugo_real Q4_[] = {Q2(0, 35.0 / 32.0),  Q2(1, 35.0 / 128.0), Q2(2, -3.0 / 8.0),
                                Q2(3, -1.0 / 256.0), Q2(4, 5.0 / 64.0),   Q2(5, -5.0 / 256.0)};
static const rugo_real Q6_[] = {Q2(0, 525.0 / 512.0),   Q2(1, 2625.0 / 8192.0), Q2(2, -733.0 / 2048.0),
                                Q2(3, -557.0 / 8192.0), Q2(4, 115.0 / 1024.0),  Q2(5, -55.0 / 8192.0),
                                Q2(6, -35.0 / 2048.0),  Q2(7, 35.0 / 8192.0)};
static const rugo_real Q8_[] = {Q2(0, 8085.0 / 8192.0),   Q2(1, 11319.0 / 32768.0), Q2(2, -1403.0 / 4096.0),
                                Q2(3, -1807.0 / 16384.0), Q2(4, 523.0 / 4096.0),    Q2(5, 205.0 / 16384.0),
                                Q2(6, -133.0 / 4096.0),   Q2(7, 217.0 / 65536.0),   Q2(8, 63.0 / 16384.0),
                                Q2(9, -63.0 / 65536.0)};
static const rugo_real Q12_[] = {
    Q2(0, 495495.0 / 524288.0),    Q2(1, 778635.0 / 2097152.0), Q2(2, -5249.0 / 16384.0),
    Q2(3, -1354283.0 / 8388608.0), Q2(4, 288995.0 / 2097152.0), Q2(5, 401465.0 / 8388608.0),
    Q2(6, -3415.0 / 65536.0),      Q2(7, -32543.0 / 4194304.0), Q2(8, 15153.0 / 1048576.0),
    Q2(9, -1095.0 / 4194304.0),    Q2(10, -165.0 / 65536.0),    Q2(11, 3135.0 / 8388608.0),
    Q2(12, 429.0 / 2097152.0),     Q2(13, -429.0 / 8388608.0)};
#undef Q2

/* b_i = (-1)^i Pq_i, Pq = [3/8, 1/4, 1/16]; p = 2 Pq (full p = (1, 4, 6, 4, 1)/8). Common to all. */
static const rugo_real B_[] = {3.0 / 8.0, -1.0 / 4.0, 1.0 / 16.0};
static const rugo_real P_[] = {3.0 / 4.0, 1.0 / 2.0, 1.0 / 8.0};

typedef struct filter_info {
    const char* name;
    const rugo_real* a;
    const rugo_real* q;
    int a_count; /* half-length of a and of q */
} filter_info;

#define COUNT_OF(x) ((int)(sizeof(x) / sizeof((x)[0])))
static const filter_info FILTERS[RUGO_FILTER_COUNT] = {
    {"cdf4.2", A2, Q2_, COUNT_OF(A2)},     {"cdf4.4", A4, Q4_, COUNT_OF(A4)},
    {"cdf4.6", A6, Q6_, COUNT_OF(A6)},     {"cdf4.8", A8, Q8_, COUNT_OF(A8)},
    {"cdf4.12", A12, Q12_, COUNT_OF(A12)},
};
#define P_COUNT COUNT_OF(P_)
#define B_COUNT COUNT_OF(B_)

static int filter_valid(rugo_filter f) { return (int)f >= 0 && (int)f < (int)RUGO_FILTER_COUNT; }

const char* rugo_filter_name(rugo_filter f) { return filter_valid(f) ? FILTERS[f].name : NULL; }

rugo_status rugo_filter_from_name(const char* name, rugo_filter* out) {
    if (name == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    for (int i = 0; i < (int)RUGO_FILTER_COUNT; ++i) {
        if (strcmp(name, FILTERS[i].name) == 0) {
            *out = (rugo_filter)i;
            return RUGO_OK;
        }
    }
    return RUGO_ERR_BAD_FILTER;
}

rugo_status rugo_filter_taps(rugo_filter f, rugo_filter_part part, const rugo_real** taps, int* count) {
    if (!filter_valid(f)) return RUGO_ERR_BAD_FILTER;
    const rugo_real* t;
    int c;
    switch (part) {
    case RUGO_FILTER_A:
        t = FILTERS[f].a;
        c = FILTERS[f].a_count;
        break;
    case RUGO_FILTER_B:
        t = B_;
        c = B_COUNT;
        break;
    case RUGO_FILTER_P:
        t = P_;
        c = P_COUNT;
        break;
    case RUGO_FILTER_Q:
        t = FILTERS[f].q;
        c = FILTERS[f].a_count;
        break;
    default:
        return RUGO_ERR_BAD_ARGUMENT;
    }
    if (taps) *taps = t;
    if (count) *count = c;
    return RUGO_OK;
}

/* ---- Single steps --------------------------------------------------------------------------- */

/* 1 if the byte ranges [a, a + na) and [b, b + nb) overlap. Compared as integers: the buffers may be
 * unrelated objects, where relational pointer comparison is undefined. */
static int overlaps(const void* a, size_t na, const void* b, size_t nb) {
    uintptr_t pa = (uintptr_t)a, pb = (uintptr_t)b;
    return pa < pb + nb && pb < pa + na;
}

static rugo_status check_step(rugo_filter f, int half) {
    if (!filter_valid(f)) return RUGO_ERR_BAD_FILTER;
    if (half < 2) return RUGO_ERR_TOO_FEW_POINTS;
    if (half > RUGO_MAX_CONTROL_POINTS / 2) return RUGO_ERR_TOO_MANY_POINTS;
    return RUGO_OK;
}

/* Cyclic index with a cheap test first: inside the level (the common case) no division is needed.
 * Same arithmetic either way, so results are bit-identical to plain wrapping. */
static inline int wrap_near(int i, int n) { return (unsigned)i < (unsigned)n ? i : rugo__wrap(i, n); }

/* Unchecked kernels (arguments validated by the callers). */
static void analyze_step(const filter_info* fi, const rugo_vec2* x, int half, rugo_vec2* c, rugo_vec2* d) {
    const int n = 2 * half;
    const rugo_real* a = fi->a;
    const int na = fi->a_count;
    for (int s = 0; s < half; ++s) {
        /* (2.27): c_s = a_0 x_{2s} + sum_{i>=1} a_i (x_{2s-i} + x_{2s+i}) */
        const int ce = 2 * s;
        rugo_real cx = a[0] * x[ce].x, cy = a[0] * x[ce].y;
        for (int i = 1; i < na; ++i) {
            const rugo_vec2 l = x[wrap_near(ce - i, n)], r = x[wrap_near(ce + i, n)];
            cx += a[i] * (l.x + r.x);
            cy += a[i] * (l.y + r.y);
        }
        c[s] = rugo_v2(cx, cy);
        /* (2.28, corrected): d_s = b_0 x_{2s-1} + sum_{i>=1} b_i (x_{2s-1-i} + x_{2s-1+i}) */
        const int co = ce - 1;
        rugo_vec2 m = x[wrap_near(co, n)];
        rugo_real dx = B_[0] * m.x, dy = B_[0] * m.y;
        for (int i = 1; i < B_COUNT; ++i) {
            const rugo_vec2 l = x[wrap_near(co - i, n)], r = x[wrap_near(co + i, n)];
            dx += B_[i] * (l.x + r.x);
            dy += B_[i] * (l.y + r.y);
        }
        d[s] = rugo_v2(dx, dy);
    }
}

static void synthesize_step(const filter_info* fi, const rugo_vec2* c, const rugo_vec2* d, int half,
                            rugo_vec2* x) {
    const rugo_real* q = fi->q;
    const int nq = fi->a_count;
    for (int s = 0; s < half; ++s) {
        /* (2.29, corrected), even output:
         * x_{2s} = p_0 c_s + sum_{i>=1} p_{2i} (c_{s-i} + c_{s+i}) + sum_{i>=0} q_{2i+1} (d_{s-i} +
         * d_{s+i+1}) */
        rugo_real ex = P_[0] * c[s].x, ey = P_[0] * c[s].y;
        for (int i = 1; 2 * i < P_COUNT; ++i) {
            const rugo_vec2 l = c[wrap_near(s - i, half)], r = c[wrap_near(s + i, half)];
            ex += P_[2 * i] * (l.x + r.x);
            ey += P_[2 * i] * (l.y + r.y);
        }
        /* odd output:
         * x_{2s+1} = sum_{i>=0} p_{2i+1} (c_{s-i} + c_{s+i+1}) + q_0 d_{s+1} + sum_{i>=1} q_{2i} (d_{s+1-i} +
         * d_{s+1+i}) */
        rugo_real ox = 0.0, oy = 0.0;
        for (int i = 0; 2 * i + 1 < P_COUNT; ++i) {
            const rugo_vec2 l = c[wrap_near(s - i, half)], r = c[wrap_near(s + i + 1, half)];
            ox += P_[2 * i + 1] * (l.x + r.x);
            oy += P_[2 * i + 1] * (l.y + r.y);
        }
        if (d != NULL) {
            for (int i = 0; 2 * i + 1 < nq; ++i) {
                const rugo_vec2 l = d[wrap_near(s - i, half)], r = d[wrap_near(s + i + 1, half)];
                ex += q[2 * i + 1] * (l.x + r.x);
                ey += q[2 * i + 1] * (l.y + r.y);
            }
            const rugo_vec2 m = d[wrap_near(s + 1, half)];
            ox += q[0] * m.x;
            oy += q[0] * m.y;
            for (int i = 1; 2 * i < nq; ++i) {
                const rugo_vec2 l = d[wrap_near(s + 1 - i, half)], r = d[wrap_near(s + 1 + i, half)];
                ox += q[2 * i] * (l.x + r.x);
                oy += q[2 * i] * (l.y + r.y);
            }
        }
        x[2 * s] = rugo_v2(ex, ey);
        x[2 * s + 1] = rugo_v2(ox, oy);
    }
}

rugo_status rugo_wavelet_analyze(rugo_filter f, const rugo_vec2* fine, int half, rugo_vec2* coarse,
                                 rugo_vec2* detail) {
    if (fine == NULL || coarse == NULL || detail == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_step(f, half);
    if (st != RUGO_OK) return st;
    const size_t hb = (size_t)half * sizeof(rugo_vec2);
    if (overlaps(fine, 2 * hb, coarse, hb) || overlaps(fine, 2 * hb, detail, hb) ||
        overlaps(coarse, hb, detail, hb))
        return RUGO_ERR_BAD_ARGUMENT;
    analyze_step(&FILTERS[f], fine, half, coarse, detail);
    return RUGO_OK;
}

rugo_status rugo_wavelet_synthesize(rugo_filter f, const rugo_vec2* coarse, const rugo_vec2* detail, int half,
                                    rugo_vec2* fine) {
    if (coarse == NULL || fine == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_step(f, half);
    if (st != RUGO_OK) return st;
    const size_t hb = (size_t)half * sizeof(rugo_vec2);
    if (overlaps(fine, 2 * hb, coarse, hb) || (detail != NULL && overlaps(fine, 2 * hb, detail, hb)))
        return RUGO_ERR_BAD_ARGUMENT;
    synthesize_step(&FILTERS[f], coarse, detail, half, fine);
    return RUGO_OK;
}

rugo_status rugo_wavelet_refine(const rugo_vec2* coarse, int half, rugo_vec2* fine) {
    /* Zero details: only p, which every filter shares. */
    return rugo_wavelet_synthesize(RUGO_FILTER_DEFAULT, coarse, NULL, half, fine);
}

/* ---- Multi-level ---------------------------------------------------------------------------- */

static rugo_status check_levels(rugo_filter f, const rugo_vec2* data, int n, int levels) {
    if (data == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (!filter_valid(f)) return RUGO_ERR_BAD_FILTER;
    if (n < 4) return RUGO_ERR_TOO_FEW_POINTS;
    if (n > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    if (!rugo__is_power_of_two(n)) return RUGO_ERR_NOT_POWER_OF_TWO;
    /* n / 2^levels >= 4, i.e. levels <= log2(n) - 2. */
    if (levels < 0 || levels > 30 || (n >> levels) < 4) return RUGO_ERR_BAD_LEVEL;
    return RUGO_OK;
}

typedef enum { DIR_ANALYZE, DIR_SYNTHESIZE } direction;

static rugo_status run_levels(direction dir, rugo_filter f, rugo_vec2* data, int n, int levels,
                              rugo_vec2* scratch, const rugo_allocator* allocator) {
    rugo_status st = check_levels(f, data, n, levels);
    if (st != RUGO_OK) return st;
    if (levels == 0) return RUGO_OK;
    rugo_vec2* buf = scratch;
    if (buf == NULL) {
        buf = (rugo_vec2*)rugo__alloc_array(allocator, (size_t)n, sizeof(rugo_vec2));
        if (buf == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    } else if (overlaps(buf, (size_t)n * sizeof(rugo_vec2), data, (size_t)n * sizeof(rugo_vec2))) {
        return RUGO_ERR_BAD_ARGUMENT;
    }
    const filter_info* fi = &FILTERS[f];
    if (dir == DIR_ANALYZE) {
        /* data[0, len) -> coarse in data[0, len/2), detail in data[len/2, len). */
        for (int k = 0, len = n; k < levels; ++k, len /= 2) {
            const int half = len / 2;
            analyze_step(fi, data, half, buf, buf + half);
            memcpy(data, buf, (size_t)len * sizeof(rugo_vec2));
        }
    } else {
        for (int len = n >> (levels - 1); len <= n; len *= 2) {
            const int half = len / 2;
            synthesize_step(fi, data, data + half, half, buf);
            memcpy(data, buf, (size_t)len * sizeof(rugo_vec2));
        }
    }
    if (scratch == NULL) rugo__free(allocator, buf);
    return RUGO_OK;
}

rugo_status rugo_wavelet_analyze_levels(rugo_filter f, rugo_vec2* data, int n, int levels, rugo_vec2* scratch,
                                        const rugo_allocator* allocator) {
    return run_levels(DIR_ANALYZE, f, data, n, levels, scratch, allocator);
}

rugo_status rugo_wavelet_synthesize_levels(rugo_filter f, rugo_vec2* data, int n, int levels,
                                           rugo_vec2* scratch, const rugo_allocator* allocator) {
    return run_levels(DIR_SYNTHESIZE, f, data, n, levels, scratch, allocator);
}
