/* librugo — biorthogonal cubic B-spline wavelets CDF(4, m~) on closed (periodic) control polygons
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
 * buffers); OUT_OF_MEMORY. Values are not checked for finiteness: NaN in, NaN out. */
#ifndef RUGO_WAVELET_H
#define RUGO_WAVELET_H

#include "rugo/base.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rugo_filter {
    RUGO_FILTER_CDF4_2 = 0,
    RUGO_FILTER_CDF4_4 = 1,
    RUGO_FILTER_CDF4_6 = 2,
    RUGO_FILTER_CDF4_8 = 3, /* the thesis' choice and the default */
    RUGO_FILTER_CDF4_12 = 4,
    RUGO_FILTER_COUNT
} rugo_filter;

#define RUGO_FILTER_DEFAULT RUGO_FILTER_CDF4_8

/* "cdf4.2", "cdf4.4", "cdf4.6", "cdf4.8", "cdf4.12"; NULL for an invalid value. */
const char* rugo_filter_name(rugo_filter f);
/* Parses a name as above; RUGO_ERR_BAD_FILTER if unknown. */
rugo_status rugo_filter_from_name(const char* name, rugo_filter* out);

/* Half-filters (index 0 = centre, symmetric), exact values as doubles, for inspection and tests:
 * a: analysis scaling (lowpass), b: analysis wavelet, p: synthesis scaling, q: synthesis wavelet.
 * Each pointer may be NULL; *count receives the half-length. RUGO_ERR_BAD_FILTER if f is invalid. */
typedef enum rugo_filter_part { RUGO_FILTER_A, RUGO_FILTER_B, RUGO_FILTER_P, RUGO_FILTER_Q } rugo_filter_part;
rugo_status rugo_filter_taps(rugo_filter f, rugo_filter_part part, const rugo_real** taps, int* count);

/* One analysis step. fine has 2*half points; coarse and detail receive half points each.
 * half >= 2 (4 fine points at least); buffers must not overlap. */
rugo_status rugo_wavelet_analyze(rugo_filter f, const rugo_vec2* fine, int half, rugo_vec2* coarse,
                                 rugo_vec2* detail);

/* One synthesis step: coarse and detail (half points each) to fine (2*half points). detail may be
 * NULL, meaning zero details (refinement). Buffers must not overlap. */
rugo_status rugo_wavelet_synthesize(rugo_filter f, const rugo_vec2* coarse, const rugo_vec2* detail,
                                    int half, rugo_vec2* fine);

/* Refinement: synthesis with zero details (equals cubic B-spline subdivision). */
rugo_status rugo_wavelet_refine(const rugo_vec2* coarse, int half, rugo_vec2* fine);

/* Multi-level analysis in place. data holds n = 2^J points. After the call, for levels = K:
 * data[0 .. n/2^K) are the coarsest points C^{J-K}, followed by the details D^{J-K} (n/2^K points),
 * then D^{J-K+1} (n/2^{K-1}), ..., D^{J-1} (n/2): the standard pyramid layout. n / 2^K >= 4.
 * scratch must hold n points (or be NULL, and then the call allocates through allocator). */
rugo_status rugo_wavelet_analyze_levels(rugo_filter f, rugo_vec2* data, int n, int levels,
                                        rugo_vec2* scratch, const rugo_allocator* allocator);
/* Inverse of rugo_wavelet_analyze_levels. */
rugo_status rugo_wavelet_synthesize_levels(rugo_filter f, rugo_vec2* data, int n, int levels,
                                           rugo_vec2* scratch, const rugo_allocator* allocator);

#ifdef __cplusplus
}
#endif

#endif
