/* Multiresolution pyramid of a contour, details in local frames, direct manipulation and
 * multiresolution deformation (SPEC 2.3, 3; thesis 2.2-2.3).
 *
 * Invariant: every level of the pyramid is the analysis of the finest control points. Edits build
 * new finest points by synthesis (with details fixed in world coordinates or re-oriented in local
 * frames) and then re-analyse, so the stored levels never drift apart. Edits run in buffers owned
 * by the pyramid: after creation nothing allocates. An edit that would produce a non-finite value
 * is refused and leaves the pyramid as it was. */
#include "rugo/multires.h"

#include "core/internal.h"
#include "curve/internal.h" /* rugo__pyramid_from_levels */

#include <string.h>

/* Catches defs that did not come from rugo_default_pyramid_def ("RUGP"). */
#define PYRAMID_DEF_COOKIE 0x52554750

/* Level j of a per-level array lives at offset 2^j: levels J_min..J fit in 2^(J+1) entries, and
 * details (levels < J) in 2^J. */
#define LEVEL_OFFSET(j) ((size_t)1 << (j))

struct rugo_pyramid {
    rugo_allocator allocator;
    rugo_filter filter;
    int finest;        /* J */
    int coarsest;      /* J_min */
    int count;         /* 2^J */
    bool reversed;     /* the last input was clockwise and was reversed */
    int check_flags;   /* rugo_contour_check flags used on input */
    rugo_vec2* block;  /* one allocation holding everything below */
    rugo_vec2* points; /* C^j at LEVEL_OFFSET(j), J_min <= j <= J */
    rugo_vec2* world;  /* D^j at LEVEL_OFFSET(j), J_min <= j < J */
    rugo_vec2* local;  /* D^j in local frames (tangent, normal components) */
    rugo_vec2* delta;  /* per-level control-point changes of the edit under way */
    rugo_vec2* buf_a;  /* 2^J: synthesis ping-pong */
    rugo_vec2* buf_b;  /* 2^J */
    rugo_vec2* buf_d;  /* 2^(J-1): re-oriented details of one level */
};

rugo_pyramid_def rugo_default_pyramid_def(void) {
    rugo_pyramid_def d;
    memset(&d, 0, sizeof d);
    d.points = NULL;
    d.count = 0;
    d.filter = RUGO_FILTER_DEFAULT;
    d.coarsest_level = 0;
    d.check_self_intersection = true;
    d.cookie = PYRAMID_DEF_COOKIE;
    return d;
}

static rugo_vec2* level_points(const rugo_pyramid* p, int j) { return p->points + LEVEL_OFFSET(j); }
static rugo_vec2* level_world(const rugo_pyramid* p, int j) { return p->world + LEVEL_OFFSET(j); }
static rugo_vec2* level_local(const rugo_pyramid* p, int j) { return p->local + LEVEL_OFFSET(j); }
static rugo_vec2* level_delta(const rugo_pyramid* p, int j) { return p->delta + LEVEL_OFFSET(j); }

static int all_finite(const rugo_vec2* v, size_t n) {
    for (size_t i = 0; i < n; ++i)
        if (!rugo__v2_finite(v[i])) return 0;
    return 1;
}

/* The frame of detail d^j_s: tangent and normal of f^j at segment s-1, t = 1/2 (the point of f^j
 * that corresponds to fine index 2s-1). */
static void detail_frame(rugo_contour coarse, int s, rugo_vec2* tangent, rugo_vec2* normal) {
    int seg = rugo__wrap(s - 1, coarse.count);
    *tangent = rugo_contour_tangent(coarse, seg, 0.5);
    *normal = rugo_contour_normal(coarse, seg, 0.5);
}

