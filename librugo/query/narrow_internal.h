/* Private to the narrow phase (the narrow*.c files of librugo/query; narrow.c describes how it works):
 * the limits and tolerances of its searches, the state a call carries through them, the small Bezier,
 * interval and parameter-box helpers they all use, and what each file offers the others. Not
 * installed; narrow.h is the narrow phase's interface for the contact queries. */
#ifndef RUGO_QUERY_NARROW_INTERNAL_H
#define RUGO_QUERY_NARROW_INTERNAL_H

#include "query/narrow.h"

#include "core/internal.h"

#include <float.h>
#include <math.h>

#define EPS DBL_EPSILON

enum {
    STACK_MAX = 128,   /* depth-first stack; depth <= 2 * 26 + 1 */
    BOX_BUDGET = 6000, /* boxes per search */
    NEWTON_MAX = 40,
    TMP_CROSS = 32, /* working root lists (larger than the output arrays, to detect overflow) */
    TMP_STAT = 64,
    KIND_PROBE = 99 /* crossing kind still to be decided by probing */
};

#define H_MIN (1.0 / 67108864.0)  /* 2^-26: smallest box side in parameter */
#define D_MIN (8.0 * EPS)         /* sub-pieces smaller than this cannot be told apart */
#define TAU_F (32.0 * EPS)        /* round-off allowance on coordinates (local frame) */
#define TAU_TOUCH (512.0 * EPS)   /* distance counted as zero: touching */
#define SLACK 1e-12               /* a Newton root this far outside its box still counts as inside */
#define DOM_SLACK 1e-10           /* roots this far outside [0,1] are clamped in */
#define R_ROOT 1e-9               /* minimal parameter distance between distinct roots */
#define R_FALLBACK 1e-6           /* merge radius around crossings found in leaves */
#define H_ACC (1.0 / 262144.0)    /* 2^-18: uncertified stationary boxes this small accept a Newton root */
#define R_MERGE 1e-5              /* ... and everything within this parameter distance of it */
#define H_TOUCH (1.0 / 1048576.0) /* 2^-20: crossing boxes this small try the touching hypothesis */
#define POINT_TOL 1e-13           /* a piece within this extent is a point */
#define END_ZONE 1e-4             /* a root this close to a zero-speed end is at that end (rugo__near_end) */

/* A box of the parameter square: s in [s0, s1], t in [t0, t1]. */
typedef struct box {
    rugo_real s0, s1, t0, t1;
} box;

/* A root of a search, with the radius within which another is the same one. */
typedef struct root {
    rugo_real s, t;
    rugo_real radius; /* dedupe radius in parameter */
    int kind;
    int fallback;
} root;

/* What one call of the narrow phase carries through its searches: the pieces in the local frame, the
 * counters it reports, the tests of the whole square both searches share, and the root lists. */
typedef struct narrow_ctx {
    rugo_vec2 f[4], g[4];     /* local frame */
    rugo_vec2 df[3], dg[3];   /* hodographs (derivative in the global parameter) */
    rugo_vec2 ddf[2], ddg[2]; /* second derivatives */
    rugo_vec2 origin;
    rugo_real scale;  /* caller point = origin + scale * local point */
    rugo_real cutoff; /* local frame; negative: no stationary pairs */
    int newton, fallback, overflow;
    int ncross, nstat;
    /* Tests of the whole square [0,1]^2, shared by the two searches (both start there). */
    int root_apart; /* the hulls of f and g are more than TAU_F apart: no crossing */
    int root_cone_done, root_cone;
    rugo_real root_rho;
    rugo_real root_cross[9]; /* cross(df[i], dg[j]) at 3 i + j (solve) */
    root cross[TMP_CROSS];   /* (the lists last: they are not cleared) */
    root stat[TMP_STAT];
} narrow_ctx;

/* ---------------------------------------------------------------------------------------------------
 * Small helpers. */

/* max / min without the NaN handling of fmax / fmin (which are library calls): inputs are finite. */
static inline rugo_real rugo__max(rugo_real a, rugo_real b) { return a > b ? a : b; }

static inline rugo_real rugo__min(rugo_real a, rugo_real b) { return a < b ? a : b; }

static inline rugo_vec2 rugo__lerp(rugo_vec2 a, rugo_vec2 b, rugo_real u) {
    return rugo_v2((1.0 - u) * a.x + u * b.x, (1.0 - u) * a.y + u * b.y);
}

static inline rugo_real rugo__v2_max_abs(rugo_vec2 v) { return rugo__max(fabs(v.x), fabs(v.y)); }

