/* The narrow phase at a resolution δ > 0 (narrow_resolved.h states what it finds and guarantees).
 *
 * Search. A depth-first walk of the parameter square, as the round-off narrow phase's, but with only
 * two tests per box: the control polygons' separating-axis gap (a lower bound of the distance;
 * minus the largest band coefficients, a lower bound of φ) against what the box is asked for, and the
 * flatness of the two sub-pieces. A sub-piece's flatness is the largest distance of its middle
 * control points from where the linear Bezier over the same parameters puts them, for the curve and
 * for its band: a bound of |f(s) - chord(s)| + |λ(s) - linear(s)| at every parameter, so a leaf's
 * chords carry the curves and bands to within flat_f + flat_g <= δ, parameter by parameter. The piece
 * with the larger flatness is halved. A banded piece is first cut at its band's knot (1/2).
 *
 * Leaf. The chord functions are closed forms: the crossing of two segments; the minimum of
 * |P(u) - Q(v)| - λ_P(u) - λ_Q(v) over the unit square, which is convex (a norm of an affine map minus
 * linear terms) and whose minimum lies on an edge of the square except between parallel chords
 * (where it is flat along the facing pairs, whose ends are on edges): each edge is a point against a
 * segment with a linear band, whose minimiser has a closed form. Polishing is Newton on the true
 * pieces: for crossings on f - g = 0, for minima on the gradient of φ with its exact Hessian, for
 * saddles on the stationarity system of the distance. A polished root is kept only if Newton
 * converged inside the pieces' domain; otherwise the chord's answer stands (within δ).
 *
 * Cost: a box costs two de Casteljau restrictions and a few dot products; a leaf a few square roots
 * and, when it holds something, up to NEWTON_MAX Newton steps. The number of leaves is bounded by the
 * products of δ-flat pieces of f and g near each other: about sqrt(curvature x length^2 / δ) each. */
#include "query/narrow_resolved.h"

#include "core/internal.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define EPS DBL_EPSILON
/* Newton has converged when a step moves both parameters by less than this: round-off of the
 * residual divided by a small speed can keep steps of a few ulps going for ever. */
#define NEWTON_TOL 1e-13

enum {
    STACK_MAX = 100,    /* depth-first stack: one more frame per halving, of either piece */
    MAX_DEPTH = 48,     /* halvings of one parameter (2^-48: below any useful δ) */
    BOX_BUDGET = 20000, /* boxes per call, then overflow (the caller falls back to the round-off phase) */
    NEWTON_MAX = 12,
    DESCENT_MAX = 24, /* steps of a leaf's walk to its minimum */
    TMP_ROOTS = 64
};

typedef struct box {
    rugo_real s0, s1, t0, t1;
} box;

/* A sub-piece with what its box tests need, computed once when it is made. The band over the sub-piece
 * is one cubic (l, Bernstein coefficients in the sub-piece's parameter), except for a whole banded
 * piece, whose band has its knot inside (knot: halves). */
typedef struct sub {
    rugo_vec2 p[4];
    rugo_real l[4];
    int knot;                     /* a whole piece whose band is two cubics (halves) */
    const rugo_real (*halves)[4]; /* the piece's two halves (when knot) */
    rugo_real l0, l1;             /* λ at the two ends */
    rugo_real lmax;               /* the band's largest value over the sub-piece (>= 0) */
    rugo_real band_dev;           /* |band - linear| bound */
    rugo_real band_slope;         /* max |dλ/du|, the sub-piece's parameter */
    int have_flat, have_cone;     /* flat and the cone are computed when a box first needs them */
    rugo_real flat;               /* |sub-piece - its linear Bezier| + band_dev */
    rugo_vec2 centre;             /* of the control points */
    rugo_vec2 normal;             /* unit normal of the chord (0 for a point) */
    /* tangent cone (cone_ok: the hodograph's directions stay within 90 degrees of the chord) */
    int cone_ok;
    rugo_vec2 axis;
    rugo_real cos_half, sin_half; /* its half-angle */
    rugo_real sin_band;           /* sin of the angle the band's slope allows: min(1, |λ'| / |f'|) */
} sub;

typedef struct found {
    rugo_real s, t, phi;
    int kind;
    int polished;
} found;

typedef struct rctx {
    const rugo__banded_piece* f;
    const rugo__banded_piece* g;
    int banded_f, banded_g;
    rugo_real cutoff, saddle_cutoff, delta, scale;
    int want;
    int newton, fallback, overflow;
    int ncross, nmin, nsaddle;
    found cross[TMP_ROOTS];
    found mins[TMP_ROOTS];
    found saddles[TMP_ROOTS];
} rctx;

/* ---------------------------------------------------------------------------------------------- */
/* Evaluation */

static rugo_real mx(rugo_real a, rugo_real b) { return a > b ? a : b; }
static rugo_real mn(rugo_real a, rugo_real b) { return a < b ? a : b; }
static rugo_real vlen(rugo_vec2 v) { return sqrt(v.x * v.x + v.y * v.y); }

static rugo_vec2 lerp(rugo_vec2 a, rugo_vec2 b, rugo_real u) {
    return rugo_v2((1.0 - u) * a.x + u * b.x, (1.0 - u) * a.y + u * b.y);
}

/* Cubic Bezier point, first and second derivative at u. */
static void bez3(const rugo_vec2 p[4], rugo_real u, rugo_vec2* x, rugo_vec2* d1, rugo_vec2* d2) {
    const rugo_vec2 a = lerp(p[0], p[1], u), b = lerp(p[1], p[2], u), c = lerp(p[2], p[3], u);
    const rugo_vec2 ab = lerp(a, b, u), bc = lerp(b, c, u);
    *x = lerp(ab, bc, u);
    *d1 = rugo_v2_scale(3.0, rugo_v2_sub(bc, ab));
    const rugo_vec2 dd0 = rugo_v2_add(rugo_v2_sub(p[2], rugo_v2_scale(2.0, p[1])), p[0]);
    const rugo_vec2 dd1 = rugo_v2_add(rugo_v2_sub(p[3], rugo_v2_scale(2.0, p[2])), p[1]);
    *d2 = rugo_v2_scale(6.0, lerp(dd0, dd1, u));
}

/* Cubic in Bernstein form, value and first two derivatives at u. */
static void bern3(const rugo_real l[4], rugo_real u, rugo_real* v, rugo_real* d1, rugo_real* d2) {
    const rugo_real w = 1.0 - u;
    const rugo_real a = w * l[0] + u * l[1], b = w * l[1] + u * l[2], c = w * l[2] + u * l[3];
    const rugo_real ab = w * a + u * b, bc = w * b + u * c;
    *v = w * ab + u * bc;
    *d1 = 3.0 * (bc - ab);
    *d2 = 6.0 * (w * (l[2] - 2.0 * l[1] + l[0]) + u * (l[3] - 2.0 * l[2] + l[1]));
}

/* λ of a banded piece at s and its derivatives in s (the half's cubic over its own parameter 2s - h;
 * s = 1/2 belongs to the second half), clamped below at 0 as the queries clamp it. */
static void band_at(const rugo__banded_piece* p, int banded, rugo_real s, rugo_real* v, rugo_real* d1,
                    rugo_real* d2) {
    *v = *d1 = *d2 = 0.0;
    if (!banded) return;
    const int h = s >= 0.5;
    bern3(p->band[h], 2.0 * s - (rugo_real)h, v, d1, d2);
    *d1 *= 2.0;
    *d2 *= 4.0;
    if (!(*v > 0.0)) *v = *d1 = *d2 = 0.0;
}

/* Max and bound of the deviation from the linear function through its end values, of a cubic band in
 * Bernstein form over [0, 1] (the linear function's coefficients are its values at i/3). */