/* Re-analyses every level from the finest points and recomputes the local details. */
static void rebuild(rugo_pyramid* p) {
    for (int j = p->finest; j > p->coarsest; --j) {
        rugo_status st = rugo_wavelet_analyze(p->filter, level_points(p, j), 1 << (j - 1),
                                              level_points(p, j - 1), level_world(p, j - 1));
        RUGO_ASSERT(st == RUGO_OK);
        (void)st;
    }
    for (int j = p->coarsest; j < p->finest; ++j) {
        rugo_contour c;
        c.points = level_points(p, j);
        c.count = 1 << j;
        const rugo_vec2* w = level_world(p, j);
        rugo_vec2* l = level_local(p, j);
        for (int s = 0; s < c.count; ++s) {
            rugo_vec2 tg, nm;
            detail_frame(c, s, &tg, &nm);
            l[s] = rugo_v2(rugo_v2_dot(w[s], tg), rugo_v2_dot(w[s], nm));
        }
    }
}

static int pyramid_finite(const rugo_pyramid* p) {
    /* Levels J_min..J of points and J_min..J-1 of details occupy contiguous ranges. */
    size_t lo = LEVEL_OFFSET(p->coarsest), hi = LEVEL_OFFSET(p->finest);
    return all_finite(p->points + lo, 2 * hi - lo) && all_finite(p->world + lo, hi - lo) &&
           all_finite(p->local + lo, hi - lo);
}

/* Makes `fresh` (2^J points, not aliasing the finest level) the finest level and rebuilds; if the
 * rebuilt pyramid holds a non-finite value (overflow), restores the old finest points, which
 * `backup` (2^J points) receives, and fails. */
static rugo_status commit_finest(rugo_pyramid* p, const rugo_vec2* fresh, rugo_vec2* backup) {
    const size_t bytes = (size_t)p->count * sizeof(rugo_vec2);
    if (!all_finite(fresh, (size_t)p->count)) return RUGO_ERR_NOT_FINITE;
    rugo_vec2* fin = level_points(p, p->finest);
    memcpy(backup, fin, bytes);
    memcpy(fin, fresh, bytes);
    rebuild(p);
    if (pyramid_finite(p)) return RUGO_OK;
    memcpy(fin, backup, bytes);
    rebuild(p);
    return RUGO_ERR_NOT_FINITE;
}

/* Zeroes the edit deltas of levels lo..J. */
static void clear_deltas(rugo_pyramid* p, int lo) {
    size_t a = LEVEL_OFFSET(lo), b = LEVEL_OFFSET(p->finest + 1);
    memset(p->delta + a, 0, (b - a) * sizeof(rugo_vec2));
}

/* The edit under way: C'^lo = C^lo + delta^lo, then for each finer level
 * C'^{j+1} = synthesis(C'^j, D'^j) + delta^{j+1}, with D'^j the stored world details (FIXED) or the
 * stored local details expressed in the frames of the new curve f'^j (LOCAL); finally the new
 * finest points are re-analysed into the whole pyramid. */
static rugo_status apply_edit(rugo_pyramid* p, int lo, rugo_detail_mode mode) {
    rugo_vec2* cur = p->buf_a;
    rugo_vec2* nxt = p->buf_b;
    const rugo_vec2* c0 = level_points(p, lo);
    const rugo_vec2* d0 = level_delta(p, lo);
    for (int i = 0; i < (1 << lo); ++i)
        cur[i] = rugo_v2_add(c0[i], d0[i]);
    for (int j = lo; j < p->finest; ++j) {
        const int m = 1 << j;
        const rugo_vec2* details = level_world(p, j);
        if (mode == RUGO_DETAILS_LOCAL) {
            rugo_contour c;
            c.points = cur;
            c.count = m;
            const rugo_vec2* l = level_local(p, j);
            for (int s = 0; s < m; ++s) {
                rugo_vec2 tg, nm;
                detail_frame(c, s, &tg, &nm);
                p->buf_d[s] = rugo_v2_add(rugo_v2_scale(l[s].x, tg), rugo_v2_scale(l[s].y, nm));
            }
            details = p->buf_d;
        }
        rugo_status st = rugo_wavelet_synthesize(p->filter, cur, details, m, nxt);
        RUGO_ASSERT(st == RUGO_OK);
        (void)st;
        const rugo_vec2* dd = level_delta(p, j + 1);
        for (int i = 0; i < 2 * m; ++i)
            nxt[i] = rugo_v2_add(nxt[i], dd[i]);
        rugo_vec2* tmp = cur;
        cur = nxt;
        nxt = tmp;
    }
    return commit_finest(p, cur, nxt);
}

