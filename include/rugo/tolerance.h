/** @file rugo/tolerance.h
 * librugo — tolerances at every level, tolerance at a point, friction and restitution from roughness
 * (SPEC 6; thesis 5.3-5.5, 7.3).
 *
 * Two quantities per segment of every level j of a pyramid:
 *  - λ (total tolerance): a statistical band, λ = q σ. At the finest level it is the roughness input;
 *    at a coarser level it is the segment's own estimate from its perturbation (the detail between
 *    level j and j+1) plus the mean of its two finer segments' totals (5.3):
 *        λ^j_k = own^j_k + (λ^{j+1}_{2k} + λ^{j+1}_{2k+1}) / 2.
 *    Friction and restitution use λ. Being statistical, it is exceeded by some asperities.
 *  - β (hard bound): the largest distance of the finest curve plus its band from the segment,
 *    computed conservatively (Bezier hull bounds), so it is never exceeded. Boxes and certified
 *    level-of-detail errors use β. At the finest level β_k bounds λ(t) over the segment.
 * Lengths are in the shape's units; μ and ε are dimensionless.
 *
 * Ownership: rugo_tolerances is created by rugo_tolerances_create, owned by the caller and freed by
 * rugo_tolerances_destroy; it does not keep the pyramid or the input values. The level views it gives
 * point into it. The functions of λ(t), friction and restitution allocate nothing. */
#ifndef RUGO_TOLERANCE_H
#define RUGO_TOLERANCE_H

#include "rugo/base.h"
#include "rugo/multires.h"
#include "rugo/rough.h"

