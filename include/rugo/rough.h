/** @file rugo/rough.h
 * librugo — roughness: the tolerance library and generators of perturbations (SPEC 4; thesis 2.4, 5.2).
 *
 * A rough surface is described statistically: every finest segment j carries a tolerance λ_j (a length,
 * in the shape's units), the half-width of a band around the curve within which its asperities lie
 * with high probability; λ = q σ with σ the standard deviation of the asperities normal to the curve
 * (5.2). Collision uses the tolerances. Explicit perturbation geometry is optional and for display
 * (thesis 5.2: "explicitar as rugosidades ... afeta somente a visualização").
 *
 * Everything here is deterministic: the same inputs and seed give the same bits (random.h).
 * Ownership: output arrays are caller-owned (n values or count << levels points); only rugo_roughen
 * allocates, through its def's allocator, and frees before it returns. */
#ifndef RUGO_ROUGH_H
#define RUGO_ROUGH_H

#include "rugo/base.h"
#include "rugo/random.h"
#include "rugo/wavelet.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The thesis' band factor: λ = q σ with q = 0.95 (5.2). Note P(|Z| <= 0.95) = 0.658 for a normal Z, so
 * about a third of the asperities lie outside such a band; q = 1.96 would give a 95% band. */
#define RUGO_DEFAULT_Q 0.95

/* ---- the tolerance library ---------------------------------------------------------------------- */

/** The thesis' tolerance library (Fig. 5.5), values in the thesis' length units (its objects are
 * tens of units across): scale them to your shapes. */
typedef enum rugo_tolerance_preset {
    RUGO_PRESET_TIPO_1 = 0, /**< constant 0.25 on every segment ("atrito constante", Fig. 7.5) */
    RUGO_PRESET_TIPO_2 = 1, /**< varied: seeded blocks, see rugo_tolerances_preset */
    RUGO_PRESET_TIPO_3 = 2, /**< 0.32 0.24 0.20 0.24, repeating (Fig. 5.5) */
    RUGO_PRESET_TIPO_5 = 3, /**< 0.55 x4, 0.04 x4, 0.65 x4, 0.04 x4, repeating (Fig. 5.5) */
    RUGO_PRESET_COUNT       /**< the number of presets (not a preset) */
} rugo_tolerance_preset;

/** The size (the larger side of the bounds, length units) the presets' values are for: the thesis'
 * objects measure about a hundred units, so tipo_5's bands of 0.04-0.65 are 0.04%-0.65% of the size.
 * `rugo roughen --preset` multiplies them by size / RUGO_PRESET_REFERENCE_SIZE unless --absolute: on a
 * 1 m rock, tipo_5 gives bands of 0.4-6.5 mm, in the range of the default friction map (tolerance.h). */
#define RUGO_PRESET_REFERENCE_SIZE 100.0

/** The preset's name, "tipo_1", "tipo_2", "tipo_3" or "tipo_5" (a static string); NULL for an invalid
 * value. */
RUGO_API const char* rugo_preset_name(rugo_tolerance_preset p);
/** Parses a preset name as above into *out. Errors: NULL_ARGUMENT, BAD_ARGUMENT (unknown name). */
RUGO_API rugo_status rugo_preset_from_name(const char* name, rugo_tolerance_preset* out);

/** Fills out[0..n) with a preset. tipo_2 is the only seeded one: consecutive blocks of 1 to 4 segments
 * (length uniform), each with a value uniform in [0.04, 0.65] (the range of the thesis' library),
 * drawn from rugo_rng seeded with `seed`; the other presets ignore the seed. Patterns start at
 * segment 0 exactly as in Fig. 5.5. Errors: NULL_ARGUMENT, BAD_ARGUMENT (bad preset), TOO_FEW_POINTS
 * (n < 1), TOO_MANY_POINTS. */
RUGO_API rugo_status rugo_tolerances_preset(rugo_tolerance_preset p, uint64_t seed, int n, rugo_real* out);

/** The same tolerance `value` (length units) on all n segments: out[0..n) (caller-owned). The
 * constructors below validate their values (NOT_FINITE, NEGATIVE_TOLERANCE) and counts
 * (TOO_FEW_POINTS for n < 1, TOO_MANY_POINTS), and return NULL_ARGUMENT for a NULL array. */
RUGO_API rugo_status rugo_tolerances_constant(rugo_real value, int n, rugo_real* out);
/** out[i] = pattern[i mod period]. BAD_ARGUMENT for period < 1. */
RUGO_API rugo_status rugo_tolerances_pattern(const rugo_real* pattern, int period, int n, rugo_real* out);
/** values[0] on the first block_length segments, values[1] on the next, ..., cycling through values
 * (count of them). BAD_ARGUMENT for count < 1 or block_length < 1. */