/* Adds to delta^level the least-norm change (2.30)-(2.31) of the control points of `segment` that
 * moves f^level_segment(t) by d. The four points are c_{seg-1..seg+2}; should some coincide
 * cyclically (fewer than 4 points on a level) their basis values merge into one weight each, and
 * the least-norm solution is delta_k = w_k d / sum w^2 over the distinct indices k. */
static void add_point_delta(rugo_pyramid* p, int level, int segment, rugo_real t, rugo_vec2 d) {
    const int m = 1 << level;
    rugo_real basis[4], w[4];
    int idx[4], nu = 0;
    rugo_bspline_basis(t, basis);
    for (int i = 0; i < 4; ++i) {
        int k = rugo__wrap(segment - 1 + i, m), u = 0;
        while (u < nu && idx[u] != k)
            ++u;
        if (u == nu) {
            idx[nu] = k;
            w[nu++] = 0.0;
        }
        w[u] += basis[i];
    }
    rugo_real norm2 = 0.0;
    for (int u = 0; u < nu; ++u)
        norm2 += w[u] * w[u];
    RUGO_ASSERT(norm2 > 0.0); /* the basis values are >= 0 and sum to 1 */
    rugo_vec2* dl = level_delta(p, level);
    for (int u = 0; u < nu; ++u)
        dl[idx[u]] = rugo_v2_add(dl[idx[u]], rugo_v2_scale(w[u] / norm2, d));
}

/* ---- Creation ------------------------------------------------------------------------------- */

