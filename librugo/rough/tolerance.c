/* Tolerances at every level of a pyramid, the tolerance at a point, friction and restitution from
 * roughness (SPEC 6; thesis 5.3-5.5, 7.3).
 *
 * Per level j (J_min <= j <= J) three arrays of 2^j values: own (the estimate from this level's
 * perturbation; the input at the finest level), total (λ, accumulated by (5.3)) and bound (β, the
 * hard bound). Indices follow the pyramid's segments (counter-clockwise; if the pyramid reversed a
 * clockwise input, the caller's finest λ must already be in the reversed order).
 *
 * Estimators of own^j_k (level j < J, segment k, perturbation = details D^j):
 *  - COEFFICIENTS (5.3.1): the outward (local y) components v_s of the 2m+1 details centred on
 *    d_{k+1} (the one inserted inside segment k, fine index 2k+1), indices cyclic;
 *    σ = sqrt(Σ v_s² / (2m+1)) (mean taken as 0, as the thesis does); own = q σ. When a level has
 *    fewer than 2m+1 details, all of them are used once.
 *  - DETAIL (5.3.2): the detail contour g = f^{j+1} - f-bar^{j+1} (f^j refined, i.e. f^j itself by
 *    segment alignment) on the two fine halves of segment k, sampled at the centres of
 *    DETAIL_SAMPLES_PER_HALF equal parameter cells per half; each sample's outward component
 *    g(u)·n^j_k(u) (n = outward normal of the coarse curve f^j at the same parameter). Of these
 *    2 * DETAIL_SAMPLES_PER_HALF values take the `extremes` largest and the `extremes` smallest and
 *    estimate σ as their root mean square (mean 0): σ = sqrt(Σ_extremes w² / (2 extremes));
 *    own = q σ; `extremes` is limited to DETAIL_SAMPLES_PER_HALF (then every sample counts once).
 *    This σ measures the segment's largest excursions, not the σ of the coefficients: with CDF(4,8)
 *    and N(0, σ²) outward details it averages 0.88 σ (tests/test_tolerance.c), and on the thesis'
 *    Fig. 5.9 experiment the coefficient estimator is 1.02-1.11 times it on average
 *    (samples/fig5_9_estimators.c).
 *
 * Finite inputs whose accumulation overflows (tolerances near DBL_MAX) give RUGO_ERR_NOT_FINITE.
 *
 * Hard bound β (beyond the thesis, SPEC 6.2):
 *  - finest level: β^J_k >= max over t of λ(t) on segment k (rugo_tolerance_at on the finest λ with
 *    the clamp `minimum`). λ(t) on a segment is two cubic pieces (t < 1/2 and t >= 1/2); each
 *    piece's Bernstein coefficients on its half bound it from above (convex hull), then the clamp,
 *    then a round-off pad.
 *  - level j < J: every finest segment i inside coarse segment k (i = k 2^r + s, r = J - j) is a
 *    cubic Bezier curve, and so is coarse segment k restricted to its parameter cell
 *    [s / 2^r, (s+1) / 2^r] (blossoming). Their difference D(u) = f^J_i(u) - f^j_k((s + u) / 2^r) is a
 *    cubic Bezier curve whose control points bound |D| (convex hull; tightened by BOUND_SPLITS
 *    de Casteljau halvings). A finest point is at most |D(u)| from a point of coarse segment k, and
 *    its band reaches at most β^J_i further, so
 *        β^j_k = max_i (max |control points of D| + pad + β^J_i).
 *    The pad covers the round-off of these few operations (a multiple of DBL_EPSILON times the
 *    coordinates' magnitude) so that the bound is never exceeded by the computed curves. */
#include "rugo/tolerance.h"

#include "rugo/contour.h"
#include "core/internal.h"
#include "rough/internal.h"

#include <float.h>
#include <string.h>

/* "RUGT": catches defs that did not come from rugo_default_tolerance_def. */
#define TOLERANCE_DEF_COOKIE 0x52554754