/* Local frame: magnitudes are O(1), so the plain formula cannot overflow (hypot is much slower). */
static inline rugo_real rugo__v2_norm(rugo_vec2 v) { return sqrt(v.x * v.x + v.y * v.y); }

static inline int rugo__sign(rugo_real v) { return (v > 0.0) - (v < 0.0); }

/* de Casteljau evaluation, degree n <= 3. */
static inline rugo_vec2 rugo__bezier_eval(const rugo_vec2* p, int n, rugo_real u) {
    rugo_vec2 w[4];
    for (int i = 0; i <= n; ++i)
        w[i] = p[i];
    for (int k = 1; k <= n; ++k)
        for (int i = 0; i <= n - k; ++i)
            w[i] = rugo__lerp(w[i], w[i + 1], u);
    return w[0];
}

/* Bezier points of p (degree n <= 3) on any interval [a, b] with 0 < b, a < b: within [0, 1] the
 * restriction of the piece (the sub-boxes of a search), outside it the polynomial extrapolated (de
 * Casteljau with parameters beyond 1 or below 0: the boxes around a root found just outside a box,
 * the exclusion boxes). */
static inline void rugo__sub_bezier(const rugo_vec2* p, int n, rugo_real a, rugo_real b, rugo_vec2* out) {
    rugo_vec2 w[4], part[4];
    for (int i = 0; i <= n; ++i)
        w[i] = p[i];
    if (b != 1.0) {
        part[0] = w[0];
        for (int k = 1; k <= n; ++k) {
            for (int i = 0; i <= n - k; ++i)
                w[i] = rugo__lerp(w[i], w[i + 1], b);
            part[k] = w[0];
        }
        for (int i = 0; i <= n; ++i)
            w[i] = part[i];
    }
    if (a != 0.0) {
        rugo_real u = a / b;
        part[n] = w[n];
        for (int k = 1; k <= n; ++k) {
            for (int i = 0; i <= n - k; ++i)
                w[i] = rugo__lerp(w[i], w[i + 1], u);
            part[n - k] = w[n - k];
        }
        for (int i = 0; i <= n; ++i)
            w[i] = part[i];
    }
    for (int i = 0; i <= n; ++i)
        out[i] = w[i];
}

/* Largest distance (max-norm) between control points: a size of the sub-piece. */
static inline rugo_real rugo__polygon_diameter(const rugo_vec2* p, int n) {
    rugo_real lox = p[0].x, hix = p[0].x, loy = p[0].y, hiy = p[0].y;
    for (int i = 1; i <= n; ++i) {
        lox = rugo__min(lox, p[i].x);
        hix = rugo__max(hix, p[i].x);
        loy = rugo__min(loy, p[i].y);
        hiy = rugo__max(hiy, p[i].y);
    }
    return rugo__max(hix - lox, hiy - loy);
}

/* Largest max-norm offset of a control point from the first: within POINT_TOL a piece is a point. */
static inline rugo_real rugo__piece_extent(const rugo_vec2 p[4]) {
    rugo_real e = 0.0;
    for (int i = 1; i < 4; ++i)
        e = rugo__max(e, rugo__v2_max_abs(rugo_v2_sub(p[i], p[0])));
    return e;
}

/* ---------------------------------------------------------------------------------------------------
 * Interval arithmetic (round-off is covered by explicit margins). */

typedef struct ival {
    rugo_real lo, hi;
} ival;

static inline ival rugo__iv(rugo_real lo, rugo_real hi) {
    ival r;
    r.lo = lo;
    r.hi = hi;
    return r;
}

static inline ival rugo__iv_add(ival a, ival b) { return rugo__iv(a.lo + b.lo, a.hi + b.hi); }

static inline ival rugo__iv_neg(ival a) { return rugo__iv(-a.hi, -a.lo); }

static inline ival rugo__iv_mul(ival a, ival b) {
    rugo_real p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
    return rugo__iv(rugo__min(rugo__min(p0, p1), rugo__min(p2, p3)),
                    rugo__max(rugo__max(p0, p1), rugo__max(p2, p3)));
}

static inline ival rugo__iv_sq(ival a) {
    rugo_real l = a.lo * a.lo, h = a.hi * a.hi;
    if (a.lo <= 0.0 && a.hi >= 0.0) return rugo__iv(0.0, rugo__max(l, h));
    return rugo__iv(rugo__min(l, h), rugo__max(l, h));
}

static inline rugo_real rugo__iv_mag(ival a) { return rugo__max(fabs(a.lo), fabs(a.hi)); }