#ifdef __cplusplus
extern "C" {
#endif

/** How a coarser level's own tolerance is estimated from its perturbation (thesis 5.3). */
typedef enum rugo_tolerance_estimator {
    /** From wavelet coefficients (5.3.1): the normal components (local frames) of the 2k+1 details
     * nearest the segment — centred on the detail inserted inside it (fine index 2j+1, i.e. d_{j+1}
     * in SPEC 2.2's indexing) — give σ with mean 0; own = q σ. */
    RUGO_ESTIMATOR_COEFFICIENTS = 0,
    /** From the detail contour (5.3.2): g = f^{j+1} - f^j (f^j refined) on the segment's two fine
     * halves, sampled; the `extremes` largest and smallest normal components give σ; own = q σ.
     * The thesis finds this one more exact. Default. */
    RUGO_ESTIMATOR_DETAIL = 1
} rugo_tolerance_estimator;

/** What rugo_tolerances_create needs. Start from rugo_default_tolerance_def(). */
typedef struct rugo_tolerance_def {
    const rugo_pyramid* pyramid;        /**< geometry of every level; borrowed only during creation */
    const rugo_real* finest;            /**< λ per finest segment (2^J values) in the PYRAMID's segment order
                                           (counter-clockwise: remap if the pyramid reversed the input) */
    int count;                          /**< must equal 2^J */
    rugo_real q;                        /**< default RUGO_DEFAULT_Q */
    rugo_tolerance_estimator estimator; /**< default RUGO_ESTIMATOR_DETAIL */
    int neighbours;           /**< k of the 2k+1 coefficients; >= 1, default 1 (a window wider than a
                                 level uses each of its details once) */
    int extremes;             /**< maxima and minima per segment for the detail estimator (of 32 samples,
                                 16 per fine half); 3..16, default 3 */
    rugo_real minimum;        /**< floor of λ(t) (clamping of the cubic interpolation); >= 0, default 0 */
    rugo_allocator allocator; /**< zeroed = malloc/free */
    int cookie;               /**< set by rugo_default_tolerance_def; catches uninitialised defs */
} rugo_tolerance_def;

/** A def with the defaults above and its cookie set; fill in pyramid, finest and count. */
RUGO_API rugo_tolerance_def rugo_default_tolerance_def(void);

/** λ, own estimates and β of every level of a pyramid (opaque; see rugo_tolerances_level). */
typedef struct rugo_tolerances rugo_tolerances;

/** Builds λ and β for every level of the pyramid. On success *out is new and owned by the caller (free
 * with rugo_tolerances_destroy); on error it is NULL. Errors: NULL_ARGUMENT, BAD_ARGUMENT (cookie, count
 * mismatch, neighbours or extremes out of range, estimator), NOT_FINITE, NEGATIVE_TOLERANCE,
 * BAD_QUANTILE (q <= 0 or not finite), OUT_OF_MEMORY. */
RUGO_API rugo_status rugo_tolerances_create(const rugo_tolerance_def* def, rugo_tolerances** out);
/** Frees t through its allocator; NULL is allowed. Level views into it become invalid. */
RUGO_API void rugo_tolerances_destroy(rugo_tolerances* t);

/** The finest level J; -1 for NULL. */
RUGO_API int rugo_tolerances_finest_level(const rugo_tolerances* t);
/** The coarsest level J_min; -1 for NULL. */
RUGO_API int rugo_tolerances_coarsest_level(const rugo_tolerances* t);

/** The tolerances of one level: views of count values each, in length units, indexed by segment. */
typedef struct rugo_tolerance_level {
    int level;              /**< the level j */
    int count;              /**< 2^level segments */
    const rugo_real* own;   /**< own^j_k: the estimate from this level's perturbation (finest: the input) */
    const rugo_real* total; /**< λ^j_k, accumulated by (5.3) */
    const rugo_real* bound; /**< β^j_k, the hard bound */
} rugo_tolerance_level;

/** Views of one level into *out (valid until destroy). Errors: NULL_ARGUMENT, BAD_LEVEL (outside the
 * pyramid's levels). */
RUGO_API rugo_status rugo_tolerances_level(const rugo_tolerances* t, int level, rugo_tolerance_level* out);

/** λ(t) at the point f_segment(t) of a contour whose segments carry `lambda` (count values), by the
 * corrected cubic interpolation of SPEC 6.3 (λ_i attached to the midpoint of segment i; continuous
 * along the whole contour; equal to λ_j at f_j(1/2)), clamped below at `minimum`. Segment indices
 * wrap; t in [0, 1]. NaN for NULL lambda or count < 1; a NaN λ stays NaN (the clamp does not hide it). */
RUGO_API rugo_real rugo_tolerance_at(const rugo_real* lambda, int count, int segment, rugo_real t,
                                     rugo_real minimum);

/** A certified upper bound of λ(t) over segment `segment` (t in [0, 1]) for the interpolation of
 * rugo_tolerance_at, never below `minimum`: the largest Bernstein coefficient of the two cubic
 * pieces plus a round-off pad. Within ~1.5% of the true maximum. NaN for NULL lambda or count < 1. */
RUGO_API rugo_real rugo_tolerance_bound_on_segment(const rugo_real* lambda, int count, int segment,
                                                   rugo_real minimum);

/** A certified bound of the error of a coarser level of detail against the finest, per coarse segment:
 * with t the common parameter (coarse segment k over t in [0, 1] is refined by finest segments
 * k 2^r .. k 2^r + 2^r - 1, r = log2(finest.count / coarse.count)),
 *     per_segment[k] >= max over segment k of |f^j(t) - f^J(t)| + |λ^j(t) - λ^J(t)|,
 * λ as rugo_tolerance_at interpolates it (any common clamp). The disc of radius λ about each curve
 * point then moves by at most per_segment[k] between the levels, so the band-adjusted distance of two
 * bodies (the smallest |f_A - f_B| - λ_A - λ_B) changes by at most the sum of their bounds. Computed as
 * the tolerance module's β (SPEC 6.2): Bezier hull bounds of the difference curve and Bernstein bounds
 * of the difference of the two λ pieces, plus round-off pads; never below the true value.
 * `coarse_lambda` and `finest_lambda` hold coarse.count and finest.count values; per_segment (may be
 * NULL) receives coarse.count values and *max_error the largest (round-off pads only when the levels
 * coincide).
 * Errors (then *max_error is NaN): NULL_ARGUMENT, BAD_ARGUMENT (coarse.count < 4, or finest.count not
 * coarse.count times a power of two), NOT_FINITE (a point or λ not finite, or the bound overflows). */
RUGO_API rugo_status rugo_tolerance_level_error(rugo_contour coarse, const rugo_real* coarse_lambda,
                                                rugo_contour finest, const rugo_real* finest_lambda,
                                                rugo_real* per_segment, rugo_real* max_error);

/* ---- friction (5.5, 6.4) ------------------------------------------------------------------------ */

/** The friction map of a surface: μ(λ) = base if λ <= λ_min, base + α (λ - λ_min) otherwise (the
 * thesis' (5.6) has base = 0). λ is a length in the shape's units, so the map is too: α has units of
 * 1/length. The default is stated in metres, as Box2D's units are: μ = 0.3 for bands up to 0.5 mm,
 * rising linearly to μ = 0.9 at a 6 mm band (α = 0.6 / 0.0055 m ≈ 109.1 per metre), so game-sized
 * rough surfaces (bands of a fraction of a millimetre to a few millimetres) get a plausible μ. The
 * map keeps rising beyond 6 mm (μ ≈ 1.4 at 1 cm): bands that large are rough terrain, not a surface
 * finish. For shapes in other units calibrate with rugo_friction_calibrate; the thesis' own map (α = 1,
 * λ_min = 0.04, base = 0, for its dimensionless tolerances) is rugo_thesis_friction_map. α = 0 gives a
 * constant μ = base (an ordinary material). */
typedef struct rugo_friction_map {
    rugo_real alpha;      /**< slope α of μ over λ (1/length); >= 0 */
    rugo_real lambda_min; /**< tolerance of a smooth surface (length); >= 0 */
    rugo_real base;       /**< μ of a smooth surface (λ <= λ_min); >= 0 */
} rugo_friction_map;

/** Smallest band of the default map, metres: μ = RUGO_DEFAULT_MU_MIN up to it. */
#define RUGO_DEFAULT_FRICTION_LAMBDA_MIN 0.0005
/** Band of the default map at which μ reaches RUGO_DEFAULT_MU_MAX, metres. */
#define RUGO_DEFAULT_FRICTION_LAMBDA_MAX 0.006
/** μ of the default map at and below RUGO_DEFAULT_FRICTION_LAMBDA_MIN. */
#define RUGO_DEFAULT_MU_MIN 0.3
/** μ of the default map at RUGO_DEFAULT_FRICTION_LAMBDA_MAX. */
#define RUGO_DEFAULT_MU_MAX 0.9

/** The default map, in metres: rugo_friction_calibrate(0.0005, 0.006, 0.3, 0.9): base 0.3, λ_min
 * 0.0005 m, α = 0.6 / 0.0055 per metre. */
RUGO_API rugo_friction_map rugo_default_friction_map(void);
/** The thesis' map: α = 1, λ_min = 0.04, base = 0 (μ = 0 for every band up to 0.04 units; its presets'
 * tolerances 0.04-0.65 give μ from 0 to 0.61). For reproducing the thesis. */
RUGO_API rugo_friction_map rugo_thesis_friction_map(void);
/** Validates a map. Errors: NULL_ARGUMENT, NOT_FINITE, BAD_ARGUMENT (alpha < 0 or base < 0),
 * NEGATIVE_TOLERANCE (lambda_min < 0). */
RUGO_API rugo_status rugo_friction_map_check(const rugo_friction_map* m);
/** The friction coefficient μ(λ) of the map at a tolerance λ (length units); NaN for a NULL map or a
 * NaN λ. The map is not validated here (rugo_friction_map_check). */
RUGO_API rugo_real rugo_friction(const rugo_friction_map* m, rugo_real lambda);
/** Calibration: the map with μ = mu_min for bands up to lambda_min and μ = mu_max at lambda_max,
 * linear between (and beyond): base = mu_min, α = (mu_max - mu_min) / (lambda_max - lambda_min). E.g.
 * (0.0005, 0.006, 0.3, 0.9) is the default map; mu_min = mu_max gives a constant μ.
 * Checks in this order (out untouched on error): NULL_ARGUMENT, NOT_FINITE (also an α that
 * overflows), NEGATIVE_TOLERANCE (a λ < 0), BAD_ARGUMENT (mu_min < 0), EMPTY_RANGE (lambda_min >=
 * lambda_max: equality would divide by zero; or mu_max < mu_min: μ falling with roughness). */
RUGO_API rugo_status rugo_friction_calibrate(rugo_real lambda_min, rugo_real lambda_max, rugo_real mu_min,
                                             rugo_real mu_max, rugo_friction_map* out);

/** Mixing of a pair's values (7.2): the thesis takes the max for μ and the min for ε. */
typedef enum rugo_mix_rule {
    RUGO_MIX_MAX = 0,      /**< max(a, b) */
    RUGO_MIX_MIN = 1,      /**< min(a, b) */
    RUGO_MIX_MEAN = 2,     /**< (a + b) / 2 */
    RUGO_MIX_GEOMETRIC = 3 /**< sqrt(a b), Box2D's b2MixFriction (sqrt(a) sqrt(b) where a b overflows or
                                underflows) */
} rugo_mix_rule;
/** The value of a and b mixed by `rule`; NaN for an invalid rule. */
RUGO_API rugo_real rugo_mix(rugo_mix_rule rule, rugo_real a, rugo_real b);

/* ---- restitution in continuous contact (6.5, 7.3) --------------------------------------------- */

/** A surface's restitution in continuous contact: ε_c(δ) = (ε_max - ε) δ² / λ² + ε for a penetration δ inside
 * the band λ (δ clamped to [0, λ]; λ = 0 gives ε). Defaults ε = 0.5, ε_max = 0.9 (thesis). */
typedef struct rugo_restitution {
    rugo_real epsilon;     /**< ε: the base coefficient of restitution (no penetration), in [0, 1] */
    rugo_real epsilon_max; /**< ε_max: at the edge of the band (δ = λ), in [ε, 1] */
} rugo_restitution;

/** ε = 0.5, ε_max = 0.9 (the thesis' values). */
RUGO_API rugo_restitution rugo_default_restitution(void);
/** Validates r. Errors: NULL_ARGUMENT, NOT_FINITE, BAD_ARGUMENT (outside [0, 1]), EMPTY_RANGE (epsilon >
 * epsilon_max). */
RUGO_API rugo_status rugo_restitution_check(const rugo_restitution* r);
/** ε_c(δ) for a penetration δ into a band λ (both length units): ε for δ <= 0 or λ <= 0, ε_max for
 * δ >= λ. NaN for a NULL r or a NaN argument. r is not validated here (rugo_restitution_check). */
RUGO_API rugo_real rugo_restitution_in_band(const rugo_restitution* r, rugo_real delta, rugo_real lambda);

#ifdef __cplusplus
}
#endif

#endif
