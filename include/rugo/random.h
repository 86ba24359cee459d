/** @file rugo/random.h
 * librugo — the seeded random generator used for roughness (and by anyone who wants reproducible
 * noise). Same seed, same sequence, bit for bit, on every run and every platform with IEEE doubles.
 *
 * Algorithm: xoshiro256** (Blackman & Vigna, 2018) for 64-bit words; its 256-bit state is filled from
 * the 64-bit seed by splitmix64, which never yields the all-zero state. Uniform doubles take the top
 * 53 bits. Gaussian samples use the Marsaglia polar method (two uniforms in the unit disc, one log and
 * one sqrt per pair, the second sample kept as a spare): no trigonometry, so the only libm calls are
 * log and sqrt — sqrt is exact in IEEE arithmetic; log is deterministic for a given libm.
 *
 * A generator is a plain value owned by the caller (no allocation); one generator must not be used by
 * two threads at once. The functions take a non-NULL generator (only rugo_rng_seed checks for NULL). */
#ifndef RUGO_RANDOM_H
#define RUGO_RANDOM_H

#include "rugo/base.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** The generator's state: a value type, seeded by rugo_rng_seed (an unseeded one must not be used). */
typedef struct rugo_rng {
    uint64_t state[4]; /**< xoshiro256** state, never all zero once seeded */
    rugo_real spare;   /**< the polar method's second sample */
    bool has_spare;    /**< true if spare holds an unused sample */
} rugo_rng;

/** Seeds the generator (any seed, including 0, is valid); does nothing for NULL. */
RUGO_API void rugo_rng_seed(rugo_rng* rng, uint64_t seed);
/** Next 64 random bits. */
RUGO_API uint64_t rugo_rng_next(rugo_rng* rng);
/** Uniform in [0, 1), multiples of 2^-53. */
RUGO_API rugo_real rugo_rng_uniform(rugo_rng* rng);
/** Uniform in [lo, hi] (hi itself can come out by rounding of lo + (hi - lo) u; when hi - lo overflows,
 * lo (1 - u) + hi u); not checked: NaN in, NaN out. */
RUGO_API rugo_real rugo_rng_range(rugo_rng* rng, rugo_real lo, rugo_real hi);
/** Uniform integer in [0, n) for n >= 1 (unbiased, by rejection). 0 if n < 1. */
RUGO_API uint32_t rugo_rng_below(rugo_rng* rng, uint32_t n);
/** Standard normal N(0, 1) (dimensionless; scale by σ). */
RUGO_API rugo_real rugo_rng_gaussian(rugo_rng* rng);

#ifdef __cplusplus
}
#endif

#endif