static void band_stats(const rugo_real l[4], rugo_real* lmax, rugo_real* dev) {
    *lmax = mx(0.0, mx(mx(l[0], l[1]), mx(l[2], l[3])));
    *dev = mx(fabs(l[1] - (2.0 * l[0] + l[3]) / 3.0), fabs(l[2] - (l[0] + 2.0 * l[3]) / 3.0));
}

/* Fills what every box test needs from p, l, knot, halves; the flatness and the tangent cone wait
 * until a box needs them (sub_flat, sub_cone). */
static void finish_sub(sub* q) {
    const rugo_vec2* p = q->p;
    rugo_real slope = 0.0;
    if (q->knot) {
        /* two cubics against the one linear function through λ(0) and λ(1) */
        q->l0 = q->halves[0][0];
        q->l1 = q->halves[1][3];
        rugo_real lmax = 0.0, dev = 0.0;
        for (int h = 0; h < 2; ++h) {
            const rugo_real a = q->l0 + 0.5 * (rugo_real)h * (q->l1 - q->l0), b = a + 0.5 * (q->l1 - q->l0);
            for (int i = 0; i < 4; ++i) {
                lmax = mx(lmax, q->halves[h][i]);
                dev = mx(dev, fabs(q->halves[h][i] - (a + (b - a) * (rugo_real)i / 3.0)));
                if (i < 3) slope = mx(slope, 6.0 * fabs(q->halves[h][i + 1] - q->halves[h][i]));
            }
        }
        q->lmax = lmax;
        q->band_dev = dev;
    } else {
        q->l0 = q->l[0];
        q->l1 = q->l[3];
        band_stats(q->l, &q->lmax, &q->band_dev);
        for (int i = 0; i < 3; ++i)
            slope = mx(slope, 3.0 * fabs(q->l[i + 1] - q->l[i]));
    }
    q->band_slope = slope;
    q->centre =
        rugo_v2(0.25 * (p[0].x + p[1].x + p[2].x + p[3].x), 0.25 * (p[0].y + p[1].y + p[2].y + p[3].y));
    const rugo_vec2 chord = rugo_v2_sub(p[3], p[0]);
    const rugo_real len = vlen(chord);
    q->normal = len > 0.0 ? rugo_v2(-chord.y / len, chord.x / len) : rugo_v2(0.0, 0.0);
    q->have_flat = q->have_cone = 0;
}

/* |sub-piece - its linear Bezier| + |band - linear|: the chord's error, parameter by parameter. */
static rugo_real sub_flat(sub* q) {
    if (!q->have_flat) {
        const rugo_vec2* p = q->p;
        const rugo_vec2 m1 = lerp(p[0], p[3], 1.0 / 3.0), m2 = lerp(p[0], p[3], 2.0 / 3.0);
        q->flat = mx(vlen(rugo_v2_sub(p[1], m1)), vlen(rugo_v2_sub(p[2], m2))) + q->band_dev;
        q->have_flat = 1;
    }
    return q->flat;
}

/* The cone of f' (the hodograph's control points 3 (p_i+1 - p_i)) about the chord; cone_ok is 0 when
 * they spread over 90 degrees or more. */
static void sub_cone(sub* q) {
    if (q->have_cone) return;
    q->have_cone = 1;
    q->cone_ok = 0;
    const rugo_vec2* p = q->p;
    const rugo_vec2 chord = rugo_v2_sub(p[3], p[0]);
    const rugo_real len = vlen(chord);
    if (!(len > 0.0)) return;
    const rugo_vec2 axis = rugo_v2_scale(1.0 / len, chord);
    rugo_real cosmin = 1.0, speed = HUGE_VAL;
    for (int i = 0; i < 3; ++i) {
        const rugo_vec2 d = rugo_v2_scale(3.0, rugo_v2_sub(p[i + 1], p[i]));
        const rugo_real dl = vlen(d), along = rugo_v2_dot(d, axis);
        if (!(along > 0.0)) return;
        cosmin = mn(cosmin, along / dl);
        speed = mn(speed, along);
    }
    q->cone_ok = 1;
    q->axis = axis;
    q->cos_half = cosmin;
    q->sin_half = sqrt(mx(0.0, 1.0 - cosmin * cosmin));
    q->sin_band = mn(1.0, q->band_slope / speed);
}

/* The whole piece as a sub-piece. */
static void root_sub(const rugo__banded_piece* p, int banded, sub* q) {
    for (int i = 0; i < 4; ++i)
        q->p[i] = p->p[i];
    q->knot = banded;
    q->halves = p->band;
    for (int i = 0; i < 4; ++i)
        q->l[i] = 0.0;
    finish_sub(q);
}

/* The two halves of a sub-piece (de Casteljau at 1/2; a whole banded piece's band splits at its knot). */
static void split_sub(const sub* q, sub* lo, sub* hi) {
    const rugo_vec2* p = q->p;
    const rugo_vec2 a = lerp(p[0], p[1], 0.5), b = lerp(p[1], p[2], 0.5), c = lerp(p[2], p[3], 0.5);
    const rugo_vec2 ab = lerp(a, b, 0.5), bc = lerp(b, c, 0.5), m = lerp(ab, bc, 0.5);
    lo->p[0] = p[0];
    lo->p[1] = a;
    lo->p[2] = ab;
    lo->p[3] = m;
    hi->p[0] = m;
    hi->p[1] = bc;
    hi->p[2] = c;
    hi->p[3] = p[3];
    lo->knot = hi->knot = 0;
    lo->halves = hi->halves = NULL;
    if (q->knot) {
        memcpy(lo->l, q->halves[0], sizeof lo->l);
        memcpy(hi->l, q->halves[1], sizeof hi->l);
    } else {
        const rugo_real* l = q->l;
        const rugo_real la = 0.5 * (l[0] + l[1]), lb = 0.5 * (l[1] + l[2]), lc = 0.5 * (l[2] + l[3]);
        const rugo_real lab = 0.5 * (la + lb), lbc = 0.5 * (lb + lc), lm = 0.5 * (lab + lbc);
        lo->l[0] = l[0];
        lo->l[1] = la;
        lo->l[2] = lab;
        lo->l[3] = lm;
        hi->l[0] = lm;
        hi->l[1] = lbc;
        hi->l[2] = lc;
        hi->l[3] = l[3];
    }
    finish_sub(lo);
    finish_sub(hi);
}

/* Gap between the projections of the two control polygons on unit direction d (<= 0: they overlap). */
static rugo_real projection_gap(rugo_vec2 d, const rugo_vec2 F[4], const rugo_vec2 G[4]) {
    rugo_real flo = HUGE_VAL, fhi = -HUGE_VAL, glo = HUGE_VAL, ghi = -HUGE_VAL;
    for (int i = 0; i < 4; ++i) {
        const rugo_real a = rugo_v2_dot(F[i], d), b = rugo_v2_dot(G[i], d);
        flo = mn(flo, a);
        fhi = mx(fhi, a);
        glo = mn(glo, b);
        ghi = mx(ghi, b);
    }
    return mx(glo - fhi, flo - ghi);
}

/* A lower bound of the distance between the two sub-pieces (0 when their hulls may meet): the largest
 * projection gap over the line through the polygons' centres and the chords' normals. */
static rugo_real hull_gap(const sub* F, const sub* G) {
    rugo_real best = 0.0;
    const rugo_vec2 d = rugo_v2_sub(G->centre, F->centre);
    const rugo_real l = vlen(d);
    if (l > 0.0) best = projection_gap(rugo_v2_scale(1.0 / l, d), F->p, G->p);
    if (F->normal.x != 0.0 || F->normal.y != 0.0) best = mx(best, projection_gap(F->normal, F->p, G->p));
    if (G->normal.x != 0.0 || G->normal.y != 0.0) best = mx(best, projection_gap(G->normal, F->p, G->p));
    return best;
}