/* Samples of the detail contour per fine half of a coarse segment; extremes <= this. */
#define DETAIL_SAMPLES_PER_HALF 16
#define DETAIL_SAMPLES (2 * DETAIL_SAMPLES_PER_HALF)

/* Halvings of the difference curve in the β bound (2 -> 4 pieces: hull error ~1/16 of one piece). */
#define BOUND_SPLITS 2

struct rugo_tolerances {
    rugo_allocator allocator;
    int finest;   /* J */
    int coarsest; /* J_min */
    rugo_real* block;
    rugo_real* own; /* level j at offset(j) */
    rugo_real* total;
    rugo_real* bound;
};

static size_t level_offset(const rugo_tolerances* t, int j) {
    return ((size_t)1 << j) - ((size_t)1 << t->coarsest);
}

rugo_tolerance_def rugo_default_tolerance_def(void) {
    rugo_tolerance_def d;
    memset(&d, 0, sizeof d);
    d.pyramid = NULL;
    d.finest = NULL;
    d.count = 0;
    d.q = RUGO_DEFAULT_Q;
    d.estimator = RUGO_ESTIMATOR_DETAIL;
    d.neighbours = 1;
    d.extremes = 3;
    d.minimum = 0.0;
    d.cookie = TOLERANCE_DEF_COOKIE;
    return d;
}

/* ---- λ(t): the corrected cubic interpolation (SPEC 6.3) ---------------------------------------- */

/* The piece of λ(t) that holds segment `segment` at parameter t: the cubic through λ_{k-1..k+2} at
 * u = 0..3 and the u where it is evaluated. */
static void piece_of(int segment, rugo_real t, int* k, rugo_real* u) {
    if (t < 0.5) {
        *k = segment - 1;
        *u = t + 1.5;
    } else {
        *k = segment;
        *u = t + 0.5; /* the thesis prints t + 1.0 (SPEC 12) */
    }
}

rugo_real rugo_tolerance_at(const rugo_real* lambda, int count, int segment, rugo_real t, rugo_real minimum) {
    if (lambda == NULL || count < 1) return NAN;
    int k;
    rugo_real u;
    piece_of(rugo__wrap(segment, count), t, &k, &u); /* wrapped first: k - 1 .. k + 2 cannot overflow */
    const rugo_real l0 = lambda[rugo__wrap(k - 1, count)], l1 = lambda[rugo__wrap(k, count)];
    const rugo_real l2 = lambda[rugo__wrap(k + 1, count)], l3 = lambda[rugo__wrap(k + 2, count)];
    /* The cubic γ(u) = [1 u u² u³] M^{-1} [λ_{k-1} .. λ_{k+2}]^T of SPEC 6.3, evaluated in its
     * Lagrange form (the same polynomial): exact at the nodes, so λ(1/2 of segment j) = λ_j to the
     * last bit, and better conditioned than the monomial coefficients. */
    const rugo_real u0 = u, u1 = u - 1.0, u2 = u - 2.0, u3 = u - 3.0;
    rugo_real v = -(u1 * u2 * u3) / 6.0 * l0 + (u0 * u2 * u3) / 2.0 * l1 - (u0 * u1 * u3) / 2.0 * l2 +
                  (u0 * u1 * u2) / 6.0 * l3;
    if (v < minimum) v = minimum; /* NaN stays NaN */
    return v;
}

/* The Bernstein coefficients b[0..3] (in s in [0, 1]) of the piece of λ through l[0..3] (the cubic
 * γ(u) of SPEC 6.3) restricted to u = u0 + h s. */
