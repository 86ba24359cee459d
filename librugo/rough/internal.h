/* Private helpers of the rough layer for the layers above it. Not installed. May include: core, curve.
 *
 * The checks of a roughness description's arc-length sources (roughness_resample.c), shared by the
 * resampling, the shape-file writer, and the shape-file and CSV readers, which report the offending
 * member: one definition of a valid range or profile for all of them. Each returns RUGO_OK or the
 * status the readers report (BAD_FIELD for a value out of its range; the writer and the resampling turn
 * that into BAD_ARGUMENT), with the offending member and a message. */
#ifndef RUGO_ROUGH_INTERNAL_H
#define RUGO_ROUGH_INTERNAL_H

#include "rugo/shape_file.h"

#include <stddef.h>

/* Member of a range: 0 from, 1 to, 2 tolerance (-1: the range as a whole). */
rugo_status rugo__roughness_range_check(const rugo_roughness_range* g, int* member_index, char* msg,
                                        size_t size);

/* Sample `cur` of a profile after `prev` (NULL for the first); *column: 0 for s, 1 for λ. */
rugo_status rugo__roughness_sample_check(const rugo_profile_sample* prev, const rugo_profile_sample* cur,
                                         int* column, char* msg, size_t size);

/* The whole source of kind RANGES or PROFILE, for the writer and the resampling (statuses as
 * documented there: BAD_ARGUMENT where the reader says BAD_FIELD). */
rugo_status rugo__roughness_arc_source_check(const rugo_roughness_desc* r);

/* λ(t) on segment `segment` (wrapping) as rugo_tolerance_at interpolates it (tolerance.c), before its
 * clamp: two cubics, over t in [0, 1/2] and [1/2, 1], each as Bernstein coefficients in its own
 * parameter (2t and 2t - 1). The contact queries at a resolution carry the band this way. */
void rugo__tolerance_halves(const rugo_real* lambda, int count, int segment, rugo_real out[2][4]);

#endif