/* cos and sin of a + b from theirs (angles in [0, pi/2]); 0 when a + b reaches pi/2. */
static int add_angle(rugo_real* c, rugo_real* s, rugo_real c2, rugo_real s2) {
    const rugo_real cc = *c * c2 - *s * s2, ss = *s * c2 + *c * s2;
    *c = cc;
    *s = ss;
    return cc > 0.0;
}

/* 1 when the box provably holds no stationary point of φ (band = 1) or of the distance (band = 0):
 * there f' and g' both lie within asin(|λ'| / |f'|) of the normal to f - g, so their lines are that
 * close to parallel; cones whose lines stay farther apart exclude it. No transcendental function: the
 * allowed angle is summed as rotations (cos, sin), and compared by its cosine with the angle between
 * the cones' axes (as lines). */
static int cones_exclude(sub* F, sub* G, int band) {
    sub_cone(F);
    sub_cone(G);
    if (!F->cone_ok || !G->cone_ok) return 0;
    rugo_real c = F->cos_half, s = F->sin_half;
    if (!add_angle(&c, &s, G->cos_half, G->sin_half)) return 0;
    if (band) {
        const rugo_real sa = F->sin_band, sb = G->sin_band;
        if (!add_angle(&c, &s, sqrt(mx(0.0, 1.0 - sa * sa)), sa)) return 0;
        if (!add_angle(&c, &s, sqrt(mx(0.0, 1.0 - sb * sb)), sb)) return 0;
    }
    const rugo_real cos_between = fabs(rugo_v2_dot(F->axis, G->axis));
    return cos_between < c * (1.0 - 1e-12) - 1e-12;
}

/* ---------------------------------------------------------------------------------------------- */
/* Roots: recording and merging */

static void sort_found(found* a, int n);
static int reduce_runs(found* a, int n, rugo_real reach);

/* Adds (s, t) to a list unless a root within r (in both parameters) is there; a polished root
 * replaces an unpolished one. Returns the index, or -1 when the list is full (overflow). */
static int add_found(rctx* c, found* list, int* n, rugo_real s, rugo_real t, rugo_real phi, int kind,
                     int polished, rugo_real r) {
    for (int i = 0; i < *n; ++i)
        if (fabs(list[i].s - s) <= r && fabs(list[i].t - t) <= r) {
            if (polished && !list[i].polished) {
                list[i].s = s;
                list[i].t = t;
                list[i].phi = phi;
                list[i].kind = kind;
                list[i].polished = 1;
            }
            return i;
        }
    if (*n >= TMP_ROOTS && list == c->mins) {
        /* a long conforming stretch: keep its ends and its deepest point so far */
        sort_found(list, *n);
        *n = reduce_runs(list, *n, 1.01);
    }
    if (*n >= TMP_ROOTS) {
        c->overflow = 1;
        return -1;
    }
    list[*n].s = s;
    list[*n].t = t;
    list[*n].phi = phi;
    list[*n].kind = kind;
    list[*n].polished = polished;
    return (*n)++;
}

/* ---------------------------------------------------------------------------------------------- */
/* Newton polishing on the true pieces */