RUGO_API rugo_status rugo_tolerances_blocks(const rugo_real* values, int count, int block_length, int n,
                                            rugo_real* out);
/** Independent uniform values in [lo, hi] from rugo_rng seeded with `seed` (EMPTY_RANGE if lo > hi,
 * NEGATIVE_TOLERANCE if lo < 0). */
RUGO_API rugo_status rugo_tolerances_random(rugo_real lo, rugo_real hi, uint64_t seed, int n, rugo_real* out);
/** Validates caller-supplied values per segment: NULL_ARGUMENT, TOO_FEW_POINTS, NOT_FINITE,
 * NEGATIVE_TOLERANCE (the index of the first bad value goes to *bad_index if not NULL). */
RUGO_API rugo_status rugo_tolerances_check(const rugo_real* values, int n, int* bad_index);

/* ---- perturbation generators -------------------------------------------------------------------- */

/** How rugo_roughen generates perturbation geometry. */
typedef enum rugo_roughen_method {
    RUGO_ROUGHEN_WAVELET = 0, /**< add levels above the finest with N(0, σ²) details (2.32, Fig. 2.12) */
    RUGO_ROUGHEN_LOCAL = 1    /**< refine and push segment midpoints along the normal (Fig. 2.13) */
} rugo_roughen_method;

/** What rugo_roughen needs. Start from rugo_default_roughen_def(); points and tolerances are borrowed
 * for the call only. */
typedef struct rugo_roughen_def {
    const rugo_vec2* points;     /**< the contour f^n: count control points, counter-clockwise, count = 2^J */
    int count;                   /**< number of control points, a power of two >= 4 */
    const rugo_real* tolerances; /**< λ per segment of f^n (count values); σ = λ / q per segment */
    rugo_real q;                 /**< default RUGO_DEFAULT_Q */
    rugo_roughen_method method;  /**< default RUGO_ROUGHEN_WAVELET */
    int levels;         /**< levels added (wavelet) or refine-and-push rounds (local); >= 1, default 2 */
    rugo_filter filter; /**< wavelet method's synthesis filter; default RUGO_FILTER_DEFAULT */
    uint64_t seed;      /**< seed of the rugo_rng that draws the perturbations; default 0 */
    rugo_allocator allocator; /**< for working space; zeroed = malloc/free */
    int cookie;               /**< set by rugo_default_roughen_def; catches uninitialised defs */
} rugo_roughen_def;

/** A def with the defaults above and its cookie set; fill in points, count and tolerances. */
RUGO_API rugo_roughen_def rugo_default_roughen_def(void);

/** Generates perturbation geometry: out receives count << levels control points (caller-owned).
 *   wavelet: for each added level, details d_s = (0, N(0, σ²)) in the local frame (tangent, outward
 *            normal) of the current curve at the detail's segment midpoint (as multires.h), σ of the
 *            original segment the detail lies on; then one synthesis step.
 *   local:   each round refines the current contour once (synthesis with zero details), then moves
 *            the midpoint of every segment of the contour as it was before the round along its
 *            outward normal by N(0, σ²) with the least-norm control point change (2.30), σ of the
 *            original segment it lies on (thesis 2.4: the process repeats on the resulting contour,
 *            so the pushes double every round).
 * One Gaussian is drawn per perturbation, in a fixed order (level or round, then detail index or
 * segment), even where σ = 0, so one segment's noise does not depend on the others' tolerances.
 * Clockwise input works (the normal is flipped to point outward). out may alias def->points.
 * λ = q σ is a band on the drawn coefficients, not on the generated curve: the curve's RMS normal
 * deviation is about 0.95 σ (wavelet) / 0.83 σ (local) after one level and grows with more levels
 * (1.35 σ / 1.18 σ after two), so the fraction of generated geometry inside ±λ is not P(|Z| <= q).
 * Errors: NULL_ARGUMENT, BAD_ARGUMENT (cookie, method, levels < 1 or output beyond
 * RUGO_MAX_CONTROL_POINTS), TOO_FEW_POINTS, TOO_MANY_POINTS, NOT_POWER_OF_TWO, NOT_FINITE (input,
 * or a result that overflows; out is then untouched), NEGATIVE_TOLERANCE, BAD_QUANTILE, BAD_FILTER
 * (checked for both methods), OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_roughen(const rugo_roughen_def* def, rugo_vec2* out);

#ifdef __cplusplus
}
#endif

#endif
