/* The tolerance library and the generators of perturbation geometry (SPEC 4; thesis 2.4, 5.2).
 *
 * Random draws, in this fixed order (so outputs are bit-identical run to run and platform to
 * platform with IEEE doubles and the same libm log):
 *  - tipo_2 and rugo_tolerances_random: one rugo_rng seeded with the seed; tipo_2 draws, per block,
 *    first its length (1 + rugo_rng_below(4)) and then its value (rugo_rng_range(0.04, 0.65));
 *    random draws one rugo_rng_range(lo, hi) per segment, segment 0 first.
 *  - rugo_roughen: one rugo_rng seeded with def->seed; one Gaussian per perturbation, in order of
 *    added level / round (first to last), then of detail index s (wavelet) or original segment k
 *    (local). A Gaussian is drawn even where σ = 0, so the noise on one segment does not depend on
 *    the tolerances of the others. */
#include "rugo/rough.h"

#include "rugo/contour.h"
#include "rugo/multires.h"

#include "core/internal.h"

#include <string.h>

/* Catches defs that did not come from rugo_default_roughen_def ("RUGH"). */
#define ROUGHEN_DEF_COOKIE 0x52554748

/* The thesis' library (Fig. 5.5). */
static const rugo_real TIPO_1_VALUE = 0.25;
static const rugo_real TIPO_3_PATTERN[4] = {0.32, 0.24, 0.20, 0.24};
static const rugo_real TIPO_5_VALUES[4] = {0.55, 0.04, 0.65, 0.04};
enum { TIPO_5_BLOCK = 4 };
/* tipo_2: blocks of 1..TIPO_2_MAX_BLOCK segments, values in the library's range. */
static const rugo_real TIPO_2_LO = 0.04, TIPO_2_HI = 0.65;
enum { TIPO_2_MAX_BLOCK = 4 };

static const char* const PRESET_NAMES[RUGO_PRESET_COUNT] = {"tipo_1", "tipo_2", "tipo_3", "tipo_5"};

const char* rugo_preset_name(rugo_tolerance_preset p) {
    if ((int)p < 0 || (int)p >= (int)RUGO_PRESET_COUNT) return NULL;
    return PRESET_NAMES[p];
}

