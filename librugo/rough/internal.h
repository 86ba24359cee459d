/* Private helpers of the rough layer (tolerance.c) for the layers above it. Not installed.
 * May include: core, curve. */
#ifndef RUGO_ROUGH_INTERNAL_H
#define RUGO_ROUGH_INTERNAL_H

#include "rugo/base.h"

/* λ(t) on segment `segment` (wrapping) as rugo_tolerance_at interpolates it, before its clamp: two
 * cubics, over t in [0, 1/2] and [1/2, 1], each as Bernstein coefficients in its own parameter
 * (2t and 2t - 1). */
void rugo__tolerance_halves(const rugo_real* lambda, int count, int segment, rugo_real out[2][4]);

#endif