static int in_domain(rugo_real s, rugo_real t) {
    return s >= -1e-12 && s <= 1.0 + 1e-12 && t >= -1e-12 && t <= 1.0 + 1e-12;
}
/* Newton may overshoot on its way to a root inside the domain: iterates may roam this far. */
static int near_domain(rugo_real s, rugo_real t) { return s >= -0.5 && s <= 1.5 && t >= -0.5 && t <= 1.5; }
static rugo_real clamp01(rugo_real v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

/* f(s) = g(t) from (s, t); 1 and the root when Newton converged inside the domain. */
static int polish_crossing(rctx* c, rugo_real* s, rugo_real* t) {
    rugo_real S = *s, T = *t;
    for (int it = 0; it < NEWTON_MAX; ++it) {
        rugo_vec2 fp, fd, fdd, gp, gd, gdd;
        bez3(c->f->p, S, &fp, &fd, &fdd);
        bez3(c->g->p, T, &gp, &gd, &gdd);
        const rugo_vec2 F = rugo_v2_sub(fp, gp);
        /* [fd -gd] (dS, dT) = -F */
        const rugo_real det = -fd.x * gd.y + gd.x * fd.y;
        if (!(fabs(det) > 1e-300)) return 0;
        const rugo_real dS = (-F.x * -gd.y - -gd.x * -F.y) / det;
        const rugo_real dT = (fd.x * -F.y - fd.y * -F.x) / det;
        ++c->newton;
        S += dS;
        T += dT;
        if (!near_domain(S, T) || !isfinite(S) || !isfinite(T)) return 0;
        if (fabs(dS) <= NEWTON_TOL && fabs(dT) <= NEWTON_TOL) {
            if (!in_domain(S, T)) return 0;
            *s = clamp01(S);
            *t = clamp01(T);
            return 1;
        }
    }
    return 0;
}

typedef struct phi_eval {
    rugo_real phi, d;
    rugo_real gs, gt;        /* gradient */
    rugo_real hss, hst, htt; /* Hessian */
} phi_eval;

/* φ = |f(s) - g(t)| - λ_f(s) - λ_g(t), its gradient and Hessian (0: the points coincide). */
static int eval_phi(const rctx* c, rugo_real s, rugo_real t, phi_eval* e) {
    rugo_vec2 fp, fd, fdd, gp, gd, gdd;
    bez3(c->f->p, s, &fp, &fd, &fdd);
    bez3(c->g->p, t, &gp, &gd, &gdd);
    rugo_real la, la1, la2, lb, lb1, lb2;
    band_at(c->f, c->banded_f, s, &la, &la1, &la2);
    band_at(c->g, c->banded_g, t, &lb, &lb1, &lb2);
    const rugo_vec2 r = rugo_v2_sub(fp, gp);
    const rugo_real d = vlen(r);
    e->d = d;
    e->phi = d - la - lb;
    if (!(d > 0.0)) return 0;
    const rugo_vec2 u = rugo_v2_scale(1.0 / d, r);
    const rugo_real uf = rugo_v2_dot(u, fd), ug = rugo_v2_dot(u, gd);
    e->gs = uf - la1;
    e->gt = -ug - lb1;
    e->hss = rugo_v2_dot(u, fdd) + (rugo_v2_dot(fd, fd) - uf * uf) / d - la2;
    e->htt = -rugo_v2_dot(u, gdd) + (rugo_v2_dot(gd, gd) - ug * ug) / d - lb2;
    e->hst = (-rugo_v2_dot(fd, gd) + uf * ug) / d;
    return 1;
}

/* Newton on grad φ = 0 from (s, t), while the Hessian is positive definite and φ does not rise; 1 and
 * the minimum when it converged inside the domain. */
static int polish_minimum(rctx* c, rugo_real* s, rugo_real* t, rugo_real* phi) {
    rugo_real S = *s, T = *t;
    phi_eval e;
    if (!eval_phi(c, S, T, &e)) return 0;
    for (int it = 0; it < NEWTON_MAX; ++it) {
        const rugo_real det = e.hss * e.htt - e.hst * e.hst;
        if (!(e.hss > 0.0) || !(det > 0.0)) return 0;
        const rugo_real dS = -(e.htt * e.gs - e.hst * e.gt) / det;
        const rugo_real dT = -(e.hss * e.gt - e.hst * e.gs) / det;
        ++c->newton;
        const rugo_real S1 = S + dS, T1 = T + dT;
        if (!in_domain(S1, T1) || !isfinite(S1) || !isfinite(T1)) return 0;
        phi_eval e1;
        if (!eval_phi(c, clamp01(S1), clamp01(T1), &e1)) return 0;
        /* Near the minimum φ is flat to round-off: allow its rounding, not a real rise. */
        if (e1.phi > e.phi + 64.0 * EPS * (fabs(e.phi) + e.d + c->scale)) return 0;
        S = clamp01(S1);
        T = clamp01(T1);
        e = e1;
        if (fabs(dS) <= NEWTON_TOL && fabs(dT) <= NEWTON_TOL) {
            *s = S;
            *t = T;
            *phi = e.phi;
            return 1;
        }
    }
    return 0;
}

/* Newton on φ along one parameter (free_t: t, with s fixed; else s), while φ's second derivative that
 * way is positive and φ does not rise, within the piece's domain: a minimum pinned in the other
 * parameter (at the band's knot, at a zero-speed end) polished to round-off along its line. *e is
 * updated with the point. */
static void polish_along(rctx* c, int free_t, rugo_real* s, rugo_real* t, phi_eval* e) {
    rugo_real S = *s, T = *t;
    phi_eval cur = *e;
    for (int it = 0; it < NEWTON_MAX; ++it) {
        const rugo_real g = free_t ? cur.gt : cur.gs, h = free_t ? cur.htt : cur.hss;
        if (!(h > 0.0)) return;
        const rugo_real step = -g / h;
        const rugo_real S1 = free_t ? S : clamp01(S + step), T1 = free_t ? clamp01(T + step) : T;
        phi_eval e1;
        ++c->newton;
        if (!eval_phi(c, S1, T1, &e1)) return;
        if (e1.phi > cur.phi + 64.0 * EPS * (fabs(cur.phi) + cur.d + c->scale)) return;
        S = S1;
        T = T1;
        cur = e1;
        *s = S;
        *t = T;
        *e = cur;
        if (fabs(step) <= NEWTON_TOL) return;
    }
}

/* The stationarity system of the distance, H1 = (f-g)·f' = 0, H2 = (f-g)·g' = 0 (SPEC 8), from (s, t):
 * 1 and the root when it converged inside the domain, with the kind from D = |f-g|^2/2's Hessian. */
static int polish_stationary(rctx* c, rugo_real* s, rugo_real* t, int* kind) {
    rugo_real S = *s, T = *t;
    for (int it = 0; it < NEWTON_MAX; ++it) {
        rugo_vec2 fp, fd, fdd, gp, gd, gdd;
        bez3(c->f->p, S, &fp, &fd, &fdd);
        bez3(c->g->p, T, &gp, &gd, &gdd);
        const rugo_vec2 r = rugo_v2_sub(fp, gp);
        const rugo_real h1 = rugo_v2_dot(r, fd), h2 = rugo_v2_dot(r, gd);
        const rugo_real j11 = rugo_v2_dot(fd, fd) + rugo_v2_dot(r, fdd), j12 = -rugo_v2_dot(gd, fd);
        const rugo_real j21 = rugo_v2_dot(gd, fd), j22 = -rugo_v2_dot(gd, gd) + rugo_v2_dot(r, gdd);
        const rugo_real det = j11 * j22 - j12 * j21;
        if (!(fabs(det) > 1e-300)) return 0;
        const rugo_real dS = -(j22 * h1 - j12 * h2) / det;
        const rugo_real dT = -(j11 * h2 - j21 * h1) / det;
        ++c->newton;
        S += dS;
        T += dT;
        if (!in_domain(S, T) || !isfinite(S) || !isfinite(T)) return 0;
        if (fabs(dS) <= NEWTON_TOL && fabs(dT) <= NEWTON_TOL) {
            S = clamp01(S);
            T = clamp01(T);
            bez3(c->f->p, S, &fp, &fd, &fdd);
            bez3(c->g->p, T, &gp, &gd, &gdd);
            const rugo_vec2 rr = rugo_v2_sub(fp, gp);
            /* Hessian of D: [[|f'|^2 + r·f'', -f'·g'], [-f'·g', |g'|^2 - r·g'']] */
            const rugo_real dss = rugo_v2_dot(fd, fd) + rugo_v2_dot(rr, fdd);
            const rugo_real dtt = rugo_v2_dot(gd, gd) - rugo_v2_dot(rr, gdd);
            const rugo_real dst = -rugo_v2_dot(fd, gd);
            const rugo_real hdet = dss * dtt - dst * dst;
            *kind = hdet < 0.0 ? RUGO__SADDLE : (dss > 0.0 ? RUGO__MINIMUM : RUGO__MAXIMUM);
            *s = S;
            *t = T;
            return 1;
        }
    }
    return 0;
}

/* ---------------------------------------------------------------------------------------------- */
/* Leaves */

/* min over v in [0, 1] of |x - (q0 + v V)| - (b0 + v db): a convex function of v whose unconstrained
 * minimiser is the foot of x shifted by db h / (L sqrt(L^2 - db^2)) (|db| < L; else an end). */
static rugo_real point_chord(rugo_vec2 x, rugo_vec2 q0, rugo_vec2 V, rugo_real b0, rugo_real db,
                             rugo_real* v_out) {
    const rugo_real L2 = rugo_v2_dot(V, V);
    const rugo_vec2 w = rugo_v2_sub(x, q0);
    rugo_real v;
    if (!(L2 > 0.0)) {
        v = 0.0;
    } else {
        const rugo_real foot = rugo_v2_dot(w, V) / L2;
        const rugo_real L = sqrt(L2);
        if (fabs(db) < L) {
            const rugo_real h = fabs(rugo_v2_cross(V, w)) / L;
            v = foot + db * h / (L * sqrt(L2 - db * db));
        } else {
            v = db > 0.0 ? 1.0 : 0.0;
        }
        v = clamp01(v);
    }
    *v_out = v;
    return vlen(rugo_v2_sub(w, rugo_v2_scale(v, V))) - (b0 + v * db);
}

/* The slope of φ (per unit of a piece's parameter) below which a stretch is flat: φ then changes by
 * less than this over a whole piece, so by less than the resolution over any stretch of the curves. A
 * point where φ falls faster than that across the edge of its leaf is not a minimum: the descent goes
 * on into the neighbouring leaf or segment pair, which finds the minimum at its end. */
static rugo_real flat_slope(const rctx* c) { return mn(1e-10 * c->scale, 0.25 * c->delta); }

/* Where the first Newton step from the chords' minimum lands more than a box away, across an edge of
 * the box that is neither an end of the piece nor the band's knot (where φ may bend), the minimum it
 * heads for lies in another leaf, which finds it: this one can stop after one evaluation. */
static int leaves_box(const rctx* c, box b, rugo_real s, rugo_real t) {
    const rugo_real hs = b.s1 - b.s0, ht = b.t1 - b.t0;
    /* at a knot the Hessian is one side's: its step says nothing of the other coordinate either */
    if (c->banded_f && (b.s0 == 0.5 || b.s1 == 0.5)) return 0;
    if (c->banded_g && (b.t0 == 0.5 || b.t1 == 0.5)) return 0;
    if (s < b.s0 - hs && b.s0 > 0.0 && !(c->banded_f && b.s0 == 0.5)) return 1;
    if (s > b.s1 + hs && b.s1 < 1.0 && !(c->banded_f && b.s1 == 0.5)) return 1;
    if (t < b.t0 - ht && b.t0 > 0.0 && !(c->banded_g && b.t0 == 0.5)) return 1;
    if (t > b.t1 + ht && b.t1 < 1.0 && !(c->banded_g && b.t1 == 0.5)) return 1;
    return 0;
}

/* 1 when (s, t) lies on an edge of the box and φ falls across it faster than a flat stretch's slope:
 * the walk is leaving the box there, and the rest of it is another leaf's (or segment pair's). */
static int leaving(const rctx* c, box b, rugo_real s, rugo_real t, const phi_eval* e) {
    const rugo_real tol = flat_slope(c);
    return (s == b.s0 && e->gs > tol) || (s == b.s1 && e->gs < -tol) || (t == b.t0 && e->gt > tol) ||
           (t == b.t1 && e->gt < -tol);
}

/* The model q(d) = g·d + d·H d / 2 at a point; H with its eigenvalues lifted to positive (by its
 * smallest, plus 1e-9 of its largest) where it is not positive definite: along a floor that curves the
 * wrong way the model's minimum is then on the box's edge. */
typedef struct quad_model {
    rugo_real gs, gt, a, b, d; /* H = [[a, b], [b, d]] */
} quad_model;

static rugo_real quad_value(const quad_model* q, rugo_real x, rugo_real y) {
    return q->gs * x + q->gt * y + 0.5 * (q->a * x * x + 2.0 * q->b * x * y + q->d * y * y);
}

/* The minimiser of q along one coordinate with the other fixed at `fixed`, clamped to [lo, hi]. */
static rugo_real quad_line(rugo_real g, rugo_real h, rugo_real cross, rugo_real fixed, rugo_real lo,
                           rugo_real hi) {
    const rugo_real slope = g + cross * fixed;
    rugo_real x = h > 0.0 ? -slope / h : (slope > 0.0 ? lo : hi);
    return mn(hi, mx(lo, x));
}

/* The step (dS, dT) to the minimum of the model over the box (a convex quadratic over a rectangle: its
 * free minimum when that lies inside, else the best of the four edges' minima). */
static void quad_step(const phi_eval* e, box bx, rugo_real s, rugo_real t, rugo_real* dS, rugo_real* dT) {
    quad_model q = {e->gs, e->gt, e->hss, e->hst, e->htt};
    const rugo_real half_tr = 0.5 * (q.a + q.d), dh = 0.5 * (q.a - q.d);
    const rugo_real root = sqrt(dh * dh + q.b * q.b);
    const rugo_real lmin = half_tr - root, lmax = fabs(half_tr) + root;
    if (!(lmin > 1e-9 * lmax)) {
        const rugo_real mu = mx(0.0, -lmin) + 1e-9 * lmax;
        q.a += mu;
        q.d += mu;
    }
    const rugo_real xlo = bx.s0 - s, xhi = bx.s1 - s, ylo = bx.t0 - t, yhi = bx.t1 - t;
    const rugo_real det = q.a * q.d - q.b * q.b;
    if (det > 0.0) {
        const rugo_real x = -(q.d * q.gs - q.b * q.gt) / det, y = -(q.a * q.gt - q.b * q.gs) / det;
        if (x >= xlo && x <= xhi && y >= ylo && y <= yhi) {
            *dS = x;
            *dT = y;
            return;
        }
    }
    rugo_real best = HUGE_VAL, bx_ = 0.0, by_ = 0.0;
    const rugo_real ys[2] = {ylo, yhi}, xs[2] = {xlo, xhi};
    for (int k = 0; k < 2; ++k) {
        const rugo_real x = quad_line(q.gs, q.a, q.b, ys[k], xlo, xhi), v = quad_value(&q, x, ys[k]);
        if (v < best) best = v, bx_ = x, by_ = ys[k];
        const rugo_real y = quad_line(q.gt, q.d, q.b, xs[k], ylo, yhi), w = quad_value(&q, xs[k], y);
        if (w < best) best = w, bx_ = xs[k], by_ = y;
    }
    *dS = bx_;
    *dT = by_;
}

/* The minimum of φ over the leaf's box, walked to from the chords' minimum (s, t) by the box-constrained
 * steps of quad_step. Inside the box it is a local minimum of φ: polished. On an edge across which φ
 * falls (faster than flat_slope) it is none: the walk goes on in the neighbouring leaf or segment pair,
 * which reports the minimum where it ends, so this leaf reports nothing. What stays is the band's knot,
 * a zero-speed end (a sharp corner) and stretches flat to round-off (parallel straight pieces), whose
 * points stand for the stretch. */
static void leaf_minimum(rctx* c, box b, rugo_real s, rugo_real t) {
    const rugo_real hs = b.s1 - b.s0, ht = b.t1 - b.t0;
    phi_eval e;
    if (!eval_phi(c, s, t, &e)) return; /* the curves meet: a crossing or a touching, found as such */
    int converged = 0; /* a full Newton step below NEWTON_TOL: a minimum of φ to round-off */
    for (int it = 0; it < DESCENT_MAX && !converged; ++it) {
        const rugo_real det = e.hss * e.htt - e.hst * e.hst;
        const int newton = e.hss > 0.0 && det > 0.0;
        rugo_real dS, dT;
        if (newton) {
            dS = -(e.htt * e.gs - e.hst * e.gt) / det;
            dT = -(e.hss * e.gt - e.hst * e.gs) / det;
            /* (a valley of φ, its Hessian far from round, can throw the first step far past a minimum
             * that lies inside: only a well-rounded one decides at once) */
            const rugo_real tr = e.hss + e.htt;
            if (it == 0 && det >= 1e-4 * tr * tr && leaves_box(c, b, s + dS, t + dT)) return;
            converged = fabs(dS) <= NEWTON_TOL && fabs(dT) <= NEWTON_TOL;
        }
        /* The step: the minimum over the box of the quadratic model of φ (its Hessian's eigenvalues
         * lifted to positive where they are not: along a valley whose floor curves the wrong way), so
         * that a walk along a narrow valley follows its floor to the box's edge; halved until φ falls. */
        quad_step(&e, b, s, t, &dS, &dT);
        int accepted = 0;
        for (int half = 0; half < 30 && !accepted; ++half, dS *= 0.5, dT *= 0.5) {
            const rugo_real S1 = mn(b.s1, mx(b.s0, s + dS)), T1 = mn(b.t1, mx(b.t0, t + dT));
            if (S1 == s && T1 == t) break;
            phi_eval e1;
            ++c->newton;
            if (!eval_phi(c, S1, T1, &e1)) return;
            if (e1.phi < e.phi || (converged && e1.phi <= e.phi)) {
                s = S1;
                t = T1;
                e = e1;
                accepted = 1;
            }
        }
        if (!accepted || leaving(c, b, s, t, &e)) break;
    }
    const rugo_real es = 1e-9 * hs, et = 1e-9 * ht;
    const int inside = s > b.s0 + es && s < b.s1 - es && t > b.t0 + et && t < b.t1 - et;
    if (inside && (converged || polish_minimum(c, &s, &t, &e.phi))) {
        add_found(c, c->mins, &c->nmin, s, t, e.phi, RUGO__MINIMUM, 1, 1e-9);
        return;
    }
    /* The minimum rests on edges of the box. Each edge is one of three kinds:
     *  - the knot of a banded piece's band (1/2), where λ has a kink: a minimum of φ when φ also rises
     *    on the other side (the band's one-sided slope there decides);
     *  - an end of the piece where the curve stops (zero speed: a sharp corner of coincident control
     *    points): RUGO__END_MINIMUM, which the caller confirms with the neighbouring segment's piece;
     *  - else the minimum lies beyond, in a neighbouring leaf or segment, when φ falls that way faster
     *    than flat_slope; slower, the point stands for a stretch flat to round-off. (A rule that let
     *    φ fall by up to δ per piece kept points on long gentle slopes, tens of δ above the minimum
     *    they lead to.) */
    rugo_real drop = 0.0;
    int kink = 0, corner = 0, pinned_s = 0, pinned_t = 0;
    for (int k = 0; k < 4; ++k) {
        const int is_s = k < 2, low = (k % 2) == 0;
        const rugo_real x = is_s ? s : t, edge = is_s ? (low ? b.s0 : b.s1) : (low ? b.t0 : b.t1);
        if (fabs(x - edge) > (is_s ? es : et)) continue;
        const rugo_real g = is_s ? e.gs : e.gt; /* right-sided at a knot (band_at's convention) */
        const rugo__banded_piece* p = is_s ? c->f : c->g;
        const int banded = is_s ? c->banded_f : c->banded_g;
        if (banded && edge == 0.5) {
            rugo_real v, d1, d2, vl, d1l, d2l;
            bern3(p->band[1], 0.0, &v, &d1, &d2);
            bern3(p->band[0], 1.0, &vl, &d1l, &d2l);
            const rugo_real g_left = v > 0.0 ? g + 2.0 * d1 - 2.0 * d1l : g; /* the left half's slope */
            if (g_left <= 0.0 && g >= 0.0) {
                kink = 1;
                pinned_s |= is_s;
                pinned_t |= !is_s;
                continue;
            }
        }
        if (edge == 0.0 || edge == 1.0) {
            rugo_vec2 pt, d, dd;
            bez3(p->p, edge, &pt, &d, &dd);
            if (vlen(d) <= 1e-9 * c->scale) {
                corner = 1;
                pinned_s |= is_s;
                pinned_t |= !is_s;
                continue;
            }
        }
        drop = mx(drop, low ? g : -g);
    }
    if (drop > flat_slope(c)) return;
    if (kink || corner) {
        /* the pinned parameter stays; the other one is polished along the pin's line */
        if (pinned_s != pinned_t) polish_along(c, pinned_s, &s, &t, &e);
        add_found(c, c->mins, &c->nmin, s, t, e.phi, corner ? RUGO__END_MINIMUM : RUGO__MINIMUM, 1, 1e-9);
        return;
    }
    rugo_real ps = s, pt = t, pphi = e.phi;
    if (polish_minimum(c, &ps, &pt, &pphi)) {
        add_found(c, c->mins, &c->nmin, ps, pt, pphi, RUGO__MINIMUM, 1, 1e-9);
        return;
    }
    ++c->fallback;
    add_found(c, c->mins, &c->nmin, s, t, e.phi, RUGO__MINIMUM, 0, 1e-12);
}

/* Chords that face each other along a stretch over which φ is flat (slope below flat_slope: parallel
 * to round-off): a conforming stretch, whose two ends are its points (Box2D clips faces the same way).
 * 1 when the leaf is one; its ends are then recorded. */
static int conforming_leaf(rctx* c, box b, const sub* F, const sub* G) {
    const rugo_vec2 P0 = F->p[0], U = rugo_v2_sub(F->p[3], F->p[0]);
    const rugo_vec2 Q0 = G->p[0], V = rugo_v2_sub(G->p[3], G->p[0]);
    const rugo_real UU = rugo_v2_dot(U, U), VV = rugo_v2_dot(V, V);
    if (!(UU > 0.0) || !(VV > 0.0)) return 0;
    const rugo_real q0 = rugo_v2_dot(rugo_v2_sub(Q0, P0), U) / UU,
                    q1 = rugo_v2_dot(rugo_v2_sub(G->p[3], P0), U) / UU;
    const rugo_real ua = mx(0.0, mn(q0, q1)), ub = mn(1.0, mx(q0, q1));
    if (!(ua < ub)) return 0;
    rugo_real us[2] = {ua, ub}, vs[2], phis[2];
    for (int k = 0; k < 2; ++k) {
        const rugo_vec2 p = rugo_v2_add(P0, rugo_v2_scale(us[k], U));
        vs[k] = clamp01(rugo_v2_dot(rugo_v2_sub(p, Q0), V) / VV);
        const rugo_vec2 q = rugo_v2_add(Q0, rugo_v2_scale(vs[k], V));
        const rugo_real la = mx(0.0, (1.0 - us[k]) * F->l0 + us[k] * F->l1);
        const rugo_real lb = mx(0.0, (1.0 - vs[k]) * G->l0 + vs[k] * G->l1);
        phis[k] = vlen(rugo_v2_sub(p, q)) - la - lb;
    }
    /* flat to δ over the whole piece's parameter range, not only across this leaf */
    const rugo_real slope = fabs(phis[1] - phis[0]) / ((ub - ua) * (b.s1 - b.s0));
    if (!(slope <= flat_slope(c)) || !(mn(phis[0], phis[1]) <= c->cutoff + c->delta)) return 0;
    for (int k = 0; k < 2; ++k) {
        const rugo_real s = b.s0 + us[k] * (b.s1 - b.s0), t = b.t0 + vs[k] * (b.t1 - b.t0);
        phi_eval e;
        eval_phi(c, s, t, &e);
        ++c->fallback;
        add_found(c, c->mins, &c->nmin, s, t, e.phi, RUGO__MINIMUM, 0, 1e-12);
    }
    return 1;
}

static void leaf(rctx* c, box b, sub* F, sub* G) {
    const rugo_vec2 P0 = F->p[0], U = rugo_v2_sub(F->p[3], F->p[0]);
    const rugo_vec2 Q0 = G->p[0], V = rugo_v2_sub(G->p[3], G->p[0]);
    const rugo_real hs = b.s1 - b.s0, ht = b.t1 - b.t0;
    const rugo_real denom = rugo_v2_cross(U, V);
    const rugo_vec2 w = rugo_v2_sub(Q0, P0);
    int chords_cross = 0;
    /* Crossing of the chords (parallel chords: none; their overlap is a conforming stretch, below). */
    if (fabs(denom) > 1e-14 * (rugo_v2_dot(U, U) + rugo_v2_dot(V, V))) {
        const rugo_real u = rugo_v2_cross(w, V) / denom, v = rugo_v2_cross(w, U) / denom;
        const rugo_real e = 1e-12;
        if (u >= -e && u <= 1.0 + e && v >= -e && v <= 1.0 + e) {
            chords_cross = 1;
            rugo_real s = b.s0 + clamp01(u) * hs, t = b.t0 + clamp01(v) * ht;
            if (polish_crossing(c, &s, &t)) {
                if (c->want & RUGO__RESOLVED_CROSSINGS) {
                    rugo_vec2 fp, fd, fdd, gp, gd, gdd;
                    bez3(c->f->p, s, &fp, &fd, &fdd);
                    bez3(c->g->p, t, &gp, &gd, &gdd);
                    rugo_real cr = rugo_v2_cross(fd, gd);
                    if (cr == 0.0) cr = denom;
                    add_found(c, c->cross, &c->ncross, s, t, 0.0, cr > 0.0 ? 1 : (cr < 0.0 ? -1 : 0), 1,
                              1e-9);
                }
            } else if (c->want & RUGO__RESOLVED_MINIMA) {
                /* Chords that cross where the curves have no crossing Newton can find: the curves come
                 * within δ there (a touching, or an overlap shallower than δ): a minimum to δ. */
                s = b.s0 + clamp01(u) * hs;
                t = b.t0 + clamp01(v) * ht;
                phi_eval pe;
                eval_phi(c, s, t, &pe);
                ++c->fallback;
                add_found(c, c->mins, &c->nmin, s, t, pe.phi, RUGO__MINIMUM, 0, 0.0);
            }
        }
    }
    if (!chords_cross) {
        /* Chords that miss each other by less than the two flatnesses may stand for curves that do
         * cross (near a leaf's end, where a chord's crossing moves off the other's end): Newton decides. */
        rugo_real x, u = 0.0, v = 0.0, gapd = point_chord(P0, Q0, V, 0.0, 0.0, &v);
        rugo_real d1 = point_chord(F->p[3], Q0, V, 0.0, 0.0, &x);
        if (d1 < gapd) gapd = d1, u = 1.0, v = x;
        d1 = point_chord(Q0, P0, U, 0.0, 0.0, &x);
        if (d1 < gapd) gapd = d1, u = x, v = 0.0;
        d1 = point_chord(G->p[3], P0, U, 0.0, 0.0, &x);
        if (d1 < gapd) gapd = d1, u = x, v = 1.0;
        if (gapd <= sub_flat(F) + sub_flat(G)) {
            rugo_real s = b.s0 + u * hs, t = b.t0 + v * ht;
            int ok = polish_crossing(c, &s, &t);
            if (!ok) { /* the closest chord points may lead to a root outside the domain: the centre */
                s = b.s0 + 0.5 * hs;
                t = b.t0 + 0.5 * ht;
                ok = polish_crossing(c, &s, &t);
            }
            if (ok) {
                chords_cross = 1;
                if (c->want & RUGO__RESOLVED_CROSSINGS) {
                    rugo_vec2 fp, fd, fdd, gp, gd, gdd;
                    bez3(c->f->p, s, &fp, &fd, &fdd);
                    bez3(c->g->p, t, &gp, &gd, &gdd);
                    const rugo_real cr = rugo_v2_cross(fd, gd);
                    add_found(c, c->cross, &c->ncross, s, t, 0.0, cr > 0.0 ? 1 : (cr < 0.0 ? -1 : 0), 1,
                              1e-9);
                }
            }
        }
    }
    if ((c->want & RUGO__RESOLVED_MINIMA) && !chords_cross) {
        /* Four edges of the square: the ends of one chord against the other. */
        const rugo_real a0 = mx(0.0, F->l0), da = mx(0.0, F->l1) - a0;
        const rugo_real b0 = mx(0.0, G->l0), db = mx(0.0, G->l1) - b0;
        rugo_real best = HUGE_VAL, bu = 0.0, bv = 0.0, x;
        rugo_real val = point_chord(P0, Q0, V, b0 + a0, db, &x);
        if (val < best) best = val, bu = 0.0, bv = x;
        val = point_chord(F->p[3], Q0, V, b0 + a0 + da, db, &x);
        if (val < best) best = val, bu = 1.0, bv = x;
        val = point_chord(Q0, P0, U, a0 + b0, da, &x);
        if (val < best) best = val, bu = x, bv = 0.0;
        val = point_chord(G->p[3], P0, U, a0 + b0 + db, da, &x);
        if (val < best) best = val, bu = x, bv = 1.0;
        if (best <= c->cutoff + c->delta && !conforming_leaf(c, b, F, G))
            leaf_minimum(c, b, b.s0 + bu * hs, b.t0 + bv * ht);
    }
    if (c->want & RUGO__RESOLVED_SADDLES) {
        /* A depth pair joins anti-parallel stretches facing each other across an overlap. */
        if (rugo_v2_dot(U, V) < 0.0) {
            const rugo_vec2 mid = lerp(F->p[0], F->p[3], 0.5);
            const rugo_real L2 = rugo_v2_dot(V, V);
            const rugo_real v = L2 > 0.0 ? clamp01(rugo_v2_dot(rugo_v2_sub(mid, Q0), V) / L2) : 0.5;
            rugo_real s = b.s0 + 0.5 * hs, t = b.t0 + v * ht;
            int kind = 0;
            if (polish_stationary(c, &s, &t, &kind) && kind == RUGO__SADDLE) {
                rugo_vec2 fp, fd, fdd, gp, gd, gdd;
                bez3(c->f->p, s, &fp, &fd, &fdd);
                bez3(c->g->p, t, &gp, &gd, &gdd);
                const rugo_real d = vlen(rugo_v2_sub(fp, gp));
                if (d <= c->saddle_cutoff)
                    add_found(c, c->saddles, &c->nsaddle, s, t, d, RUGO__SADDLE, 1, 1e-9);
            }
        }
    }
}

/* The two sub-pieces' tangent lines are never parallel (cones apart with no band allowance). */
/* The box's one possible crossing (transversal pieces), by Newton from the chords' crossing (or the
 * box's centre): 1 when the box is settled — a root found inside it, or the pieces apart (which the
 * caller's hull test did not prove). Minima need no search there: the tangents are never parallel,
 * and with bands only within the slopes' allowance, which the caller checks (cones_exclude). */
static int crossing_in_box(rctx* c, box b, sub* F, sub* G) {
    if ((c->want & RUGO__RESOLVED_MINIMA) && !cones_exclude(F, G, 1)) return 0;
    const rugo_vec2 U = rugo_v2_sub(F->p[3], F->p[0]), V = rugo_v2_sub(G->p[3], G->p[0]);
    const rugo_vec2 w = rugo_v2_sub(G->p[0], F->p[0]);
    const rugo_real denom = rugo_v2_cross(U, V);
    rugo_real u = 0.5, v = 0.5;
    if (denom != 0.0) {
        u = clamp01(rugo_v2_cross(w, V) / denom);
        v = clamp01(rugo_v2_cross(w, U) / denom);
    }
    rugo_real s = b.s0 + u * (b.s1 - b.s0), t = b.t0 + v * (b.t1 - b.t0);
    if (!polish_crossing(c, &s, &t)) return 0;
    const rugo_real pad = 1e-12;
    if (s < b.s0 - pad || s > b.s1 + pad || t < b.t0 - pad || t > b.t1 + pad) return 0;
    if (c->want & RUGO__RESOLVED_CROSSINGS) {
        rugo_vec2 fp, fd, fdd, gp, gd, gdd;
        bez3(c->f->p, s, &fp, &fd, &fdd);
        bez3(c->g->p, t, &gp, &gd, &gdd);
        const rugo_real cr = rugo_v2_cross(fd, gd);
        add_found(c, c->cross, &c->ncross, s, t, 0.0, cr > 0.0 ? 1 : (cr < 0.0 ? -1 : 0), 1, 1e-9);
    }
    return 1;
}

/* ---------------------------------------------------------------------------------------------- */
/* Search */

/* A box of the search with its two sub-pieces (carried down by halving, not recomputed). */
typedef struct frame {
    box b;
    sub F, G;
} frame;

static void search(rctx* c) {
    frame st[STACK_MAX];
    int n = 1, boxes = 0;
    st[0].b.s0 = st[0].b.t0 = 0.0;
    st[0].b.s1 = st[0].b.t1 = 1.0;
    root_sub(c->f, c->banded_f, &st[0].F);
    root_sub(c->g, c->banded_g, &st[0].G);
    const rugo_real half_delta = 0.5 * c->delta;
    const rugo_real min_width = ldexp(1.0, -MAX_DEPTH);
    while (n > 0) {
        const box b = st[--n].b;
        if (++boxes > BOX_BUDGET) {
            c->overflow = 1;
            return;
        }
        sub* F = &st[n].F;
        sub* G = &st[n].G;
        const rugo_real gap = hull_gap(F, G);
        const int cross = (c->want & RUGO__RESOLVED_CROSSINGS) && gap <= 0.0;
        int need = cross;
        if (!need && (c->want & RUGO__RESOLVED_MINIMA) && gap - F->lmax - G->lmax <= c->cutoff + c->delta &&
            !cones_exclude(F, G, 1))
            need = 1;
        if (!need && (c->want & RUGO__RESOLVED_SADDLES) && gap <= c->saddle_cutoff && !cones_exclude(F, G, 0))
            need = 1;
        if (!need) continue;
        /* Tangent lines apart over the whole box: at most one crossing there (two would give, by
         * Rolle, tangents of both parallel to the chord between them) and no stationary point. Newton
         * from the chords' crossing then settles the box when it converges inside it. */
        if (gap <= 0.0 && cones_exclude(F, G, 0) && crossing_in_box(c, b, F, G)) continue;
        const int tiny_f = b.s1 - b.s0 <= min_width, tiny_g = b.t1 - b.t0 <= min_width;
        const rugo_real ff = sub_flat(F), fg = sub_flat(G);
        if ((ff <= half_delta || tiny_f) && (fg <= half_delta || tiny_g)) {
            leaf(c, b, F, G);
            continue;
        }
        if (n + 2 > STACK_MAX) {
            c->overflow = 1;
            return;
        }
        /* The sub-piece farther from flat is halved; the two halves go on the stack, the lower on top:
         * the higher half takes this frame's place (the other sub-piece stays where it is), the lower
         * one the next frame, so a split copies one sub-piece, not two frames. */
        const int split_f = !tiny_f && ff > half_delta && (ff >= fg || tiny_g || fg <= half_delta);
        frame* hi = &st[n];
        frame* lo = &st[n + 1];
        sub upper;
        lo->b = b;
        if (split_f) {
            const rugo_real m = 0.5 * (b.s0 + b.s1);
            lo->b.s1 = hi->b.s0 = m;
            split_sub(F, &lo->F, &upper);
            lo->G = *G;
            hi->F = upper;
        } else {
            const rugo_real m = 0.5 * (b.t0 + b.t1);
            lo->b.t1 = hi->b.t0 = m;
            split_sub(G, &lo->G, &upper);
            lo->F = *F;
            hi->G = upper;
        }
        n += 2;
    }
}

/* ---------------------------------------------------------------------------------------------- */
/* Output */

static void sort_found(found* a, int n) {
    for (int i = 1; i < n; ++i) {
        const found v = a[i];
        int j = i - 1;
        while (j >= 0 && (a[j].s > v.s || (a[j].s == v.s && a[j].t > v.t))) {
            a[j + 1] = a[j];
            --j;
        }
        a[j + 1] = v;
    }
}

/* Unpolished minima along a conforming stretch come one or two per leaf: keep each run's two ends
 * (a run: consecutive unpolished minima by s, each within `reach` of the next in both parameters),
 * and its deepest point unless a polished minimum inside the run is as deep. Polished minima stay. */
static int reduce_runs(found* a, int n, rugo_real reach) {
    found keep[TMP_ROOTS];
    int w = 0;
    for (int i = 0; i < n;) {
        if (a[i].polished) {
            ++i;
            continue;
        }
        int last = i, deep = i, j = i + 1;
        for (; j < n; ++j) {
            if (a[j].polished) continue;
            if (fabs(a[j].s - a[last].s) > reach || fabs(a[j].t - a[last].t) > reach) break;
            last = j;
            if (a[j].phi < a[deep].phi) deep = j;
        }
        int covered = 0;
        for (int k = i; k <= last; ++k)
            covered |= a[k].polished && a[k].phi <= a[deep].phi;
        keep[w++] = a[i];
        if (deep != i && deep != last && !covered) keep[w++] = a[deep];
        if (last != i) keep[w++] = a[last];
        i = j;
    }
    for (int i = 0; i < n; ++i)
        if (a[i].polished) keep[w++] = a[i];
    memcpy(a, keep, (size_t)w * sizeof *a);
    sort_found(a, w);
    return w;
}

static void fill(const rctx* c, const found* r, int kind, rugo__pair_point* p) {
    rugo_vec2 fd, fdd, gd, gdd;
    p->s = r->s;
    p->t = r->t;
    bez3(c->f->p, r->s, &p->pa, &fd, &fdd);
    bez3(c->g->p, r->t, &p->pb, &gd, &gdd);
    p->distance = vlen(rugo_v2_sub(p->pb, p->pa));
    p->kind = kind;
    p->flat = !r->polished;
}

static int all_finite(const rugo__banded_piece* p) {
    for (int i = 0; i < 4; ++i) {
        if (!isfinite(p->p[i].x) || !isfinite(p->p[i].y)) return 0;
        if (!isfinite(p->band[0][i]) || !isfinite(p->band[1][i])) return 0;
    }
    return 1;
}

static int is_banded(const rugo__banded_piece* p) {
    for (int h = 0; h < 2; ++h)
        for (int i = 0; i < 4; ++i)
            if (p->band[h][i] != 0.0) return 1;
    return 0;
}

void rugo__narrow_resolved(const rugo__banded_piece* f, const rugo__banded_piece* g, rugo_real cutoff,
                           rugo_real saddle_cutoff, rugo_real delta, int want, rugo__narrow_result* out) {
    memset(out, 0, sizeof *out);
    if (!all_finite(f) || !all_finite(g) || !(delta > 0.0) || !isfinite(delta)) return;
    if (!(cutoff == cutoff)) want &= ~RUGO__RESOLVED_MINIMA;
    if (!(saddle_cutoff == saddle_cutoff)) want &= ~RUGO__RESOLVED_SADDLES;
    rctx c;
    c.f = f;
    c.g = g;
    c.banded_f = is_banded(f);
    c.banded_g = is_banded(g);
    c.cutoff = cutoff;
    c.saddle_cutoff = saddle_cutoff;
    c.delta = delta;
    c.want = want;
    c.newton = c.fallback = c.overflow = 0;
    c.ncross = c.nmin = c.nsaddle = 0;
    rugo_real ext = 0.0;
    for (int i = 0; i < 4; ++i) {
        ext = mx(ext, mx(fabs(f->p[i].x - f->p[0].x), fabs(f->p[i].y - f->p[0].y)));
        ext = mx(ext, mx(fabs(g->p[i].x - f->p[0].x), fabs(g->p[i].y - f->p[0].y)));
    }
    c.scale = ext;
    search(&c);

    sort_found(c.cross, c.ncross);
    sort_found(c.mins, c.nmin);
    sort_found(c.saddles, c.nsaddle);
    c.nmin = reduce_runs(c.mins, c.nmin, 1.01);
    for (int i = 0; i < c.ncross; ++i) {
        if (out->crossing_count >= RUGO__NARROW_MAX_CROSSINGS) {
            out->overflow = 1;
            break;
        }
        fill(&c, &c.cross[i], c.cross[i].kind, &out->crossings[out->crossing_count++]);
    }
    /* Stationary pairs: minima and saddles merged by s. */
    int i = 0, j = 0;
    while (i < c.nmin || j < c.nsaddle) {
        const int take_min = j >= c.nsaddle || (i < c.nmin && c.mins[i].s <= c.saddles[j].s);
        const found* r = take_min ? &c.mins[i++] : &c.saddles[j++];
        if (out->stationary_count >= RUGO__NARROW_MAX_STATIONARY) {
            out->overflow = 1;
            break;
        }
        fill(&c, r, r->kind, &out->stationary[out->stationary_count++]);
    }
    out->newton_iterations = c.newton;
    out->fallback = c.fallback;
    out->overflow |= c.overflow;
}

int rugo__polish_band_minimum(const rugo__banded_piece* f, const rugo__banded_piece* g, rugo_real* s,
                              rugo_real* t, rugo_real* phi) {
    rctx c;
    c.f = f;
    c.g = g;
    c.banded_f = is_banded(f);
    c.banded_g = is_banded(g);
    c.newton = 0;
    rugo_real ext = 0.0;
    for (int i = 0; i < 4; ++i) {
        ext = mx(ext, mx(fabs(f->p[i].x - f->p[0].x), fabs(f->p[i].y - f->p[0].y)));
        ext = mx(ext, mx(fabs(g->p[i].x - f->p[0].x), fabs(g->p[i].y - f->p[0].y)));
    }
    c.scale = ext;
    return polish_minimum(&c, s, t, phi);
}

void rugo__banded_piece_smooth(const rugo_vec2 p[4], rugo__banded_piece* out) {
    memset(out, 0, sizeof *out);
    for (int i = 0; i < 4; ++i)
        out->p[i] = p[i];
}
