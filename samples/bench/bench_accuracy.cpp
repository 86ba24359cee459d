/* Accuracy of the contact queries at a resolution (issue 20): an independent check of what
 * rugo_contact_query.resolution promises (include/rugo/collide.h, docs/contacts.md "Resolution").
 *
 * Usage: bench_accuracy [--quick] [--poses N] [--seed S] [--kind NAME] [--delta REL] [--rule band|thesis]
 *                       [--reference-check N] [--pose P] [--verbose] [OUTDIR]
 *        (--pose P: only pose P of each selected cell, its shapes, transforms and query written to
 *        OUTDIR/repro.txt; with --verbose the contacts and reference minima are printed: a reproducer)
 *        (default OUTDIR out/bench_accuracy; --quick: a few hundred poses, checks, OUTDIR as given)
 *
 * What is checked, for each pose and query (lod 0, margin m, resolution δ, rule band-adjusted or thesis):
 *  φ(s, t) = |f_A(s) - f_B(t)| - λ_A(s) - λ_B(t) (band-adjusted distance; rule "band") or d = |f_A - f_B|
 *  (rule "thesis", kept when its φ <= m). The query promises, at resolution δ:
 *   (1) no local minimum of the objective with φ <= m - δ is missed;
 *   (2) every reported value (separation - tolerance_a - tolerance_b for "band", separation for "thesis")
 *       is within δ of the true local minimum it stands for;
 *   (3) point and normal errors that follow from δ (measured: the excess of the objective at the
 *       reported pair over that minimum, which must be <= δ, and the normal's angle to the minimum's);
 *   a stretch parallel to within δ is one region (its ends and deepest point); overlaps shallower than δ
 *   may come out as a touching. δ = 0: round-off answers.
 *
 * Shape kinds (pairs A, B; 64 to 128 control points; sizes ~1): ellipse (convex smooth), concave (a
 * five-armed star and the samples' bean against small ellipses and each other), rough (roughened
 * outlines with tipo_2 / tipo_5 bands x 0.06: λ up to 0.04, varying per segment), straight (boxes with
 * rounded corners: collinear control points), corners (a triangle and boxes whose corners are 3 or 4
 * coincident control points, corner on face and corner on corner), conforming (a disc in bowls whose
 * bay is 1.01 / 1.001 / 1.0001 times its radius, a box lying on a slab within tilts of ~δ). Poses are
 * placed by this program's reference alone (never by librugo): a point of A and one of B facing each
 * other, then B moved along the normal until the pose's smallest objective (or the curves' signed
 * distance, for a third of the rough poses) equals the target gap g, drawn from [-2δ, m] (80 % within
 * [-2δ, 10δ]); m = 20δ; δ in {1e-3, 1e-5, 0} x the smaller shape's size (the diagonal of its finest
 * curve's bounds); at δ = 0 the gaps are drawn at the scale 1e-6 x size.
 *
 * Reference (independent of librugo's narrow phase; long double throughout): the finest control points
 * placed in the world, each B-spline segment evaluated by its own basis functions, λ(t) by the SPEC 6.3
 * Lagrange cubics (checked against rugo_tolerance_at at start-up). K samples per segment on both curves;
 * for every sample of one curve, the other curve's samples within reach; along them the discrete local
 * minima of the objective, each refined in the other parameter (bracketed Newton/bisection on the
 * derivative, which converges into λ's kinks too): the valley points. Valley points of consecutive
 * samples are linked into chains; every chain local minimum is refined in both parameters by a damped
 * Newton iteration (Levenberg-Marquardt, confined to one smooth piece of λ at a time and walking into the
 * next where its gradient points); both curves' chains give minima, deduplicated. A minimum counts if the
 * curves face each other there (B on A's outward side and A on B's, within the corner's normal cone at
 * zero speed) and it is not a crossing (d -> 0). Crossings and overlaps: the signed distance along the
 * chains (sign from the foot point's normal or corner cone), its local minima refined by Newton on the
 * stationarity system (f-g).f' = (f-g).g' = 0: a negative one is an overlap region's deepest pair (also
 * between samples: overlaps far shallower than the sampling are found). Containment by a winding count.
 *
 * Comparison: a reported contact with separation < 0 is an overlap contact, matched to the reference
 * region under its parameters (depth error |s + depth|); any other contact is put on the chain node
 * under its parameters and descends along the chain to the local minimum it stands for: separation error
 * (reported value - that minimum's), excess (the true objective at the reported pair - the minimum's),
 * normal error (angle to the minimum's (point_b - point_a) direction). A required minimum (facing, not a
 * crossing, φ <= m - δ - ε, away from overlaps) is missed unless some contact lies on its stretch: the
 * chain around it while the objective stays <= its value + δ + ε. A contact is spurious if the minimum
 * it stands for does not face, or has φ > m + δ + ε, or there is none. States: INTERSECTING may come out
 * CONTACT when every overlap is <= δ + ε deep; CONTACT may come out APART when no minimum has φ <= m - δ
 * - ε, and INTERSECTING when the curves come within δ + ε; APART may come out CONTACT when some minimum
 * has φ <= m + δ + ε. ε = 1e-12 x size (round-off allowance).
 *
 * Output: OUTDIR/bench_accuracy.csv (one row per kind x δ x rule), OUTDIR/bench_accuracy_poses.csv (one
 * row per pose and rule, with both transforms as %a: the reproducers start there), the table on stdout.
 * --quick (the test sample_bench_accuracy): the reference's own checks (known answers: two discs, a disc
 * over a line, an overlap of two discs 1e-4 and 1e-9 deep, constant bands; λ against rugo_tolerance_at;
 * K = 16 against K = 48) and a few hundred poses; exits non-zero on any miss or separation error > δ + ε
 * in any cell (kind, δ, rule). With Box2D (RUGO_BENCH_WITH_BOX2D) the δ = 1e-3 poses are also given to
 * Box2D 2.4.1 polygon compounds of the same outlines at m = 64, 256, 1024, 4096 vertices (--quick: 64,
 * 256; polygon_baseline.hpp, shared with bench_queries): OUTDIR/bench_accuracy_box2d.csv. */
#include "rugo/rugo.h"

extern "C" {
#include "sample_check.h"
}

#include "bench_outlines.hpp"
#ifdef RUGO_BENCH_WITH_BOX2D
#include "polygon_baseline.hpp"
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