rugo_status rugo_preset_from_name(const char* name, rugo_tolerance_preset* out) {
    if (name == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    for (int i = 0; i < (int)RUGO_PRESET_COUNT; ++i)
        if (strcmp(name, PRESET_NAMES[i]) == 0) {
            *out = (rugo_tolerance_preset)i;
            return RUGO_OK;
        }
    return RUGO_ERR_BAD_ARGUMENT;
}

/* ---- validation ------------------------------------------------------------------------------ */

static rugo_status check_count(int n) {
    if (n < 1) return RUGO_ERR_TOO_FEW_POINTS;
    if (n > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    return RUGO_OK;
}

static rugo_status check_value(rugo_real v) {
    if (!isfinite(v)) return RUGO_ERR_NOT_FINITE;
    if (v < 0.0) return RUGO_ERR_NEGATIVE_TOLERANCE; /* -0.0 is a zero tolerance */
    return RUGO_OK;
}

/* Values without a count check (the caller's count is validated separately). */
static rugo_status check_values(const rugo_real* values, int n, int* bad_index) {
    for (int i = 0; i < n; ++i) {
        rugo_status st = check_value(values[i]);
        if (st != RUGO_OK) {
            if (bad_index != NULL) *bad_index = i;
            return st;
        }
    }
    return RUGO_OK;
}

rugo_status rugo_tolerances_check(const rugo_real* values, int n, int* bad_index) {
    if (bad_index != NULL) *bad_index = -1;
    if (values == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (n < 1) return RUGO_ERR_TOO_FEW_POINTS;
    return check_values(values, n, bad_index);
}

/* ---- constructors -----------------------------------------------------------------------------
 * Each validates everything before writing, so out is untouched on error. Order of checks:
 * NULL_ARGUMENT, the count n (TOO_FEW_POINTS, TOO_MANY_POINTS), the shape arguments
 * (BAD_ARGUMENT), then the values (NOT_FINITE, EMPTY_RANGE, NEGATIVE_TOLERANCE). */

rugo_status rugo_tolerances_constant(rugo_real value, int n, rugo_real* out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_count(n);
    if (st == RUGO_OK) st = check_value(value);
    if (st != RUGO_OK) return st;
    for (int i = 0; i < n; ++i)
        out[i] = value;
    return RUGO_OK;
}

rugo_status rugo_tolerances_pattern(const rugo_real* pattern, int period, int n, rugo_real* out) {
    if (pattern == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_count(n);
    if (st != RUGO_OK) return st;
    if (period < 1 || period > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_BAD_ARGUMENT;
    st = check_values(pattern, period, NULL);
    if (st != RUGO_OK) return st;
    for (int i = 0; i < n; ++i)
        out[i] = pattern[i % period];
    return RUGO_OK;
}

rugo_status rugo_tolerances_blocks(const rugo_real* values, int count, int block_length, int n,
                                   rugo_real* out) {
    if (values == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_count(n);
    if (st != RUGO_OK) return st;
    if (count < 1 || count > RUGO_MAX_CONTROL_POINTS || block_length < 1) return RUGO_ERR_BAD_ARGUMENT;
    st = check_values(values, count, NULL);
    if (st != RUGO_OK) return st;
    for (int i = 0; i < n; ++i)
        out[i] = values[(i / block_length) % count];
    return RUGO_OK;
}

/* Uniform in [lo, hi]; the clamp only guards the last ulp of lo + (hi - lo) u against rounding up. */
static rugo_real uniform_closed(rugo_rng* rng, rugo_real lo, rugo_real hi) {
    rugo_real v = rugo_rng_range(rng, lo, hi);
    return v > hi ? hi : v;
}

rugo_status rugo_tolerances_random(rugo_real lo, rugo_real hi, uint64_t seed, int n, rugo_real* out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_count(n);
    if (st != RUGO_OK) return st;
    if (!isfinite(lo) || !isfinite(hi)) return RUGO_ERR_NOT_FINITE;
    if (lo > hi) return RUGO_ERR_EMPTY_RANGE;
    if (lo < 0.0) return RUGO_ERR_NEGATIVE_TOLERANCE;
    rugo_rng rng;
    rugo_rng_seed(&rng, seed);
    for (int i = 0; i < n; ++i)
        out[i] = uniform_closed(&rng, lo, hi);
    return RUGO_OK;
}

rugo_status rugo_tolerances_preset(rugo_tolerance_preset p, uint64_t seed, int n, rugo_real* out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if ((int)p < 0 || (int)p >= (int)RUGO_PRESET_COUNT) return RUGO_ERR_BAD_ARGUMENT;
    rugo_status st = check_count(n);
    if (st != RUGO_OK) return st;
    switch (p) {
    case RUGO_PRESET_TIPO_1:
        return rugo_tolerances_constant(TIPO_1_VALUE, n, out);
    case RUGO_PRESET_TIPO_3:
        return rugo_tolerances_pattern(TIPO_3_PATTERN, 4, n, out);
    case RUGO_PRESET_TIPO_5:
        return rugo_tolerances_blocks(TIPO_5_VALUES, 4, TIPO_5_BLOCK, n, out);
    case RUGO_PRESET_TIPO_2: {
        rugo_rng rng;
        rugo_rng_seed(&rng, seed);
        int i = 0;
        while (i < n) {
            int length = 1 + (int)rugo_rng_below(&rng, TIPO_2_MAX_BLOCK);
            rugo_real value = uniform_closed(&rng, TIPO_2_LO, TIPO_2_HI);
            for (int k = 0; k < length && i < n; ++k)
                out[i++] = value;
        }
        return RUGO_OK;
    }
    case RUGO_PRESET_COUNT:
        break;
    }
    return RUGO_ERR_BAD_ARGUMENT;
}

/* ---- perturbation generators ------------------------------------------------------------------ */

rugo_roughen_def rugo_default_roughen_def(void) {
    rugo_roughen_def d;
    memset(&d, 0, sizeof d);
    d.points = NULL;
    d.count = 0;
    d.tolerances = NULL;
    d.q = RUGO_DEFAULT_Q;
    d.method = RUGO_ROUGHEN_WAVELET;
    d.levels = 2;
    d.filter = RUGO_FILTER_DEFAULT;
    d.seed = 0;
    d.cookie = ROUGHEN_DEF_COOKIE;
    return d;
}

static int level_of_count(int n) {
    int j = 0;
    while ((1 << j) < n)
        ++j;
    return j;
}

/* Validates the def, in this order: cookie, NULL pointers, method, levels, filter (checked for both
 * methods), count (TOO_FEW_POINTS, TOO_MANY_POINTS, NOT_POWER_OF_TWO), output size, q, points,
 * tolerances (first bad value). */
static rugo_status check_roughen_def(const rugo_roughen_def* def) {
    if (def->cookie != ROUGHEN_DEF_COOKIE) return RUGO_ERR_BAD_ARGUMENT;
    if (def->points == NULL || def->tolerances == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (def->method != RUGO_ROUGHEN_WAVELET && def->method != RUGO_ROUGHEN_LOCAL)
        return RUGO_ERR_BAD_ARGUMENT;
    if (def->levels < 1) return RUGO_ERR_BAD_ARGUMENT;
    if ((int)def->filter < 0 || (int)def->filter >= (int)RUGO_FILTER_COUNT) return RUGO_ERR_BAD_FILTER;
    if (def->count < 4) return RUGO_ERR_TOO_FEW_POINTS;
    if (def->count > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_TOO_MANY_POINTS;
    if (!rugo__is_power_of_two(def->count)) return RUGO_ERR_NOT_POWER_OF_TWO;
    /* count << levels <= RUGO_MAX_CONTROL_POINTS, written so that nothing overflows. */
    if (def->levels > 30 || def->count > (RUGO_MAX_CONTROL_POINTS >> def->levels))
        return RUGO_ERR_BAD_ARGUMENT;
    if (!(isfinite(def->q) && def->q > 0.0)) return RUGO_ERR_BAD_QUANTILE;
    for (int i = 0; i < def->count; ++i)
        if (!rugo__v2_finite(def->points[i])) return RUGO_ERR_NOT_FINITE;
    return check_values(def->tolerances, def->count, NULL);
}

/* +1 for a counter-clockwise contour, -1 for a clockwise one: rugo_contour_normal points outward
 * only for counter-clockwise curves, so the generators multiply it by this sign. */
static rugo_real orientation_sign(const rugo_vec2* points, int count) {
    rugo_contour c;
    c.points = points;
    c.count = count;
    return rugo_contour_signed_area(c) < 0.0 ? -1.0 : 1.0;
}

/* Wavelet method (2.32): for each added level, from the current curve f (m points, level L),
 * details d_s = (0, N(0, σ²)) in the local frame of f at segment s-1, t = 1/2 (multires.h), σ of
 * the original segment that point lies on; then one synthesis step to 2m points. */
static void roughen_wavelet(const rugo_roughen_def* def, rugo_rng* rng, rugo_real sign, rugo_vec2* cur,
                            rugo_vec2* nxt, rugo_vec2* details, rugo_vec2** result) {
    const int n = def->count, base = level_of_count(n);
    for (int r = 0; r < def->levels; ++r) {
        const int m = n << r;
        rugo_contour c;
        c.points = cur;
        c.count = m;
        for (int s = 0; s < m; ++s) {
            const int seg = rugo__wrap(s - 1, m);
            int k;
            rugo_level_parameter(base + r, seg, 0.5, base, &k, NULL);
            const rugo_real sigma = def->tolerances[k] / def->q;
            const rugo_real g = rugo_rng_gaussian(rng);
            details[s] = rugo_v2_scale(sign * g * sigma, rugo_contour_normal(c, seg, 0.5));
        }
        rugo_status st = rugo_wavelet_synthesize(def->filter, cur, details, m, nxt);
        RUGO_ASSERT(st == RUGO_OK);
        (void)st;
        rugo_vec2* tmp = cur;
        cur = nxt;
        nxt = tmp;
    }
    *result = cur;
}

/* Local method (Fig. 2.13, 2.30): each round refines the current curve (m -> 2m points), then moves
 * the point of the refined curve that corresponds to the midpoint of each original segment k along
 * its outward normal by N(0, σ_k²), with the least-norm change of the four control points of the
 * refined segment holding it, ΔC_i = Δf N_i / |N|². All moves of a round are computed on the
 * refined, not yet moved, curve and added together. */
static void roughen_local(const rugo_roughen_def* def, rugo_rng* rng, rugo_real sign, rugo_vec2* cur,
                          rugo_vec2* nxt, rugo_vec2* delta, rugo_vec2** result) {
    const int n = def->count, base = level_of_count(n);
    for (int r = 1; r <= def->levels; ++r) {
        /* Thesis 2.4: every segment of the contour as it stands before this round (n 2^(r-1) of them)
         * gets its midpoint pushed, on the contour refined once more; the roughness of a segment
         * comes from the original segment it lies on. */
        const int m = n << r, prev = m / 2;
        rugo_status st = rugo_wavelet_refine(cur, prev, nxt);
        RUGO_ASSERT(st == RUGO_OK);
        (void)st;
        rugo_contour c;
        c.points = nxt;
        c.count = m;
        memset(delta, 0, (size_t)m * sizeof(rugo_vec2));
        for (int k = 0; k < prev; ++k) {
            int seg;
            rugo_real t;
            rugo_level_parameter(base + r - 1, k, 0.5, base + r, &seg, &t);
            const rugo_real sigma = def->tolerances[k >> (r - 1)] / def->q;
            const rugo_real g = rugo_rng_gaussian(rng);
            const rugo_vec2 df = rugo_v2_scale(sign * g * sigma, rugo_contour_normal(c, seg, t));
            rugo_real w[4];
            rugo_bspline_basis(t, w);
            /* m >= 8, so the four control points seg-1 .. seg+2 are distinct. */
            const rugo_real norm2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2] + w[3] * w[3];
            for (int i = 0; i < 4; ++i) {
                const int idx = rugo__wrap(seg - 1 + i, m);
                delta[idx] = rugo_v2_add(delta[idx], rugo_v2_scale(w[i] / norm2, df));
            }
        }
        for (int i = 0; i < m; ++i)
            nxt[i] = rugo_v2_add(nxt[i], delta[i]);
        rugo_vec2* tmp = cur;
        cur = nxt;
        nxt = tmp;
    }
    *result = cur;
}

rugo_status rugo_roughen(const rugo_roughen_def* def, rugo_vec2* out) {
    if (def == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_roughen_def(def);
    if (st != RUGO_OK) return st;

    const int total = def->count << def->levels;
    /* Two ping-pong curves and one work array (details or control-point moves) of the final size;
     * the input is copied first and out written last, so out may alias the input. */
    rugo_allocator al = rugo__allocator_or_default(&def->allocator);
    rugo_vec2* block = (rugo_vec2*)rugo__alloc_array(&al, 3 * (size_t)total, sizeof(rugo_vec2));
    if (block == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    rugo_vec2* a = block;
    rugo_vec2* b = block + total;
    rugo_vec2* work = block + 2 * (size_t)total;
    memcpy(a, def->points, (size_t)def->count * sizeof(rugo_vec2));

    rugo_rng rng;
    rugo_rng_seed(&rng, def->seed);
    const rugo_real sign = orientation_sign(def->points, def->count);
    rugo_vec2* result = NULL;
    if (def->method == RUGO_ROUGHEN_WAVELET)
        roughen_wavelet(def, &rng, sign, a, b, work, &result);
    else
        roughen_local(def, &rng, sign, a, b, work, &result);

    st = RUGO_OK;
    for (int i = 0; i < total; ++i)
        if (!rugo__v2_finite(result[i])) {
            st = RUGO_ERR_NOT_FINITE; /* finite input whose perturbation overflows */
            break;
        }
    if (st == RUGO_OK) memcpy(out, result, (size_t)total * sizeof(rugo_vec2));
    rugo__free(&al, block);
    return st;
}