static void piece_bernstein(const rugo_real l[4], rugo_real u0, rugo_real h, rugo_real b[4]) {
    /* a = M^{-1} λ (SPEC 6.3). */
    const rugo_real a0 = l[0];
    const rugo_real a1 = -11.0 / 6.0 * l[0] + 3.0 * l[1] - 1.5 * l[2] + l[3] / 3.0;
    const rugo_real a2 = l[0] - 2.5 * l[1] + 2.0 * l[2] - 0.5 * l[3];
    const rugo_real a3 = (-l[0] + 3.0 * l[1] - 3.0 * l[2] + l[3]) / 6.0;
    /* Taylor coefficients at u0, then Bernstein. */
    const rugo_real c0 = a0 + u0 * (a1 + u0 * (a2 + u0 * a3));
    const rugo_real c1 = h * (a1 + u0 * (2.0 * a2 + 3.0 * a3 * u0));
    const rugo_real c2 = h * h * (a2 + 3.0 * a3 * u0);
    const rugo_real c3 = h * h * h * a3;
    b[0] = c0;
    b[1] = c0 + c1 / 3.0;
    b[2] = c0 + (2.0 * c1 + c2) / 3.0;
    b[3] = c0 + c1 + c2 + c3;
}

/* The four λ values of the piece starting at segment index k - 1 (wrapping); raises *scale to their
 * largest magnitude. */
static void piece_values(const rugo_real* lambda, int count, int k, rugo_real l[4], rugo_real* scale) {
    for (int i = 0; i < 4; ++i) {
        l[i] = lambda[rugo__wrap(k - 1 + i, count)];
        if (fabs(l[i]) > *scale) *scale = fabs(l[i]);
    }
}

void rugo__tolerance_halves(const rugo_real* lambda, int count, int segment, rugo_real out[2][4]) {
    rugo_real scale = 0.0;
    const int seg = rugo__wrap(segment, count);
    for (int half = 0; half < 2; ++half) {
        int k;
        rugo_real u0;
        piece_of(seg, half == 0 ? 0.0 : 0.5, &k, &u0); /* the piece covers u0 .. u0 + 1/2 */
        rugo_real l[4];
        piece_values(lambda, count, k, l, &scale);
        piece_bernstein(l, u0, 0.5, out[half]);
    }
}

/* Upper bound of λ(t) over segment k of the finest level: Bernstein coefficients of both pieces. */
static rugo_real finest_bound(const rugo_real* lambda, int count, int segment, rugo_real minimum) {
    rugo_real best = minimum, scale = fabs(minimum);
    for (int half = 0; half < 2; ++half) {
        int k;
        rugo_real u0;
        piece_of(segment, half == 0 ? 0.0 : 0.5, &k, &u0); /* the piece covers u0 .. u0 + 1/2 */
        rugo_real l[4], b[4];
        piece_values(lambda, count, k, l, &scale);
        piece_bernstein(l, u0, 0.5, b);
        for (int i = 0; i < 4; ++i)
            if (b[i] > best) best = b[i];
    }
    /* Round-off of this computation and of rugo_tolerance_at: a few ulps of values up to ~10 scale. */
    return best + 256.0 * DBL_EPSILON * scale;
}

rugo_real rugo_tolerance_bound_on_segment(const rugo_real* lambda, int count, int segment,
                                          rugo_real minimum) {
    if (lambda == NULL || count < 1) return NAN;
    return finest_bound(lambda, count, rugo__wrap(segment, count), minimum);
}

/* ---- estimators -------------------------------------------------------------------------------- */

static rugo_real estimate_coefficients(const rugo_vec2* local, int n, int k, int neighbours) {
    int width = 2 * neighbours + 1;
    int first = k + 1 - neighbours;
    if (width > n) { /* a level with fewer details than the window: use each once */
        width = n;
        first = 0;
    }
    rugo_real sum = 0.0;
    for (int i = 0; i < width; ++i) {
        const rugo_real v = local[rugo__wrap(first + i, n)].y;
        sum += v * v;
    }
    return sqrt(sum / (rugo_real)width);
}

static void sort_reals(rugo_real* v, int n) { /* insertion sort: n is DETAIL_SAMPLES */
    for (int i = 1; i < n; ++i) {
        const rugo_real x = v[i];
        int j = i - 1;
        while (j >= 0 && v[j] > x) {
            v[j + 1] = v[j];
            --j;
        }
        v[j + 1] = x;
    }
}

