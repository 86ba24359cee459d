/** @file rugo/wavelet.h
 * librugo — biorthogonal cubic B-spline wavelets CDF(4, m~) on closed (periodic) control polygons
 * (SPEC 2.1-2.2, thesis Appendix A with exact rational coefficients and corrected formulas 2.27-2.29).
 *
 * One analysis step maps 2m fine points C^j to m coarse points C^{j-1} and m details D^{j-1};
 * synthesis inverts it to round-off. d_s is centred at fine index 2s-1. The analysis lowpass sums to 1
 * (so coarse points keep the mean). Refinement is synthesis with zero details: it doubles the points
 * and leaves the curve unchanged (cubic B-spline subdivision).
 *
 * Filters longer than a level wrap around periodically; perfect reconstruction still holds down to 4
 * points for every filter (tested). Errors: NULL_ARGUMENT; TOO_FEW_POINTS (half < 2);
 * TOO_MANY_POINTS (beyond RUGO_MAX_CONTROL_POINTS); NOT_POWER_OF_TWO (multi-level n); BAD_LEVEL
 * (levels < 0 or n / 2^levels < 4; levels = 0 is a no-op); BAD_FILTER; BAD_ARGUMENT (overlapping
 * buffers); OUT_OF_MEMORY. Values are not checked for finiteness: NaN in, NaN out.
 *
 * Ownership: all point buffers belong to the caller; only the multi-level functions allocate, and only
 * when given no scratch (freed before they return). Coordinates are in the caller's length units. */
#ifndef RUGO_WAVELET_H
#define RUGO_WAVELET_H

#include "rugo/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The wavelet filters: CDF(4, m~), the cubic B-spline (4) with an analysis filter of m~ vanishing
 * moments; longer filters give smoother coarse levels and cost more. */
typedef enum rugo_filter {
    RUGO_FILTER_CDF4_2 = 0,  /**< CDF(4, 2), the shortest */
    RUGO_FILTER_CDF4_4 = 1,  /**< CDF(4, 4) */
    RUGO_FILTER_CDF4_6 = 2,  /**< CDF(4, 6) */
    RUGO_FILTER_CDF4_8 = 3,  /**< the thesis' choice and the default */
    RUGO_FILTER_CDF4_12 = 4, /**< CDF(4, 12), the longest */
    RUGO_FILTER_COUNT        /**< the number of filters (not a filter) */
} rugo_filter;

/** The default filter of every def: CDF(4, 8), the thesis' choice. */
#define RUGO_FILTER_DEFAULT RUGO_FILTER_CDF4_8

/** The filter's name, "cdf4.2", "cdf4.4", "cdf4.6", "cdf4.8" or "cdf4.12" (a static string); NULL for
 * an invalid value. */
RUGO_API const char* rugo_filter_name(rugo_filter f);
/** Parses a name as above into *out. Errors: NULL_ARGUMENT (name or out NULL), BAD_FILTER (unknown
 * name; *out is left unchanged). */
RUGO_API rugo_status rugo_filter_from_name(const char* name, rugo_filter* out);

/** Half-filters (index 0 = centre, symmetric), exact values as doubles, for inspection and tests:
 * a: analysis scaling (lowpass), b: analysis wavelet, p: synthesis scaling, q: synthesis wavelet.
 * *taps points to static data (never free it); each pointer may be NULL; *count receives the
 * half-length. Errors: BAD_FILTER (invalid f), BAD_ARGUMENT (invalid part). */
typedef enum rugo_filter_part {
    RUGO_FILTER_A, /**< analysis scaling filter (lowpass; sums to 1) */
    RUGO_FILTER_B, /**< analysis wavelet filter */
    RUGO_FILTER_P, /**< synthesis scaling filter (cubic B-spline subdivision) */
    RUGO_FILTER_Q  /**< synthesis wavelet filter */
} rugo_filter_part;
/** Writes the half-filter `part` of filter f to *taps and *count; see rugo_filter_part. */
RUGO_API rugo_status rugo_filter_taps(rugo_filter f, rugo_filter_part part, const rugo_real** taps,
                                      int* count);

/** One analysis step. fine has 2*half points; coarse and detail receive half points each.
 * half >= 2 (4 fine points at least); buffers must not overlap. */
RUGO_API rugo_status rugo_wavelet_analyze(rugo_filter f, const rugo_vec2* fine, int half, rugo_vec2* coarse,
                                          rugo_vec2* detail);

/** One synthesis step: coarse and detail (half points each) to fine (2*half points). detail may be
 * NULL, meaning zero details (refinement). Buffers must not overlap. */
RUGO_API rugo_status rugo_wavelet_synthesize(rugo_filter f, const rugo_vec2* coarse, const rugo_vec2* detail,
                                             int half, rugo_vec2* fine);

/** Refinement: synthesis with zero details (equals cubic B-spline subdivision; the curve does not
 * change). coarse has half points, fine receives 2*half (caller-owned, not overlapping). Errors as
 * rugo_wavelet_synthesize. */
RUGO_API rugo_status rugo_wavelet_refine(const rugo_vec2* coarse, int half, rugo_vec2* fine);

/** Multi-level analysis in place. data holds n = 2^J points. After the call, for levels = K:
 * data[0 .. n/2^K) are the coarsest points C^{J-K}, followed by the details D^{J-K} (n/2^K points),
 * then D^{J-K+1} (n/2^{K-1}), ..., D^{J-1} (n/2): the standard pyramid layout. n / 2^K >= 4.
 * scratch must hold n points (or be NULL, and then the call allocates through allocator). */
RUGO_API rugo_status rugo_wavelet_analyze_levels(rugo_filter f, rugo_vec2* data, int n, int levels,
                                                 rugo_vec2* scratch, const rugo_allocator* allocator);
/** Inverse of rugo_wavelet_analyze_levels: data in the pyramid layout becomes the n finest points
 * again (round-off aside). Same arguments, scratch and errors. */
RUGO_API rugo_status rugo_wavelet_synthesize_levels(rugo_filter f, rugo_vec2* data, int n, int levels,
                                                    rugo_vec2* scratch, const rugo_allocator* allocator);

#ifdef __cplusplus
}
#endif

#endif