static inline ival rugo__iv_scale(rugo_real k, ival a) {
    return k >= 0.0 ? rugo__iv(k * a.lo, k * a.hi) : rugo__iv(k * a.hi, k * a.lo);
}

/* Componentwise ranges of a control polygon (n + 1 points). */
static inline void rugo__iv_range(const rugo_vec2* p, int n, ival* x, ival* y) {
    *x = rugo__iv(p[0].x, p[0].x);
    *y = rugo__iv(p[0].y, p[0].y);
    for (int i = 1; i <= n; ++i) {
        x->lo = rugo__min(x->lo, p[i].x);
        x->hi = rugo__max(x->hi, p[i].x);
        y->lo = rugo__min(y->lo, p[i].y);
        y->hi = rugo__max(y->hi, p[i].y);
    }
}

/* +1 / -1 if every value is above tau / below -tau, else 0. */
static inline int rugo__one_sign(const rugo_real* v, int n, rugo_real tau) {
    if (v[0] > tau) {
        for (int i = 1; i < n; ++i)
            if (!(v[i] > tau)) return 0;
        return 1;
    }
    if (v[0] < -tau) {
        for (int i = 1; i < n; ++i)
            if (!(v[i] < -tau)) return 0;
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------------------------------------------
 * Parameter boxes and where a root lies. */

/* The whole parameter square, where both searches start. */
static inline int rugo__is_whole_square(box b) {
    return b.s0 == 0.0 && b.s1 == 1.0 && b.t0 == 0.0 && b.t1 == 1.0;
}

/* Whether (s,t) lies in the box widened by SLACK (DOM_SLACK at the edges of the domain). */
static inline int rugo__in_box(box b, rugo_real s, rugo_real t) {
    rugo_real sl = b.s0 == 0.0 ? DOM_SLACK : SLACK, sh = b.s1 == 1.0 ? DOM_SLACK : SLACK;
    rugo_real tl = b.t0 == 0.0 ? DOM_SLACK : SLACK, th = b.t1 == 1.0 ? DOM_SLACK : SLACK;
    return s >= b.s0 - sl && s <= b.s1 + sh && t >= b.t0 - tl && t <= b.t1 + th;
}

/* Whether the ball (max-norm) of radius rho around (s,t) lies in the box widened as rugo__in_box. */
static inline int rugo__in_box_ball(box b, rugo_real s, rugo_real t, rugo_real rho) {
    return rugo__in_box(b, s - rho, t - rho) && rugo__in_box(b, s + rho, t + rho);
}

static inline int rugo__in_domain(rugo_real s, rugo_real t) {
    return s >= -DOM_SLACK && s <= 1.0 + DOM_SLACK && t >= -DOM_SLACK && t <= 1.0 + DOM_SLACK;
}

static inline rugo_real rugo__clamp01(rugo_real v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

/* Whether (s,t) left the box lim widened by its own size on every side (lim may be NULL), or
 * [-0.5, 1.5]^2: then Newton gives up. */
static inline int rugo__newton_wandered(const box* lim, rugo_real s, rugo_real t) {
    if (!(s >= -0.5 && s <= 1.5 && t >= -0.5 && t <= 1.5)) return 1;
    if (!lim) return 0;
    rugo_real ws = lim->s1 - lim->s0, wt = lim->t1 - lim->t0;
    return s < lim->s0 - ws || s > lim->s1 + ws || t < lim->t0 - wt || t > lim->t1 + wt;
}

/* Whether a root parameter is at an end of the domain, where a piece that stops there (zero speed)
 * gives the systems a multiple root, located only to ~1e-5 in parameter (the position to ~1e-15 of the
 * piece, its offset from the end growing with the third power of the parameter's). Such roots are
 * moved onto the end (snap_to_zero_speed_end) and classified from the piece's side. */
static inline int rugo__near_end(rugo_real u) { return u <= END_ZONE || u >= 1.0 - END_ZONE; }

/* Whether (s, t) lies in the parameter square, up to a hair. Beyond it the pieces' polynomials are
 * extrapolated past their segments' ends, and that is not the curve: at a zero-speed corner (three
 * coincident control points) the extrapolated cubic runs on along the same side, while the curve turns
 * into the next segment. */
static inline int rugo__in_unit(rugo_real u) { return u >= -1e-12 && u <= 1.0 + 1e-12; }

static inline int rugo__in_square(rugo_real s, rugo_real t) { return rugo__in_unit(s) && rugo__in_unit(t); }

/* ---------------------------------------------------------------------------------------------------
 * Speeds and distances. */

/* Whether a speed |d| is round-off against a derivative size m of its piece. */
static inline int rugo__zero_speed(rugo_vec2 d, rugo_real m) {
    return rugo_v2_dot(d, d) <= 1e3 * EPS * m * m;
}

/* rugo__zero_speed against the size of the piece's hodograph control points h[3]. */
static inline int rugo__speed_vanishes(rugo_vec2 d, const rugo_vec2 h[3]) {
    return rugo__zero_speed(
        d, rugo__max(rugo__v2_max_abs(h[0]), rugo__max(rugo__v2_max_abs(h[1]), rugo__v2_max_abs(h[2]))));
}

/* D = |f(s) - g(t)|^2 / 2. */
static inline rugo_real rugo__half_dist2(const narrow_ctx* c, rugo_real s, rugo_real t) {
    rugo_vec2 r = rugo_v2_sub(rugo__bezier_eval(c->f, 3, s), rugo__bezier_eval(c->g, 3, t));
    return 0.5 * rugo_v2_dot(r, r);
}

/* ---------------------------------------------------------------------------------------------------
 * The stationary system's forms and values; the sub-pieces a search keeps from box to box. */

/* The stationary system in one of three equivalent forms (away from crossings):
 *   STAT_HH: (H1, H2)  (6.14);
 *   STAT_CH2: (C, H2) with C = cross(f', g'), valid where g' != 0: f' parallel to g' and (f-g)·g' = 0
 *            give (f-g)·f' = 0 too;
 *   STAT_CH1: (C, H1), where f' != 0.
 * At a near-touching (distance d, curvature difference dk) the Jacobian of (H1, H2) has determinant
 * ~ d dk, that of (C, H) ~ dk: the second forms stay well conditioned down to touching curves, and
 * they do not have the transversal crossings as roots. */
enum { STAT_HH = 0, STAT_CH2 = 1, STAT_CH1 = 2 };

/* Values at a parameter pair for the stationary system. */
typedef struct pair_eval {
    rugo_vec2 r, fp, gp, fpp, gpp; /* r = f - g */
    rugo_real h1, h2, n1, n2;      /* H and its round-off level */
    rugo_real j11, j12, j21, j22;  /* dH/d(s,t) */
    rugo_real cc, nc, cs, ct;      /* C, its round-off level, dC/ds, dC/dt */
} pair_eval;

/* The sub-pieces of one piece on the parameter range [a, b] of the last box (a depth-first search
 * splits one parameter at a time, so the next box often keeps the other's range): rugo__sub_bezier of
 * the piece (P), its hodograph (dP) and, once asked for, its second derivative (ddP). */
typedef struct piece_memo {
    rugo_real a, b;
    int have_dd;
    rugo_vec2 P[4], dP[3], ddP[2];
} piece_memo;

static inline void rugo__memo_init(piece_memo* m) {
    m->a = m->b = -1.0; /* no box has this range */
    m->have_dd = 0;
}

static inline void rugo__memo_range(piece_memo* m, const rugo_vec2 p[4], const rugo_vec2 dp[3], rugo_real a,
                                    rugo_real b) {
    if (a == m->a && b == m->b) return;
    rugo__sub_bezier(p, 3, a, b, m->P);
    rugo__sub_bezier(dp, 2, a, b, m->dP);
    m->a = a;
    m->b = b;
    m->have_dd = 0;
}

static inline void rugo__memo_dd(piece_memo* m, const rugo_vec2 ddp[2]) {
    if (m->have_dd) return;
    rugo__sub_bezier(ddp, 1, m->a, m->b, m->ddP);
    m->have_dd = 1;
}

/* ---------------------------------------------------------------------------------------------------
 * Bounds that prune a box (narrow_bounds.c). */

/* Whether a lower bound of the distance between the convex hulls of F and G (4 points each) exceeds
 * thr. */
int rugo__hull_gap_above(const rugo_vec2 F[4], const rugo_vec2 G[4], rugo_real thr);
/* Sign of cross(f', g') certified over a box from the control points of the two sub-hodographs (0 if
 * not one-signed), from the 9 cross products c; *radius (may be NULL): the existence radius of a root
 * whose residual is at round-off. */
int rugo__cone_sign_of(const rugo_real c[9], const rugo_vec2 dF[3], const rugo_vec2 dG[3], rugo_real* radius);
int rugo__cone_sign(const rugo_vec2 dF[3], const rugo_vec2 dG[3], rugo_real* radius);
/* rugo__cone_sign of the whole pieces, computed once per call for both searches. */
int rugo__whole_square_cone(narrow_ctx* c);
/* Krawczyk's test: 1 if no root of the system (values v at the box's centre, round-off n, point
 * Jacobian jc there, interval Jacobian rows (a b), (c d) over the box) lies in the box. */
int rugo__krawczyk_excludes(box bx, const rugo_real v[2], const rugo_real n[2], const rugo_real jc[4], ival a,
                            ival b, ival c, ival d);
/* 1 if the hull of a hodograph's control points (3) keeps away from the origin. */
int rugo__hodograph_nonzero(const rugo_vec2 d[3]);

/* ---------------------------------------------------------------------------------------------------
 * Root lists and the box stack (narrow_roots.c). */

/* Adds a root unless one within the larger of the two radii exists (a certified root replaces one
 * accepted without a certificate, fb). 0 when the list (cap) is full: overflow. */
int rugo__add_root(root* list, int* n, int cap, rugo_real s, rugo_real t, rugo_real radius, int kind, int fb);
/* Whether a root lies within r of (s, t) (max-norm). */
int rugo__near_root(const root* list, int n, rugo_real s, rugo_real t, rugo_real r);
/* Whether box b lies within the merge radius of a root accepted without a certificate. */
int rugo__box_covered(const root* list, int n, box b);
/* Dedupe radius from a condition estimate (uncertainty of a root ~ eps * condition). */
rugo_real rugo__root_radius(rugo_real cond);
/* For a root (s, t) found outside box b: the box e spanning b and a square of half-width *r0 about the
 * root; 0 if the root is not clearly outside. */
int rugo__exclusion_box(box b, rugo_real s, rugo_real t, box* e, rugo_real* r0);
/* Pushes a box on the search stack (*ns boxes); 0 when the stack is full. */
int rugo__push_box(box* st, int* ns, rugo_real s0, rugo_real s1, rugo_real t0, rugo_real t1);
/* Splits b in two halves on the stack (the larger sub-piece's parameter); 0 if neither can be split. */
int rugo__split_box(box* st, int* ns, box b, rugo_real diam_f, rugo_real diam_g);

/* ---------------------------------------------------------------------------------------------------
 * Stationary pairs (narrow_stationary.c). */

/* Values of the stationary system's terms at (s, t). */
pair_eval rugo__eval_pair(const narrow_ctx* c, rugo_real s, rugo_real t);
/* Newton on the stationary system in form mode (STAT_*), from (*s, *t) within lim's neighbourhood: 1 and
 * the root if it converged, else 0 and the best iterate; *res its residual in round-off units (0 when
 * converged). start (may be NULL): rugo__eval_pair at the start; last (may be NULL): the values at the
 * root. */
int rugo__newton_stat(narrow_ctx* c, int mode, const box* lim, rugo_real* s, rugo_real* t, rugo_real* res,
                      const pair_eval* start, pair_eval* last);
/* All stationary pairs within the cutoff into c->stat (c->overflow when the list or the budget ends). */
void rugo__search_stationary(narrow_ctx* c);

/* ---------------------------------------------------------------------------------------------------
 * Crossings (narrow_crossings.c). */

/* All crossings into c->cross (c->overflow when the list or the budget ends); uncertified ones with kind
 * KIND_PROBE. */
void rugo__search_crossings(narrow_ctx* c);
/* The kind of a crossing at (s, t) from the side of g(t -+ delta) relative to f: +1 into f's inside, -1
 * out of it, 0 undecided (a touching). */
int rugo__probe_crossing_kind(narrow_ctx* c, rugo_real s, rugo_real t);

/* ---------------------------------------------------------------------------------------------------
 * Kinds of stationary pairs (narrow_classify.c). */

/* Moves a stationary pair near an end where its piece stops (zero speed) onto that end. */
void rugo__snap_to_zero_speed_end(const narrow_ctx* c, rugo_real* s, rugo_real* t);
/* The kind (rugo__stationary_kind) of the stationary pair (s, t) at distance dist (local frame). */
int rugo__classify_stationary(const narrow_ctx* c, rugo_real s, rugo_real t, rugo_real dist);

/* ---------------------------------------------------------------------------------------------------
 * A piece against a point (narrow_point.c). */

/* The point query in a local frame: a[] are the Bezier points of f - c (already scaled). Parameters,
 * local distances and kinds of the stationary points within the cutoff into s_out, d_out, k_out; returns
 * their count (<= 6). */
int rugo__point_stationary(const rugo_vec2 a[4], rugo_real cutoff, rugo_real* s_out, rugo_real* d_out,
                           int* k_out);

#endif