namespace {

using namespace bench_outlines;

typedef long double ld;

double now_ns() {
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* splitmix64: seeded, the same sequence on every platform. */
struct Rng {
    uint64_t s;
    explicit Rng(uint64_t seed) : s(seed * 0x2545f4914f6cdd1dull + 0x9e3779b97f4a7c15ull) {}
    uint64_t next() {
        uint64_t z = (s += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uni() { return (double)(next() >> 11) * 0x1.0p-53; }
    double range(double a, double b) { return a + (b - a) * uni(); }
    int below(int n) { return std::min(n - 1, (int)(uni() * n)); }
};

ld lhypot(ld x, ld y) { return std::sqrt(x * x + y * y); }

/* ------------------------------------------------------------------------------------------------
 * Shapes */

struct Corner {
    double u;              /* global parameter of the corner point */
    rugo_vec2 n_in, n_out; /* outward normals of the arriving and leaving flanks (local frame) */
    bool convex;
};

struct Body {
    std::string name;
    rugo_shape* shape = nullptr;
    std::vector<rugo_vec2> pts; /* finest control points as the shape holds them (CCW, local frame) */
    std::vector<double> lam;    /* finest λ per segment in the shape's order; empty: smooth */
    double size = 0.0;          /* diagonal of the finest curve's bounds */
    double lam_max = 0.0;       /* an upper bound of λ(t) */
    std::vector<Corner> corners;
};

bool make_body(Body& b, const std::string& name, const std::vector<rugo_vec2>& p,
               const std::vector<double>* tol) {
    b.name = name;
    rugo_shape_def d = rugo_default_shape_def();
    d.points = p.data();
    d.count = (int)p.size();
    d.tolerances = tol ? tol->data() : nullptr;
    rugo_contour_problem pr;
    const rugo_status st = rugo_shape_create(&d, &b.shape, &pr);
    if (st != RUGO_OK) {
        std::fprintf(stderr, "%s: rugo_shape_create: %s\n", name.c_str(), rugo_status_string(st));
        return false;
    }
    const int J = rugo_shape_finest_level(b.shape);
    rugo_contour c;
    rugo_shape_level(b.shape, J, &c);
    b.pts.assign(c.points, c.points + c.count);
    b.lam.clear();
    b.lam_max = 0.0;
    if (tol) {
        rugo_tolerance_level tl;
        rugo_shape_tolerance_level(b.shape, J, &tl);
        b.lam.assign(tl.total, tl.total + tl.count);
        for (double v : b.lam)
            b.lam_max = std::max(b.lam_max, v);
        b.lam_max *= 1.3; /* the cubic interpolation overshoots by less than this */
    }
    rugo_vec2 lo, hi;
    rugo_contour_bounds(c, &lo, &hi);
    b.size = std::hypot(hi.x - lo.x, hi.y - lo.y);
    /* corners: runs of 3 or 4 equal control points */
    const int n = c.count;
    b.corners.clear();
    for (int a = 0; a < n; ++a) {
        const rugo_vec2 pa = b.pts[(size_t)a], pm = b.pts[(size_t)((a - 1 + n) % n)];
        if (pm.x == pa.x && pm.y == pa.y) continue; /* not the start of a run */
        int L = 1;
        while (L < n) {
            const rugo_vec2 q = b.pts[(size_t)((a + L) % n)];
            if (q.x != pa.x || q.y != pa.y) break;
            ++L;
        }
        if (L < 3) continue;
        Corner k;
        k.u = L == 3 ? a + 1.0 : a + 1.5;
        const rugo_vec2 nx = b.pts[(size_t)((a + L) % n)];
        const rugo_vec2 din = rugo_v2(pa.x - pm.x, pa.y - pm.y), dout = rugo_v2(nx.x - pa.x, nx.y - pa.y);
        const double li = std::hypot(din.x, din.y), lo2 = std::hypot(dout.x, dout.y);
        k.n_in = rugo_v2(din.y / li, -din.x / li);
        k.n_out = rugo_v2(dout.y / lo2, -dout.x / lo2);
        k.convex = din.x * dout.y - din.y * dout.x > 0.0;
        b.corners.push_back(k);
    }
    return true;
}

/* ------------------------------------------------------------------------------------------------
 * A curve placed in the world, in long double */

struct Side {
    const Body* body = nullptr;
    int n = 0, K = 16;
    std::vector<ld> cx, cy; /* world control points */
    const double* lam = nullptr;
    ld lam_max = 0;
    std::vector<ld> sx, sy; /* samples u = i / K */
    std::vector<double> fx, fy;
    ld h = 0;         /* largest distance between consecutive samples */
    ld speed_ref = 0; /* a typical speed |f'| (length per unit parameter) */
};

struct Ev {
    ld x, y, dx, dy, ddx, ddy;
};

ld wrap_u(ld u, int n) {
    const ld nn = (ld)n;
    u = std::fmod(u, nn);
    if (u < 0) u += nn;
    if (u >= nn) u = 0;
    return u;
}

int wrap_i(long i, int n) {
    long r = i % n;
    if (r < 0) r += n;
    return (int)r;
}

/* f(u), f'(u), f''(u) of the uniform cubic B-spline: segment j = floor(u) over c_{j-1} .. c_{j+2}. */
Ev eval(const Side& c, ld u) {
    u = wrap_u(u, c.n);
    int j = (int)std::floor(u);
    if (j >= c.n) j = c.n - 1;
    const ld t = u - (ld)j, mt = 1 - t;
    const int i0 = wrap_i(j - 1, c.n), i1 = j, i2 = wrap_i(j + 1, c.n), i3 = wrap_i(j + 2, c.n);
    const ld b0 = mt * mt * mt / 6, b1 = (3 * t * t * t - 6 * t * t + 4) / 6,
             b2 = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, b3 = t * t * t / 6;
    const ld d0 = -mt * mt / 2, d1 = (3 * t * t - 4 * t) / 2, d2 = (-3 * t * t + 2 * t + 1) / 2,
             d3 = t * t / 2;
    const ld e0 = mt, e1 = 3 * t - 2, e2 = -3 * t + 1, e3 = t;
    Ev r;
    r.x = b0 * c.cx[(size_t)i0] + b1 * c.cx[(size_t)i1] + b2 * c.cx[(size_t)i2] + b3 * c.cx[(size_t)i3];
    r.y = b0 * c.cy[(size_t)i0] + b1 * c.cy[(size_t)i1] + b2 * c.cy[(size_t)i2] + b3 * c.cy[(size_t)i3];
    r.dx = d0 * c.cx[(size_t)i0] + d1 * c.cx[(size_t)i1] + d2 * c.cx[(size_t)i2] + d3 * c.cx[(size_t)i3];
    r.dy = d0 * c.cy[(size_t)i0] + d1 * c.cy[(size_t)i1] + d2 * c.cy[(size_t)i2] + d3 * c.cy[(size_t)i3];
    r.ddx = e0 * c.cx[(size_t)i0] + e1 * c.cx[(size_t)i1] + e2 * c.cx[(size_t)i2] + e3 * c.cx[(size_t)i3];
    r.ddy = e0 * c.cy[(size_t)i0] + e1 * c.cy[(size_t)i1] + e2 * c.cy[(size_t)i2] + e3 * c.cy[(size_t)i3];
    return r;
}

/* λ and its derivatives. SPEC 6.3: piece k is the cubic through λ_{k-1}, λ_k, λ_{k+1}, λ_{k+2} at w = 0, 1,
 * 2, 3; it holds u in [k + 1/2, k + 3/2) with w = u - k + 1/2 (λ_j at the middle of segment j); clamped
 * below at 0. Kinks at the middles of segments. */
struct Lam {
    ld v, d1, d2;
};

Lam lam_piece(const Side& c, long k, ld u) {
    Lam r = {0, 0, 0};
    if (c.lam == nullptr) return r;
    const ld w = u - (ld)k + (ld)0.5;
    const ld l0 = c.lam[wrap_i(k - 1, c.n)], l1 = c.lam[wrap_i(k, c.n)], l2 = c.lam[wrap_i(k + 1, c.n)],
             l3 = c.lam[wrap_i(k + 2, c.n)];
    const ld w1 = w - 1, w2 = w - 2, w3 = w - 3;
    r.v = -(w1 * w2 * w3) / 6 * l0 + (w * w2 * w3) / 2 * l1 - (w * w1 * w3) / 2 * l2 + (w * w1 * w2) / 6 * l3;
    r.d1 = -(3 * w * w - 12 * w + 11) / 6 * l0 + (3 * w * w - 10 * w + 6) / 2 * l1 -
           (3 * w * w - 8 * w + 3) / 2 * l2 + (3 * w * w - 6 * w + 2) / 6 * l3;
    r.d2 = -(6 * w - 12) / 6 * l0 + (6 * w - 10) / 2 * l1 - (6 * w - 8) / 2 * l2 + (6 * w - 6) / 6 * l3;
    if (r.v < 0) r = {0, 0, 0};
    return r;
}

long piece_of(ld u) { return (long)std::floor(u - (ld)0.5); }

Lam lam_at(const Side& c, ld u) { return lam_piece(c, piece_of(u), u); }

void place_side(Side& s, const Body& b, rugo_transform xf, int K) {
    s.body = &b;
    s.n = (int)b.pts.size();
    s.K = K;
    s.cx.resize(b.pts.size());
    s.cy.resize(b.pts.size());
    const ld c = xf.q.c, sn = xf.q.s;
    for (size_t i = 0; i < b.pts.size(); ++i) {
        s.cx[i] = (ld)xf.p.x + c * (ld)b.pts[i].x - sn * (ld)b.pts[i].y;
        s.cy[i] = (ld)xf.p.y + sn * (ld)b.pts[i].x + c * (ld)b.pts[i].y;
    }
    s.lam = b.lam.empty() ? nullptr : b.lam.data();
    s.lam_max = b.lam_max;
    const int N = s.n * K;
    s.sx.resize((size_t)N);
    s.sy.resize((size_t)N);
    s.fx.resize((size_t)N);
    s.fy.resize((size_t)N);
    ld sp = 0;
    for (int i = 0; i < N; ++i) {
        const Ev e = eval(s, (ld)i / K);
        s.sx[(size_t)i] = e.x;
        s.sy[(size_t)i] = e.y;
        s.fx[(size_t)i] = (double)e.x;
        s.fy[(size_t)i] = (double)e.y;
        sp += lhypot(e.dx, e.dy);
    }
    s.speed_ref = sp / N;
    s.h = 0;
    for (int i = 0; i < N; ++i) {
        const int j = (i + 1) % N;
        s.h = std::max(s.h, lhypot(s.sx[(size_t)j] - s.sx[(size_t)i], s.sy[(size_t)j] - s.sy[(size_t)i]));
    }
}

/* Outward normals on either side of u (equal where the speed is not ~0; at a corner of coincident control
 * points, the flanks' normals from the nearest points with speed). */
void normals_at(const Side& c, ld u, ld* n1x, ld* n1y, ld* n2x, ld* n2y) {
    const Ev e = eval(c, u);
    ld sp = lhypot(e.dx, e.dy);
    if (sp > 1e-6L * c.speed_ref) {
        *n1x = *n2x = e.dy / sp;
        *n1y = *n2y = -e.dx / sp;
        return;
    }
    for (int side = 0; side < 2; ++side) {
        ld du = side == 0 ? -1e-3L : 1e-3L, nx = 0, ny = 0;
        for (int k = 1; k <= 2500; ++k) {
            const Ev q = eval(c, u + du * k);
            const ld s = lhypot(q.dx, q.dy);
            if (s > 1e-4L * c.speed_ref) {
                nx = q.dy / s;
                ny = -q.dx / s;
                break;
            }
        }
        if (side == 0) {
            *n1x = nx;
            *n1y = ny;
        } else {
            *n2x = nx;
            *n2y = ny;
        }
    }
}

/* ------------------------------------------------------------------------------------------------
 * The objective: φ = d - λ_A - λ_B ("band") or d ("thesis"), with gradient and Hessian in (s, t).
 * For the band, λ's pieces ka, kb are given (one-sided derivatives on the kinks). */

struct Obj {
    ld f, gs, gt, hss, hst, htt, d;
};

Obj objective(const Side& A, const Side& B, ld s, ld t, bool band, long ka, long kb) {
    const Ev a = eval(A, s), b = eval(B, t);
    const ld rx = a.x - b.x, ry = a.y - b.y, d = lhypot(rx, ry);
    Obj o = {d, 0, 0, 0, 0, 0, d};
    if (d > 0) {
        const ld ra = rx * a.dx + ry * a.dy, rb = rx * b.dx + ry * b.dy, d3 = d * d * d;
        o.gs = ra / d;
        o.gt = -rb / d;
        o.hss = (a.dx * a.dx + a.dy * a.dy + rx * a.ddx + ry * a.ddy) / d - ra * ra / d3;
        o.htt = (b.dx * b.dx + b.dy * b.dy - rx * b.ddx - ry * b.ddy) / d - rb * rb / d3;
        o.hst = -(a.dx * b.dx + a.dy * b.dy) / d + ra * rb / d3;
    }
    if (band) {
        const Lam la = lam_piece(A, ka, s), lb = lam_piece(B, kb, t);
        o.f -= la.v + lb.v;
        o.gs -= la.d1;
        o.gt -= lb.d1;
        o.hss -= la.d2;
        o.htt -= lb.d2;
    }
    return o;
}

ld phi_at(const Side& A, const Side& B, ld s, ld t) {
    const Ev a = eval(A, s), b = eval(B, t);
    return lhypot(a.x - b.x, a.y - b.y) - lam_at(A, s).v - lam_at(B, t).v;
}

struct MinRes {
    ld s, t, f, d, gs, gt;
    bool attached;
};

/* Damped Newton (Levenberg-Marquardt) for a local minimum in the box [slo, shi] x [tlo, thi] (one smooth
 * piece of each λ), projected at the bounds. */
MinRes lm_cell(const Side& A, const Side& B, bool band, ld s0, ld t0, long ka, long kb, ld slo, ld shi,
               ld tlo, ld thi, ld dtiny) {
    ld s = std::min(shi, std::max(slo, s0)), t = std::min(thi, std::max(tlo, t0));
    Obj o = objective(A, B, s, t, band, ka, kb);
    ld mu = 1e-12L * (std::fabs(o.hss) + std::fabs(o.htt) + 1e-30L);
    MinRes r = {s, t, o.f, o.d, o.gs, o.gt, false};
    for (int it = 0; it < 300; ++it) {
        if (o.d < dtiny) {
            r.attached = true;
            break;
        }
        const bool fs = !((s <= slo && o.gs > 0) || (s >= shi && o.gs < 0));
        const bool ft = !((t <= tlo && o.gt > 0) || (t >= thi && o.gt < 0));
        if (!fs && !ft) break;
        ld a = fs ? o.hss : 1, c = ft ? o.htt : 1, b = (fs && ft) ? o.hst : 0;
        const ld lmin = (a + c) / 2 - std::sqrt((a - c) * (a - c) / 4 + b * b);
        if (lmin + mu <= 0) mu = -lmin * 1.5L + 1e-12L * (std::fabs(a) + std::fabs(c) + 1e-30L);
        a += mu;
        c += mu;
        const ld det = a * c - b * b;
        const ld gs = fs ? o.gs : 0, gt = ft ? o.gt : 0;
        ld ps = -(gs * c - b * gt) / det, pt = -(a * gt - b * gs) / det;
        const ld len = std::fabs(ps) + std::fabs(pt);
        if (len > 0.25L) {
            ps *= 0.25L / len;
            pt *= 0.25L / len;
        }
        const ld s2 = std::min(shi, std::max(slo, s + ps)), t2 = std::min(thi, std::max(tlo, t + pt));
        const Obj o2 = objective(A, B, s2, t2, band, ka, kb);
        const ld step = std::fabs(s2 - s) + std::fabs(t2 - t);
        if (o2.f < o.f) {
            s = s2;
            t = t2;
            o = o2;
            mu *= 0.2L;
            if (step < 1e-17L) break;
        } else {
            if (step < 1e-17L) break;
            mu = mu * 8 + 1e-30L;
            if (mu > 1e30L * (std::fabs(o.hss) + std::fabs(o.htt) + 1)) break;
        }
    }
    r.s = s;
    r.t = t;
    r.f = o.f;
    r.d = o.d;
    r.gs = o.gs;
    r.gt = o.gt;
    if (o.d < dtiny) r.attached = true;
    return r;
}

bool on_kink(ld u) {
    const ld w = u - (ld)0.5;
    return std::fabs(w - std::round(w)) < 1e-12L;
}

/* A local minimum from (s0, t0): for the band, within λ's pieces, walking into the next piece where the
 * projected gradient points out of the current one; on a kink both pieces are tried. */
MinRes minimize2(const Side& A, const Side& B, bool band, ld s0, ld t0, ld dtiny) {
    const ld inf = 1e30L;
    if (!band) return lm_cell(A, B, false, s0, t0, 0, 0, -inf, inf, -inf, inf, dtiny);
    std::vector<long> kas = {piece_of(s0)}, kbs = {piece_of(t0)};
    if (on_kink(s0)) kas.push_back(kas[0] - 1);
    if (on_kink(t0)) kbs.push_back(kbs[0] - 1);
    MinRes best;
    best.f = inf;
    for (long ka0 : kas)
        for (long kb0 : kbs) {
            long ka = ka0, kb = kb0;
            ld s = s0, t = t0;
            MinRes r;
            for (int mv = 0; mv < 16; ++mv) {
                r = lm_cell(A, B, true, s, t, ka, kb, (ld)ka + 0.5L, (ld)ka + 1.5L, (ld)kb + 0.5L,
                            (ld)kb + 1.5L, dtiny);
                if (r.attached) break;
                bool moved = false;
                if (r.s <= (ld)ka + 0.5L && r.gs > 0) {
                    --ka;
                    moved = true;
                } else if (r.s >= (ld)ka + 1.5L && r.gs < 0) {
                    ++ka;
                    moved = true;
                }
                if (r.t <= (ld)kb + 0.5L && r.gt > 0) {
                    --kb;
                    moved = true;
                } else if (r.t >= (ld)kb + 1.5L && r.gt < 0) {
                    ++kb;
                    moved = true;
                }
                if (!moved) break;
                s = r.s;
                t = r.t;
            }
            if (r.f < best.f) best = r;
        }
    return best;
}

/* The minimum over t of |p - Q(t)| - λ_Q(t) (band) or |p - Q(t)| in [ta, tb]: bisection on the
 * derivative with Newton steps where bracketed (it converges into kinks), else golden section. */
void min_1d(const Side& Q, bool band, ld px, ld py, ld ta, ld tb, ld* tout, ld* vout, ld* dout) {
    auto val = [&](ld t, ld* g, ld* g2, ld* d) {
        const Ev q = eval(Q, t);
        const ld rx = q.x - px, ry = q.y - py, dd = lhypot(rx, ry);
        ld v = dd, gg = 0, hh = 0;
        if (dd > 0) {
            const ld rq = rx * q.dx + ry * q.dy;
            gg = rq / dd;
            hh = (q.dx * q.dx + q.dy * q.dy + rx * q.ddx + ry * q.ddy) / dd - rq * rq / (dd * dd * dd);
        }
        if (band) {
            const Lam l = lam_at(Q, t);
            v -= l.v;
            gg -= l.d1;
            hh -= l.d2;
        }
        if (g) *g = gg;
        if (g2) *g2 = hh;
        if (d) *d = dd;
        return v;
    };
    ld ga, gb;
    val(ta, &ga, nullptr, nullptr);
    val(tb, &gb, nullptr, nullptr);
    ld t;
    if (ga < 0 && gb > 0) {
        ld lo = ta, hi = tb;
        t = (lo + hi) / 2;
        for (int it = 0; it < 200 && hi - lo > 1e-18L * (1 + std::fabs(lo)); ++it) {
            ld g, g2;
            val(t, &g, &g2, nullptr);
            if (g < 0)
                lo = t;
            else if (g > 0)
                hi = t;
            else
                break;
            ld tn = g2 > 0 ? t - g / g2 : (lo + hi) / 2;
            if (!(tn > lo && tn < hi)) tn = (lo + hi) / 2;
            if (std::fabs(tn - t) < 1e-19L) {
                t = tn;
                break;
            }
            t = tn;
        }
    } else {
        const ld gr = 0.6180339887498948482L;
        ld a = ta, b = tb, c = b - gr * (b - a), e = a + gr * (b - a);
        ld fc = val(c, nullptr, nullptr, nullptr), fe = val(e, nullptr, nullptr, nullptr);
        for (int it = 0; it < 120 && b - a > 1e-18L; ++it) {
            if (fc < fe) {
                b = e;
                e = c;
                fe = fc;
                c = b - gr * (b - a);
                fc = val(c, nullptr, nullptr, nullptr);
            } else {
                a = c;
                c = e;
                fc = fe;
                e = a + gr * (b - a);
                fe = val(e, nullptr, nullptr, nullptr);
            }
        }
        t = (a + b) / 2;
        ld fa = val(ta, nullptr, nullptr, nullptr), fb = val(tb, nullptr, nullptr, nullptr),
           ft = val(t, nullptr, nullptr, nullptr);
        if (fa < ft) t = ta;
        if (fb < std::min(fa, ft)) t = tb;
    }
    *vout = val(t, nullptr, nullptr, dout);
    *tout = t;
}

/* Newton on the stationarity system of the distance, (f-g).f' = (f-g).g' = 0 (any kind of stationary
 * pair: the deepest pair of an overlap is a saddle). Returns false if it does not settle near the start. */
bool stationary(const Side& A, const Side& B, ld* s, ld* t, ld reach) {
    const ld s0 = *s, t0 = *t;
    bool ok = false;
    for (int it = 0; it < 80; ++it) {
        const Ev f = eval(A, *s), q = eval(B, *t);
        const ld rx = f.x - q.x, ry = f.y - q.y;
        const ld F1 = rx * f.dx + ry * f.dy, F2 = rx * q.dx + ry * q.dy;
        const ld j11 = f.dx * f.dx + f.dy * f.dy + rx * f.ddx + ry * f.ddy,
                 j12 = -(q.dx * f.dx + q.dy * f.dy);
        const ld j21 = f.dx * q.dx + f.dy * q.dy,
                 j22 = -(q.dx * q.dx + q.dy * q.dy) + rx * q.ddx + ry * q.ddy;
        const ld det = j11 * j22 - j12 * j21;
        if (det == 0) break;
        const ld ds = -(F1 * j22 - j12 * F2) / det, dt = -(j11 * F2 - j21 * F1) / det;
        *s += ds;
        *t += dt;
        if (std::fabs(ds) + std::fabs(dt) < 1e-18L * (1 + std::fabs(*s) + std::fabs(*t))) {
            ok = true;
            break;
        }
    }
    if (!ok || std::fabs(*s - s0) > reach || std::fabs(*t - t0) > reach) {
        *s = s0;
        *t = t0;
        return false;
    }
    return true;
}

/* Newton on f(s) = g(t) (a crossing). */
bool crossing_newton(const Side& A, const Side& B, ld* s, ld* t, ld reach) {
    const ld s0 = *s, t0 = *t;
    for (int it = 0; it < 60; ++it) {
        const Ev f = eval(A, *s), q = eval(B, *t);
        const ld rx = f.x - q.x, ry = f.y - q.y;
        /* [f' -g'] (ds, dt) = -(f - g) */
        const ld det = f.dx * (-q.dy) - (-q.dx) * f.dy;
        if (det == 0) return false;
        const ld ds = -(rx * (-q.dy) - (-q.dx) * ry) / det, dt = -(f.dx * ry - f.dy * rx) / det;
        *s += ds;
        *t += dt;
        if (std::fabs(*s - s0) > reach || std::fabs(*t - t0) > reach) return false;
        if (std::fabs(ds) + std::fabs(dt) < 1e-18L * (1 + std::fabs(*s) + std::fabs(*t))) return true;
    }
    return false;
}

/* Signed distance of p from curve Q at its foot point u: positive outside Q (the foot's outward normal, or
 * the corner's two flank normals at zero speed). */
ld signed_at(const Side& Q, ld u, ld px, ld py) {
    const Ev q = eval(Q, u);
    const ld rx = px - q.x, ry = py - q.y, d = lhypot(rx, ry);
    ld n1x, n1y, n2x, n2y;
    normals_at(Q, u, &n1x, &n1y, &n2x, &n2y);
    const ld side = rx * (n1x + n2x) + ry * (n1y + n2y);
    return side >= 0 ? d : -d;
}

/* Winding number test of p against Q's sample polygon. */
bool inside_polygon(const Side& Q, ld px, ld py) {
    const int N = (int)Q.sx.size();
    int w = 0;
    for (int i = 0; i < N; ++i) {
        const int j = (i + 1) % N;
        const ld ax = Q.sx[(size_t)i], ay = Q.sy[(size_t)i], bx = Q.sx[(size_t)j], by = Q.sy[(size_t)j];
        const ld cr = (bx - ax) * (py - ay) - (px - ax) * (by - ay);
        if (ay <= py) {
            if (by > py && cr > 0) ++w;
        } else if (by <= py && cr < 0) {
            --w;
        }
    }
    return w != 0;
}

/* ------------------------------------------------------------------------------------------------
 * The reference of one pose */

/* Samples of Q within `reach` of every sample of P (flattened lists). */
struct Near {
    std::vector<int> off, idx;
};

void build_near(const Side& P, const Side& Q, ld reach, Near& nr) {
    const int np = (int)P.sx.size(), nq = (int)Q.sx.size();
    double lox = 1e300, loy = 1e300, hix = -1e300, hiy = -1e300;
    for (int j = 0; j < nq; ++j) {
        lox = std::min(lox, Q.fx[(size_t)j]);
        loy = std::min(loy, Q.fy[(size_t)j]);
        hix = std::max(hix, Q.fx[(size_t)j]);
        hiy = std::max(hiy, Q.fy[(size_t)j]);
    }
    const double hcell = std::max((double)reach, 1e-9 * (hix - lox + hiy - loy));
    const double R = (double)reach * (1 + 1e-12);
    const int gx = std::min(4096, (int)((hix - lox) / hcell) + 1),
              gy = std::min(4096, (int)((hiy - loy) / hcell) + 1);
    const double cw = (hix - lox) / gx + 1e-300, chh = (hiy - loy) / gy + 1e-300;
    std::vector<int> start((size_t)(gx * gy + 1), 0), items((size_t)nq);
    auto cell_of = [&](double x, double y, int* cx, int* cy) {
        *cx = std::min(gx - 1, std::max(0, (int)std::floor((x - lox) / cw)));
        *cy = std::min(gy - 1, std::max(0, (int)std::floor((y - loy) / chh)));
    };
    for (int j = 0; j < nq; ++j) {
        int cx, cy;
        cell_of(Q.fx[(size_t)j], Q.fy[(size_t)j], &cx, &cy);
        start[(size_t)(cy * gx + cx) + 1]++;
    }
    for (size_t k = 1; k < start.size(); ++k)
        start[k] += start[k - 1];
    {
        std::vector<int> fill(start.begin(), start.end() - 1);
        for (int j = 0; j < nq; ++j) {
            int cx, cy;
            cell_of(Q.fx[(size_t)j], Q.fy[(size_t)j], &cx, &cy);
            items[(size_t)fill[(size_t)(cy * gx + cx)]++] = j;
        }
    }
    const int rx = (int)std::ceil(R / cw), ry = (int)std::ceil(R / chh);
    nr.off.assign((size_t)np + 1, 0);
    nr.idx.clear();
    std::vector<int> tmp;
    for (int i = 0; i < np; ++i) {
        const double px = P.fx[(size_t)i], py = P.fy[(size_t)i];
        tmp.clear();
        if (px >= lox - R && px <= hix + R && py >= loy - R && py <= hiy + R) {
            int cx, cy;
            cell_of(px, py, &cx, &cy);
            for (int yy = std::max(0, cy - ry); yy <= std::min(gy - 1, cy + ry); ++yy)
                for (int xx = std::max(0, cx - rx); xx <= std::min(gx - 1, cx + rx); ++xx) {
                    const int c = yy * gx + xx;
                    for (int k = start[(size_t)c]; k < start[(size_t)c + 1]; ++k) {
                        const int j = items[(size_t)k];
                        const double dx = Q.fx[(size_t)j] - px, dy = Q.fy[(size_t)j] - py;
                        if (dx * dx + dy * dy <= R * R) tmp.push_back(j);
                    }
                }
            std::sort(tmp.begin(), tmp.end());
        }
        nr.idx.insert(nr.idx.end(), tmp.begin(), tmp.end());
        nr.off[(size_t)i + 1] = (int)nr.idx.size();
    }
}

/* A valley point: for sample i of P, a local minimum over Q's parameter t of the objective. */
struct Node {
    int i;
    ld t, v, d, sig; /* t on Q; objective; distance; signed distance (d-profile: from the foot's side) */
    int prev, next;
};

struct Profile {
    std::vector<Node> nodes;
    std::vector<int> start; /* nodes of sample i: start[i] .. start[i+1]-1 */
};

/* The chains of valley points of P against Q (P plays A's role when p_is_a). */
void build_profile(const Side& P, const Side& Q, const Near& nr, bool band, Profile& pr) {
    const int np = (int)P.sx.size(), nq = (int)Q.sx.size();
    const ld hq = (ld)1 / Q.K;
    pr.nodes.clear();
    pr.start.assign((size_t)np + 1, 0);
    std::vector<ld> vals;
    for (int i = 0; i < np; ++i) {
        pr.start[(size_t)i] = (int)pr.nodes.size();
        const int b = nr.off[(size_t)i], e = nr.off[(size_t)i + 1];
        if (b == e) continue;
        const ld px = P.sx[(size_t)i], py = P.sy[(size_t)i];
        vals.resize((size_t)(e - b));
        for (int k = b; k < e; ++k) {
            const int j = nr.idx[(size_t)k];
            ld v = lhypot(Q.sx[(size_t)j] - px, Q.sy[(size_t)j] - py);
            if (band) v -= lam_at(Q, (ld)j * hq).v;
            vals[(size_t)(k - b)] = v;
        }
        auto value_of = [&](int j, bool* present) {
            const int* lo = nr.idx.data() + b;
            const int* hi = nr.idx.data() + e;
            const int* it = std::lower_bound(lo, hi, j);
            if (it == hi || *it != j) {
                *present = false;
                return (ld)0;
            }
            *present = true;
            return vals[(size_t)(it - lo)];
        };
        const ld lamp = band ? lam_at(P, (ld)i / P.K).v : 0;
        const int first_node = (int)pr.nodes.size();
        for (int k = b; k < e; ++k) {
            const int j = nr.idx[(size_t)k];
            const ld v = vals[(size_t)(k - b)];
            bool pm, pp;
            const int jm = (j - 1 + nq) % nq, jp = (j + 1) % nq;
            const ld vm = value_of(jm, &pm), vp = value_of(jp, &pp);
            /* strict order on (value, index) so that a plateau gives one minimum */
            if (pm && (vm < v || (vm == v && jm < j))) continue;
            if (pp && (vp < v || (vp == v && jp < j))) continue;
            ld t, vv, dd;
            min_1d(Q, band, px, py, (ld)(j - 1) * hq, (ld)(j + 1) * hq, &t, &vv, &dd);
            t = wrap_u(t, Q.n);
            bool dup = false;
            for (int m = first_node; m < (int)pr.nodes.size(); ++m) {
                ld dt = std::fabs(pr.nodes[(size_t)m].t - t);
                dt = std::min(dt, (ld)Q.n - dt);
                if (dt < 1e-9L) dup = true;
            }
            if (dup) continue;
            Node nd;
            nd.i = i;
            nd.t = t;
            nd.v = vv - lamp;
            nd.d = dd;
            nd.sig = band ? 0 : signed_at(Q, t, px, py);
            nd.prev = nd.next = -1;
            pr.nodes.push_back(nd);
        }
    }
    pr.start[(size_t)np] = (int)pr.nodes.size();
    /* links: mutual nearest valley points of consecutive samples, close on Q */
    const ld lim = 2 * (P.h + Q.h);
    // The valley point of sample k nearest on Q to node `from` (the last of equals), -1 if none within lim.
    auto nearest = [&](int from, int k) {
        const Ev q = eval(Q, pr.nodes[(size_t)from].t);
        int best = -1;
        ld bd = lim;
        for (int c = pr.start[(size_t)k]; c < pr.start[(size_t)k + 1]; ++c) {
            const Ev qc = eval(Q, pr.nodes[(size_t)c].t);
            const ld dd = lhypot(q.x - qc.x, q.y - qc.y);
            if (dd <= bd) {
                bd = dd;
                best = c;
            }
        }
        return best;
    };
    for (int i = 0; i < np; ++i) {
        const int i2 = (i + 1) % np;
        for (int a = pr.start[(size_t)i]; a < pr.start[(size_t)i + 1]; ++a) {
            const int best = nearest(a, i2);
            if (best < 0 || pr.nodes[(size_t)best].prev >= 0) continue;
            /* mutual: a is also the nearest of i's points to best */
            if (nearest(best, i) != a) continue;
            pr.nodes[(size_t)a].next = best;
            pr.nodes[(size_t)best].prev = a;
        }
    }
}

bool chain_less(const Profile& pr, int a, int b) {
    const ld va = pr.nodes[(size_t)a].v, vb = pr.nodes[(size_t)b].v;
    return va < vb || (va == vb && a < b);
}

bool chain_min(const Profile& pr, int a) {
    const Node& n = pr.nodes[(size_t)a];
    if (n.prev >= 0 && chain_less(pr, n.prev, a)) return false;
    if (n.next >= 0 && chain_less(pr, n.next, a)) return false;
    return true;
}

int chain_descend(const Profile& pr, int a) {
    for (int guard = 0; guard < 1000000; ++guard) {
        const Node& n = pr.nodes[(size_t)a];
        int best = a;
        if (n.prev >= 0 && chain_less(pr, n.prev, best)) best = n.prev;
        if (n.next >= 0 && chain_less(pr, n.next, best)) best = n.next;
        if (best == a) return a;
        a = best;
    }
    return a;
}

/* A reference minimum of the objective. */
struct RMin {
    ld s, t, f, d, phi;
    ld ax, ay, bx, by, nx, ny; /* points, unit normal A -> B */
    bool facing, attached, from_b_only;
    int seed_lo, seed_hi; /* A-profile nodes around it (-1: none) */
};

/* An overlap region: its deepest pair. */
struct Region {
    ld depth;
    ld s, t; /* the deepest pair */
    ld ax, ay, bx, by;
    ld s_lo, s_hi, t_lo, t_hi; /* parameter ranges (unwrapped: lo <= hi, may exceed [0, n)) */
};

struct Crossing {
    ld s, t, x, y;
};

struct Reference {
    Side A, B;
    ld size = 0, reach = 0;
    Near nab, nba;
    Profile dA, dB; /* distance profiles (also give the signed distances) */
    Profile fA, fB; /* band profiles (empty for smooth pairs: the distance ones serve) */
    bool banded = false;
    std::vector<Crossing> xs;
    std::vector<Region> regions;
    bool contained = false; /* one curve inside the other, no crossing */
    int anomalies = 0;      /* crossings without an overlap region, etc. */
    ld min_d = 0;           /* smallest distance between the curves (over valley points) */
    /* minima per objective: [0] band φ, [1] distance */
    std::vector<RMin> mins[2];
    std::vector<int> node_min[2]; /* A-profile chain minimum node -> index into mins (or -1) */
};

bool in_cyclic(ld x, ld lo, ld hi, int n) {
    const ld nn = (ld)n;
    for (int k = -1; k <= 1; ++k) {
        const ld y = x + k * nn;
        if (y >= lo && y <= hi) return true;
    }
    return false;
}

bool ranges_meet(ld a0, ld a1, ld b0, ld b1, int n) {
    const ld nn = (ld)n;
    for (int k = -1; k <= 1; ++k)
        if (a0 <= b1 + k * nn && b0 + k * nn <= a1) return true;
    return false;
}

/* The run of negative signed distance around sample i of a distance profile: sample range (unwrapped). */
void negative_run(const Profile& pr, int N, int i, int* lo, int* hi) {
    auto sig_of = [&](int k) {
        const int kk = wrap_i(k, N);
        ld best = 1e30L, bd = 1e30L;
        for (int a = pr.start[(size_t)kk]; a < pr.start[(size_t)kk + 1]; ++a)
            if (pr.nodes[(size_t)a].d < bd) {
                bd = pr.nodes[(size_t)a].d;
                best = pr.nodes[(size_t)a].sig;
            }
        return best;
    };
    *lo = *hi = i;
    if (!(sig_of(i) < 0)) return;
    while (*lo > i - N && sig_of(*lo - 1) < 0)
        --*lo;
    while (*hi < i + N && sig_of(*hi + 1) < 0)
        ++*hi;
}

void compute_minima(Reference& R, int which, ld margin, ld delta);

/* Everything of one pose that does not depend on the rule. */
void build_reference(Reference& R, const Body& a, rugo_transform xa, const Body& b, rugo_transform xb,
                     ld margin, ld delta, int K) {
    place_side(R.A, a, xa, K);
    place_side(R.B, b, xb, K);
    R.size = std::min(a.size, b.size);
    R.banded = !a.lam.empty() || !b.lam.empty();
    R.reach = margin + delta + R.A.lam_max + R.B.lam_max + 3 * (R.A.h + R.B.h);
    build_near(R.A, R.B, R.reach, R.nab);
    build_near(R.B, R.A, R.reach, R.nba);
    build_profile(R.A, R.B, R.nab, false, R.dA);
    build_profile(R.B, R.A, R.nba, false, R.dB);
    if (R.banded) {
        build_profile(R.A, R.B, R.nab, true, R.fA);
        build_profile(R.B, R.A, R.nba, true, R.fB);
    } else {
        R.fA.nodes.clear();
        R.fB.nodes.clear();
    }
    const int NA = (int)R.A.sx.size(), NB = (int)R.B.sx.size();
    R.min_d = 1e30L;
    for (const Node& n : R.dA.nodes)
        R.min_d = std::min(R.min_d, n.d);
    for (const Node& n : R.dB.nodes)
        R.min_d = std::min(R.min_d, n.d);
    /* crossings of the sample polylines, refined */
    R.xs.clear();
    R.anomalies = 0;
    const ld hx = R.A.h + R.B.h;
    for (int i = 0; i < NA; ++i) {
        const int i2 = (i + 1) % NA;
        for (int k = R.nab.off[(size_t)i]; k < R.nab.off[(size_t)i + 1]; ++k) {
            const int j = R.nab.idx[(size_t)k], j2 = (j + 1) % NB;
            const ld ax = R.A.sx[(size_t)i], ay = R.A.sy[(size_t)i], bx = R.A.sx[(size_t)i2],
                     by = R.A.sy[(size_t)i2];
            const ld cx = R.B.sx[(size_t)j], cy = R.B.sy[(size_t)j], dx = R.B.sx[(size_t)j2],
                     dy = R.B.sy[(size_t)j2];
            if (lhypot(cx - ax, cy - ay) > hx) continue;
            const ld ux = bx - ax, uy = by - ay, vx = dx - cx, vy = dy - cy;
            const ld den = ux * vy - uy * vx;
            if (den == 0) continue;
            const ld p = ((cx - ax) * vy - (cy - ay) * vx) / den, q = ((cx - ax) * uy - (cy - ay) * ux) / den;
            if (p < 0 || p >= 1 || q < 0 || q >= 1) continue;
            ld s = ((ld)i + p) / R.A.K, t = ((ld)j + q) / R.B.K;
            if (!crossing_newton(R.A, R.B, &s, &t, 2.0L / K)) {
                s = ((ld)i + p) / R.A.K;
                t = ((ld)j + q) / R.B.K;
            }
            s = wrap_u(s, R.A.n);
            t = wrap_u(t, R.B.n);
            bool dup = false;
            for (const Crossing& c : R.xs) {
                ld ds = std::fabs(c.s - s), dt = std::fabs(c.t - t);
                ds = std::min(ds, (ld)R.A.n - ds);
                dt = std::min(dt, (ld)R.B.n - dt);
                if (ds < 1e-9L && dt < 1e-9L) dup = true;
            }
            if (!dup) {
                const Ev e = eval(R.A, s);
                R.xs.push_back({s, t, e.x, e.y});
            }
        }
    }
    /* overlap candidates: local minima of the signed distance along the chains of both sides, refined to
     * stationary pairs of the distance; negative ones are deepest pairs of overlap regions */
    struct Cand {
        ld depth, s, t, s_lo, s_hi, t_lo, t_hi;
    };
    std::vector<Cand> cands;
    for (int side = 0; side < 2; ++side) {
        const Profile& pr = side == 0 ? R.dA : R.dB;
        const Side& P = side == 0 ? R.A : R.B;
        const Side& Q = side == 0 ? R.B : R.A;
        const Profile& other = side == 0 ? R.dB : R.dA;
        const int NP = (int)P.sx.size(), NQ = (int)Q.sx.size();
        for (int na = 0; na < (int)pr.nodes.size(); ++na) {
            const Node& n = pr.nodes[(size_t)na];
            if (!(n.sig < P.h + Q.h)) continue;
            /* the nearest branch only, and a local minimum of the signed distance along its chain */
            bool nearest = true;
            for (int c = pr.start[(size_t)n.i]; c < pr.start[(size_t)n.i + 1]; ++c)
                if (pr.nodes[(size_t)c].d < n.d) nearest = false;
            if (!nearest) continue;
            if (n.prev >= 0 && pr.nodes[(size_t)n.prev].sig < n.sig) continue;
            if (n.next >= 0 && pr.nodes[(size_t)n.next].sig <= n.sig) continue;
            ld s = (ld)n.i / P.K, t = n.t;
            if (side == 0) {
                stationary(R.A, R.B, &s, &t, 3.0L / K);
            } else {
                ld ss = t, tt = s;
                stationary(R.A, R.B, &ss, &tt, 3.0L / K);
                s = tt;
                t = ss;
            }
            /* s on P, t on Q again */
            const Ev pe = eval(P, s);
            const ld sg = signed_at(Q, t, pe.x, pe.y);
            if (!(sg < 0)) continue;
            Cand c;
            c.depth = -sg;
            int lo, hi, lo2, hi2;
            negative_run(pr, NP, wrap_i(std::lround(s * P.K), NP), &lo, &hi);
            negative_run(other, NQ, wrap_i(std::lround(t * Q.K), NQ), &lo2, &hi2);
            ld ps_lo = (ld)(lo - 1) / P.K, ps_hi = (ld)(hi + 1) / P.K, qt_lo = (ld)(lo2 - 1) / Q.K,
               qt_hi = (ld)(hi2 + 1) / Q.K;
            /* keep the deepest point inside its ranges */
            const ld sw = wrap_u(s, P.n), tw = wrap_u(t, Q.n);
            if (!in_cyclic(sw, ps_lo, ps_hi, P.n)) {
                ps_lo = sw - 1.0L / P.K;
                ps_hi = sw + 1.0L / P.K;
            }
            if (!in_cyclic(tw, qt_lo, qt_hi, Q.n)) {
                qt_lo = tw - 1.0L / Q.K;
                qt_hi = tw + 1.0L / Q.K;
            }
            if (side == 0) {
                c.s = sw;
                c.t = tw;
                c.s_lo = ps_lo;
                c.s_hi = ps_hi;
                c.t_lo = qt_lo;
                c.t_hi = qt_hi;
            } else {
                c.s = tw;
                c.t = sw;
                c.s_lo = qt_lo;
                c.s_hi = qt_hi;
                c.t_lo = ps_lo;
                c.t_hi = ps_hi;
            }
            cands.push_back(c);
        }
    }
    /* group candidates whose ranges meet on both curves */
    std::vector<int> grp(cands.size());
    for (size_t k = 0; k < cands.size(); ++k)
        grp[k] = (int)k;
    auto root = [&](int x) {
        while (grp[(size_t)x] != x)
            x = grp[(size_t)x] = grp[(size_t)grp[(size_t)x]];
        return x;
    };
    for (size_t p = 0; p < cands.size(); ++p)
        for (size_t q = p + 1; q < cands.size(); ++q)
            if (ranges_meet(cands[p].s_lo, cands[p].s_hi, cands[q].s_lo, cands[q].s_hi, R.A.n) &&
                ranges_meet(cands[p].t_lo, cands[p].t_hi, cands[q].t_lo, cands[q].t_hi, R.B.n))
                grp[(size_t)root((int)p)] = root((int)q);
    R.regions.clear();
    std::vector<int> reg_of(cands.size(), -1);
    for (size_t k = 0; k < cands.size(); ++k) {
        const int r = root((int)k);
        if (reg_of[(size_t)r] < 0) {
            reg_of[(size_t)r] = (int)R.regions.size();
            Region g;
            g.depth = -1;
            g.s_lo = cands[k].s_lo;
            g.s_hi = cands[k].s_hi;
            g.t_lo = cands[k].t_lo;
            g.t_hi = cands[k].t_hi;
            R.regions.push_back(g);
        }
        Region& g = R.regions[(size_t)reg_of[(size_t)r]];
        if (cands[k].depth > g.depth) {
            g.depth = cands[k].depth;
            g.s = cands[k].s;
            g.t = cands[k].t;
        }
        /* widen the ranges (same unwrapped frame as the region's) */
        auto widen = [](ld* lo, ld* hi, ld x0, ld x1, int n) {
            const ld nn = (ld)n;
            ld bestk = 0, bd = 1e30L;
            for (int kk = -1; kk <= 1; ++kk) {
                const ld c = (x0 + x1) / 2 + kk * nn, m = (*lo + *hi) / 2;
                if (std::fabs(c - m) < bd) {
                    bd = std::fabs(c - m);
                    bestk = kk * nn;
                }
            }
            *lo = std::min(*lo, x0 + bestk);
            *hi = std::max(*hi, x1 + bestk);
        };
        widen(&g.s_lo, &g.s_hi, cands[k].s_lo, cands[k].s_hi, R.A.n);
        widen(&g.t_lo, &g.t_hi, cands[k].t_lo, cands[k].t_hi, R.B.n);
    }
    for (Region& g : R.regions) {
        const Ev ea = eval(R.A, g.s), eb = eval(R.B, g.t);
        g.ax = ea.x;
        g.ay = ea.y;
        g.bx = eb.x;
        g.by = eb.y;
    }
    /* crossings that no region explains */
    for (const Crossing& c : R.xs) {
        bool found = false;
        for (const Region& g : R.regions)
            if (in_cyclic(c.s, g.s_lo - 2.0L / K, g.s_hi + 2.0L / K, R.A.n)) found = true;
        if (!found) ++R.anomalies;
    }
    /* containment: a sample far from the other curve (else the one of largest |signed distance|) */
    R.contained = false;
    if (R.regions.empty() && R.xs.empty()) {
        for (int side = 0; side < 2 && !R.contained; ++side) {
            const Side& P = side == 0 ? R.B : R.A;
            const Side& Q = side == 0 ? R.A : R.B;
            const Near& nr = side == 0 ? R.nba : R.nab;
            const Profile& pr = side == 0 ? R.dB : R.dA;
            int far = -1;
            for (int i = 0; i < (int)P.sx.size() && far < 0; ++i)
                if (nr.off[(size_t)i] == nr.off[(size_t)i + 1]) far = i;
            if (far >= 0) {
                R.contained = inside_polygon(Q, P.sx[(size_t)far], P.sy[(size_t)far]);
            } else {
                ld best = -1, sg = 0;
                for (const Node& n : pr.nodes)
                    if (std::fabs(n.sig) > best) {
                        best = std::fabs(n.sig);
                        sg = n.sig;
                    }
                R.contained = sg < 0;
            }
        }
    }
    compute_minima(R, 1, margin, delta);
    if (R.banded)
        compute_minima(R, 0, margin, delta);
    else {
        R.mins[0] = R.mins[1];
        R.node_min[0] = R.node_min[1];
    }
}

/* The minima of objective `which` (0: band φ, 1: distance) from both sides' chains. */
void compute_minima(Reference& R, int which, ld margin, ld delta) {
    const bool band = which == 0;
    const Profile& pa = band ? R.fA : R.dA;
    const Profile& pb = band ? R.fB : R.dB;
    std::vector<RMin>& out = R.mins[which];
    out.clear();
    R.node_min[which].assign(pa.nodes.size(), -1);
    const ld cand = margin + delta + (R.A.h + R.B.h);
    const ld dtiny = 1e-14L * R.size;
    for (int side = 0; side < 2; ++side) {
        const Profile& pr = side == 0 ? pa : pb;
        const Side& P = side == 0 ? R.A : R.B;
        const Side& Q = side == 0 ? R.B : R.A;
        for (int a = 0; a < (int)pr.nodes.size(); ++a) {
            if (!chain_min(pr, a)) continue;
            const Node& n = pr.nodes[(size_t)a];
            const ld sp = (ld)n.i / P.K;
            /* candidate: the node's φ within reach of the threshold */
            const ld phin = band ? n.v : n.d - lam_at(P, sp).v - lam_at(Q, n.t).v;
            if (phin > cand) continue;
            MinRes r = side == 0 ? minimize2(R.A, R.B, band, sp, n.t, dtiny)
                                 : minimize2(R.A, R.B, band, n.t, sp, dtiny);
            r.s = wrap_u(r.s, R.A.n);
            r.t = wrap_u(r.t, R.B.n);
            int found = -1;
            for (int m = 0; m < (int)out.size(); ++m) {
                ld ds = std::fabs(out[(size_t)m].s - r.s), dt = std::fabs(out[(size_t)m].t - r.t);
                ds = std::min(ds, (ld)R.A.n - ds);
                dt = std::min(dt, (ld)R.B.n - dt);
                if (ds < 1e-8L && dt < 1e-8L) found = m;
                /* the same pair of world points (a corner of coincident control points is one point over
                 * a range of parameters, where the minimizer stops anywhere) */
                const Ev qa = eval(R.A, r.s), qb = eval(R.B, r.t);
                const RMin& o2 = out[(size_t)m];
                if (lhypot(qa.x - o2.ax, qa.y - o2.ay) < 1e-9L * R.size &&
                    lhypot(qb.x - o2.bx, qb.y - o2.by) < 1e-9L * R.size)
                    found = m;
            }
            if (found < 0) {
                RMin m;
                m.s = r.s;
                m.t = r.t;
                m.f = r.f;
                m.d = r.d;
                /* a minimum at d ~ 0 is a crossing (the distance has a cone there, not a minimum) when the
                 * sampled curves cross next to it; a true gap far below the sampling is a minimum */
                bool at_crossing = false;
                for (const Crossing& x : R.xs) {
                    ld ds = std::fabs(x.s - r.s), dt = std::fabs(x.t - r.t);
                    ds = std::min(ds, (ld)R.A.n - ds);
                    dt = std::min(dt, (ld)R.B.n - dt);
                    if (ds < 2.0L / R.A.K && dt < 2.0L / R.B.K) at_crossing = true;
                }
                for (const Region& g : R.regions)
                    if (in_cyclic(r.s, g.s_lo, g.s_hi, R.A.n) && in_cyclic(r.t, g.t_lo, g.t_hi, R.B.n))
                        at_crossing = true;
                m.attached = r.attached || (r.d < 1e-9L * R.size && at_crossing);
                m.from_b_only = side == 1;
                const Ev ea = eval(R.A, r.s), eb = eval(R.B, r.t);
                m.ax = ea.x;
                m.ay = ea.y;
                m.bx = eb.x;
                m.by = eb.y;
                m.phi = phi_at(R.A, R.B, r.s, r.t);
                const ld vx = eb.x - ea.x, vy = eb.y - ea.y, dd = lhypot(vx, vy);
                ld n1x, n1y, n2x, n2y, m1x, m1y, m2x, m2y;
                normals_at(R.A, r.s, &n1x, &n1y, &n2x, &n2y);
                normals_at(R.B, r.t, &m1x, &m1y, &m2x, &m2y);
                if (dd > 1e-7L * R.size) {
                    m.nx = vx / dd;
                    m.ny = vy / dd;
                } else {
                    const ld l = lhypot(n1x + n2x, n1y + n2y);
                    m.nx = (n1x + n2x) / l;
                    m.ny = (n1y + n2y) / l;
                }
                const ld tol = 1e-9L * dd;
                const bool fa = vx * n1x + vy * n1y > -tol || vx * n2x + vy * n2y > -tol;
                const bool fb = -vx * m1x - vy * m1y > -tol || -vx * m2x - vy * m2y > -tol;
                m.facing = dd < 1e-12L * R.size || (fa && fb);
                m.seed_lo = m.seed_hi = -1;
                out.push_back(m);
                found = (int)out.size() - 1;
            } else if (side == 0) {
                out[(size_t)found].from_b_only = false;
            }
            if (side == 0) R.node_min[which][(size_t)a] = found;
        }
    }
    /* seeds: A-profile nodes at the samples around each minimum, on its branch */
    const int NA = (int)R.A.sx.size();
    for (RMin& m : out) {
        const Ev eb = eval(R.B, m.t);
        const long i0 = (long)std::floor(m.s * R.A.K);
        for (int side = 0; side < 2; ++side) {
            const int i = wrap_i(i0 + side, NA);
            int best = -1;
            ld bd = 2 * (R.A.h + R.B.h);
            for (int a = pa.start[(size_t)i]; a < pa.start[(size_t)i + 1]; ++a) {
                const Ev q = eval(R.B, pa.nodes[(size_t)a].t);
                const ld dd = lhypot(q.x - eb.x, q.y - eb.y);
                if (dd <= bd) {
                    bd = dd;
                    best = a;
                }
            }
            if (side == 0)
                m.seed_lo = best;
            else
                m.seed_hi = best;
        }
    }
}

/* The stretch of a minimum at `level`: the A-profile nodes reached from its seeds along the chain while
 * the objective stays <= level (the seeds themselves always). Returns the node list. */
void stretch(const Profile& pr, const RMin& m, ld level, std::vector<int>& out) {
    out.clear();
    const int cap = (int)pr.nodes.size();
    for (int seed : {m.seed_lo, m.seed_hi}) {
        if (seed < 0) continue;
        out.push_back(seed);
        for (int dir = 0; dir < 2; ++dir) {
            int a = seed;
            for (int guard = 0; guard < cap; ++guard) {
                const int nx = dir == 0 ? pr.nodes[(size_t)a].prev : pr.nodes[(size_t)a].next;
                if (nx < 0 || nx == seed || pr.nodes[(size_t)nx].v > level) break;
                out.push_back(nx);
                a = nx;
            }
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

/* ------------------------------------------------------------------------------------------------
 * Comparing one query's answer with the reference */

enum { RULE_BAND = 0, RULE_THESIS = 1 };

struct Outcome {
    int ref_state = 0, rep_state = 0;
    bool state_bad = false, state_tolerated = false;
    int required = 0, missed = 0, contacts = 0, spurious = 0, via_stretch = 0, near_overlap = 0;
    int regions = 0, region_missed = 0, shallow_no_contact = 0, unmatched_overlap = 0, anomalies = 0;
    int normal_over = 0, by_descent = 0;
    std::vector<double> sep_err, normal_err; /* per contact of a minimum: |reported - reference|, angle */
    double max_excess = 0, max_oncurve = 0, max_lam = 0, max_region_err = 0, max_region_normal = 0;
    double time_ns = 0;
    int status = 0;
    std::string first; /* the first thing found wrong */
};

double angle_between(ld ax, ld ay, ld bx, ld by) {
    const ld la = lhypot(ax, ay), lb = lhypot(bx, by);
    if (la == 0 || lb == 0) return kPi;
    const ld c = (ax * bx + ay * by) / (la * lb), s = (ax * by - ay * bx) / (la * lb);
    return (double)std::fabs(std::atan2(s, c));
}

/* The A-profile node under a contact: the sample nearest s_c, the valley point nearest B(t_c). */
int node_of(const Reference& R, const Profile& pr, ld s, ld t) {
    const int NA = (int)R.A.sx.size();
    const Ev eb = eval(R.B, t);
    const long i0 = std::lround(s * R.A.K);
    int best = -1;
    ld bd = 2 * (R.A.h + R.B.h);
    for (long di : {0L, -1L, 1L}) {
        const int i = wrap_i(i0 + di, NA);
        for (int a = pr.start[(size_t)i]; a < pr.start[(size_t)i + 1]; ++a) {
            const Ev q = eval(R.B, pr.nodes[(size_t)a].t);
            const ld dd = lhypot(q.x - eb.x, q.y - eb.y) + (di != 0 ? R.A.h : 0);
            if (dd <= bd) {
                bd = dd;
                best = a;
            }
        }
        if (best >= 0) break;
    }
    return best;
}

/* Whether the reported pair (cs, ct) lies on minimum m's stretch at `level`: walking along A from m.s to
 * cs (the shorter way), the objective minimised over B's parameter near the line from m.t to ct stays
 * <= level. The chains of valley points break on exactly parallel flats (every sample has the same
 * value), where this walk does not. */
bool connected(const Reference& R, bool band, const RMin& m, ld cs, ld ct, ld level) {
    ld ds = cs - m.s, dt = ct - m.t;
    const ld na = (ld)R.A.n, nb = (ld)R.B.n;
    ds -= na * std::round(ds / na);
    dt -= nb * std::round(dt / nb);
    const int N = std::max(8, (int)std::ceil(std::fabs(ds) * R.A.K * 4));
    const ld w = 2.0L / R.B.K + 2 * std::fabs(dt) / N;
    for (int k = 1; k < N; ++k) {
        const ld sa = m.s + ds * k / N, tg = m.t + dt * k / N;
        const Ev e = eval(R.A, sa);
        ld t = 0, v = 0, d = 0;
        min_1d(R.B, band, e.x, e.y, tg - w, tg + w, &t, &v, &d);
        if (band) v -= lam_at(R.A, sa).v;
        if (v > level) return false;
    }
    return true;
}

/* A query at a resolution may answer on a coarser level of either shape (its certified error within its
 * share of δ; docs/contacts.md, "Resolution"): the contact's parameters are then the coarse curve's. Level
 * j's parameter u is the finest level's u 2^(J - j) (each level halves the control points), which is what
 * the reference, built on the finest curves, reads. */
void to_finest_parameters(const rugo_shape* a, const rugo_shape* b, rugo_contact* cs, int count) {
    for (int k = 0; k < count; ++k) {
        rugo_contact& c = cs[k];
        const int ja = rugo_shape_finest_level(a) - c.level_a, jb = rugo_shape_finest_level(b) - c.level_b;
        if (ja > 0) {
            const double u = std::ldexp((double)c.segment_a + c.t_a, ja);
            c.segment_a = (int)std::floor(u);
            c.t_a = u - std::floor(u);
        }
        if (jb > 0) {
            const double u = std::ldexp((double)c.segment_b + c.t_b, jb);
            c.segment_b = (int)std::floor(u);
            c.t_b = u - std::floor(u);
        }
    }
}

void evaluate(const Reference& R, int rule, ld delta, ld margin, const rugo_contact* cs, int count,
              int rep_state, Outcome& o) {
    const ld eps = 1e-12L * R.size;
    const bool band = rule == RULE_BAND;
    const int which = band ? 0 : 1;
    const std::vector<RMin>& mins = R.mins[which];
    const Profile& pr = (band && R.banded) ? R.fA : R.dA;
    const std::vector<int>& nmap = R.node_min[which];
    const int K = R.A.K;
    auto note = [&](const char* fmt, double a, double b) {
        if (!o.first.empty()) return;
        char buf[256];
        std::snprintf(buf, sizeof buf, fmt, a, b);
        o.first = buf;
    };
    o.anomalies = R.anomalies;
    /* the reference state */
    ld max_depth = 0;
    for (const Region& g : R.regions)
        max_depth = std::max(max_depth, g.depth);
    bool strict = false, loose = false, any = false;
    for (const RMin& m : mins) {
        if (!m.facing || m.attached) continue;
        any |= m.phi <= margin;
        strict |= m.phi <= margin - delta - eps;
        loose |= m.phi <= margin + delta + eps;
    }
    ld min_d = R.min_d;
    for (const RMin& m : R.mins[1])
        min_d = std::min(min_d, m.d);
    const bool crossing = !R.regions.empty() || R.contained || !R.xs.empty();
    o.ref_state = crossing ? RUGO_STATE_INTERSECTING : any ? RUGO_STATE_CONTACT : RUGO_STATE_APART;
    o.rep_state = rep_state;
    if (o.rep_state != o.ref_state) {
        bool ok = false;
        if (o.ref_state == RUGO_STATE_INTERSECTING)
            ok = o.rep_state == RUGO_STATE_CONTACT && !R.contained && max_depth <= delta + eps;
        else if (o.rep_state == RUGO_STATE_INTERSECTING)
            ok = min_d <= delta + eps;
        else if (o.ref_state == RUGO_STATE_CONTACT)
            ok = !strict;
        else
            ok = loose;
        if (ok)
            o.state_tolerated = true;
        else {
            o.state_bad = true;
            note("state: reference %.0f, reported %.0f", (double)o.ref_state, (double)o.rep_state);
        }
    }
    if (o.rep_state == RUGO_STATE_INTERSECTING && count == 0) {
        o.state_bad = true;
        note("INTERSECTING without a contact (%g %g)", 0.0, 0.0);
    }
    /* the reported contacts */
    std::vector<char> covered(mins.size(), 0);
    std::vector<int> cnode((size_t)count, -1);
    std::vector<std::vector<int>> reg_contacts(R.regions.size());
    for (int k = 0; k < count; ++k) {
        const rugo_contact& c = cs[k];
        const ld s = (ld)c.segment_a + (ld)c.t_a, t = (ld)c.segment_b + (ld)c.t_b;
        const Ev ea = eval(R.A, s), eb = eval(R.B, t);
        o.max_oncurve =
            std::max(o.max_oncurve, (double)std::max(lhypot((ld)c.point_a.x - ea.x, (ld)c.point_a.y - ea.y),
                                                     lhypot((ld)c.point_b.x - eb.x, (ld)c.point_b.y - eb.y)));
        o.max_lam = std::max(o.max_lam, (double)std::max(std::fabs((ld)c.tolerance_a - lam_at(R.A, s).v),
                                                         std::fabs((ld)c.tolerance_b - lam_at(R.B, t).v)));
        const ld obj_rep = band ? (ld)c.separation - (ld)c.tolerance_a - (ld)c.tolerance_b : (ld)c.separation;
        if ((ld)c.separation < -eps) {
            int g = -1;
            for (int r = 0; r < (int)R.regions.size() && g < 0; ++r) {
                const Region& rg = R.regions[(size_t)r];
                if (in_cyclic(wrap_u(s, R.A.n), rg.s_lo - 2.0L / K, rg.s_hi + 2.0L / K, R.A.n) &&
                    in_cyclic(wrap_u(t, R.B.n), rg.t_lo - 2.0L / K, rg.t_hi + 2.0L / K, R.B.n))
                    g = r;
            }
            if (g >= 0) {
                reg_contacts[(size_t)g].push_back(k);
                continue;
            }
            if (R.contained) continue; /* the way out of a containment */
            ++o.unmatched_overlap;
        }
        ++o.contacts;
        const int nd = node_of(R, pr, s, t);
        cnode[(size_t)k] = nd;
        int mi = -1;
        if (nd >= 0) {
            const int cm = chain_descend(pr, nd);
            mi = nmap[(size_t)cm];
        }
        if (mi < 0) {
            /* near an overlap region, a touching below the resolution is allowed */
            bool near_region = false;
            for (const Region& rg : R.regions)
                if (in_cyclic(wrap_u(s, R.A.n), rg.s_lo - 2.0L / K, rg.s_hi + 2.0L / K, R.A.n))
                    near_region = true;
            if (near_region && std::fabs((ld)c.separation) <= delta + eps) continue;
            ++o.spurious;
            note("spurious contact: no minimum under it (separation %.3g, s %.6g)", c.separation, (double)s);
            continue;
        }
        const RMin& m = mins[(size_t)mi];
        ld e = obj_rep - m.f;
        /* the chains at K samples per segment can step over a minimum shallower than the sampling (nearly
         * parallel rough stretches): the local minimum reached by descending the true objective from the
         * reported pair itself is the one it stands for when that is closer in value */
        if (std::fabs(e) > delta + eps) {
            MinRes r = minimize2(R.A, R.B, band, s, t, 1e-14L * R.size);
            if (!r.attached && r.f < 1e29L && std::fabs(obj_rep - r.f) < std::fabs(e)) {
                e = obj_rep - r.f;
                ++o.by_descent;
            }
        }
        const ld obj_true = band ? phi_at(R.A, R.B, s, t) : lhypot(ea.x - eb.x, ea.y - eb.y);
        o.sep_err.push_back((double)std::fabs(e));
        o.max_excess = std::max(o.max_excess, (double)(obj_true - (obj_rep - e)));
        const double na = angle_between(c.normal.x, c.normal.y, m.nx, m.ny);
        o.normal_err.push_back(na);
        if (std::fabs(e) > delta + eps)
            note("separation error %.3g (minimum at s = %.9g)", (double)e, (double)m.s);
        if (!m.facing) {
            ++o.spurious;
            note("spurious contact: its minimum does not face (separation %.3g, s %.6g)", c.separation,
                 (double)m.s);
        } else if (m.phi > margin + delta + eps && !m.attached) {
            ++o.spurious;
            note("spurious contact: its minimum is above the threshold by %.3g (s %.6g)",
                 (double)(m.phi - margin), (double)m.s);
        }
        covered[(size_t)mi] = 1;
        /* the normal's bound from δ: the directions along the minimum's δ-stretch, and the tilt an
         * off-valley pair within δ allows */
        if (na > 1e-6) {
            std::vector<int> st;
            stretch(pr, m, m.f + delta + eps, st);
            double spread = 0;
            for (int a : st) {
                const Node& n = pr.nodes[(size_t)a];
                const Ev pa = eval(R.A, (ld)n.i / K), pb = eval(R.B, n.t);
                const ld vx = pb.x - pa.x, vy = pb.y - pa.y;
                if (lhypot(vx, vy) > 1e-7L * R.size)
                    spread = std::max(spread, angle_between(vx, vy, m.nx, m.ny));
            }
            const double tilt = (double)std::asin(std::min((ld)1, 2 * delta / std::max(m.d, (ld)1e-300)));
            if (na > spread + tilt + 1e-6) ++o.normal_over;
        }
    }
    /* overlap regions */
    for (size_t r = 0; r < R.regions.size(); ++r) {
        const Region& g = R.regions[r];
        ++o.regions;
        const auto& rc = reg_contacts[r];
        if (g.depth > delta + eps) {
            if (rc.empty()) {
                ++o.region_missed;
                note("overlap region %.3g deep without a contact (s %.6g)", (double)g.depth, (double)g.s);
                continue;
            }
            int best = rc[0];
            for (int k : rc)
                if (cs[k].separation < cs[best].separation) best = k;
            const double err = (double)std::fabs((ld)cs[best].separation + g.depth);
            o.max_region_err = std::max(o.max_region_err, err);
            o.max_region_normal =
                std::max(o.max_region_normal,
                         angle_between(cs[best].normal.x, cs[best].normal.y, g.ax - g.bx, g.ay - g.by));
            if (err > delta + eps) note("overlap depth error %.3g (depth %.3g)", err, (double)g.depth);
        } else {
            bool any_c = !rc.empty();
            for (int k = 0; k < count && !any_c; ++k) {
                const ld s = (ld)cs[k].segment_a + (ld)cs[k].t_a;
                if (in_cyclic(wrap_u(s, R.A.n), g.s_lo - 3.0L / K, g.s_hi + 3.0L / K, R.A.n)) any_c = true;
            }
            if (!any_c) {
                ++o.shallow_no_contact;
                note("shallow overlap %.3g deep without a contact (s %.6g)", (double)g.depth, (double)g.s);
            }
        }
    }
    if (R.contained && count == 0) note("containment without a contact (%g %g)", 0.0, 0.0);
    /* missed minima */
    std::vector<int> st;
    for (size_t mi = 0; mi < mins.size(); ++mi) {
        const RMin& m = mins[mi];
        if (!m.facing || m.attached || m.phi > margin - delta - eps) continue;
        bool near_overlap = R.contained;
        for (const Region& g : R.regions)
            if (in_cyclic(m.s, g.s_lo - 4.0L / K - R.reach / R.A.speed_ref,
                          g.s_hi + 4.0L / K + R.reach / R.A.speed_ref, R.A.n))
                near_overlap = true;
        if (near_overlap) {
            ++o.near_overlap;
            continue;
        }
        ++o.required;
        if (covered[mi]) continue;
        stretch(pr, m, m.f + delta + eps, st);
        bool ok = false;
        for (int k = 0; k < count && !ok; ++k)
            if (cnode[(size_t)k] >= 0 && std::binary_search(st.begin(), st.end(), cnode[(size_t)k]))
                ok = true;
        /* a contact at the minimum's own points (to 1e-7 of the size, the location a corner's minimum
         * has: the distance is flat in the parameter where the speed vanishes) */
        const ld near = std::max(delta, 1e-7L * R.size);
        for (int k = 0; k < count && !ok; ++k)
            ok = lhypot((ld)cs[k].point_a.x - m.ax, (ld)cs[k].point_a.y - m.ay) <= near &&
                 lhypot((ld)cs[k].point_b.x - m.bx, (ld)cs[k].point_b.y - m.by) <= near;
        for (int k = 0; k < count && !ok; ++k)
            ok = connected(R, band, m, (ld)cs[k].segment_a + (ld)cs[k].t_a,
                           (ld)cs[k].segment_b + (ld)cs[k].t_b, m.f + delta + eps);
        if (ok) {
            ++o.via_stretch;
            continue;
        }
        ++o.missed;
        note("missed minimum: objective %.17g at s = %.9g", (double)m.f, (double)m.s);
    }
}

/* ------------------------------------------------------------------------------------------------
 * Bodies, kinds, poses */

enum { MODE_GENERIC = 0, MODE_BOWL = 1, MODE_FLAT = 2 };

struct PairSpec {
    int a, b;
    double corner_a, corner_b;
    int mode;
};

struct Kind {
    std::string name;
    std::vector<PairSpec> pairs;
    bool rough;
};

struct World {
    std::vector<Body> bodies;
    std::vector<Side> local; /* each body at the identity, for placing poses */
    std::vector<Kind> kinds;
    std::vector<double> bowl_gap; /* per body: R_bay - r_disc for bowls (else 0) */
};

bool build_world(World& w) {
    std::vector<Body>& b = w.bodies;
    b.resize(17);
    bool ok = true;
    ok &= make_body(b[0], "ellipse_a", ellipse_pts(64, 0.5, 0.3), nullptr);
    ok &= make_body(b[1], "ellipse_b", ellipse_pts(64, 0.35, 0.25), nullptr);
    ok &= make_body(b[2], "star", star_pts(128, 0.5, 0.3, 5), nullptr);
    ok &= make_body(b[3], "bean", bean_pts(128, 0.45), nullptr);
    ok &= make_body(b[4], "ellipse_small", ellipse_pts(64, 0.15, 0.1), nullptr);
    {
        std::vector<rugo_vec2> p = rough_pts(ellipse_pts(32, 0.5, 0.4), 0.004, 11);
        std::vector<double> lam(p.size());
        rugo_tolerances_preset(RUGO_PRESET_TIPO_2, 5, (int)lam.size(), lam.data());
        for (double& v : lam)
            v *= 0.06;
        ok &= !p.empty() && make_body(b[5], "rough_tipo2", p, &lam);
    }
    {
        std::vector<rugo_vec2> p = rough_pts(bean_pts(32, 0.45), 0.004, 12);
        std::vector<double> lam(p.size());
        rugo_tolerances_preset(RUGO_PRESET_TIPO_5, 0, (int)lam.size(), lam.data());
        for (double& v : lam)
            v *= 0.06;
        ok &= !p.empty() && make_body(b[6], "rough_tipo5", p, &lam);
    }
    ok &= make_body(b[7], "rbox_a", rbox_pts(64, 1.0, 0.6), nullptr);
    ok &= make_body(b[8], "rbox_b", rbox_pts(64, 0.5, 0.5), nullptr);
    ok &= make_body(
        b[9], "triangle_334",
        sharp_pts({rugo_v2(-0.5, -0.35), rugo_v2(0.5, -0.35), rugo_v2(0.05, 0.45)}, {3, 3, 4}, 18), nullptr);
    ok &=
        make_body(b[10], "box_4pt",
                  sharp_pts({rugo_v2(-0.3, -0.2), rugo_v2(0.3, -0.2), rugo_v2(0.3, 0.2), rugo_v2(-0.3, 0.2)},
                            {4, 4, 4, 4}, 12),
                  nullptr);
    ok &= make_body(
        b[11], "box_3pt",
        sharp_pts({rugo_v2(-0.25, -0.25), rugo_v2(0.25, -0.25), rugo_v2(0.25, 0.25), rugo_v2(-0.25, 0.25)},
                  {3, 3, 3, 3}, 13),
        nullptr);
    ok &= make_body(b[12], "disc", disc_pts(64, 0.4), nullptr);
    ok &= make_body(b[13], "bowl_1e-2", bowl_pts(128, 0.4 * (1 + 1e-2)), nullptr);
    ok &= make_body(b[14], "bowl_1e-3", bowl_pts(128, 0.4 * (1 + 1e-3)), nullptr);
    ok &= make_body(b[15], "bowl_1e-4", bowl_pts(128, 0.4 * (1 + 1e-4)), nullptr);
    ok &= make_body(b[16], "slab", rbox_pts(128, 2.0, 0.4), nullptr);
    if (!ok) return false;
    w.bowl_gap.assign(b.size(), 0.0);
    w.bowl_gap[13] = 0.4e-2;
    w.bowl_gap[14] = 0.4e-3;
    w.bowl_gap[15] = 0.4e-4;
    w.local.resize(b.size());
    for (size_t i = 0; i < b.size(); ++i)
        place_side(w.local[i], b[i], rugo_identity_transform(), 4);
    w.kinds = {
        {"ellipse",
         {{0, 1, 0, 0, MODE_GENERIC}, {1, 0, 0, 0, MODE_GENERIC}, {0, 0, 0, 0, MODE_GENERIC}},
         false},
        {"concave",
         {{2, 4, 0, 0, MODE_GENERIC},
          {3, 4, 0, 0, MODE_GENERIC},
          {2, 1, 0, 0, MODE_GENERIC},
          {3, 2, 0, 0, MODE_GENERIC}},
         false},
        {"rough", {{5, 6, 0, 0, MODE_GENERIC}, {6, 5, 0, 0, MODE_GENERIC}, {5, 1, 0, 0, MODE_GENERIC}}, true},
        {"straight",
         {{7, 8, 0, 0, MODE_GENERIC}, {8, 1, 0, 0, MODE_GENERIC}, {7, 7, 0, 0, MODE_GENERIC}},
         false},
        {"corners",
         {{9, 8, 0.6, 0, MODE_GENERIC},
          {10, 1, 0.6, 0, MODE_GENERIC},
          {11, 9, 0.5, 0.5, MODE_GENERIC},
          {9, 10, 0.5, 0.5, MODE_GENERIC}},
         false},
        {"conforming",
         {{13, 12, 0, 0, MODE_BOWL},
          {14, 12, 0, 0, MODE_BOWL},
          {15, 12, 0, 0, MODE_BOWL},
          {16, 8, 0, 0, MODE_FLAT},
          {16, 11, 0, 0, MODE_FLAT}},
         false},
    };
    return true;
}

void destroy_world(World& w) {
    for (Body& b : w.bodies)
        rugo_shape_destroy(b.shape);
}

/* The pose's gap as placing measures it: the smallest band-adjusted distance (facing minima; overlap
 * regions count as their depth plus the bands) or, for a distance target, the curves' signed distance. */
ld pose_measure(const Reference& R, bool dist) {
    ld m = 1e30L;
    if (R.contained) return -1e30L;
    for (const Region& g : R.regions)
        m = std::min(m, dist ? -g.depth : -g.depth - lam_at(R.A, g.s).v - lam_at(R.B, g.t).v);
    for (const RMin& x : R.mins[dist ? 1 : 0])
        if (x.facing && !x.attached) m = std::min(m, dist ? x.d : x.f);
    if (m == 1e30L && !R.xs.empty()) m = 0;
    return m;
}

rugo_rot rot_of(double a) { return rugo_rot_from_angle(a); }

/* A pose of pair p near the target gap g (see the top of this file), placed by the reference alone. */
bool place_pose(const World& w, const PairSpec& ps, Rng& rng, ld delta, ld margin, ld g, bool dist,
                rugo_transform* xa, rugo_transform* xb, ld* achieved) {
    const Body& A = w.bodies[(size_t)ps.a];
    const Body& B = w.bodies[(size_t)ps.b];
    const Side& la = w.local[(size_t)ps.a];
    const Side& lb = w.local[(size_t)ps.b];
    for (int attempt = 0; attempt < 40; ++attempt) {
        const double tha = rng.range(-kPi, kPi);
        *xa = rugo_make_transform(rng.range(-1, 1), rng.range(-1, 1), tha);
        double thb = 0;
        rugo_vec2 n = rugo_v2(0, 1); /* world direction from A to B along which B is moved */
        rugo_vec2 pb = rugo_v2(0, 0);
        if (ps.mode == MODE_BOWL) {
            const double gap = w.bowl_gap[(size_t)ps.a];
            n = rugo_rotate(xa->q, rugo_v2(0, 1));
            const rugo_vec2 c = rugo_v2(rng.range(-3, 3) * gap, -gap + (double)g);
            pb = rugo_transform_point(*xa, c);
            thb = rng.range(-kPi, kPi);
        } else if (ps.mode == MODE_FLAT) {
            const double cs[4] = {0, 0.3, 3, 30};
            const double gs = delta > 0 ? (double)delta : 1e-6 * std::min(A.size, B.size);
            const double psi = rng.range(-1, 1) * cs[rng.below(4)] * gs / 0.5;
            n = rugo_rotate(xa->q, rugo_v2(0, 1));
            const rugo_vec2 c = rugo_v2(rng.range(-0.6, 0.6), 0.2 + 0.25 * std::cos(psi) + (double)g);
            pb = rugo_transform_point(*xa, c);
            thb = tha + psi;
        } else {
            /* a point of A and its outward direction (a corner's: inside its normal cone) */
            ld ua = 0, ub = 0;
            rugo_vec2 na, nb;
            auto pick = [&](const Body& body, const Side& side, double pc, ld* u, rugo_vec2* nrm) {
                std::vector<const Corner*> cv;
                for (const Corner& k : body.corners)
                    if (k.convex) cv.push_back(&k);
                if (!cv.empty() && rng.uni() < pc) {
                    const Corner& k = *cv[(size_t)rng.below((int)cv.size())];
                    const double wv = rng.range(0.1, 0.9);
                    const double x = (1 - wv) * k.n_in.x + wv * k.n_out.x,
                                 y = (1 - wv) * k.n_in.y + wv * k.n_out.y;
                    const double l = std::hypot(x, y);
                    *u = k.u;
                    *nrm = rugo_v2(x / l, y / l);
                    return true;
                }
                for (int tries = 0; tries < 100; ++tries) {
                    *u = (ld)rng.range(0, side.n);
                    const Ev e = eval(side, *u);
                    const ld sp = lhypot(e.dx, e.dy);
                    if (sp < 1e-3L * side.speed_ref) continue;
                    *nrm = rugo_v2((double)(e.dy / sp), (double)(-e.dx / sp));
                    return true;
                }
                return false;
            };
            if (!pick(A, la, ps.corner_a, &ua, &na) || !pick(B, lb, ps.corner_b, &ub, &nb)) continue;
            n = rugo_rotate(xa->q, na);
            thb = std::atan2(-n.y, -n.x) - std::atan2(nb.y, nb.x);
            const Ev ea = eval(la, ua), eb = eval(lb, ub);
            const rugo_vec2 pa = rugo_transform_point(*xa, rugo_v2((double)ea.x, (double)ea.y));
            const double lam = dist ? 0.0 : (double)(lam_at(la, ua).v + lam_at(lb, ub).v);
            const rugo_vec2 qb = rugo_rotate(rot_of(thb), rugo_v2((double)eb.x, (double)eb.y));
            pb = rugo_v2(pa.x + ((double)g + lam) * n.x - qb.x, pa.y + ((double)g + lam) * n.y - qb.y);
        }
        xb->p = pb;
        xb->q = rot_of(thb);
        /* move B along n until the measured gap is the target */
        const double gs = delta > 0 ? (double)delta : 1e-6 * std::min(A.size, B.size);
        Reference R;
        ld m = 0;
        bool good = false;
        for (int it = 0; it < 8; ++it) {
            build_reference(R, A, *xa, B, *xb, margin, delta, 8);
            m = pose_measure(R, dist);
            if (m < -1.0L || m > 1e29L) break;
            if (std::fabs(m - g) <= 0.02L * gs) {
                good = true;
                break;
            }
            const double sh = (double)(g - m);
            xb->p = rugo_v2(xb->p.x + sh * n.x, xb->p.y + sh * n.y);
        }
        if (!good) continue;
        *achieved = m;
        return true;
    }
    return false;
}

/* ------------------------------------------------------------------------------------------------
 * Runs */

struct Cell {
    std::string kind;
    double delta_rel = 0;
    int rule = 0;
    long poses = 0, failed_place = 0, required = 0, missed = 0, contacts = 0, spurious = 0, via_stretch = 0;
    long regions = 0, region_missed = 0, shallow_no_contact = 0, state_bad = 0, state_tolerated = 0,
         normal_over = 0;
    long unmatched_overlap = 0, anomalies = 0, near_overlap = 0, errors_over = 0, status_errors = 0,
         by_descent = 0;
    std::vector<double> sep, nrm, times;
    double max_excess = 0, max_oncurve = 0, max_lam = 0, max_region_err = 0, max_region_normal = 0;
    double delta_abs_min = 1e300; /* δ of the smallest shape of the kind (for units) */
};

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t k = std::min(v.size() - 1, (size_t)std::ceil(q * (double)(v.size() - 1)));
    return v[k];
}

double vmax(const std::vector<double>& v) {
    double m = 0;
    for (double x : v)
        m = sample_max(m, x);
    return m;
}

struct Options {
    bool quick = false, verbose = false;
    int poses = 0; /* per kind and δ */
    uint64_t seed = 20;
    std::string kind, out = "out/bench_accuracy";
    double only_delta = -1;
    int only_rule = -1;
    int ref_check = 0;  /* poses re-run with K = 48 */
    int only_pose = -1; /* --pose P: only that pose (the earlier ones are placed, not queried) */
    int K = 16;
};

const double kDeltas[3] = {1e-3, 1e-5, 0.0};

/* ------------------------------------------------------------------------------------------------
 * The reference's own checks */

/* Control points of a disc, mirror-symmetric about the x axis bit for bit (c_{n-k} = (x_k, -y_k)), so
 * that the joint at c_0 lies exactly on the axis and faces a mirrored disc along it. */
std::vector<rugo_vec2> sym_disc(int n, double rho) {
    std::vector<rugo_vec2> p((size_t)n);
    p[0] = rugo_v2(rho, 0);
    p[(size_t)n / 2] = rugo_v2(-rho, 0);
    for (int k = 1; k < n / 2; ++k) {
        const double th = 2.0 * kPi * k / n;
        p[(size_t)k] = rugo_v2(rho * std::cos(th), rho * std::sin(th));
        p[(size_t)(n - k)] = rugo_v2(rho * std::cos(th), -rho * std::sin(th));
    }
    return p;
}

struct SelfCheck {
    double worst_known = 0, worst_normal = 0, worst_lam = 0, worst_lam_d1 = 0, worst_eval = 0;
    bool ok = true;
};

void check_known(const char* what, ld got, ld want, double tol, SelfCheck& sc) {
    const double e = (double)std::fabs(got - want);
    sc.worst_known = sample_max(sc.worst_known, e);
    if (!(e <= tol)) {
        sc.ok = false;
        std::printf("  reference check FAILED: %s: %.20Lg, known %.20Lg (error %.3g)\n", what, got, want, e);
    }
}

SelfCheck reference_checks(const World& w, int K) {
    SelfCheck sc;
    /* λ: our Lagrange cubics against rugo_tolerance_at; derivatives against differences */
    Rng rng(7);
    for (const Body& b : w.bodies) {
        if (b.lam.empty()) continue;
        Side s;
        place_side(s, b, rugo_identity_transform(), 2);
        const int n = (int)b.lam.size();
        double lmax = 0;
        for (double v : b.lam)
            lmax = std::max(lmax, v);
        for (int k = 0; k < 4000; ++k) {
            const int seg = rng.below(n);
            double t = rng.uni();
            if (k % 8 == 0) t = 0.5;
            if (k % 8 == 1) t = 0.0;
            const double ref = rugo_tolerance_at(b.lam.data(), n, seg, t, 0.0);
            const ld mine = lam_at(s, (ld)seg + (ld)t).v;
            sc.worst_lam = sample_max(sc.worst_lam, (double)std::fabs(mine - (ld)ref) / lmax);
            if (t > 0.02 && t < 0.48) {
                const ld hh = 1e-7L, u = (ld)seg + (ld)t;
                const ld fd = (lam_at(s, u + hh).v - lam_at(s, u - hh).v) / (2 * hh);
                const Lam l = lam_at(s, u);
                if (l.v > 1e-3L * lmax)
                    sc.worst_lam_d1 = sample_max(sc.worst_lam_d1, (double)std::fabs(fd - l.d1) / lmax);
            }
        }
    }
    if (!(sc.worst_lam <= 1e-15)) sc.ok = false;
    if (!(sc.worst_lam_d1 <= 1e-6)) sc.ok = false;
    /* points: our evaluation against rugo_contour_point */
    for (const Body& b : w.bodies) {
        Side s;
        place_side(s, b, rugo_identity_transform(), 2);
        const rugo_contour c = {b.pts.data(), (int)b.pts.size()};
        for (int k = 0; k < 500; ++k) {
            const int seg = rng.below(c.count);
            const double t = rng.uni();
            const rugo_vec2 p = rugo_contour_point(c, seg, t);
            const Ev e = eval(s, (ld)seg + (ld)t);
            sc.worst_eval = sample_max(sc.worst_eval, (double)lhypot(e.x - (ld)p.x, e.y - (ld)p.y) / b.size);
        }
    }
    if (!(sc.worst_eval <= 1e-15)) sc.ok = false;
    /* known answers */
    const int n = 64;
    const double rho = 0.4 * 6.0 / (4.0 + 2.0 * std::cos(2.0 * kPi / n));
    const std::vector<rugo_vec2> dp = sym_disc(n, rho);
    Body da, db, dla, dlb, slab;
    std::vector<double> l1((size_t)n, 0.01), l2((size_t)n, 0.02);
    bool ok = make_body(da, "disc", dp, nullptr) && make_body(db, "disc", dp, nullptr) &&
              make_body(dla, "disc_l01", dp, &l1) && make_body(dlb, "disc_l02", dp, &l2) &&
              make_body(slab, "slab", rbox_pts(128, 2.0, 0.4), nullptr);
    if (!ok) {
        sc.ok = false;
        return sc;
    }
    const ld xj = ((ld)dp[(size_t)n - 1].x + 4 * (ld)dp[0].x + (ld)dp[1].x) / 6; /* the joint at c_0 */
    rugo_transform xa = rugo_identity_transform(), xb;
    xb.q.c = -1.0;
    xb.q.s = 0.0;
    const double size = da.size;
    for (double g : {1e-3, 1e-7, 1e-12, -1e-4, -1e-9}) {
        xb.p = rugo_v2((double)(2 * xj) + g, 0.0);
        const ld want = (ld)xb.p.x - 2 * xj;
        for (int banded = 0; banded < 2; ++banded) {
            Reference R;
            build_reference(R, banded ? dla : da, xa, banded ? dlb : db, xb, 0.01, 0, K);
            char what[160];
            if (g > 0) {
                ld best = 1e30L, bn = 0;
                for (const RMin& m : R.mins[banded ? 0 : 1])
                    if (m.facing && !m.attached && m.f < best) {
                        best = m.f;
                        bn = (ld)angle_between(m.nx, m.ny, 1, 0);
                    }
                std::snprintf(what, sizeof what, "two discs %s gap %g: smallest %s",
                              banded ? "(bands 0.01, 0.02)" : "", g, banded ? "φ" : "distance");
                check_known(what, best, banded ? want - 0.03L : want, 1e-15 * size, sc);
                sc.worst_normal = sample_max(sc.worst_normal, (double)bn);
                if (!(bn <= 1e-12)) sc.ok = false;
                if (!R.regions.empty() || !R.xs.empty()) {
                    sc.ok = false;
                    std::printf("  reference check FAILED: two discs gap %g: overlap found\n", g);
                }
            } else {
                std::snprintf(what, sizeof what, "two discs overlap %g: depth", -g);
                if (R.regions.size() != 1) {
                    sc.ok = false;
                    std::printf("  reference check FAILED: two discs overlap %g: %zu regions\n", -g,
                                R.regions.size());
                } else {
                    check_known(what, R.regions[0].depth, -want, 1e-15 * size, sc);
                    sc.worst_normal =
                        sample_max(sc.worst_normal, angle_between(R.regions[0].ax - R.regions[0].bx,
                                                                  R.regions[0].ay - R.regions[0].by, 1, 0));
                }
                if (g == -1e-4 && R.xs.size() != 2) {
                    sc.ok = false;
                    std::printf("  reference check FAILED: two discs overlap 1e-4: %zu crossings\n",
                                R.xs.size());
                }
            }
        }
    }
    /* a disc over a straight face: the disc's joint at c_0 turned to point down */
    xb.q.c = 0.0;
    xb.q.s = -1.0;
    for (double g : {1e-3, 1e-6, 1e-10}) {
        xb.p = rugo_v2(0.1, 0.2 + (double)xj + g);
        const ld want = (ld)xb.p.y - xj - (ld)0.2;
        Reference R;
        build_reference(R, slab, xa, da, xb, 0.01, 0, K);
        ld best = 1e30L, bn = 0;
        for (const RMin& m : R.mins[1])
            if (m.facing && !m.attached && m.f < best) {
                best = m.f;
                bn = (ld)angle_between(m.nx, m.ny, 0, 1);
            }
        char what[120];
        std::snprintf(what, sizeof what, "disc over a line, gap %g", g);
        check_known(what, best, want, 1e-15 * size, sc);
        sc.worst_normal = sample_max(sc.worst_normal, (double)bn);
        if (!(bn <= 1e-12)) sc.ok = false;
    }
    for (Body* b : {&da, &db, &dla, &dlb, &slab})
        rugo_shape_destroy(b->shape);
    return sc;
}

/* The reference at K against the reference at 3K on one pose: the minima within the threshold and the
 * overlap depths, matched both ways. Returns the largest difference (length units); counts unmatched. */
double compare_densities(const Body& a, rugo_transform xa, const Body& b, rugo_transform xb, ld margin,
                         ld delta, int K, int* unmatched) {
    Reference r1, r2;
    build_reference(r1, a, xa, b, xb, margin, delta, K);
    build_reference(r2, a, xa, b, xb, margin, delta, 3 * K);
    double worst = 0;
    for (int which = 0; which < 2; ++which)
        for (int dir = 0; dir < 2; ++dir) {
            const std::vector<RMin>& p = dir == 0 ? r1.mins[which] : r2.mins[which];
            const std::vector<RMin>& q = dir == 0 ? r2.mins[which] : r1.mins[which];
            for (const RMin& m : p) {
                if (!m.facing || m.attached || m.phi > margin) continue;
                ld best = 1e30L;
                for (const RMin& x : q) {
                    if (std::fabs(x.s - m.s) > 2.0L / K && std::fabs(x.s - m.s) < (ld)r1.A.n - 2.0L / K)
                        continue;
                    best = std::min(best, std::fabs(x.f - m.f));
                }
                if (best > 1e-12L * r1.size) {
                    /* a flat stretch may put its minimum anywhere on it: compare with the stretch's level */
                    ++*unmatched;
                } else {
                    worst = std::max(worst, (double)best);
                }
            }
        }
    for (int dir = 0; dir < 2; ++dir) {
        const std::vector<Region>& p = dir == 0 ? r1.regions : r2.regions;
        const std::vector<Region>& q = dir == 0 ? r2.regions : r1.regions;
        for (const Region& g : p) {
            ld best = 1e30L;
            for (const Region& x : q)
                best = std::min(best, std::fabs(x.depth - g.depth));
            if (best > 1e-12L * r1.size)
                ++*unmatched;
            else
                worst = std::max(worst, (double)best);
        }
    }
    return worst;
}

/* ------------------------------------------------------------------------------------------------ */

#ifdef RUGO_BENCH_WITH_BOX2D
/* ------------------------------------------------------------------------------------------------
 * Box2D 2.4.1 polygon compounds of the same outlines (polygon_baseline.hpp, shared with bench_queries),
 * on the δ = 1e-3 poses, against the same reference: the curve distance (Box2D has no bands), overlap
 * depths as negative separations. A Box2D contact counts for every reference minimum or overlap region
 * whose point on A lies within W = 0.05 × size of its point on A; per minimum the smallest separation
 * of those contacts counts (what a solver sees). Missed: a minimum with d <= margin / 2 (or an
 * overlap region deeper than 1e-3 × size) without a contact; spurious: a contact with separation <=
 * margin / 2 that belongs to none while the curves are farther apart than margin + 0.01 × size there. */

const int kPolyM[4] = {64, 256, 1024, 4096};

struct BoxCell {
    std::string kind;
    int m = 0;
    long poses = 0, targets = 0, missed = 0, spurious = 0, unbuilt = 0;
    std::vector<double> sep, nrm, times;
};

void box2d_pose(const Reference& R, ld margin, const polygon_baseline::PolyBody& PA, rugo_transform xa,
                const polygon_baseline::PolyBody& PB, rugo_transform xb, BoxCell& cell) {
    using namespace polygon_baseline;
    const b2Transform ba = b2xf(xa), bb = b2xf(xb);
    std::vector<std::pair<int, int>> pairs;
    std::vector<Cnt> got;
    double best = 1e300;
    for (int rep = 0; rep < 3; ++rep) {
        got.clear();
        int points = 0;
        const double t0 = now_ns();
        box2d_pairs(PA, ba, PB, bb, pairs);
        for (const auto& pr : pairs)
            box2d_collide(PA, ba, PB, bb, pr.first, pr.second, &got, &points);
        best = std::min(best, now_ns() - t0);
    }
    cell.times.push_back(best);
    ++cell.poses;
    /* targets: facing minima of the distance within the margin, and overlap regions */
    struct Target {
        ld ax, ay, v, nx, ny;
        bool required;
        double best_s = 1e300, best_n = 0;
        bool hit = false;
    };
    std::vector<Target> tg;
    for (const RMin& m : R.mins[1])
        if (m.facing && !m.attached && m.d <= margin + 0.01L * R.size)
            tg.push_back({m.ax, m.ay, m.d, m.nx, m.ny, m.d <= margin / 2});
    for (const Region& g : R.regions) {
        const ld l = lhypot(g.ax - g.bx, g.ay - g.by);
        tg.push_back({g.ax, g.ay, -g.depth, l > 0 ? (g.ax - g.bx) / l : 0, l > 0 ? (g.ay - g.by) / l : 0,
                      g.depth > 1e-3L * R.size});
    }
    const ld W = 0.05L * R.size;
    for (const Cnt& c : got) {
        bool any = false;
        for (Target& t : tg) {
            if (lhypot((ld)c.ax - t.ax, (ld)c.ay - t.ay) > W) continue;
            any = true;
            if (c.s < t.best_s) {
                t.best_s = c.s;
                t.best_n = angle_between(c.nx, c.ny, t.nx, t.ny);
            }
            t.hit = true;
        }
        if (!any && c.s <= (double)(margin / 2)) {
            /* spurious only where the curves are apart beyond the margin there (nearest samples of B to
             * the contact's point on A; the samples are within h of the curve) */
            ld g = 1e30L;
            for (size_t j = 0; j < R.B.sx.size(); ++j)
                g = std::min(g, lhypot(R.B.sx[j] - (ld)c.ax, R.B.sy[j] - (ld)c.ay));
            if (g > margin + R.B.h + 0.01L * R.size) ++cell.spurious;
        }
    }
    for (const Target& t : tg) {
        if (t.required) ++cell.targets;
        if (!t.hit) {
            if (t.required) ++cell.missed;
            continue;
        }
        cell.sep.push_back(std::fabs(t.best_s - (double)t.v) / (double)R.size);
        cell.nrm.push_back(t.best_n);
    }
}
#endif

/* A reproducer's data (--pose): both shapes' finest control points (and λ per segment) as the shapes hold
 * them, the transforms and the query's lengths, all as %a, into OUTDIR/repro.txt. */
void write_repro(const std::string& dir, const Body& A, rugo_transform xa, const Body& B, rugo_transform xb,
                 double delta, double margin) {
    const std::string path = dir + "/repro.txt";
    FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return;
    std::fprintf(
        f, "# rugo_collide_shapes(A, xa, B, xb, query): lod 0, resolution %a, margin %a (rule as given)\n",
        delta, margin);
    std::fprintf(f, "xa %a %a %a %a\nxb %a %a %a %a\n", xa.p.x, xa.p.y, xa.q.c, xa.q.s, xb.p.x, xb.p.y,
                 xb.q.c, xb.q.s);
    for (const Body* b : {&A, &B}) {
        std::fprintf(f, "shape %s %zu points%s\n", b->name.c_str(), b->pts.size(),
                     b->lam.empty() ? "" : " with tolerances");
        for (size_t i = 0; i < b->pts.size(); ++i) {
            std::fprintf(f, "%a %a", b->pts[i].x, b->pts[i].y);
            if (!b->lam.empty()) std::fprintf(f, " %a", b->lam[i]);
            std::fprintf(f, "\n");
        }
    }
    std::fclose(f);
    std::printf("reproducer data: %s\n", path.c_str());
}

const char* state_name(int s) { return s == 0 ? "apart" : s == 1 ? "contact" : "intersecting"; }

int run(const Options& opt) {
    World w;
    if (!build_world(w)) return 2;
    if (sample_mkdir(opt.out.c_str()) != 0) {
        std::fprintf(stderr, "cannot create %s\n", opt.out.c_str());
        return 2;
    }
    std::printf("bench_accuracy: %s run, K = %d samples per segment, seed %llu\n",
                opt.quick ? "quick" : "full", opt.K, (unsigned long long)opt.seed);
    /* the reference's own accuracy */
    const double t0 = now_ns();
    const SelfCheck sc = reference_checks(w, opt.K);
    std::printf("reference checks (%.1f s): known answers (two discs at gaps 1e-3 .. 1e-12 with and without "
                "bands, overlaps 1e-4 "
                "and 1e-9, a disc over a line at 1e-3 .. 1e-10): worst error %.2e (size ~1.1), normal %.2e "
                "rad; λ against "
                "rugo_tolerance_at %.2e of λ_max, λ' against differences %.2e; points against "
                "rugo_contour_point %.2e of the "
                "size: %s\n",
                (now_ns() - t0) * 1e-9, sc.worst_known, sc.worst_normal, sc.worst_lam, sc.worst_lam_d1,
                sc.worst_eval, sc.ok ? "ok" : "FAILED");
    sample_expect("reference known answers and consistency", sc.ok);
    std::vector<Cell> cells;
    auto cell_of = [&](const std::string& kind, double dr, int rule) -> Cell& {
        for (Cell& c : cells)
            if (c.kind == kind && c.delta_rel == dr && c.rule == rule) return c;
        Cell c;
        c.kind = kind;
        c.delta_rel = dr;
        c.rule = rule;
        cells.push_back(c);
        return cells.back();
    };
    const std::string pose_csv = opt.out + "/bench_accuracy_poses.csv";
    FILE* pf = std::fopen(pose_csv.c_str(), "w");
    if (!pf) return 2;
    std::fprintf(pf, "kind,pair_a,pair_b,delta_rel,delta,margin,rule,pose,target,gap,ref_state,rep_state,"
                     "state_flag,required,missed,"
                     "contacts,spurious,max_sep_err,max_excess,max_normal_rad,regions,region_missed,max_"
                     "region_err,time_ns,first_problem,"
                     "xa_px,xa_py,xa_c,xa_s,xb_px,xb_py,xb_c,xb_s\n");
    rugo_collide_context* ctx = nullptr;
    rugo_collide_context_create(nullptr, &ctx);
    std::vector<rugo_contact> buf(1024);
#ifdef RUGO_BENCH_WITH_BOX2D
    /* the polygon compounds of every body at every m (built once; strip pieces where star-shaped) */
    std::vector<std::vector<polygon_baseline::PolyBody>> polys(w.bodies.size());
    const int n_m = opt.quick ? 2 : 4;
    for (size_t i = 0; i < w.bodies.size(); ++i) {
        polys[i].resize((size_t)n_m);
        for (int k = 0; k < n_m; ++k)
            polygon_baseline::build_poly(w.bodies[i].pts, kPolyM[k], true, polys[i][(size_t)k]);
    }
    std::vector<BoxCell> bcells;
    auto bcell_of = [&](const std::string& kind, int m) -> BoxCell& {
        for (BoxCell& c : bcells)
            if (c.kind == kind && c.m == m) return c;
        BoxCell c;
        c.kind = kind;
        c.m = m;
        bcells.push_back(c);
        return bcells.back();
    };
#endif
    long ref_checked = 0;
    int ref_unmatched = 0;
    double ref_worst = 0;
    const double run_start = now_ns();
    for (size_t ki = 0; ki < w.kinds.size(); ++ki) {
        const Kind& kind = w.kinds[ki];
        if (!opt.kind.empty() && opt.kind != kind.name) continue;
        for (int di = 0; di < 3; ++di) {
            if (opt.only_delta >= 0 && opt.only_delta != kDeltas[di]) continue;
            Rng rng(opt.seed * 1000003ull + ki * 101ull + (uint64_t)di);
            const double cell_start = now_ns();
            for (int p = 0; p < opt.poses; ++p) {
                const PairSpec& ps = kind.pairs[(size_t)(p % (int)kind.pairs.size())];
                const Body& A = w.bodies[(size_t)ps.a];
                const Body& B = w.bodies[(size_t)ps.b];
                const double msize = std::min(A.size, B.size);
                const double delta = kDeltas[di] * msize;
                const double gs = delta > 0 ? delta : 1e-6 * msize;
                const double margin = 20 * gs;
                bool dist = false;
                double g = rng.uni() < 0.8 ? rng.range(-2 * gs, 10 * gs) : rng.range(10 * gs, 20 * gs);
                if (kind.rough && rng.uni() < 1.0 / 3.0) {
                    dist = true;
                    g = rng.range(-2 * gs, 10 * gs);
                }
                rugo_transform xa, xb;
                ld achieved = 0;
                if (!place_pose(w, ps, rng, delta, margin, g, dist, &xa, &xb, &achieved)) {
                    for (int rule = 0; rule < 2; ++rule)
                        cell_of(kind.name, kDeltas[di], rule).failed_place++;
                    continue;
                }
                if (opt.only_pose >= 0 && p != opt.only_pose) continue;
                if (opt.only_pose >= 0) write_repro(opt.out, A, xa, B, xb, delta, margin);
                Reference R;
                build_reference(R, A, xa, B, xb, margin, delta, opt.K);
                if (opt.ref_check > 0 && p < opt.ref_check) {
                    int um = 0;
                    ref_worst =
                        std::max(ref_worst, compare_densities(A, xa, B, xb, margin, delta, opt.K, &um));
                    ref_unmatched += um;
                    ++ref_checked;
                    if (um > 0 && opt.verbose)
                        std::printf("  K check: %s pose %d delta %g: %d unmatched\n", kind.name.c_str(), p,
                                    kDeltas[di], um);
                }
#ifdef RUGO_BENCH_WITH_BOX2D
                if (kDeltas[di] == 1e-3)
                    for (int k = 0; k < n_m; ++k) {
                        BoxCell& bc = bcell_of(kind.name, kPolyM[k]);
                        const polygon_baseline::PolyBody& PA = polys[(size_t)ps.a][(size_t)k];
                        const polygon_baseline::PolyBody& PB = polys[(size_t)ps.b][(size_t)k];
                        if (!PA.ok || !PB.ok) {
                            ++bc.unbuilt;
                            continue;
                        }
                        box2d_pose(R, margin, PA, xa, PB, xb, bc);
                    }
#endif
                for (int rule = 0; rule < 2; ++rule) {
                    if (opt.only_rule >= 0 && rule != opt.only_rule) continue;
                    Cell& cell = cell_of(kind.name, kDeltas[di], rule);
                    rugo_contact_query q = rugo_default_contact_query();
                    q.resolution = delta;
                    q.contact_rule = rule == RULE_BAND ? RUGO_CONTACT_BAND_ADJUSTED : RUGO_CONTACT_THESIS;
                    q.lod = 0;
                    q.margin = margin;
                    rugo_contact_output out = rugo_contact_output_of(buf.data(), (int)buf.size());
                    double best = 1e300;
                    rugo_status st = RUGO_OK;
                    for (int rep = 0; rep < 3; ++rep) {
                        out = rugo_contact_output_of(buf.data(), (int)buf.size());
                        const double ts = now_ns();
                        st = rugo_collide_shapes(A.shape, xa, B.shape, xb, &q, ctx, &out);
                        const double te = now_ns() - ts;
                        best = std::min(best, te);
                        if (te > 2e6) break;
                    }
                    Outcome o;
                    o.time_ns = best;
                    if (st != RUGO_OK) {
                        ++cell.status_errors;
                        o.first = std::string("query error: ") + rugo_status_string(st);
                    }
                    to_finest_parameters(A.shape, B.shape, buf.data(), out.count);
                    evaluate(R, rule, delta, margin, buf.data(), out.count, out.state, o);
                    if (out.stats.contacts_found > out.capacity && o.first.empty())
                        o.first = "contacts beyond capacity";
                    const double unit = delta > 0 ? delta : msize;
                    ++cell.poses;
                    cell.required += o.required;
                    cell.missed += o.missed;
                    cell.via_stretch += o.via_stretch;
                    cell.near_overlap += o.near_overlap;
                    cell.contacts += o.contacts;
                    cell.spurious += o.spurious;
                    cell.regions += o.regions;
                    cell.region_missed += o.region_missed;
                    cell.shallow_no_contact += o.shallow_no_contact;
                    cell.state_bad += o.state_bad;
                    cell.state_tolerated += o.state_tolerated;
                    cell.normal_over += o.normal_over;
                    cell.by_descent += o.by_descent;
                    cell.unmatched_overlap += o.unmatched_overlap;
                    cell.anomalies += o.anomalies > 0;
                    double mse = 0;
                    for (double e : o.sep_err) {
                        cell.sep.push_back(e / unit);
                        mse = std::max(mse, e);
                        if (e > delta + 1e-12 * msize) ++cell.errors_over;
                    }
                    for (double a : o.normal_err)
                        cell.nrm.push_back(a);
                    cell.times.push_back(o.time_ns);
                    cell.max_excess = sample_max(cell.max_excess, o.max_excess / unit);
                    cell.max_oncurve = sample_max(cell.max_oncurve, o.max_oncurve / unit);
                    cell.max_lam = sample_max(cell.max_lam, o.max_lam / msize);
                    cell.max_region_err = sample_max(cell.max_region_err, o.max_region_err / unit);
                    cell.max_region_normal = sample_max(cell.max_region_normal, o.max_region_normal);
                    const char* flag = o.state_bad ? "bad" : o.state_tolerated ? "tolerated" : "same";
                    std::string first = o.first;
                    for (char& ch : first)
                        if (ch == ',') ch = ';';
                    std::fprintf(pf,
                                 "%s,%s,%s,%g,%a,%a,%s,%d,%s,%a,%s,%s,%s,%d,%d,%d,%d,%.3e,%.3e,%.3e,%d,%d,%."
                                 "3e,%.0f,%s,%a,%a,%a,%a,%a,%a,%a,%a\n",
                                 kind.name.c_str(), A.name.c_str(), B.name.c_str(), kDeltas[di], delta,
                                 margin, rule == 0 ? "band" : "thesis", p, dist ? "dist" : "phi",
                                 (double)achieved, state_name(o.ref_state), state_name(o.rep_state), flag,
                                 o.required, o.missed, o.contacts, o.spurious, mse, o.max_excess,
                                 vmax(o.normal_err), o.regions, o.region_missed, o.max_region_err, o.time_ns,
                                 first.c_str(), xa.p.x, xa.p.y, xa.q.c, xa.q.s, xb.p.x, xb.p.y, xb.q.c,
                                 xb.q.s);
                    if (opt.verbose && !o.first.empty())
                        std::printf("  %s %s/%s delta %g %s pose %d: %s\n", kind.name.c_str(), A.name.c_str(),
                                    B.name.c_str(), kDeltas[di], rule == 0 ? "band" : "thesis", p,
                                    o.first.c_str());
                    if (opt.verbose && !o.first.empty()) {
                        std::printf("    state %s (reference %s); xa %a %a %a %a xb %a %a %a %a\n",
                                    state_name(out.state), state_name(o.ref_state), xa.p.x, xa.p.y, xa.q.c,
                                    xa.q.s, xb.p.x, xb.p.y, xb.q.c, xb.q.s);
                        for (int k = 0; k < out.count; ++k)
                            std::printf("    contact %d: s %.9f t %.9f separation %.9g band-adjusted %.9g "
                                        "region %d\n",
                                        k, buf[(size_t)k].segment_a + buf[(size_t)k].t_a,
                                        buf[(size_t)k].segment_b + buf[(size_t)k].t_b,
                                        buf[(size_t)k].separation,
                                        buf[(size_t)k].separation - buf[(size_t)k].tolerance_a -
                                            buf[(size_t)k].tolerance_b,
                                        buf[(size_t)k].region);
                        const int which = (rule == RULE_BAND) ? 0 : 1;
                        for (const RMin& m : R.mins[which])
                            if (m.facing && !m.attached && m.phi <= margin)
                                std::printf("    reference minimum: s %.9f t %.9f objective %.9g\n",
                                            (double)m.s, (double)m.t, (double)m.f);
                    }
                }
            }
            std::fprintf(stderr, "  %s delta %g: %d poses in %.1f s\n", kind.name.c_str(), kDeltas[di],
                         opt.poses, (now_ns() - cell_start) * 1e-9);
        }
    }
    std::fclose(pf);
    rugo_collide_context_destroy(ctx);
    if (opt.ref_check > 0)
        std::printf("reference at K = %d against K = %d on %ld poses: minima and overlap depths agree within "
                    "%.2e (%d unmatched)\n",
                    opt.K, 3 * opt.K, ref_checked, ref_worst, ref_unmatched);
    /* the table */
    const std::string csv = opt.out + "/bench_accuracy.csv";
    FILE* cf = std::fopen(csv.c_str(), "w");
    if (!cf) return 2;
    std::fprintf(cf, "kind,delta_rel,rule,poses,failed_placements,required,missed,covered_by_stretch,near_"
                     "overlap,contacts,spurious,"
                     "sep_err_max,sep_err_p95,sep_err_over_delta,excess_max,normal_max_rad,normal_p95_rad,"
                     "normal_over_bound,regions,"
                     "region_missed,shallow_without_contact,region_err_max,region_normal_max_rad,unmatched_"
                     "overlap_contacts,"
                     "state_mismatches,state_tolerated,oncurve_max,lambda_err_max,reference_anomalies,time_"
                     "median_us,query_errors,"
                     "minima_by_descent\n");
    std::printf("\nErrors in units of δ (δ = 0: of the smaller shape's size); normals in radians; times: "
                "median per query.\n");
    std::printf("%-10s %6s %6s %5s %5s %6s %5s %6s %9s %9s %5s %9s %8s %8s %5s %5s %9s %6s %8s\n", "kind",
                "δ", "rule", "poses", "req", "missed", "spur", "cont", "sep max", "sep p95", ">δ", "excess",
                "nrm max", "nrm p95", "regs", "rmiss", "depth err", "states", "µs");
    bool fail = false;
    for (const Cell& c : cells) {
        const double tmed = quantile(c.times, 0.5) * 1e-3;
        std::fprintf(cf,
                     "%s,%g,%s,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%ld,%.3e,%.3e,%ld,%.3e,%.3e,%.3e,%ld,%ld,%ld,%ld,%"
                     ".3e,%.3e,%ld,%ld,%ld,%.3e,%.3e,%ld,%.2f,%ld,%ld\n",
                     c.kind.c_str(), c.delta_rel, c.rule == 0 ? "band" : "thesis", c.poses, c.failed_place,
                     c.required, c.missed, c.via_stretch, c.near_overlap, c.contacts, c.spurious, vmax(c.sep),
                     quantile(c.sep, 0.95), c.errors_over, c.max_excess, vmax(c.nrm), quantile(c.nrm, 0.95),
                     c.normal_over, c.regions, c.region_missed, c.shallow_no_contact, c.max_region_err,
                     c.max_region_normal, c.unmatched_overlap, c.state_bad, c.state_tolerated, c.max_oncurve,
                     c.max_lam, c.anomalies, tmed, c.status_errors, c.by_descent);
        std::printf("%-10s %6g %6s %5ld %5ld %6ld %5ld %6ld %9.3g %9.3g %5ld %9.3g %8.2g %8.2g %5ld %5ld "
                    "%9.3g %6ld %8.1f\n",
                    c.kind.c_str(), c.delta_rel, c.rule == 0 ? "band" : "thesis", c.poses, c.required,
                    c.missed, c.spurious, c.contacts, vmax(c.sep), quantile(c.sep, 0.95), c.errors_over,
                    c.max_excess, vmax(c.nrm), quantile(c.nrm, 0.95), c.regions,
                    c.region_missed + c.shallow_no_contact, c.max_region_err, c.state_bad, tmed);
        if (c.missed > 0 || c.errors_over > 0 || c.status_errors > 0 ||
            c.region_missed + c.shallow_no_contact > 0)
            fail = true;
    }
    std::fclose(cf);
    std::printf("(%s and %s written; %.1f s)\n", csv.c_str(), pose_csv.c_str(),
                (now_ns() - run_start) * 1e-9);
#ifdef RUGO_BENCH_WITH_BOX2D
    {
        const std::string bcsv = opt.out + "/bench_accuracy_box2d.csv";
        FILE* bf = std::fopen(bcsv.c_str(), "w");
        if (!bf) return 2;
        std::fprintf(bf, "kind,m,poses,unbuilt,targets,missed,spurious,sep_err_max,sep_err_p95,normal_max_"
                         "rad,normal_p95_rad,"
                         "time_median_us\n");
        std::printf("\nBox2D 2.4.1 polygon compounds of the same outlines (m vertices) on the δ = 1e-3 "
                    "poses, against the "
                    "curve distance; errors in units of the smaller shape's size\n");
        std::printf("%-10s %5s %5s %5s %6s %5s %9s %9s %8s %8s %8s\n", "kind", "m", "poses", "req", "missed",
                    "spur", "sep max", "sep p95", "nrm max", "nrm p95", "µs");
        for (const BoxCell& c : bcells) {
            const double tmed = quantile(c.times, 0.5) * 1e-3;
            std::fprintf(bf, "%s,%d,%ld,%ld,%ld,%ld,%ld,%.3e,%.3e,%.3e,%.3e,%.2f\n", c.kind.c_str(), c.m,
                         c.poses, c.unbuilt, c.targets, c.missed, c.spurious, vmax(c.sep),
                         quantile(c.sep, 0.95), vmax(c.nrm), quantile(c.nrm, 0.95), tmed);
            std::printf("%-10s %5d %5ld %5ld %6ld %5ld %9.3g %9.3g %8.2g %8.2g %8.1f%s\n", c.kind.c_str(),
                        c.m, c.poses, c.targets, c.missed, c.spurious, vmax(c.sep), quantile(c.sep, 0.95),
                        vmax(c.nrm), quantile(c.nrm, 0.95), tmed,
                        c.unbuilt ? " (some outlines not decomposed)" : "");
        }
        std::fclose(bf);
    }
#endif
    if (opt.quick || opt.only_pose >= 0)
        sample_expect("no missed minimum or overlap and no separation error above δ", !fail);
    destroy_world(w);
    return sample_finish();
}

} // namespace

int main(int argc, char** argv) {
    Options opt;
    bool out_given = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
        if (a == "--quick")
            opt.quick = true;
        else if (a == "--verbose")
            opt.verbose = true;
        else if (a == "--poses")
            opt.poses = std::atoi(next().c_str());
        else if (a == "--seed")
            opt.seed = std::strtoull(next().c_str(), nullptr, 10);
        else if (a == "--kind")
            opt.kind = next();
        else if (a == "--delta")
            opt.only_delta = std::atof(next().c_str());
        else if (a == "--rule") {
            const std::string r = next();
            opt.only_rule = r == "thesis" ? RULE_THESIS : RULE_BAND;
        } else if (a == "--reference-check")
            opt.ref_check = std::atoi(next().c_str());
        else if (a == "--pose")
            opt.only_pose = std::atoi(next().c_str());
        else if (a == "--samples")
            opt.K = std::max(2, std::atoi(next().c_str()) & ~1);
        else if (!a.empty() && a[0] != '-') {
            opt.out = a;
            out_given = true;
        } else {
            std::fprintf(stderr, "unknown option %s\n", a.c_str());
            return 2;
        }
    }
    (void)out_given;
    if (opt.poses <= 0) opt.poses = opt.quick ? 12 : 560;
    if (opt.quick && opt.ref_check == 0) opt.ref_check = 3;
    return run(opt);
}
