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

#endif