static rugo_real estimate_detail(rugo_contour coarse, rugo_contour fine, int k, int extremes) {
    rugo_real w[DETAIL_SAMPLES];
    for (int half = 0; half < 2; ++half)
        for (int i = 0; i < DETAIL_SAMPLES_PER_HALF; ++i) {
            const rugo_real tf = ((rugo_real)i + 0.5) / (rugo_real)DETAIL_SAMPLES_PER_HALF;
            const rugo_real u = ((rugo_real)half + tf) * 0.5;
            const rugo_vec2 g =
                rugo_v2_sub(rugo_contour_point(fine, 2 * k + half, tf), rugo_contour_point(coarse, k, u));
            w[half * DETAIL_SAMPLES_PER_HALF + i] = rugo_v2_dot(g, rugo_contour_normal(coarse, k, u));
        }
    sort_reals(w, DETAIL_SAMPLES);
    rugo_real sum = 0.0;
    for (int i = 0; i < extremes; ++i)
        sum += w[i] * w[i] + w[DETAIL_SAMPLES - 1 - i] * w[DETAIL_SAMPLES - 1 - i];
    return sqrt(sum / (rugo_real)(2 * extremes));
}

/* ---- hard bound of a coarse segment ------------------------------------------------------------ */

static rugo_vec2 lerp2(rugo_vec2 a, rugo_vec2 b, rugo_real t) {
    return rugo_v2(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
}

/* Blossom B(t1, t2, t3) of a cubic Bezier curve. */
static rugo_vec2 blossom(const rugo_vec2 p[4], rugo_real t1, rugo_real t2, rugo_real t3) {
    const rugo_vec2 a = lerp2(p[0], p[1], t1), b = lerp2(p[1], p[2], t1), c = lerp2(p[2], p[3], t1);
    const rugo_vec2 d = lerp2(a, b, t2), e = lerp2(b, c, t2);
    return lerp2(d, e, t3);
}

/* Largest |control point| of a cubic Bezier curve after `splits` halvings: >= max |D(u)|. */
static rugo_real hull_bound(const rugo_vec2 d[4], int splits) {
    if (splits <= 0) {
        rugo_real m = 0.0;
        for (int i = 0; i < 4; ++i) {
            const rugo_real len = rugo__v2_length(d[i]);
            if (len > m) m = len;
        }
        return m;
    }
    const rugo_vec2 a = lerp2(d[0], d[1], 0.5), b = lerp2(d[1], d[2], 0.5), c = lerp2(d[2], d[3], 0.5);
    const rugo_vec2 ab = lerp2(a, b, 0.5), bc = lerp2(b, c, 0.5), mid = lerp2(ab, bc, 0.5);
    const rugo_vec2 left[4] = {d[0], a, ab, mid}, right[4] = {mid, bc, c, d[3]};
    const rugo_real l = hull_bound(left, splits - 1), r = hull_bound(right, splits - 1);
    return l > r ? l : r;
}

static rugo_real coord_magnitude(const rugo_vec2 p[4]) {
    rugo_real m = 0.0;
    for (int i = 0; i < 4; ++i) {
        if (fabs(p[i].x) > m) m = fabs(p[i].x);
        if (fabs(p[i].y) > m) m = fabs(p[i].y);
    }
    return m;
}

/* Bound of |D(u)| = |f^J_i(u) - f^j_k((s + u) / 2^shift)| over u in [0, 1] for finest segment
 * i = k 2^shift + s (the part of coarse segment k that finest segment i refines), round-off included. */
static rugo_real cell_distance_bound(rugo_contour coarse, rugo_contour finest, int shift, int k, int s) {
    rugo_vec2 q[4];
    rugo_contour_bezier(coarse, k, q);
    const rugo_real inv = 1.0 / (rugo_real)(1 << shift); /* exact: a power of two */
    const int i = (k << shift) + s;
    rugo_vec2 p[4], sub[4], d[4];
    rugo_contour_bezier(finest, i, p);
    const rugo_real a = (rugo_real)s * inv, b = (rugo_real)(s + 1) * inv;
    sub[0] = blossom(q, a, a, a);
    sub[1] = blossom(q, a, a, b);
    sub[2] = blossom(q, a, b, b);
    sub[3] = blossom(q, b, b, b);
    for (int l = 0; l < 4; ++l)
        d[l] = rugo_v2_sub(p[l], sub[l]);
    rugo_real mag = coord_magnitude(p);
    const rugo_real mq = coord_magnitude(q);
    if (mq > mag) mag = mq;
    /* Bezier points from control points, blossoming, subtraction, halvings: each a few ulps of the
     * coordinates; 64 ulps covers them with room. */
    return hull_bound(d, BOUND_SPLITS) + 64.0 * DBL_EPSILON * mag;
}

static rugo_real coarse_bound(rugo_contour coarse, rugo_contour finest, int shift, int k,
                              const rugo_real* finest_beta) {
    const int cells = 1 << shift;
    rugo_real best = 0.0;
    for (int s = 0; s < cells; ++s) {
        const rugo_real value =
            cell_distance_bound(coarse, finest, shift, k, s) + finest_beta[(k << shift) + s];
        if (value > best) best = value;
    }
    return best;
}

/* Bound of |λ^j(t) - λ^J(t)| over the part of coarse segment k that finest segment k 2^shift + s
 * refines (shift >= 1: each finest half lies in one coarse piece). On each finest half both are cubic
 * in the same variable: the largest |Bernstein coefficient| of their difference bounds it, and the
 * clamp at a common minimum only shrinks it (|max(p, m) - max(q, m)| <= |p - q|). */
static rugo_real cell_band_bound(const rugo_real* coarse_lambda, int coarse_count,
                                 const rugo_real* finest_lambda, int finest_count, int shift, int k, int s) {
    const int i = (k << shift) + s;
    const rugo_real inv = 1.0 / (rugo_real)(1 << shift);
    rugo_real best = 0.0, scale = 0.0;
    for (int half = 0; half < 2; ++half) {
        int kf, kc;
        rugo_real uf, uc;
        piece_of(i, half == 0 ? 0.0 : 0.5, &kf, &uf);
        const rugo_real t0 =
            ((rugo_real)s + 0.5 * (rugo_real)half) * inv; /* coarse t where this half starts */
        piece_of(k, t0, &kc, &uc); /* the half never straddles t = 1/2, a cell boundary */
        rugo_real lf[4], lc[4], bf[4], bc[4];
        piece_values(finest_lambda, finest_count, kf, lf, &scale);
        piece_values(coarse_lambda, coarse_count, kc, lc, &scale);
        piece_bernstein(lf, uf, 0.5, bf);
        piece_bernstein(lc, uc, 0.5 * inv, bc);
        for (int m = 0; m < 4; ++m) {
            const rugo_real d = fabs(bf[m] - bc[m]);
            if (!(d <= best)) best = d; /* NaN propagates */
        }
    }
    return best + 512.0 * DBL_EPSILON * scale;
}

rugo_status rugo_tolerance_level_error(rugo_contour coarse, const rugo_real* coarse_lambda,
                                       rugo_contour finest, const rugo_real* finest_lambda,
                                       rugo_real* per_segment, rugo_real* max_error) {
    if (max_error != NULL) *max_error = NAN;
    if (coarse.points == NULL || finest.points == NULL || coarse_lambda == NULL || finest_lambda == NULL ||
        max_error == NULL)
        return RUGO_ERR_NULL_ARGUMENT;
    if (coarse.count < 4 || finest.count < coarse.count) return RUGO_ERR_BAD_ARGUMENT;
    int shift = 0;
    while (shift < 30 && (coarse.count << shift) < finest.count)
        ++shift;
    if ((coarse.count << shift) != finest.count) return RUGO_ERR_BAD_ARGUMENT;
    /* Checked up front: the bounds below take maxima of distances, which would drop a NaN point. */
    for (int i = 0; i < coarse.count; ++i)
        if (!rugo__v2_finite(coarse.points[i]) || !isfinite(coarse_lambda[i])) return RUGO_ERR_NOT_FINITE;
    for (int i = 0; i < finest.count; ++i)
        if (!rugo__v2_finite(finest.points[i]) || !isfinite(finest_lambda[i])) return RUGO_ERR_NOT_FINITE;
    rugo_real worst = 0.0;
    for (int k = 0; k < coarse.count; ++k) {
        rugo_real e = 0.0;
        for (int s = 0; s < (1 << shift); ++s) {
            const rugo_real v =
                cell_distance_bound(coarse, finest, shift, k, s) +
                cell_band_bound(coarse_lambda, coarse.count, finest_lambda, finest.count, shift, k, s);
            if (!(v <= e)) e = v; /* NaN propagates */
        }
        if (!isfinite(e)) return RUGO_ERR_NOT_FINITE;
        if (per_segment != NULL) per_segment[k] = e;
        if (e > worst) worst = e;
    }
    *max_error = worst;
    return RUGO_OK;
}

/* ---- creation ---------------------------------------------------------------------------------- */

static rugo_status check_def(const rugo_tolerance_def* def, int* finest_level, int* coarsest_level) {
    if (def->cookie != TOLERANCE_DEF_COOKIE) return RUGO_ERR_BAD_ARGUMENT;
    if (def->pyramid == NULL || def->finest == NULL) return RUGO_ERR_NULL_ARGUMENT;
    const int J = rugo_pyramid_finest_level(def->pyramid);
    const int Jmin = rugo_pyramid_coarsest_level(def->pyramid);
    if (J < 2 || J > 30 || Jmin < 2 || Jmin > J) return RUGO_ERR_BAD_ARGUMENT; /* not a live pyramid */
    if (def->count != (1 << J)) return RUGO_ERR_BAD_ARGUMENT;
    if (def->estimator != RUGO_ESTIMATOR_COEFFICIENTS && def->estimator != RUGO_ESTIMATOR_DETAIL)
        return RUGO_ERR_BAD_ARGUMENT;
    if (def->neighbours < 1 || def->neighbours > RUGO_MAX_CONTROL_POINTS) return RUGO_ERR_BAD_ARGUMENT;
    if (def->extremes < 3 || def->extremes > DETAIL_SAMPLES_PER_HALF) return RUGO_ERR_BAD_ARGUMENT;
    if (!isfinite(def->q) || !(def->q > 0.0)) return RUGO_ERR_BAD_QUANTILE;
    if (!isfinite(def->minimum)) return RUGO_ERR_NOT_FINITE;
    if (def->minimum < 0.0) return RUGO_ERR_NEGATIVE_TOLERANCE;
    for (int i = 0; i < def->count; ++i)
        if (!isfinite(def->finest[i])) return RUGO_ERR_NOT_FINITE;
    for (int i = 0; i < def->count; ++i)
        if (def->finest[i] < 0.0) return RUGO_ERR_NEGATIVE_TOLERANCE;
    *finest_level = J;
    *coarsest_level = Jmin;
    return RUGO_OK;
}

rugo_status rugo_tolerances_create(const rugo_tolerance_def* def, rugo_tolerances** out) {
    if (out != NULL) *out = NULL;
    if (def == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    int J = 0, Jmin = 0;
    rugo_status st = check_def(def, &J, &Jmin);
    if (st != RUGO_OK) return st;

    rugo_allocator al = rugo__allocator_or_default(&def->allocator);
    rugo_tolerances* t = (rugo_tolerances*)rugo__alloc_array(&al, 1, sizeof(rugo_tolerances));
    if (t == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(t, 0, sizeof *t);
    const size_t per = ((size_t)1 << (J + 1)) - ((size_t)1 << Jmin); /* levels Jmin..J */
    t->block = (rugo_real*)rugo__alloc_array(&al, 3 * per, sizeof(rugo_real));
    if (t->block == NULL) {
        rugo__free(&al, t);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    memset(t->block, 0, 3 * per * sizeof(rugo_real));
    t->allocator = al;
    t->finest = J;
    t->coarsest = Jmin;
    t->own = t->block;
    t->total = t->own + per;
    t->bound = t->total + per;

    const int n = def->count;
    rugo_real* own_J = t->own + level_offset(t, J);
    rugo_real* total_J = t->total + level_offset(t, J);
    rugo_real* bound_J = t->bound + level_offset(t, J);
    memcpy(own_J, def->finest, (size_t)n * sizeof(rugo_real));
    memcpy(total_J, def->finest, (size_t)n * sizeof(rugo_real));
    for (int k = 0; k < n; ++k)
        bound_J[k] = finest_bound(def->finest, n, k, def->minimum);

    rugo_contour finest;
    rugo_pyramid_level(def->pyramid, J, &finest);
    for (int j = J - 1; j >= Jmin; --j) {
        rugo_contour coarse, fine;
        const rugo_vec2* local = NULL;
        rugo_pyramid_level(def->pyramid, j, &coarse);
        rugo_pyramid_level(def->pyramid, j + 1, &fine);
        rugo_pyramid_details(def->pyramid, j, NULL, &local);
        const int m = 1 << j;
        rugo_real* own = t->own + level_offset(t, j);
        rugo_real* total = t->total + level_offset(t, j);
        rugo_real* bound = t->bound + level_offset(t, j);
        const rugo_real* total_up = t->total + level_offset(t, j + 1);
        for (int k = 0; k < m; ++k) {
            const rugo_real sigma = def->estimator == RUGO_ESTIMATOR_COEFFICIENTS
                                        ? estimate_coefficients(local, m, k, def->neighbours)
                                        : estimate_detail(coarse, fine, k, def->extremes);
            own[k] = def->q * sigma;
            total[k] = own[k] + (total_up[2 * k] + total_up[2 * k + 1]) / 2.0; /* (5.3) */
            bound[k] = coarse_bound(coarse, finest, J - j, k, bound_J);
        }
    }
    /* Finite pyramid and finite input give finite results, except through overflow of huge values. */
    for (size_t i = 0; i < 3 * per; ++i)
        if (!isfinite(t->block[i])) {
            rugo_tolerances_destroy(t);
            return RUGO_ERR_NOT_FINITE;
        }
    *out = t;
    return RUGO_OK;
}

void rugo_tolerances_destroy(rugo_tolerances* t) {
    if (t == NULL) return;
    rugo_allocator al = t->allocator;
    rugo__free(&al, t->block);
    rugo__free(&al, t);
}

int rugo_tolerances_finest_level(const rugo_tolerances* t) { return t ? t->finest : -1; }
int rugo_tolerances_coarsest_level(const rugo_tolerances* t) { return t ? t->coarsest : -1; }

rugo_status rugo_tolerances_level(const rugo_tolerances* t, int level, rugo_tolerance_level* out) {
    if (t == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (level < t->coarsest || level > t->finest) return RUGO_ERR_BAD_LEVEL;
    const size_t o = level_offset(t, level);
    out->level = level;
    out->count = 1 << level;
    out->own = t->own + o;
    out->total = t->total + o;
    out->bound = t->bound + o;
    return RUGO_OK;
}

/* ---- friction (5.5, 6.4) ----------------------------------------------------------------------- */

rugo_friction_map rugo_default_friction_map(void) {
    rugo_friction_map m;
    m.base = RUGO_DEFAULT_MU_MIN;
    m.lambda_min = RUGO_DEFAULT_FRICTION_LAMBDA_MIN;
    m.alpha = (RUGO_DEFAULT_MU_MAX - RUGO_DEFAULT_MU_MIN) /
              (RUGO_DEFAULT_FRICTION_LAMBDA_MAX - RUGO_DEFAULT_FRICTION_LAMBDA_MIN);
    return m;
}

rugo_friction_map rugo_thesis_friction_map(void) {
    rugo_friction_map m;
    m.alpha = 1.0;
    m.lambda_min = 0.04;
    m.base = 0.0;
    return m;
}

rugo_status rugo_friction_map_check(const rugo_friction_map* m) {
    if (m == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (!isfinite(m->alpha) || !isfinite(m->lambda_min) || !isfinite(m->base)) return RUGO_ERR_NOT_FINITE;
    if (m->alpha < 0.0 || m->base < 0.0) return RUGO_ERR_BAD_ARGUMENT;
    if (m->lambda_min < 0.0) return RUGO_ERR_NEGATIVE_TOLERANCE;
    return RUGO_OK;
}

rugo_real rugo_friction(const rugo_friction_map* m, rugo_real lambda) {
    if (m == NULL) return NAN;
    if (lambda <= m->lambda_min) return m->base; /* (5.6); NaN falls through to NaN */
    return m->base + m->alpha * (lambda - m->lambda_min);
}

rugo_status rugo_friction_calibrate(rugo_real lambda_min, rugo_real lambda_max, rugo_real mu_min,
                                    rugo_real mu_max, rugo_friction_map* out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (!isfinite(lambda_min) || !isfinite(lambda_max) || !isfinite(mu_min) || !isfinite(mu_max))
        return RUGO_ERR_NOT_FINITE;
    if (lambda_min < 0.0 || lambda_max < 0.0) return RUGO_ERR_NEGATIVE_TOLERANCE;
    if (mu_min < 0.0) return RUGO_ERR_BAD_ARGUMENT;
    if (!(lambda_min < lambda_max) || mu_max < mu_min) return RUGO_ERR_EMPTY_RANGE;
    const rugo_real alpha = (mu_max - mu_min) / (lambda_max - lambda_min);
    if (!isfinite(alpha)) return RUGO_ERR_NOT_FINITE; /* a range so narrow that α overflows */
    out->alpha = alpha;
    out->lambda_min = lambda_min;
    out->base = mu_min;
    return RUGO_OK;
}

rugo_real rugo_mix(rugo_mix_rule rule, rugo_real a, rugo_real b) {
    switch (rule) {
    case RUGO_MIX_MAX:
        return a > b ? a : b;
    case RUGO_MIX_MIN:
        return a < b ? a : b;
    case RUGO_MIX_MEAN:
        return 0.5 * a + 0.5 * b; /* no overflow for huge a + b */
    case RUGO_MIX_GEOMETRIC: {
        const rugo_real g = sqrt(a * b);
        /* a b overflows (or underflows) only for extreme values; then the product of the roots */
        return isfinite(g) && (g > 0.0 || a == 0.0 || b == 0.0) ? g : sqrt(a) * sqrt(b);
    }
    default:
        return NAN;
    }
}

/* ---- restitution in continuous contact (6.5, 7.3) -------------------------------------------- */

rugo_restitution rugo_default_restitution(void) {
    rugo_restitution r;
    r.epsilon = 0.5;
    r.epsilon_max = 0.9;
    return r;
}

rugo_status rugo_restitution_check(const rugo_restitution* r) {
    if (r == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (!isfinite(r->epsilon) || !isfinite(r->epsilon_max)) return RUGO_ERR_NOT_FINITE;
    if (r->epsilon < 0.0 || r->epsilon > 1.0 || r->epsilon_max < 0.0 || r->epsilon_max > 1.0)
        return RUGO_ERR_BAD_ARGUMENT;
    if (r->epsilon > r->epsilon_max) return RUGO_ERR_EMPTY_RANGE;
    return RUGO_OK;
}

rugo_real rugo_restitution_in_band(const rugo_restitution* r, rugo_real delta, rugo_real lambda) {
    if (r == NULL || isnan(delta) || isnan(lambda)) return NAN;
    if (!(lambda > 0.0) || !(delta > 0.0)) return r->epsilon;
    if (delta >= lambda) return r->epsilon_max; /* exactly ε_max at the band's edge and beyond */
    const rugo_real x = delta / lambda;         /* in [0, 1): the ratio form avoids overflow of λ² */
    const rugo_real e = (r->epsilon_max - r->epsilon) * x * x + r->epsilon;
    return e < r->epsilon_max ? e : r->epsilon_max; /* round-off must not break monotonicity at δ = λ */
}