rugo_status rugo_pyramid_create(const rugo_pyramid_def* def, rugo_pyramid** out,
                                rugo_contour_problem* problem) {
    if (out != NULL) *out = NULL;
    if (problem != NULL) {
        problem->index = -1;
        problem->segment_a = -1;
        problem->segment_b = -1;
        problem->where = rugo_v2(0.0, 0.0);
    }
    if (def == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (def->cookie != PYRAMID_DEF_COOKIE) return RUGO_ERR_BAD_ARGUMENT;
    if (rugo_filter_name(def->filter) == NULL) return RUGO_ERR_BAD_FILTER; /* the wavelet module decides */
    int flags = RUGO_CHECK_POWER_OF_TWO | (def->check_self_intersection ? RUGO_CHECK_SELF_INTERSECTION : 0);
    rugo_status st = rugo_contour_check(def->points, def->count, flags, problem, &def->allocator);
    if (st != RUGO_OK) return st;
    int finest = 0;
    while ((1 << finest) < def->count)
        ++finest;
    int coarsest = def->coarsest_level == 0 ? 2 : def->coarsest_level;
    if (coarsest < 2 || coarsest > finest) return RUGO_ERR_BAD_LEVEL;

    rugo_allocator al = rugo__allocator_or_default(&def->allocator);
    rugo_pyramid* p = (rugo_pyramid*)rugo__alloc_array(&al, 1, sizeof(rugo_pyramid));
    if (p == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(p, 0, sizeof *p);
    const size_t n = (size_t)def->count;
    /* points 2n, world n, local n, delta 2n, buf_a n, buf_b n, buf_d n/2. */
    p->block = (rugo_vec2*)rugo__alloc_array(&al, 8 * n + n / 2, sizeof(rugo_vec2));
    if (p->block == NULL) {
        rugo__free(&al, p);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    memset(p->block, 0, (8 * n + n / 2) * sizeof(rugo_vec2));
    p->allocator = al;
    p->filter = def->filter;
    p->finest = finest;
    p->coarsest = coarsest;
    p->count = def->count;
    p->check_flags = flags;
    p->points = p->block;
    p->world = p->points + 2 * n;
    p->local = p->world + n;
    p->delta = p->local + n;
    p->buf_a = p->delta + 2 * n;
    p->buf_b = p->buf_a + n;
    p->buf_d = p->buf_b + n;

    rugo_vec2* fin = level_points(p, finest);
    memcpy(fin, def->points, n * sizeof(rugo_vec2));
    p->reversed = rugo_contour_orient_ccw(fin, def->count);
    rebuild(p);
    if (!pyramid_finite(p)) { /* finite input whose transform overflows (coordinates near DBL_MAX) */
        rugo_pyramid_destroy(p);
        return RUGO_ERR_NOT_FINITE;
    }
    *out = p;
    return RUGO_OK;
}

void rugo_pyramid_destroy(rugo_pyramid* p) {
    if (p == NULL) return;
    rugo_allocator al = p->allocator;
    rugo__free(&al, p->block);
    rugo__free(&al, p);
}

int rugo_pyramid_finest_level(const rugo_pyramid* p) { return p ? p->finest : -1; }
int rugo_pyramid_coarsest_level(const rugo_pyramid* p) { return p ? p->coarsest : -1; }
rugo_filter rugo_pyramid_filter(const rugo_pyramid* p) { return p ? p->filter : RUGO_FILTER_COUNT; }
bool rugo_pyramid_was_reversed(const rugo_pyramid* p) { return p != NULL && p->reversed; }
rugo_allocator rugo_pyramid_allocator(const rugo_pyramid* p) {
    return p ? p->allocator : rugo_default_allocator();
}

rugo_status rugo_pyramid_level(const rugo_pyramid* p, int level, rugo_contour* out) {
    if (p == NULL || out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (level < p->coarsest || level > p->finest) return RUGO_ERR_BAD_LEVEL;
    out->points = level_points(p, level);
    out->count = 1 << level;
    return RUGO_OK;
}

rugo_status rugo_pyramid_details(const rugo_pyramid* p, int level, const rugo_vec2** world,
                                 const rugo_vec2** local) {
    if (p == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (level < p->coarsest || level >= p->finest) return RUGO_ERR_BAD_LEVEL;
    if (world) *world = level_world(p, level);
    if (local) *local = level_local(p, level);
    return RUGO_OK;
}

/* ---- Parameters across levels --------------------------------------------------------------- */

void rugo_level_parameter(int from, int segment, rugo_real t, int to, int* out_segment, rugo_real* out_t) {
    int seg = segment;
    rugo_real tt = t;
    /* Levels beyond 30 cannot index an int segment; such calls (and a NaN t) pass through unchanged. */
    if (from >= 0 && from <= 30 && to >= 0 && to <= 30 && isfinite(t)) {
        seg = rugo__wrap(segment, 1 << from);
        if (to < from) {
            /* Fine segment k covers the half (k & 1) of coarse segment k >> 1, per level. */
            const int k = from - to;
            const int low = seg & ((1 << k) - 1);
            tt = (t + (rugo_real)low) / (rugo_real)(1 << k);
            seg >>= k;
        } else if (to > from) {
            const int k = to - from;
            const rugo_real u = t * (rugo_real)(1 << k);
            rugo_real fl = floor(u);
            if (fl < 0.0) fl = 0.0;
            if (fl > (rugo_real)((1 << k) - 1))
                fl = (rugo_real)((1 << k) - 1); /* t = 1 stays in the last half */
            seg = (seg << k) + (int)fl;
            tt = u - fl;
        }
    }
    if (out_segment) *out_segment = seg;
    if (out_t) *out_t = tt;
}

/* ---- Edits ---------------------------------------------------------------------------------- */

static int mode_valid(rugo_detail_mode mode) {
    return mode == RUGO_DETAILS_FIXED || mode == RUGO_DETAILS_LOCAL;
}

rugo_status rugo_pyramid_displace_level(rugo_pyramid* p, int level, const rugo_vec2* delta,
                                        rugo_detail_mode mode) {
    if (p == NULL || delta == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (level < p->coarsest || level > p->finest) return RUGO_ERR_BAD_LEVEL;
    if (!mode_valid(mode)) return RUGO_ERR_BAD_ARGUMENT;
    if (!all_finite(delta, (size_t)1 << level)) return RUGO_ERR_NOT_FINITE;
    clear_deltas(p, level);
    memcpy(level_delta(p, level), delta, ((size_t)1 << level) * sizeof(rugo_vec2));
    return apply_edit(p, level, mode);
}

static rugo_status check_point_args(const rugo_pyramid* p, int level, int segment, rugo_real t,
                                    rugo_vec2 delta, rugo_detail_mode mode) {
    if (level < p->coarsest || level > p->finest) return RUGO_ERR_BAD_LEVEL;
    if (segment < 0 || segment >= (1 << level)) return RUGO_ERR_BAD_ARGUMENT;
    if (!(t >= 0.0 && t <= 1.0)) return RUGO_ERR_BAD_ARGUMENT; /* also rejects NaN */
    if (!mode_valid(mode)) return RUGO_ERR_BAD_ARGUMENT;
    if (!rugo__v2_finite(delta)) return RUGO_ERR_NOT_FINITE;
    return RUGO_OK;
}

rugo_status rugo_pyramid_move_point(rugo_pyramid* p, int level, int segment, rugo_real t, rugo_vec2 delta,
                                    rugo_detail_mode mode) {
    if (p == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_point_args(p, level, segment, t, delta, mode);
    if (st != RUGO_OK) return st;
    clear_deltas(p, level);
    add_point_delta(p, level, segment, t, delta);
    return apply_edit(p, level, mode);
}

rugo_status rugo_deformation_weights(int m, rugo_real w, rugo_real* out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (m < 1) return RUGO_ERR_BAD_ARGUMENT;
    if (!isfinite(w)) return RUGO_ERR_NOT_FINITE;
    /* Piece i = (e^{-w i/m} - e^{-w (i+1)/m}) / (1 - e^{-w}) = e^{-w i/m} expm1(-w/m) / expm1(-w),
     * written for |w| so nothing overflows; g for -w is g for w mirrored (piece i <-> m-1-i). Below
     * 1e-200 the weights equal 1/m to far better than double precision (and w/m could underflow). */
    const rugo_real aw = fabs(w);
    if (aw < 1e-200) {
        for (int i = 0; i < m; ++i)
            out[i] = 1.0 / (rugo_real)m;
        return RUGO_OK;
    }
    const rugo_real ratio = expm1(-aw / (rugo_real)m) / expm1(-aw);
    rugo_real sum = 0.0;
    for (int i = 0; i < m; ++i) {
        rugo_real v = exp(-aw * ((rugo_real)i / (rugo_real)m)) * ratio;
        out[w > 0.0 ? i : m - 1 - i] = v;
        sum += v;
    }
    /* The closed form sums to 1 up to a few ulps; normalising keeps Theorem 2.1's total exact to
     * round-off however many levels share the move. */
    for (int i = 0; i < m; ++i)
        out[i] /= sum;
    return RUGO_OK;
}

rugo_status rugo_pyramid_deform(rugo_pyramid* p, int segment, rugo_real t, rugo_vec2 delta, int spread,
                                rugo_real w, rugo_detail_mode mode, rugo_real* weights_out) {
    if (p == NULL) return RUGO_ERR_NULL_ARGUMENT;
    rugo_status st = check_point_args(p, p->finest, segment, t, delta, mode);
    if (st != RUGO_OK) return st;
    if (spread < 1 || spread > p->finest - p->coarsest + 1) return RUGO_ERR_BAD_LEVEL;
    rugo_real weights[32]; /* spread <= J + 1 <= 21 */
    st = rugo_deformation_weights(spread, w, weights);
    if (st != RUGO_OK) return st;
    const int lo = p->finest - spread + 1;
    clear_deltas(p, lo);
    for (int i = 0; i < spread; ++i) {
        const int level = p->finest - i;
        int seg;
        rugo_real tl;
        rugo_level_parameter(p->finest, segment, t, level, &seg, &tl);
        add_point_delta(p, level, seg, tl, rugo_v2_scale(weights[i], delta));
    }
    st = apply_edit(p, lo, mode);
    if (st == RUGO_OK && weights_out != NULL)
        memcpy(weights_out, weights, (size_t)spread * sizeof(rugo_real));
    return st;
}

rugo_status rugo_pyramid_set_finest(rugo_pyramid* p, const rugo_vec2* points, int count) {
    if (p == NULL || points == NULL) return RUGO_ERR_NULL_ARGUMENT;
    if (count != p->count) return RUGO_ERR_BAD_ARGUMENT;
    rugo_status st = rugo_contour_check(points, count, p->check_flags, NULL, &p->allocator);
    if (st != RUGO_OK) return st;
    memcpy(p->buf_a, points, (size_t)count * sizeof(rugo_vec2));
    bool reversed = rugo_contour_orient_ccw(p->buf_a, count);
    st = commit_finest(p, p->buf_a, p->buf_b);
    if (st == RUGO_OK) p->reversed = reversed;
    return st;
}

/* ---- internal (baked shapes): a pyramid from stored levels, without analysis ---------------------- */

/* Stored levels are decoded as arrays of doubles straight into the vec2 arrays. */
typedef char rugo__vec2_is_two_doubles[sizeof(rugo_vec2) == 2 * sizeof(double) ? 1 : -1];

/* The O(n) outline check of rugo__pyramid_from_levels (shape_internal.h). The signed area of a closed
 * uniform cubic B-spline is exactly Σ_i (49/144 c1_i + 7/90 c2_i + 1/720 c3_i) with
 * cd_i = cross(P_i - P_0, P_{i+d} - P_0) (1/2 ∮ cross(f, f') with the basis integrated in closed
 * form), summed with Neumaier's compensation like rugo_contour_signed_area. The joints
 * f(j, 0) = (P_{j-1} + 4 P_j + P_{j+1}) / 6 bound the curve's box from inside. */
static rugo_status outline_check(const rugo_vec2* p, size_t n) {
    const rugo_vec2 o = p[0];
    rugo_real s = 0.0, c = 0.0;
    rugo_real lox = HUGE_VAL, loy = HUGE_VAL, hix = -HUGE_VAL, hiy = -HUGE_VAL;
    rugo_vec2 prev = rugo_v2_sub(p[n - 1], o);
    rugo_vec2 d0 = rugo_v2(0.0, 0.0), d1 = rugo_v2_sub(p[1], o), d2 = rugo_v2_sub(p[2], o);
    for (size_t i = 0; i < n; ++i) {
        const rugo_vec2 d3 = rugo_v2_sub(p[(i + 3) & (n - 1)], o); /* n is a power of two */
        const rugo_real x = (49.0 / 144.0) * rugo_v2_cross(d0, d1) + (7.0 / 90.0) * rugo_v2_cross(d0, d2) +
                            (1.0 / 720.0) * rugo_v2_cross(d0, d3);
        const rugo_real t = s + x;
        c += fabs(s) >= fabs(x) ? (s - t) + x : (x - t) + s;
        s = t;
        const rugo_real jx = (prev.x + 4.0 * d0.x + d1.x) / 6.0, jy = (prev.y + 4.0 * d0.y + d1.y) / 6.0;
        lox = fmin(lox, jx);
        hix = fmax(hix, jx);
        loy = fmin(loy, jy);
        hiy = fmax(hiy, jy);
        prev = d0;
        d0 = d1;
        d1 = d2;
        d2 = d3;
    }
    const rugo_real area = s + c;
    const rugo_real diag2 = (hix - lox) * (hix - lox) + (hiy - loy) * (hiy - loy);
    if (!isfinite(area) || !isfinite(diag2)) return RUGO_ERR_NOT_FINITE;
    if (!(fabs(area) > 1e-13 * diag2)) return RUGO_ERR_ZERO_AREA;
    return area > 0.0 ? RUGO_OK : RUGO_ERR_BAD_ARGUMENT; /* clockwise */
}

rugo_status rugo__pyramid_from_levels(rugo_filter filter, int finest, int coarsest, bool reversed,
                                      const unsigned char* points, const unsigned char* world,
                                      const unsigned char* local, const rugo_allocator* allocator,
                                      rugo_pyramid** out) {
    if (out == NULL) return RUGO_ERR_NULL_ARGUMENT;
    *out = NULL;
    if (points == NULL || (finest > coarsest && (world == NULL || local == NULL)))
        return RUGO_ERR_NULL_ARGUMENT;
    if (rugo_filter_name(filter) == NULL) return RUGO_ERR_BAD_FILTER;
    if (coarsest < 2 || finest < coarsest || finest > 30 || (1 << finest) > RUGO_MAX_CONTROL_POINTS)
        return RUGO_ERR_BAD_LEVEL;
    rugo_allocator al = rugo__allocator_or_default(allocator);
    rugo_pyramid* p = (rugo_pyramid*)rugo__alloc_array(&al, 1, sizeof(rugo_pyramid));
    if (p == NULL) return RUGO_ERR_OUT_OF_MEMORY;
    memset(p, 0, sizeof *p);
    const size_t n = (size_t)1 << finest, lo = LEVEL_OFFSET(coarsest);
    /* rugo_pyramid_create's layout: points 2n, world n, local n, delta 2n, buf_a n, buf_b n, buf_d n/2. */
    p->block = (rugo_vec2*)rugo__alloc_array(&al, 8 * n + n / 2, sizeof(rugo_vec2));
    if (p->block == NULL) {
        rugo__free(&al, p);
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    p->allocator = al;
    p->filter = filter;
    p->finest = finest;
    p->coarsest = coarsest;
    p->count = (int)n;
    p->reversed = reversed;
    p->check_flags = RUGO_CHECK_POWER_OF_TWO | RUGO_CHECK_SELF_INTERSECTION; /* edits: as a default build */
    p->points = p->block;
    p->world = p->points + 2 * n;
    p->local = p->world + n;
    p->delta = p->local + n;
    p->buf_a = p->delta + 2 * n;
    p->buf_b = p->buf_a + n;
    p->buf_d = p->buf_b + n;
    /* Zero the levels below J_min, as the public constructor leaves them; decode the stored levels in
     * place. The edit buffers (delta, buf_a, buf_b, buf_d) stay as allocated: every edit writes what
     * it reads there first (clear_deltas, apply_edit, commit_finest), and untouched they cost no
     * page faults. */
    memset(p->points, 0, lo * sizeof(rugo_vec2));
    rugo__decode_f64_le((double*)(void*)(p->points + lo), points, 2 * (2 * n - lo));
    memset(p->world, 0, lo * sizeof(rugo_vec2));
    if (finest > coarsest) rugo__decode_f64_le((double*)(void*)(p->world + lo), world, 2 * (n - lo));
    memset(p->local, 0, lo * sizeof(rugo_vec2));
    if (finest > coarsest) rugo__decode_f64_le((double*)(void*)(p->local + lo), local, 2 * (n - lo));
    const rugo_status st = outline_check(level_points(p, finest), n);
    if (st != RUGO_OK) {
        rugo_pyramid_destroy(p);
        return st;
    }
    *out = p;
    return RUGO_OK;
}
