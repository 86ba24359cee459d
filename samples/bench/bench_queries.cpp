/* Benchmark (issue 7, benchmark 1): contact queries, speed against error — librugo against the polygon
 * baseline users have today (Box2D 2.4's b2CollidePolygons on convex pieces of a polygonised outline).
 *
 * Usage: bench_queries [--quick] [--hm] [OUTDIR]      (default OUTDIR out/bench_queries)
 *        bench_queries --contacts-hash [--quick]
 *        bench_queries --ray-casts [--quick]
 *
 * --contacts-hash prints, per level 0 .. -3, an FNV-1a hash of every byte of every contact (and the
 * state and count) that rugo_collide_shapes reports on the benchmark's poses, then exits: a change that
 * must not change behaviour keeps these hashes.
 *
 * --ray-casts times ray casts on the bean of 4096 segments (size 1) at its finest level and three
 * levels coarser: rugo_shape_ray_cast (through the MOBBtree) against rugo_contour_ray_cast (a pass over
 * all segments) on the same seeded rays, from a circle of radius 1.5 about the centroid towards random
 * points of the shape's bounds, each with max_fraction 2, checks that both give the same fractions, and
 * prints ns per ray for each, then exits.
 *
 * Shapes (body size 1: the diameter of the smallest circle about the centroid that holds the finest
 * curve; Box2D sees them as 1 m bodies): an ellipse (convex, axes 1 : 0.7) and a bean (the samples'
 * partly concave outline with a deep bay, sample_object), each smooth (256 control points on the
 * analytic outline) and rough (64 points roughened by two levels of the wavelet generator,
 * rugo_roughen, with tipo_3 tolerances x 0.004 of the size: asperities of RMS ~0.15 % of the size, and
 * finest tolerances tipo_3 x 0.002 for the roughness below the finest level) — 256 finest segments each.
 * Six pair kinds (smooth and rough: ellipse-ellipse, ellipse-bean, bean-bean), seeded random
 * orientations and approach directions; B is put where the finest curves first cross along the
 * direction (bisection on librugo's state) and then moved by a gap uniform in [-0.002, +0.002] of the
 * size: every pose is near contact.
 *
 * Contacts asked of every method: all contact regions with separation <= D = 0.005 (b2_linearSlop on
 * a 1 m body). librugo gets query.margin = D; Box2D reports polygon contacts up to its skin anyway.
 *
 * Methods:
 *  - rugo L (L = 0, -1, -2, -3): rugo_collide_shapes at that level of detail (finest, one to three
 *    levels coarser), margin D.
 *  - brute: the same narrow phase (librugo's internal rugo__narrow_pieces, cutoff band + margin) on
 *    every segment pair whose Bezier-hull boxes overlap, no tree: n^2 box tests per query. Its contact
 *    assembly is this program's (minima that face each other, penetration pairs), not the overlap
 *    region tracing of collide_regions.c, so its time is a lower bound of a tree-less librugo.
 *  - box2d m (m = 16 ... 4096): each finest curve approximated by the polygon of m vertices on the
 *    curve at equal arc length (in floats), decomposed into convex pieces of at most 8 vertices by
 *    this program's own code: for a star-shaped outline (all of these) a strip of truncated wedges
 *    over <= 5 boundary edges with radial sides, plus a fan core, so that no internal edge lies just
 *    under the boundary where Box2D's skin makes contacts with it; otherwise (or with --hm) ear
 *    clipping + Hertel-Mehlhorn merging capped at 8. Each piece a b2PolygonShape (vertices and normals
 *    filled directly: Set() welds vertices closer than 0.5 b2_linearSlop = 2.5 mm, which m >~ 1400 on
 *    a 1 m body needs). Per query: A's pieces whose bounding circles reach B's, their
 *    boxes in B's frame against a b2DynamicTree of B's pieces (Box2D's own broad-phase tree), the
 *    tight boxes tested, b2CollidePolygons on the survivors, b2WorldManifold for points, normal and
 *    separation. Box2D's separation includes the skin b2_polygonRadius = 2 b2_linearSlop = 0.01 m of
 *    each polygon: the core separation is the reported one + 0.02, and that is what is compared.
 *    A Box2D world would do more: fat boxes (b2_aabbExtension = 0.1 m) keep many more piece pairs in
 *    its contact list, each run through b2CollidePolygons every step.
 *  - box2d_narrow m: the same contacts; only the b2CollidePolygons + b2WorldManifold calls are timed
 *    (the pairs are found beforehand): the baseline with a free broad phase, a lower bound of its cost.
 *
 * Reference (independent of the narrow phase under test): the exact finest B-spline curves in long
 * double. For each curve, 32 samples per segment; for each sample the closest point of the other curve
 * (nearest sample from a grid, then Newton on the foot-point equation) gives the signed distance φ
 * (negative inside); every local minimum of φ along either curve within 2D is refined by Newton on the
 * stationarity system (f-g)·f' = (f-g)·g' = 0. Apart, these are the local minima of the distance;
 * in an overlap, the deepest penetration pairs (contacts.md). Pairs where the curves do not face each
 * other are dropped. A contact patch is a maximal arc of A where φ <= 2D; a patch with reference
 * minima is a region, and its separation is the smallest of its minima.
 * Matching (docs/accuracy.md): every contact a method reports belongs to the region of the patch
 * under the A-sample nearest its point on A (within W = 0.05), or to none. Per region the method's
 * separation is the smallest of its contacts there: separation error |s - s_ref|; point
 * error: midpoint of that contact to the nearest reference minimum of the region; normal error: angle
 * to that minimum's normal. Missed: a region with s_ref <= D/2 and no contact of the method. Spurious:
 * a contact with s <= D/2 that belongs to no region. For the targets, a missed or spurious contact
 * counts as an error of at least D (the effective error).
 *
 * Timing (CLOCK_MONOTONIC): every method runs over all poses 15 times; the poses are timed in groups of
 * 4 and each group's best time over the repetitions counts (a short group has a good chance to run
 * undisturbed on a shared machine); their sum over the number of poses is the time per query. The
 * sweep takes the best of 60 single queries. Ratios come from one run.
 *
 * Sweep ("work grows with contacts, not segments"): smooth shapes, gap 1e-7 of the size, margin 2e-7;
 * (a) the same ellipse pair and bean pair at 32 ... 4096 segments, one contact; (b) a comb of 34 teeth
 * (1024 segments) resting on slabs (1024 segments) that span k = 1 ... 32 teeth: k contacts. Box tests,
 * segment pairs and time per query at the finest level. (The comb has 34 teeth, the widest slab 32.)
 *
 * Output: OUTDIR/bench_queries.csv (method,param,pairs,time_ns_per_query,max_sep_err,mean_sep_err,
 * max_point_err,max_normal_err_rad,missed,spurious; also printed), the same for smooth and rough
 * pairs (bench_queries_smooth.csv, _rough.csv), bench_queries_pareto.csv (the Pareto front of time
 * against the effective max separation error, per method and subset), bench_queries_sweep.csv,
 * bench_queries_hard.csv (near-tangent, tiny overlap, rough on rough, far from the origin, parallel
 * straight sides: librugo finest and the baseline against the reference), and a one-line summary: time ratios
 * at equal maximum separation error 1e-3 and 1e-5 of the size (the baseline interpolated between its m values
 * on log scales), goal met or not.
 * --quick (the test registration): 12 poses, m <= 256, one repetition, a short sweep; checks that it
 * works and that the sanity numbers hold (finest and brute force agree with the reference, coarse
 * levels within their hard bounds, the baseline converges with m, the sweep's counts, the hard cases).
 * No check is on a time. */
#include "rugo/rugo.h"

#include <box2d/box2d.h>

extern "C" {
#include "query/narrow.h" /* internal: the narrow phase itself, for the brute-force method */
#include "sample_check.h"
#include "sample_shapes.h"
}

#include "polygon_baseline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace polygon_baseline;

constexpr double kPi = 3.14159265358979323846;
constexpr double kWindow = 0.005;                        /* D: contacts up to this separation are asked for */
constexpr double kMatch = 0.05;                          /* W: matching and region radius */
constexpr int kRefSamples = 32;                          /* reference samples per segment */
constexpr int kCap = 256;                                /* contact capacity per librugo query */
constexpr double kSkin = 2.0 * (double)b2_polygonRadius; /* both polygons' skins */

double now_ns() {
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

/* ------------------------------------------------------------------------------------------------
 * Shapes */

struct Body {
    std::string name;
    bool rough = false;
    rugo_shape* shape = nullptr;
    std::vector<rugo_vec2> pts; /* finest control points as the shape holds them (CCW, local frame) */
};

/* Moves the centroid to the origin and scales the finest curve to size 1 (diameter of the circle
 * about the centroid that holds it, from 64 samples per segment). */
void normalise(std::vector<rugo_vec2>& p) {
    rugo_contour c = {p.data(), (int)p.size()};
    if (rugo_contour_signed_area(c) < 0.0) std::reverse(p.begin(), p.end());
    const rugo_mass_properties mp = rugo_contour_mass_properties(c);
    double r = 0.0;
    for (int k = 0; k < c.count; ++k)
        for (int i = 0; i < 64; ++i) {
            const rugo_vec2 q = rugo_contour_point(c, k, i / 64.0);
            r = std::max(r, std::hypot(q.x - mp.centroid.x, q.y - mp.centroid.y));
        }
    const double s = 0.5 / r;
    for (auto& q : p)
        q = rugo_v2((q.x - mp.centroid.x) * s, (q.y - mp.centroid.y) * s);
}

std::vector<rugo_vec2> ellipse_points(int n) {
    std::vector<rugo_vec2> p((size_t)n);
    for (int k = 0; k < n; ++k) {
        const double th = 2.0 * kPi * k / n;
        p[(size_t)k] = rugo_v2(std::cos(th), 0.7 * std::sin(th));
    }
    normalise(p);
    return p;
}

std::vector<rugo_vec2> bean_points(int n) {
    std::vector<rugo_vec2> p((size_t)n);
    sample_object(n, rugo_v2(0.0, 0.0), 1.0, p.data());
    normalise(p);
    return p;
}

rugo_shape* make_shape(const std::vector<rugo_vec2>& p, const std::vector<double>* tol) {
    rugo_shape_def d = rugo_default_shape_def();
    d.points = p.data();
    d.count = (int)p.size();
    d.tolerances = tol ? tol->data() : nullptr;
    rugo_shape* s = nullptr;
    rugo_contour_problem pr;
    const rugo_status st = rugo_shape_create(&d, &s, &pr);
    if (st != RUGO_OK) {
        std::fprintf(stderr, "rugo_shape_create: %s\n", rugo_status_string(st));
        return nullptr;
    }
    return s;
}

void take_finest(Body& b) {
    rugo_contour c;
    rugo_shape_level(b.shape, rugo_shape_finest_level(b.shape), &c);
    b.pts.assign(c.points, c.points + c.count);
}

bool make_smooth(Body& b, const std::string& name, const std::vector<rugo_vec2>& p) {
    b.name = name;
    b.rough = false;
    b.shape = make_shape(p, nullptr);
    if (!b.shape) return false;
    take_finest(b);
    return true;
}

/* 64 points roughened by two wavelet levels (256 points), finest tolerances for what lies below. */
bool make_rough(Body& b, const std::string& name, std::vector<rugo_vec2> base, uint64_t seed) {
    const int n0 = (int)base.size(), n = n0 << 2;
    std::vector<double> lam0((size_t)n0), lam((size_t)n);
    if (rugo_tolerances_preset(RUGO_PRESET_TIPO_3, 0, n0, lam0.data()) != RUGO_OK) return false;
    if (rugo_tolerances_preset(RUGO_PRESET_TIPO_3, 0, n, lam.data()) != RUGO_OK) return false;
    for (auto& v : lam0)
        v *= 0.004;
    for (auto& v : lam)
        v *= 0.002;
    std::vector<rugo_vec2> out((size_t)n);
    rugo_roughen_def d = rugo_default_roughen_def();
    d.points = base.data();
    d.count = n0;
    d.tolerances = lam0.data();
    d.method = RUGO_ROUGHEN_WAVELET;
    d.levels = 2;
    d.seed = seed;
    const rugo_status st = rugo_roughen(&d, out.data());
    if (st != RUGO_OK) {
        std::fprintf(stderr, "rugo_roughen: %s\n", rugo_status_string(st));
        return false;
    }
    normalise(out);
    b.name = name;
    b.rough = true;
    b.shape = make_shape(out, &lam);
    if (!b.shape) return false;
    take_finest(b);
    return true;
}

/* ------------------------------------------------------------------------------------------------
 * Reference: exact finest curves in long double. */

typedef long double ld;

struct LCurve {
    std::vector<ld> x, y;
    int n = 0;
};

LCurve world_curve(const std::vector<rugo_vec2>& p, rugo_transform xf) {
    LCurve c;
    c.n = (int)p.size();
    c.x.resize(p.size());
    c.y.resize(p.size());
    const ld cc = xf.q.c, ss = xf.q.s;
    for (size_t i = 0; i < p.size(); ++i) {
        c.x[i] = (ld)xf.p.x + cc * (ld)p[i].x - ss * (ld)p[i].y;
        c.y[i] = (ld)xf.p.y + ss * (ld)p[i].x + cc * (ld)p[i].y;
    }
    return c;
}

struct LEval {
    ld x, y, dx, dy, ddx, ddy;
};

ld wrap_u(ld u, int n) {
    const ld nn = (ld)n;
    u = std::fmod(u, nn);
    if (u < 0) u += nn;
    if (u >= nn) u = 0;
    return u;
}

LEval eval(const LCurve& c, ld u) {
    u = wrap_u(u, c.n);
    int j = (int)std::floor(u);
    if (j >= c.n) j = c.n - 1;
    const ld t = u - (ld)j;
    const int i0 = (j - 1 + c.n) % c.n, i1 = j, i2 = (j + 1) % c.n, i3 = (j + 2) % c.n;
    const ld mt = 1 - t;
    const ld b0 = mt * mt * mt / 6, b1 = (3 * t * t * t - 6 * t * t + 4) / 6,
             b2 = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, b3 = t * t * t / 6;
    const ld d0 = -mt * mt / 2, d1 = (3 * t * t - 4 * t) / 2, d2 = (-3 * t * t + 2 * t + 1) / 2,
             d3 = t * t / 2;
    const ld e0 = mt, e1 = 3 * t - 2, e2 = -3 * t + 1, e3 = t;
    LEval r;
    r.x = b0 * c.x[i0] + b1 * c.x[i1] + b2 * c.x[i2] + b3 * c.x[i3];
    r.y = b0 * c.y[i0] + b1 * c.y[i1] + b2 * c.y[i2] + b3 * c.y[i3];
    r.dx = d0 * c.x[i0] + d1 * c.x[i1] + d2 * c.x[i2] + d3 * c.x[i3];
    r.dy = d0 * c.y[i0] + d1 * c.y[i1] + d2 * c.y[i2] + d3 * c.y[i3];
    r.ddx = e0 * c.x[i0] + e1 * c.x[i1] + e2 * c.x[i2] + e3 * c.x[i3];
    r.ddy = e0 * c.y[i0] + e1 * c.y[i1] + e2 * c.y[i2] + e3 * c.y[i3];
    return r;
}

struct RefMin {
    double ax, ay, bx, by, nx, ny, s;
    int region;
};

struct Grid {
    double x0 = 0, y0 = 0, h = 1;
    int nx = 0, ny = 0;
    std::vector<int> start, items;
};

/* The signed distance from the samples of P to curve Q; local minima within `reach` refined. Appends
 * pairs (A's point first) to out. p_is_a: P is curve A. */
void ref_side(const LCurve& P, const LCurve& Q, bool p_is_a, double reach, std::vector<RefMin>& out,
              long* unrefined, std::vector<double>* phi_out, std::vector<double>* px_out,
              std::vector<double>* py_out) {
    const int K = kRefSamples;
    const int np = P.n * K, nq = Q.n * K;
    std::vector<double> qx((size_t)nq), qy((size_t)nq);
    double lox = 1e300, loy = 1e300, hix = -1e300, hiy = -1e300;
    for (int i = 0; i < nq; ++i) {
        const LEval e = eval(Q, (ld)i / K);
        qx[(size_t)i] = (double)e.x;
        qy[(size_t)i] = (double)e.y;
        lox = std::min(lox, qx[(size_t)i]);
        loy = std::min(loy, qy[(size_t)i]);
        hix = std::max(hix, qx[(size_t)i]);
        hiy = std::max(hiy, qy[(size_t)i]);
    }
    Grid g;
    g.h = reach;
    g.x0 = lox;
    g.y0 = loy;
    g.nx = (int)((hix - lox) / g.h) + 1;
    g.ny = (int)((hiy - loy) / g.h) + 1;
    g.start.assign((size_t)(g.nx * g.ny + 1), 0);
    g.items.resize((size_t)nq);
    auto cell = [&](double x, double y) {
        const int ix = std::min(g.nx - 1, std::max(0, (int)((x - g.x0) / g.h)));
        const int iy = std::min(g.ny - 1, std::max(0, (int)((y - g.y0) / g.h)));
        return iy * g.nx + ix;
    };
    for (int i = 0; i < nq; ++i)
        g.start[(size_t)cell(qx[(size_t)i], qy[(size_t)i]) + 1]++;
    for (size_t i = 1; i < g.start.size(); ++i)
        g.start[i] += g.start[i - 1];
    {
        std::vector<int> fill(g.start.begin(), g.start.end() - 1);
        for (int i = 0; i < nq; ++i)
            g.items[(size_t)fill[(size_t)cell(qx[(size_t)i], qy[(size_t)i])]++] = i;
    }
    /* φ at P's samples; foot parameter on Q. NaN: nothing of Q within reach. */
    std::vector<double> phi((size_t)np, NAN);
    std::vector<ld> foot((size_t)np, 0);
    if (px_out) {
        px_out->resize((size_t)np);
        py_out->resize((size_t)np);
    }
    for (int i = 0; i < np; ++i) {
        const LEval e = eval(P, (ld)i / K);
        const double px = (double)e.x, py = (double)e.y;
        if (px_out) {
            (*px_out)[(size_t)i] = px;
            (*py_out)[(size_t)i] = py;
        }
        if (px < lox - reach || px > hix + reach || py < loy - reach || py > hiy + reach) continue;
        const int ix = (int)std::floor((px - g.x0) / g.h), iy = (int)std::floor((py - g.y0) / g.h);
        int best = -1;
        double bd = reach * reach;
        for (int cy = iy - 1; cy <= iy + 1; ++cy)
            for (int cx = ix - 1; cx <= ix + 1; ++cx) {
                if (cx < 0 || cy < 0 || cx >= g.nx || cy >= g.ny) continue;
                const int c = cy * g.nx + cx;
                for (int k = g.start[(size_t)c]; k < g.start[(size_t)c + 1]; ++k) {
                    const int j = g.items[(size_t)k];
                    const double dx = qx[(size_t)j] - px, dy = qy[(size_t)j] - py, d2 = dx * dx + dy * dy;
                    if (d2 < bd) {
                        bd = d2;
                        best = j;
                    }
                }
            }
        if (best < 0) continue;
        /* foot point: safeguarded Newton on h(u) = (g(u) - p)·g'(u) in [u_j - 1/K, u_j + 1/K] */
        const ld uj = (ld)best / K;
        ld lo = uj - (ld)1 / K, hi = uj + (ld)1 / K;
        auto hfun = [&](ld u, ld* dh) {
            const LEval q = eval(Q, u);
            const ld rx = q.x - e.x, ry = q.y - e.y;
            if (dh) *dh = q.dx * q.dx + q.dy * q.dy + rx * q.ddx + ry * q.ddy;
            return rx * q.dx + ry * q.dy;
        };
        ld hlo = hfun(lo, nullptr), hhi = hfun(hi, nullptr);
        ld u = uj;
        if (hlo <= 0 && hhi >= 0) {
            for (int it = 0; it < 60; ++it) {
                ld dh;
                const ld h = hfun(u, &dh);
                if (h < 0)
                    lo = u;
                else
                    hi = u;
                ld un = u - h / dh;
                if (!(dh > 0) || !(un > lo && un < hi)) un = (lo + hi) / 2;
                if (std::fabs(un - u) < 1e-19L * (ld)Q.n) {
                    u = un;
                    break;
                }
                u = un;
            }
        }
        const LEval q = eval(Q, u);
        const ld rx = e.x - q.x, ry = e.y - q.y;
        const ld d = std::sqrt(rx * rx + ry * ry);
        const ld sg = rx * q.dy - ry * q.dx; /* (p - g)·n_Q, n_Q = (g'.y, -g'.x) */
        phi[(size_t)i] = (double)(sg >= 0 ? d : -d);
        foot[(size_t)i] = u;
    }
    for (int i = 0; i < np; ++i) {
        const double v = phi[(size_t)i];
        if (std::isnan(v) || v > reach) continue;
        const double vp = phi[(size_t)((i - 1 + np) % np)], vn = phi[(size_t)((i + 1) % np)];
        if (!(std::isnan(vp) || v < vp) || !(std::isnan(vn) || v <= vn)) continue;
        /* Newton on (f - g)·f' = 0, (f - g)·g' = 0 */
        ld s = (ld)i / K, t = foot[(size_t)i];
        const ld s0 = s, t0 = t;
        bool ok = false;
        for (int it = 0; it < 50; ++it) {
            const LEval f = eval(P, s), q = eval(Q, t);
            const ld rx = f.x - q.x, ry = f.y - q.y;
            const ld F1 = rx * f.dx + ry * f.dy, F2 = rx * q.dx + ry * q.dy;
            const ld j11 = f.dx * f.dx + f.dy * f.dy + rx * f.ddx + ry * f.ddy;
            const ld j12 = -(q.dx * f.dx + q.dy * f.dy);
            const ld j21 = f.dx * q.dx + f.dy * q.dy;
            const ld j22 = -(q.dx * q.dx + q.dy * q.dy) + rx * q.ddx + ry * q.ddy;
            const ld det = j11 * j22 - j12 * j21;
            if (det == 0) break;
            const ld ds = -(F1 * j22 - j12 * F2) / det, dt = -(j11 * F2 - j21 * F1) / det;
            s += ds;
            t += dt;
            if (std::fabs(ds) + std::fabs(dt) < 1e-17L * (ld)(P.n + Q.n)) {
                ok = true;
                break;
            }
        }
        const ld lim = (ld)3 / K;
        auto pdist = [](ld a, ld b, int n) {
            ld d = std::fabs(a - b);
            return std::min(d, (ld)n - d);
        };
        if (!ok || pdist(s, s0, P.n) > lim || pdist(t, t0, Q.n) > lim) {
            s = s0;
            t = t0;
            ++*unrefined;
        }
        const LEval f = eval(P, s), q = eval(Q, t);
        const ld rx = q.x - f.x, ry = q.y - f.y; /* from P's point to Q's */
        const ld d = std::sqrt(rx * rx + ry * ry);
        /* sign: P's point outside Q <=> (f - q)·n_Q >= 0 */
        const ld out_q = -(rx * q.dy - ry * q.dx);
        const ld sgn = out_q >= 0 ? 1 : -1;
        /* facing: Q's point on P's outward side for apart pairs, on its inward side for penetration */
        const ld fp = rx * f.dy - ry * f.dx; /* (q - f)·n_P */
        if (d > 1e-12L && fp * sgn <= 0) continue;
        RefMin m;
        m.region = -1;
        const double fx = (double)f.x, fy = (double)f.y, gx = (double)q.x, gy = (double)q.y;
        if (p_is_a) {
            m.ax = fx;
            m.ay = fy;
            m.bx = gx;
            m.by = gy;
        } else {
            m.ax = gx;
            m.ay = gy;
            m.bx = fx;
            m.by = fy;
        }
        m.s = (double)(sgn * d);
        /* B's point minus A's, in long double (world points far from the origin lose the direction) */
        const ld vx = p_is_a ? rx : -rx, vy = p_is_a ? ry : -ry;
        if (d > 1e-7L) {
            m.nx = (double)(sgn * vx / d);
            m.ny = (double)(sgn * vy / d);
        } else { /* A's outward normal: exact at a stationary pair, where points no longer give it */
            const LEval fa = p_is_a ? f : q;
            const double l = (double)std::sqrt(fa.dx * fa.dx + fa.dy * fa.dy);
            m.nx = (double)fa.dy / l;
            m.ny = -(double)fa.dx / l;
        }
        bool dup = false;
        for (const auto& o : out)
            dup |= std::hypot(o.ax - m.ax, o.ay - m.ay) + std::hypot(o.bx - m.bx, o.by - m.by) < 1e-7;
        if (!dup) out.push_back(m);
    }
    if (phi_out) phi_out->swap(phi);
}

/* The reference of one pose: the minima, and the contact patches — maximal arcs of A where the signed
 * distance to B is at most 2D. A patch with at least one reference minimum is a contact region; its
 * separation is the smallest of its minima. A contact of a method belongs to the patch under the A
 * sample nearest its point on A (samples of the patches and 64 more either side are kept; a contact
 * whose nearest kept sample is a margin one, or farther than W, belongs to none). */
struct PoseRef {
    std::vector<RefMin> mins;   /* region = patch index */
    std::vector<double> sx, sy; /* kept samples of A */
    std::vector<int> sp;        /* their patch, or -1 */
    std::vector<double> smin;   /* per region: reference separation */
    int regions = 0;
};

int nearest_patch(const PoseRef& r, double x, double y) {
    double best = kMatch * kMatch;
    int p = -1;
    for (size_t k = 0; k < r.sx.size(); ++k) {
        const double dx = r.sx[k] - x, dy = r.sy[k] - y, d2 = dx * dx + dy * dy;
        if (d2 < best) {
            best = d2;
            p = r.sp[k];
        }
    }
    return p;
}

void reference(const Body& A, rugo_transform xa, const Body& B, rugo_transform xb, PoseRef& pr,
               long* unrefined) {
    pr = PoseRef();
    const LCurve ca = world_curve(A.pts, xa), cb = world_curve(B.pts, xb);
    std::vector<double> phi, ax, ay;
    std::vector<RefMin> all;
    ref_side(ca, cb, true, 2.0 * kWindow, all, unrefined, &phi, &ax, &ay);
    ref_side(cb, ca, false, 2.0 * kWindow, all, unrefined, nullptr, nullptr, nullptr);
    const int n = (int)phi.size();
    auto in = [&](int i) {
        const double v = phi[(size_t)(((i % n) + n) % n)];
        return !std::isnan(v) && v <= 2.0 * kWindow;
    };
    int start = -1;
    for (int i = 0; i < n && start < 0; ++i)
        if (!in(i)) start = i;
    if (start < 0) return; /* A within 2D of B everywhere: not a near-contact pose */
    std::vector<int> patch((size_t)n, -1);
    int patches = 0;
    for (int k = 0; k < n; ++k) {
        const int i = (start + k) % n;
        if (!in(i)) continue;
        const int prev = (i - 1 + n) % n;
        patch[(size_t)i] = in(prev) && patch[(size_t)prev] >= 0 ? patch[(size_t)prev] : patches++;
    }
    std::vector<char> keep((size_t)n, 0);
    for (int i = 0; i < n; ++i)
        if (patch[(size_t)i] >= 0)
            for (int d = -64; d <= 64; ++d)
                keep[(size_t)(((i + d) % n + n) % n)] = 1;
    for (int i = 0; i < n; ++i)
        if (keep[(size_t)i]) {
            pr.sx.push_back(ax[(size_t)i]);
            pr.sy.push_back(ay[(size_t)i]);
            pr.sp.push_back(patch[(size_t)i]);
        }
    /* minima to patches; patches with minima become regions 0..regions-1 */
    std::vector<int> label((size_t)patches, -1);
    for (auto& m : all) {
        const int p = nearest_patch(pr, m.ax, m.ay);
        if (p < 0) continue;
        if (label[(size_t)p] < 0) {
            label[(size_t)p] = pr.regions++;
            pr.smin.push_back(HUGE_VAL);
        }
        m.region = label[(size_t)p];
        pr.smin[(size_t)m.region] = std::min(pr.smin[(size_t)m.region], m.s);
        pr.mins.push_back(m);
    }
    for (auto& p : pr.sp)
        if (p >= 0) p = label[(size_t)p];
}

/* ------------------------------------------------------------------------------------------------
 * Metrics */

struct Metrics {
    double max_sep = 0, sum_sep = 0, max_pt = 0, max_nrm = 0, max_bound_ratio = 0;
    long n_sep = 0, missed = 0, spurious = 0, regions_required = 0, contacts = 0;
    bool finite = true;
};

void evaluate(const PoseRef& ref, const std::vector<Cnt>& got, Metrics& m) {
    const int regions = ref.regions;
    std::vector<int> best((size_t)regions, -1);
    for (size_t i = 0; i < got.size(); ++i) {
        const Cnt& c = got[i];
        m.finite &= std::isfinite(c.s) && std::isfinite(c.nx) && std::isfinite(c.ny) && std::isfinite(c.ax) &&
                    std::isfinite(c.by);
        /* every reported contact takes part (Box2D reports up to its skin, librugo up to band +
         * margin): a contact reported with too large a separation shows as an error, not a miss */
        m.contacts += c.s <= kWindow;
        const int r = nearest_patch(ref, c.ax, c.ay);
        if (r < 0) {
            if (c.s <= 0.5 * kWindow) ++m.spurious;
            continue;
        }
        if (best[(size_t)r] < 0 || c.s < got[(size_t)best[(size_t)r]].s) best[(size_t)r] = (int)i;
    }
    for (int r = 0; r < regions; ++r) {
        const double sref = ref.smin[(size_t)r];
        const bool required = sref <= 0.5 * kWindow;
        m.regions_required += required;
        if (best[(size_t)r] < 0) {
            m.missed += required;
            continue;
        }
        const Cnt& c = got[(size_t)best[(size_t)r]];
        /* nearest reference minimum of this region to the contact */
        const double mx = 0.5 * (c.ax + c.bx), my = 0.5 * (c.ay + c.by);
        double nd = HUGE_VAL;
        const RefMin* rm = nullptr;
        for (const auto& q : ref.mins)
            if (q.region == r) {
                const double d = std::hypot(mx - 0.5 * (q.ax + q.bx), my - 0.5 * (q.ay + q.by));
                if (d < nd) {
                    nd = d;
                    rm = &q;
                }
            }
        const double e = std::fabs(c.s - sref);
        m.max_sep = sample_max(m.max_sep, e);
        m.sum_sep += e;
        ++m.n_sep;
        m.max_pt = sample_max(m.max_pt, nd);
        const double dot = std::max(-1.0, std::min(1.0, c.nx * rm->nx + c.ny * rm->ny));
        const double cr = c.nx * rm->ny - c.ny * rm->nx;
        m.max_nrm = sample_max(m.max_nrm, std::atan2(std::fabs(cr), dot));
        if (c.bound > 0.0) m.max_bound_ratio = sample_max(m.max_bound_ratio, e / c.bound);
    }
}

/* ------------------------------------------------------------------------------------------------
 * librugo */

struct Pose {
    int a, b;
    rugo_transform xa, xb;
};

/* The resolution the "rugo L" methods run at (0: round-off; --resolution sets it). */
double g_resolution = 0.0;
/* Their contact rule: the thesis' minima of the distance, which the reference computes and the
 * polygons (which have no band) compare with; --band-adjusted: the library's default rule. */
rugo_contact_rule g_rule = RUGO_CONTACT_THESIS;

rugo_contact_query make_query(int level, double margin) {
    rugo_contact_query q = rugo_default_contact_query();
    q.lod = level;
    q.margin = margin;
    q.resolution = g_resolution;
    q.contact_rule = g_rule;
    return q;
}

rugo_contact_state state_at(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa,
                            const rugo_shape* b, rugo_transform xb) {
    /* the poses are placed by the round-off answer, whatever resolution the methods run at */
    rugo_contact_query q = rugo_default_contact_query();
    q.resolution = 0.0;
    rugo_contact_output out = rugo_contact_output_of(nullptr, 0); /* the state only */
    rugo_collide_shapes(a, xa, b, xb, &q, ctx, &out);
    return out.state;
}

/* Distance along dir from A's position at which B first stops crossing A (bisection on the state). */
double touching(rugo_collide_context* ctx, const rugo_shape* a, rugo_transform xa, const rugo_shape* b,
                rugo_transform xb, rugo_vec2 from, rugo_vec2 dir) {
    double lo = 0.0, hi = 3.0;
    for (int it = 0; it < 64; ++it) {
        const double mid = 0.5 * (lo + hi);
        xb.p = rugo_v2(from.x + mid * dir.x, from.y + mid * dir.y);
        if (state_at(ctx, a, xa, b, xb) == RUGO_STATE_INTERSECTING)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

void rugo_contacts(rugo_collide_context* ctx, const Body& A, rugo_transform xa, const Body& B,
                   rugo_transform xb, int level, std::vector<Cnt>& out, rugo_query_stats* qs) {
    static rugo_contact c[kCap];
    const rugo_contact_query q = make_query(level, kWindow);
    rugo_contact_output o = rugo_contact_output_of(c, kCap);
    rugo_collide_shapes(A.shape, xa, B.shape, xb, &q, ctx, &o);
    if (qs != nullptr) *qs = o.stats;
    const int n = o.count;
    out.clear();
    for (int i = 0; i < n; ++i) {
        Cnt k;
        k.ax = c[i].point_a.x;
        k.ay = c[i].point_a.y;
        k.bx = c[i].point_b.x;
        k.by = c[i].point_b.y;
        k.nx = c[i].normal.x;
        k.ny = c[i].normal.y;
        k.s = c[i].separation;
        rugo_tolerance_level ta, tb;
        rugo_shape_tolerance_level(A.shape, c[i].level_a, &ta);
        rugo_shape_tolerance_level(B.shape, c[i].level_b, &tb);
        /* the hard bounds near the contact: its segment and two neighbours each side (the deepest
         * finest point of the region need not lie under the same coarse segment) */
        double ba = 0.0, bb = 0.0;
        for (int d = -2; d <= 2; ++d) {
            ba = std::max(ba, ta.bound[(c[i].segment_a + d + ta.count) % ta.count]);
            bb = std::max(bb, tb.bound[(c[i].segment_b + d + tb.count) % tb.count]);
        }
        k.bound = ba + bb;
        out.push_back(k);
    }
}

/* ------------------------------------------------------------------------------------------------
 * Brute force: the same narrow phase on every segment pair, no tree. */

struct BruteSide {
    int n = 0;
    rugo_contour curve{};
    const double* lambda = nullptr;
    std::vector<std::array<rugo_vec2, 4>> bez; /* local frame */
    std::vector<double> band;                  /* bound of λ(t) per segment */
    double scale = 1.0;
};

BruteSide brute_side(const Body& b) {
    BruteSide s;
    rugo_shape_level(b.shape, rugo_shape_finest_level(b.shape), &s.curve);
    s.n = s.curve.count;
    rugo_tolerance_level tl;
    rugo_shape_tolerance_level(b.shape, rugo_shape_finest_level(b.shape), &tl);
    s.lambda = tl.total;
    s.bez.resize((size_t)s.n);
    s.band.resize((size_t)s.n);
    for (int k = 0; k < s.n; ++k) {
        rugo_contour_bezier(s.curve, k, s.bez[(size_t)k].data());
        s.band[(size_t)k] = rugo_tolerance_bound_on_segment(s.lambda, s.n, k, 0.0);
    }
    return s;
}

struct BruteScratch {
    std::vector<std::array<rugo_vec2, 4>> bb; /* B's pieces in A's frame */
    std::vector<std::array<double, 4>> boxb;  /* lo.x lo.y hi.x hi.y, grown by band */
    std::vector<std::array<double, 4>> boxa;
    struct Hit {
        int sa, sb;
        double ta, tb;
        rugo_vec2 pa, pb;
        double d;
        int kind;
    };
    std::vector<Hit> minima, stationary;
    int crossings = 0;
};

void bez_box(const rugo_vec2* b, double grow, std::array<double, 4>& box) {
    box = {b[0].x, b[0].y, b[0].x, b[0].y};
    for (int i = 1; i < 4; ++i) {
        box[0] = std::min(box[0], b[i].x);
        box[1] = std::min(box[1], b[i].y);
        box[2] = std::max(box[2], b[i].x);
        box[3] = std::max(box[3], b[i].y);
    }
    box[0] -= grow;
    box[1] -= grow;
    box[2] += grow;
    box[3] += grow;
}

void brute_prepare(BruteSide& A, BruteScratch& s) {
    s.boxa.resize((size_t)A.n);
    for (int k = 0; k < A.n; ++k)
        bez_box(A.bez[(size_t)k].data(), A.band[(size_t)k] + kWindow, s.boxa[(size_t)k]);
}

void brute_contacts(const BruteSide& A, rugo_transform xa, const BruteSide& B, rugo_transform xb,
                    BruteScratch& s, std::vector<Cnt>* out, long* pairs) {
    /* B relative to A, as librugo does: everything in A's frame */
    rugo_transform rel;
    rel.q.c = xa.q.c * xb.q.c + xa.q.s * xb.q.s;
    rel.q.s = xa.q.c * xb.q.s - xa.q.s * xb.q.c;
    rel.p = rugo_inv_rotate(xa.q, rugo_v2_sub(xb.p, xa.p));
    s.bb.resize((size_t)B.n);
    s.boxb.resize((size_t)B.n);
    for (int k = 0; k < B.n; ++k) {
        for (int i = 0; i < 4; ++i)
            s.bb[(size_t)k][(size_t)i] = rugo_transform_point(rel, B.bez[(size_t)k][(size_t)i]);
        bez_box(s.bb[(size_t)k].data(), B.band[(size_t)k], s.boxb[(size_t)k]);
    }
    s.minima.clear();
    s.stationary.clear();
    s.crossings = 0;
    long np = 0;
    for (int i = 0; i < A.n; ++i) {
        const auto& ba = s.boxa[(size_t)i];
        for (int j = 0; j < B.n; ++j) {
            const auto& bj = s.boxb[(size_t)j];
            if (ba[0] > bj[2] || bj[0] > ba[2] || ba[1] > bj[3] || bj[1] > ba[3]) continue;
            ++np;
            const rugo_vec2 o = A.bez[(size_t)i][0];
            rugo_vec2 f[4], g[4];
            for (int k = 0; k < 4; ++k) {
                f[k] = rugo_v2_sub(A.bez[(size_t)i][(size_t)k], o);
                g[k] = rugo_v2_sub(s.bb[(size_t)j][(size_t)k], o);
            }
            const double cut = A.band[(size_t)i] + B.band[(size_t)j] + kWindow;
            rugo__narrow_result r;
            rugo__narrow_pieces(f, g, cut * (1.0 + 1e-12) + 1e-12 * A.scale, &r);
            s.crossings += r.crossing_count;
            for (int k = 0; k < r.stationary_count; ++k) {
                BruteScratch::Hit h;
                h.sa = i;
                h.sb = j;
                h.ta = r.stationary[k].s;
                h.tb = r.stationary[k].t;
                if (h.ta >= 1.0) {
                    h.sa = (h.sa + 1) % A.n;
                    h.ta = 0.0;
                }
                if (h.tb >= 1.0) {
                    h.sb = (h.sb + 1) % B.n;
                    h.tb = 0.0;
                }
                h.pa = rugo_v2_add(r.stationary[k].pa, o);
                h.pb = rugo_v2_add(r.stationary[k].pb, o);
                h.d = r.stationary[k].distance;
                h.kind = r.stationary[k].kind;
                s.stationary.push_back(h);
            }
        }
    }
    if (pairs) *pairs = np;
    if (!out) return;
    out->clear();
    const double eps = 1e-9 * A.scale;
    for (size_t i = 0; i < s.stationary.size(); ++i) {
        const auto& h = s.stationary[i];
        bool dup = false;
        for (size_t j = 0; j < i && !dup; ++j) {
            const auto& o2 = s.stationary[j];
            dup = std::hypot(o2.pa.x - h.pa.x, o2.pa.y - h.pa.y) <= eps &&
                  std::hypot(o2.pb.x - h.pb.x, o2.pb.y - h.pb.y) <= eps;
        }
        if (dup) continue;
        const rugo_vec2 d = rugo_v2_sub(h.pb, h.pa);
        const rugo_vec2 na = rugo_contour_normal(A.curve, h.sa, h.ta);
        const rugo_vec2 nb = rugo_rotate(rel.q, rugo_contour_normal(B.curve, h.sb, h.tb));
        const double da = rugo_v2_dot(na, d), db = -rugo_v2_dot(nb, d);
        Cnt c;
        c.bound = 0.0;
        /* (a one-sided minimum at a sharp corner counts too: none of these smooth shapes has one) */
        if ((h.kind == RUGO__MINIMUM || h.kind == RUGO__END_MINIMUM) && da >= 0.0 && db >= 0.0) {
            const double band = rugo_tolerance_at(A.lambda, A.n, h.sa, h.ta, 0.0) +
                                rugo_tolerance_at(B.lambda, B.n, h.sb, h.tb, 0.0) + kWindow;
            if (!(h.d <= band)) continue;
            c.s = h.d;
            rugo_vec2 n = h.d > 1e-7 * A.scale ? rugo_v2_scale(1.0 / h.d, d) : na;
            c.nx = n.x;
            c.ny = n.y;
        } else if (s.crossings > 0 && da < 0.0 && db < 0.0 && h.d > 0.0) {
            c.s = -h.d; /* a penetration pair: B's point inside A and A's inside B */
            c.nx = -d.x / h.d;
            c.ny = -d.y / h.d;
        } else {
            continue;
        }
        const rugo_vec2 wa = rugo_transform_point(xa, h.pa), wb = rugo_transform_point(xa, h.pb);
        const rugo_vec2 wn = rugo_rotate(xa.q, rugo_v2(c.nx, c.ny));
        c.ax = wa.x;
        c.ay = wa.y;
        c.bx = wb.x;
        c.by = wb.y;
        c.nx = wn.x;
        c.ny = wn.y;
        out->push_back(c);
    }
}

/* ------------------------------------------------------------------------------------------------
 * Results */

struct Row {
    std::string method;
    int param;
    double pairs; /* per query */
    double time_ns;
    Metrics m;
};

void print_row(FILE* f, const Row& r) {
    std::fprintf(f, "%s,%d,%.2f,%.0f,%.3e,%.3e,%.3e,%.3e,%ld,%ld\n", r.method.c_str(), r.param, r.pairs,
                 r.time_ns, r.m.max_sep, r.m.n_sep ? r.m.sum_sep / (double)r.m.n_sep : 0.0, r.m.max_pt,
                 r.m.max_nrm, r.m.missed, r.m.spurious);
}

/* The error used for the targets: a missed or spurious contact counts as an error of at least D. */
double eff_err(const Row& r) {
    return r.m.missed + r.m.spurious > 0 ? std::max(r.m.max_sep, kWindow) : r.m.max_sep;
}

/* Time of the baseline at max separation error e, log-log interpolation between m values (errors
 * fall as m grows). Returns -1 if no m reaches e (then *reach_m = 0) or if even m = 16 is below e. */
double baseline_time_at(const std::vector<Row>& rows, const std::string& method, double e, double* m_at) {
    std::vector<const Row*> r;
    for (const auto& x : rows)
        if (x.method == method) r.push_back(&x);
    std::sort(r.begin(), r.end(), [](const Row* a, const Row* b) { return a->param < b->param; });
    *m_at = 0.0;
    if (r.empty()) return -1.0;
    if (eff_err(*r[0]) <= e) {
        *m_at = r[0]->param;
        return r[0]->time_ns;
    }
    for (size_t k = 1; k < r.size(); ++k)
        if (eff_err(*r[k]) <= e && eff_err(*r[k - 1]) > e) {
            const double l0 = std::log(eff_err(*r[k - 1])), l1 = std::log(eff_err(*r[k]));
            const double w = (std::log(e) - l0) / (l1 - l0);
            *m_at = std::exp((1 - w) * std::log((double)r[k - 1]->param) + w * std::log((double)r[k]->param));
            return std::exp((1 - w) * std::log(r[k - 1]->time_ns) + w * std::log(r[k]->time_ns));
        }
    return -1.0;
}

/* Fastest librugo configuration (tree levels) with max separation error <= e. */
const Row* rugo_fastest_at(const std::vector<Row>& rows, double e) {
    const Row* best = nullptr;
    for (const auto& x : rows)
        if (x.method == "rugo" && eff_err(x) <= e && (!best || x.time_ns < best->time_ns)) best = &x;
    return best;
}

/* ------------------------------------------------------------------------------------------------
 * Sweep shapes */

std::vector<rugo_vec2> comb_points(int teeth, double pitch, double amp, int per_tooth, double height, int n) {
    const double W = teeth * pitch, H = height;
    std::vector<rugo_vec2> p;
    const int nb = teeth * per_tooth;
    for (int j = 0; j < nb; ++j) {
        const double x = -0.5 * W + W * j / nb;
        const double y = -0.5 * H - 0.5 * amp * (1.0 - std::cos(2.0 * kPi * (x + 0.5 * W) / pitch));
        p.push_back(rugo_v2(x, y));
    }
    const int rest = n - nb;
    const int side = (int)std::lround(rest * H / (2.0 * H + W));
    const int top = rest - 2 * side;
    for (int i = 0; i < side; ++i)
        p.push_back(rugo_v2(0.5 * W, -0.5 * H + H * i / side));
    for (int i = 0; i < top; ++i)
        p.push_back(rugo_v2(0.5 * W - W * i / top, 0.5 * H));
    for (int i = 0; i < side; ++i)
        p.push_back(rugo_v2(-0.5 * W, 0.5 * H - H * i / side));
    return p;
}

std::vector<rugo_vec2> slab_points(double w, double h, int n) {
    const double per = 2.0 * (w + h);
    int nw = (int)std::lround(n * w / per), nh = n / 2 - nw;
    if (nh < 2) {
        nh = 2;
        nw = n / 2 - nh;
    }
    std::vector<rugo_vec2> p;
    for (int i = 0; i < nw; ++i)
        p.push_back(rugo_v2(-0.5 * w + w * i / nw, -0.5 * h));
    for (int i = 0; i < nh; ++i)
        p.push_back(rugo_v2(0.5 * w, -0.5 * h + h * i / nh));
    for (int i = 0; i < nw; ++i)
        p.push_back(rugo_v2(0.5 * w - w * i / nw, 0.5 * h));
    for (int i = 0; i < nh; ++i)
        p.push_back(rugo_v2(-0.5 * w, 0.5 * h - h * i / nh));
    return p;
}

struct SweepRow {
    std::string kind, shapes;
    int n, expected, contacts;
    long boxes, pairs;
    double time_ns;
};

/* One fixed situation: B moved along dir from A's position until the curves touch, then by gap more. */
SweepRow sweep_point(rugo_collide_context* ctx, const std::string& kind, const std::string& shapes, int n,
                     const rugo_shape* a, const rugo_shape* b, rugo_transform xa, rugo_transform xb,
                     rugo_vec2 from, rugo_vec2 dir, int expected, int reps) {
    const double gap = 1e-7;
    const double d = touching(ctx, a, xa, b, xb, from, dir) + gap;
    xb.p = rugo_v2(from.x + d * dir.x, from.y + d * dir.y);
    const rugo_contact_query q = make_query(0, 2.0 * gap);
    static rugo_contact c[kCap];
    rugo_contact_output out = rugo_contact_output_of(c, kCap);
    rugo_collide_shapes(a, xa, b, xb, &q, ctx, &out);
    const rugo_query_stats qs = out.stats;
    SweepRow r;
    r.kind = kind;
    r.shapes = shapes;
    r.n = n;
    r.expected = expected;
    r.contacts = qs.contacts_found;
    r.boxes = qs.box_tests;
    r.pairs = qs.segment_pairs;
    double best = HUGE_VAL; /* best single query */
    for (int rep = 0; rep < reps; ++rep) {
        const double t0 = now_ns();
        rugo_collide_shapes(a, xa, b, xb, &q, ctx, &out);
        best = std::min(best, now_ns() - t0);
    }
    r.time_ns = best;
    return r;
}

/* One hard case: librugo (finest, margin D) and the baseline at m vertices against the reference. */
struct HardRow {
    std::string name;
    int state;
    Metrics rugo, poly;
    long regions;
};

HardRow hard_case(rugo_collide_context* ctx, const std::string& name, const Body& A, rugo_transform xa,
                  const Body& B, rugo_transform xb, int m, long* unrefined) {
    HardRow h;
    h.name = name;
    PoseRef pr;
    reference(A, xa, B, xb, pr, unrefined);
    h.regions = pr.regions;
    std::vector<Cnt> got;
    rugo_query_stats qs;
    rugo_contacts(ctx, A, xa, B, xb, 0, got, &qs);
    evaluate(pr, got, h.rugo);
    const rugo_contact_query q = make_query(0, kWindow);
    rugo_contact_output out = rugo_contact_output_of(nullptr, 0); /* the state only */
    rugo_collide_shapes(A.shape, xa, B.shape, xb, &q, ctx, &out);
    h.state = (int)out.state;
    PolyBody pa, pb;
    build_poly(A.pts, m, true, pa);
    build_poly(B.pts, m, true, pb);
    if (pa.ok && pb.ok) {
        /* the polygons live in each body's frame; Box2D gets the poses in floats */
        const b2Transform ba = b2xf(xa), bb = b2xf(xb);
        std::vector<std::pair<int, int>> pl;
        box2d_pairs(pa, ba, pb, bb, pl);
        got.clear();
        int sink = 0;
        for (const auto& p : pl)
            box2d_collide(pa, ba, pb, bb, p.first, p.second, &got, &sink);
        evaluate(pr, got, h.poly);
    } else {
        h.poly.finite = false;
    }
    return h;
}

/* --ray-casts: see the top of the file. Returns the exit status. */
int bench_ray_casts(bool quick) {
    const int n = 4096, rays = quick ? 200 : 4000, batches = quick ? 1 : 5;
    rugo_shape* s = make_shape(bean_points(n), nullptr);
    if (s == nullptr) return 1;
    rugo_rng rng;
    rugo_rng_seed(&rng, 20261130);
    std::vector<rugo_vec2> o((size_t)rays), d((size_t)rays);
    for (int i = 0; i < rays; ++i) {
        const double th = rugo_rng_range(&rng, 0.0, 2.0 * kPi);
        o[(size_t)i] = rugo_v2(1.5 * std::cos(th), 1.5 * std::sin(th));
        const rugo_vec2 target = rugo_v2(rugo_rng_range(&rng, -0.5, 0.5), rugo_rng_range(&rng, -0.5, 0.5));
        d[(size_t)i] = rugo_v2_sub(target, o[(size_t)i]);
    }
    std::printf("method,segments,level,rays,hits,ns_per_ray\n");
    int bad = 0;
    const int finest = rugo_shape_finest_level(s);
    for (int level = finest; level >= finest - 3; level -= 3) {
        rugo_contour c;
        rugo_shape_level(s, level, &c);
        std::vector<double> f_tree((size_t)rays, -1.0), f_all((size_t)rays, -1.0);
        int hits = 0;
        double best_tree = 1e300, best_all = 1e300; /* best of the batches: the least disturbed */
        for (int b = 0; b < batches; ++b) {
            double t0 = now_ns();
            hits = 0;
            for (int i = 0; i < rays; ++i) {
                bool found = false;
                rugo_shape_ray_cast(s, level, o[(size_t)i], d[(size_t)i], 2.0, &f_tree[(size_t)i], nullptr,
                                    nullptr, &found);
                hits += found;
            }
            double t1 = now_ns();
            for (int i = 0; i < rays; ++i)
                rugo_contour_ray_cast(c, o[(size_t)i], d[(size_t)i], 2.0, &f_all[(size_t)i], nullptr,
                                      nullptr);
            double t2 = now_ns();
            best_tree = std::min(best_tree, (t1 - t0) / rays);
            best_all = std::min(best_all, (t2 - t1) / rays);
        }
        for (int i = 0; i < rays; ++i)
            bad += std::memcmp(&f_tree[(size_t)i], &f_all[(size_t)i], sizeof(double)) != 0;
        std::printf("rugo_shape_ray_cast,%d,%d,%d,%d,%.0f\n", c.count, level, rays, hits, best_tree);
        std::printf("rugo_contour_ray_cast,%d,%d,%d,%d,%.0f\n", c.count, level, rays, hits, best_all);
        std::printf(
            "# ray casts on %d segments: %.0f ns through the tree, %.0f ns over all segments (%.0fx)\n",
            c.count, best_tree, best_all, best_all / best_tree);
    }
    rugo_shape_destroy(s);
    if (bad != 0)
        std::printf("FAIL: %d fractions differ between the tree and the pass over all segments\n", bad);
    return bad != 0 ? 1 : 0;
}

/* One pass of queries over the poses, in ns (its own function: a profiler can count it alone). */
__attribute__((noinline)) double time_poses(rugo_collide_context* ctx, const std::vector<Body>& bodies,
                                            const std::vector<Pose>& poses, const rugo_contact_query& q,
                                            rugo_contact* buf) {
    const double t0 = now_ns();
    for (const Pose& p : poses) {
        rugo_contact_output out = rugo_contact_output_of(buf, kCap);
        rugo_collide_shapes(bodies[(size_t)p.a].shape, p.xa, bodies[(size_t)p.b].shape, p.xb, &q, ctx, &out);
    }
    return now_ns() - t0;
}

/* The two subsets under their own names (noipa: not folded into one), so that a profiler can count either
 * alone (valgrind --tool=callgrind --toggle-collect='*time_smooth_poses*'). */
__attribute__((noipa)) double time_smooth_poses(rugo_collide_context* ctx, const std::vector<Body>& bodies,
                                                const std::vector<Pose>& poses, const rugo_contact_query& q,
                                                rugo_contact* buf) {
    return time_poses(ctx, bodies, poses, q, buf);
}

__attribute__((noipa)) double time_rough_poses(rugo_collide_context* ctx, const std::vector<Body>& bodies,
                                               const std::vector<Pose>& poses, const rugo_contact_query& q,
                                               rugo_contact* buf) {
    return time_poses(ctx, bodies, poses, q, buf);
}

/* Warm queries (rugo_contact_output.cache): each pose's cache filled at the pose, then B moved relative
 * to A by one 1/60 s step of a speed v (size units per second, in a seeded direction) and a turn rate w;
 * the queries at the moved poses timed with their caches (warm) and without (cold), alternating, median
 * of the passes; the warm answers checked against the cold ones (state, separations within delta). */
int warm_queries(rugo_collide_context* ctx, const std::vector<Body>& bodies, const std::vector<Pose>& poses,
                 bool quick) {
    const rugo_contact_query q = make_query(0, kWindow);
    const size_t P = poses.size();
    std::vector<rugo_contact_cache*> caches(P, nullptr);
    for (auto& c : caches)
        rugo_contact_cache_create(nullptr, kCap, &c);
    static rugo_contact cbuf[kCap], wbuf[kCap];
    std::printf("# warm queries at level 0, resolution %g (size 1), margin %g; %zu poses\n", g_resolution,
                kWindow, P);
    std::printf("%-14s %10s %10s %8s %8s %12s %s\n", "v, w (1/s)", "cold ns", "warm ns", "cold/warm",
                "reused", "max |ds|", "state differs");
    const double speeds[][2] = {{1.0, 1.0}, {0.1, 0.1}, {0.01, 0.01}, {0.001, 0.001}, {0.0, 0.0}};
    for (const auto& vw : speeds) {
        rugo_rng rng;
        rugo_rng_seed(&rng, 20261128);
        std::vector<Pose> moved = poses;
        for (Pose& p : moved) {
            const double th = rugo_rng_range(&rng, 0.0, 2.0 * kPi), dt = 1.0 / 60.0;
            p.xb.p = rugo_v2(p.xb.p.x + vw[0] * dt * std::cos(th), p.xb.p.y + vw[0] * dt * std::sin(th));
            p.xb.q = rugo_rot_from_angle(std::atan2(p.xb.q.s, p.xb.q.c) + vw[1] * dt);
        }
        std::vector<double> cold_t, warm_t;
        long reused = 0, differs = 0;
        double max_ds = 0.0;
        const int reps = quick ? 1 : 7;
        for (int rep = 0; rep < reps; ++rep) {
            for (size_t i = 0; i < P; ++i) { /* the caches, at the step's start (not timed) */
                rugo_contact_cache_clear(caches[i]);
                rugo_contact_output out = rugo_contact_output_of(cbuf, kCap);
                out.cache = caches[i];
                rugo_collide_shapes(bodies[(size_t)poses[i].a].shape, poses[i].xa,
                                    bodies[(size_t)poses[i].b].shape, poses[i].xb, &q, ctx, &out);
            }
            double t0 = now_ns();
            for (size_t i = 0; i < P; ++i) {
                rugo_contact_output out = rugo_contact_output_of(cbuf, kCap);
                rugo_collide_shapes(bodies[(size_t)moved[i].a].shape, moved[i].xa,
                                    bodies[(size_t)moved[i].b].shape, moved[i].xb, &q, ctx, &out);
            }
            cold_t.push_back(now_ns() - t0);
            t0 = now_ns();
            for (size_t i = 0; i < P; ++i) {
                rugo_contact_output out = rugo_contact_output_of(wbuf, kCap);
                out.cache = caches[i];
                rugo_collide_shapes(bodies[(size_t)moved[i].a].shape, moved[i].xa,
                                    bodies[(size_t)moved[i].b].shape, moved[i].xb, &q, ctx, &out);
            }
            warm_t.push_back(now_ns() - t0);
        }
        /* the answers: warm (the caches now hold the moved poses' searches where they searched, so
         * refill them at the step's start first) against cold */
        for (size_t i = 0; i < P; ++i) {
            rugo_contact_cache_clear(caches[i]);
            rugo_contact_output out = rugo_contact_output_of(cbuf, kCap);
            out.cache = caches[i];
            rugo_collide_shapes(bodies[(size_t)poses[i].a].shape, poses[i].xa,
                                bodies[(size_t)poses[i].b].shape, poses[i].xb, &q, ctx, &out);
            rugo_contact_output w = rugo_contact_output_of(wbuf, kCap);
            w.cache = caches[i];
            rugo_collide_shapes(bodies[(size_t)moved[i].a].shape, moved[i].xa,
                                bodies[(size_t)moved[i].b].shape, moved[i].xb, &q, ctx, &w);
            rugo_contact_output c = rugo_contact_output_of(cbuf, kCap);
            rugo_collide_shapes(bodies[(size_t)moved[i].a].shape, moved[i].xa,
                                bodies[(size_t)moved[i].b].shape, moved[i].xb, &q, ctx, &c);
            reused += w.stats.reused;
            differs += w.state != c.state;
            for (int k = 0; k < c.count; ++k) { /* each cold contact against the warm one nearest its point */
                double best = HUGE_VAL, bd = HUGE_VAL;
                for (int j = 0; j < w.count; ++j) {
                    const double d = std::hypot(cbuf[k].point_a.x - wbuf[j].point_a.x,
                                                cbuf[k].point_a.y - wbuf[j].point_a.y);
                    if (d < bd) {
                        bd = d;
                        best = std::fabs(cbuf[k].separation - wbuf[j].separation);
                    }
                }
                if (w.count > 0) max_ds = std::max(max_ds, best);
            }
        }
        std::sort(cold_t.begin(), cold_t.end());
        std::sort(warm_t.begin(), warm_t.end());
        const double c = cold_t[cold_t.size() / 2] / (double)P, w = warm_t[warm_t.size() / 2] / (double)P;
        std::printf("%5.3f, %5.3f   %10.0f %10.0f %8.2fx %7.1f%% %12.2e %ld\n", vw[0], vw[1], c, w, c / w,
                    100.0 * (double)reused / (double)P, max_ds, differs);
    }
    for (auto& c : caches)
        rugo_contact_cache_destroy(c);
    rugo_collide_context_destroy(ctx);
    for (auto& b : bodies)
        rugo_shape_destroy(b.shape);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false, strip = true, contacts_hash = false, ray_casts = false, warm = false;
    const char* dir = "out/bench_queries";
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0)
            quick = true;
        else if (std::strcmp(argv[i], "--contacts-hash") == 0)
            contacts_hash = true;
        else if (std::strcmp(argv[i], "--ray-casts") == 0)
            ray_casts = true;
        else if (std::strcmp(argv[i], "--warm") == 0)
            warm = true;
        else if (std::strcmp(argv[i], "--resolution") == 0 && i + 1 < argc)
            g_resolution = std::atof(argv[++i]);
        else if (std::strcmp(argv[i], "--band-adjusted") == 0)
            g_rule = RUGO_CONTACT_BAND_ADJUSTED;
        else if (std::strcmp(argv[i], "--hm") == 0)
            strip = false;            /* the baseline with ear clipping + Hertel-Mehlhorn pieces only */
        else if (argv[i][0] == '-') { /* an unknown option, --help included: not a directory name */
            std::fprintf(
                stderr,
                "usage: %s [--quick] [--hm] [OUTDIR] | --contacts-hash [--quick] | --ray-casts [--quick]; "
                "[--resolution D] for the rugo methods (default 0)\n",
                argv[0]);
            std::fprintf(
                stderr,
                "usage: %s [--quick] [--hm] [OUTDIR] | --contacts-hash [--quick] | --warm; [--resolution D] "
                "[--band-adjusted] for the rugo methods (default 0, the thesis rule)\n",
                argv[0]);
            return 2;
        } else
            dir = argv[i];
    }
    if (ray_casts) return bench_ray_casts(quick);
    if (sample_mkdir(dir) != 0) {
        std::fprintf(stderr, "cannot create %s\n", dir);
        return 1;
    }
    const int poses_per_kind = quick ? 2 : 40;
    const int reps = quick ? 1 : 15;
    const std::vector<int> ms =
        quick ? std::vector<int>{16, 64, 256} : std::vector<int>{16, 32, 64, 128, 256, 512, 1024, 2048, 4096};
    const std::vector<int> levels = {0, -1, -2, -3};

    /* ---- shapes ---- */
    std::vector<Body> bodies(4);
    bool ok = make_smooth(bodies[0], "ellipse", ellipse_points(256)) &&
              make_smooth(bodies[1], "bean", bean_points(256)) &&
              make_rough(bodies[2], "ellipse_rough", ellipse_points(64), 11) &&
              make_rough(bodies[3], "bean_rough", bean_points(64), 12);
    if (!ok) return 1;
    const int kinds[6][2] = {{0, 0}, {0, 1}, {1, 1}, {2, 2}, {2, 3}, {3, 3}};

    rugo_collide_context* ctx = nullptr;
    if (rugo_collide_context_create(nullptr, &ctx) != RUGO_OK) return 1;

    /* ---- poses ---- */
    rugo_rng rng;
    rugo_rng_seed(&rng, 20261207);
    std::vector<Pose> poses;
    for (int k = 0; k < 6; ++k)
        for (int i = 0; i < poses_per_kind; ++i) {
            Pose p;
            p.a = kinds[k][0];
            p.b = kinds[k][1];
            p.xa = rugo_make_transform(0.0, 0.0, rugo_rng_range(&rng, 0.0, 2.0 * kPi));
            p.xb = rugo_make_transform(0.0, 0.0, rugo_rng_range(&rng, 0.0, 2.0 * kPi));
            const double th = rugo_rng_range(&rng, 0.0, 2.0 * kPi);
            const rugo_vec2 u = rugo_v2(std::cos(th), std::sin(th));
            const double gap = rugo_rng_range(&rng, -0.002, 0.002);
            const double d =
                touching(ctx, bodies[(size_t)p.a].shape, p.xa, bodies[(size_t)p.b].shape, p.xb, p.xa.p, u);
            p.xb.p = rugo_v2((d + gap) * u.x, (d + gap) * u.y);
            poses.push_back(p);
        }
    const size_t P = poses.size();

    if (warm) return warm_queries(ctx, bodies, poses, quick);

    if (contacts_hash) {
        for (const Body& b : bodies) { /* what a resolution may coarsen to: each level's certified error */
            std::printf("# %s level errors:", b.name.c_str());
            for (int j = rugo_shape_finest_level(b.shape); j >= rugo_shape_coarsest_level(b.shape); --j) {
                double e = 0.0;
                rugo_shape_level_error(b.shape, j, nullptr, &e);
                std::printf(" %d:%.1e", j, e);
            }
            std::printf("\n");
        }
        for (int L : levels) {
            const rugo_contact_query q = make_query(L, kWindow);
            static rugo_contact cbuf[kCap];
            std::uint64_t h = SAMPLE_FNV_OFFSET, hs = SAMPLE_FNV_OFFSET; /* all poses; the smooth ones */
            long work[2][2] = {{0, 0}, {0, 0}}; /* [smooth, rough][box tests, segment pairs] */
            for (size_t i = 0; i < P; ++i) {
                const bool smooth = !bodies[(size_t)poses[i].a].rough;
                rugo_contact_output out = rugo_contact_output_of(cbuf, kCap);
                rugo_collide_shapes(bodies[(size_t)poses[i].a].shape, poses[i].xa,
                                    bodies[(size_t)poses[i].b].shape, poses[i].xb, &q, ctx, &out);
                const int n = out.count;
                work[smooth ? 0 : 1][0] += out.stats.box_tests;
                work[smooth ? 0 : 1][1] += out.stats.segment_pairs;
                const int head[2] = {(int)out.state, n};
                h = sample_fnv1a(h, head, sizeof head);
                if (smooth) hs = sample_fnv1a(hs, head, sizeof head);
                for (int k = 0; k < n; ++k) { /* field by field: padding bytes are not part of the answer */
                    const rugo_contact& c = cbuf[k];
                    const double reals[] = {c.point_a.x,  c.point_a.y,   c.point_b.x,   c.point_b.y,
                                            c.normal.x,   c.normal.y,    c.separation,  c.t_a,
                                            c.t_b,        c.tolerance_a, c.tolerance_b, c.friction,
                                            c.restitution};
                    const int ints[] = {c.segment_a, c.segment_b, c.level_a, c.level_b, c.region};
                    h = sample_fnv1a(h, reals, sizeof reals);
                    h = sample_fnv1a(h, ints, sizeof ints);
                    h = sample_fnv1a(h, &c.id, sizeof c.id);
                    if (smooth) {
                        hs = sample_fnv1a(hs, reals, sizeof reals);
                        hs = sample_fnv1a(hs, ints, sizeof ints);
                        hs = sample_fnv1a(hs, &c.id, sizeof c.id);
                    }
                }
            }
            /* and the time per query (best of 5 passes over the poses; a quick look, not the benchmark) */
            std::vector<Pose> smooth_poses, rough_poses;
            for (const Pose& p : poses)
                (bodies[(size_t)p.a].rough ? rough_poses : smooth_poses).push_back(p);
            double best_s = HUGE_VAL, best_r = HUGE_VAL;
            for (int rep = 0; rep < 5; ++rep) {
                best_s = std::min(best_s, time_smooth_poses(ctx, bodies, smooth_poses, q, cbuf));
                best_r = std::min(best_r, time_rough_poses(ctx, bodies, rough_poses, q, cbuf));
            }
            std::printf("contacts_hash level %d: %016llx (%zu poses; smooth ones %016llx; ns per query: "
                        "%.0f, smooth %.0f, rough %.0f)\n",
                        L, (unsigned long long)h, P, (unsigned long long)hs, (best_s + best_r) / (double)P,
                        best_s / (double)smooth_poses.size(), best_r / (double)rough_poses.size());
            std::printf(
                "#   per query: box tests %.0f smooth, %.0f rough; segment pairs %.1f smooth, %.1f rough\n",
                (double)work[0][0] / (double)smooth_poses.size(),
                (double)work[1][0] / (double)rough_poses.size(),
                (double)work[0][1] / (double)smooth_poses.size(),
                (double)work[1][1] / (double)rough_poses.size());
        }
        rugo_collide_context_destroy(ctx);
        for (auto& b : bodies)
            rugo_shape_destroy(b.shape);
        return 0;
    }

    /* ---- reference ---- */
    std::vector<PoseRef> ref(P);
    long unrefined = 0, required_regions = 0, poses_without_required = 0;
    for (size_t i = 0; i < P; ++i) {
        reference(bodies[(size_t)poses[i].a], poses[i].xa, bodies[(size_t)poses[i].b], poses[i].xb, ref[i],
                  &unrefined);
        int req = 0;
        for (double sm : ref[i].smin)
            req += sm <= 0.5 * kWindow;
        required_regions += req;
        poses_without_required += req == 0;
    }
    std::printf("# %zu poses, %ld reference regions with s <= D/2 (D = %g), %ld minima left unrefined\n", P,
                required_regions, kWindow, unrefined);

    /* Subsets: 0 all poses, 1 smooth pairs, 2 rough pairs. Each method is evaluated per pose and timed
     * per subset (all = the sum of the two halves' best times). */
    const char* subset_name[3] = {"all", "smooth", "rough"};
    std::vector<size_t> idx[3];
    for (size_t i = 0; i < P; ++i) {
        idx[0].push_back(i);
        idx[bodies[(size_t)poses[i].a].rough ? 2 : 1].push_back(i);
    }
    std::vector<Row> rows[3];
    std::vector<Cnt> got;
    got.reserve(1024);
    /* run(i, out, pairs): one query on pose i; out and pairs may be null (timing). */
    auto measure = [&](const std::string& method, int param,
                       const std::function<void(size_t, std::vector<Cnt>*, long*)>& run) {
        Row r[3];
        long pairs[3] = {0, 0, 0};
        for (int k = 0; k < 3; ++k) {
            r[k].method = method;
            r[k].param = param;
        }
        for (size_t i = 0; i < P; ++i) {
            long np = 0;
            got.clear();
            run(i, &got, &np);
            const int sub = bodies[(size_t)poses[i].a].rough ? 2 : 1;
            evaluate(ref[i], got, r[0].m);
            evaluate(ref[i], got, r[sub].m);
            pairs[0] += np;
            pairs[sub] += np;
        }
        /* Poses in groups of 4: each group's best time over the repetitions, summed. On a shared machine
         * a short group has a good chance to run undisturbed in some repetition; a whole pass has not. */
        double best[3] = {0.0, 0.0, 0.0};
        for (int k = 1; k < 3; ++k) {
            const size_t G = 4, groups = (idx[k].size() + G - 1) / G;
            std::vector<double> gbest(groups, HUGE_VAL);
            for (int rep = 0; rep < reps; ++rep)
                for (size_t g = 0; g < groups; ++g) {
                    const double t0 = now_ns();
                    for (size_t j = g * G; j < std::min(idx[k].size(), (g + 1) * G); ++j)
                        run(idx[k][j], nullptr, nullptr);
                    gbest[g] = std::min(gbest[g], now_ns() - t0);
                }
            for (double t : gbest)
                best[k] += t;
        }
        best[0] = best[1] + best[2];
        for (int k = 0; k < 3; ++k) {
            const double cnt = (double)std::max<size_t>(1, idx[k].size());
            r[k].pairs = (double)pairs[k] / cnt;
            r[k].time_ns = best[k] / cnt;
            rows[k].push_back(r[k]);
        }
        return rows[0].back();
    };

    /* ---- librugo at each level ---- */
    for (int L : levels) {
        const rugo_contact_query q = make_query(L, kWindow);
        long boxes = 0;
        static rugo_contact cbuf[kCap];
        const Row& r = measure("rugo", L, [&](size_t i, std::vector<Cnt>* out, long* np) {
            const Body &A = bodies[(size_t)poses[i].a], &B = bodies[(size_t)poses[i].b];
            if (out) {
                rugo_query_stats qs;
                rugo_contacts(ctx, A, poses[i].xa, B, poses[i].xb, L, *out, &qs);
                *np = qs.segment_pairs;
                boxes += qs.box_tests;
                return;
            }
            rugo_contact_output o = rugo_contact_output_of(cbuf, kCap);
            rugo_collide_shapes(A.shape, poses[i].xa, B.shape, poses[i].xb, &q, ctx, &o);
        });
        std::printf("# rugo level %d: %.1f box tests, %.1f segment pairs per query\n", L,
                    (double)boxes / (double)P, r.pairs);
    }

    /* ---- brute force ---- */
    {
        std::vector<BruteSide> bs;
        for (const auto& b : bodies)
            bs.push_back(brute_side(b));
        std::vector<BruteScratch> scratch(bodies.size());
        for (size_t k = 0; k < bodies.size(); ++k)
            brute_prepare(bs[k], scratch[k]);
        measure("brute", 0, [&](size_t i, std::vector<Cnt>* out, long* np) {
            brute_contacts(bs[(size_t)poses[i].a], poses[i].xa, bs[(size_t)poses[i].b], poses[i].xb,
                           scratch[(size_t)poses[i].a], out ? out : &got, np);
        });
    }

    /* ---- polygon baseline ---- */
    bool poly_ok = true;
    std::vector<std::pair<int, int>> pl;
    for (int m : ms) {
        std::vector<std::unique_ptr<PolyBody>> pb;
        long pieces = 0, piece_vertices = 0, strips = 0;
        for (const auto& b : bodies) {
            pb.emplace_back(new PolyBody());
            build_poly(b.pts, m, strip, *pb.back());
            strips += pb.back()->strip;
            poly_ok &= pb.back()->ok;
            pieces += (long)pb.back()->pieces.size();
            for (const auto& pc : pb.back()->pieces)
                piece_vertices += pc.m_count;
        }
        if (!poly_ok) {
            std::fprintf(stderr, "polygon decomposition failed at m = %d\n", m);
            break;
        }
        std::vector<std::vector<std::pair<int, int>>> lists(P);
        for (size_t i = 0; i < P; ++i)
            box2d_pairs(*pb[(size_t)poses[i].a], b2xf(poses[i].xa), *pb[(size_t)poses[i].b],
                        b2xf(poses[i].xb), lists[i]);
        int sink = 0;
        const Row& r = measure("box2d", m, [&](size_t i, std::vector<Cnt>* out, long* np) {
            const PolyBody &A = *pb[(size_t)poses[i].a], &B = *pb[(size_t)poses[i].b];
            const b2Transform xa = b2xf(poses[i].xa), xb = b2xf(poses[i].xb);
            box2d_pairs(A, xa, B, xb, pl);
            if (np) *np = (long)pl.size();
            std::vector<Cnt>* o = out ? out : &got;
            o->clear();
            for (const auto& pr : pl)
                box2d_collide(A, xa, B, xb, pr.first, pr.second, o, &sink);
        });
        measure("box2d_narrow", m, [&](size_t i, std::vector<Cnt>* out, long* np) {
            const PolyBody &A = *pb[(size_t)poses[i].a], &B = *pb[(size_t)poses[i].b];
            const b2Transform xa = b2xf(poses[i].xa), xb = b2xf(poses[i].xb);
            if (np) *np = (long)lists[i].size();
            std::vector<Cnt>* o = out ? out : &got;
            o->clear();
            for (const auto& pr : lists[i])
                box2d_collide(A, xa, B, xb, pr.first, pr.second, o, &sink);
        });
        std::printf("# box2d m = %d: %.1f convex pieces per shape (%.2f vertices each; %ld of %zu shapes by "
                    "the strip "
                    "decomposition, the others by ear clipping + Hertel-Mehlhorn), %.1f b2CollidePolygons "
                    "calls per query\n",
                    m, (double)pieces / (double)bodies.size(), (double)piece_vertices / (double)pieces,
                    strips, bodies.size(), r.pairs);
    }

    /* ---- output ---- */
    char path[1200];
    const char* header = "method,param,pairs,time_ns_per_query,max_sep_err,mean_sep_err,max_point_err,"
                         "max_normal_err_rad,missed,spurious\n";
    bool io_ok = true;
    for (int k = 0; k < 3; ++k) {
        std::snprintf(path, sizeof path, k == 0 ? "%s/bench_queries.csv" : "%s/bench_queries_%s.csv", dir,
                      subset_name[k]);
        FILE* csv = std::fopen(path, "w");
        if (!csv) return 1;
        std::fputs(header, csv);
        if (k == 0) std::fputs(header, stdout);
        for (const auto& r : rows[k]) {
            print_row(csv, r);
            if (k == 0) print_row(stdout, r);
        }
        io_ok &= std::fclose(csv) == 0;
    }

    /* Pareto front per method and subset: the configurations no other configuration of the same
     * method beats in both time and effective max separation error. */
    std::snprintf(path, sizeof path, "%s/bench_queries_pareto.csv", dir);
    FILE* par = std::fopen(path, "w");
    if (!par) return 1;
    std::fprintf(par, "subset,method,param,time_ns_per_query,effective_max_sep_err\n");
    std::printf("# Pareto front (time against effective max separation error, per method)\n");
    for (int k = 0; k < 3; ++k)
        for (const auto& r : rows[k]) {
            bool dominated = false;
            for (const auto& o : rows[k])
                if (&o != &r && o.method == r.method && o.time_ns <= r.time_ns && eff_err(o) <= eff_err(r) &&
                    (o.time_ns < r.time_ns || eff_err(o) < eff_err(r)))
                    dominated = true;
            if (dominated) continue;
            std::fprintf(par, "%s,%s,%d,%.0f,%.3e\n", subset_name[k], r.method.c_str(), r.param, r.time_ns,
                         eff_err(r));
            if (k == 0)
                std::printf("# pareto %s %d: %.0f ns, %.3e\n", r.method.c_str(), r.param, r.time_ns,
                            eff_err(r));
        }
    io_ok &= std::fclose(par) == 0;

    /* ---- sweep ---- */
    std::vector<SweepRow> sweep;
    {
        const std::vector<int> ns = quick ? std::vector<int>{32, 64, 128, 256}
                                          : std::vector<int>{32, 64, 128, 256, 512, 1024, 2048, 4096};
        const int sreps = quick ? 3 : 60;
        for (int n : ns) {
            for (int pair = 0; pair < 2; ++pair) {
                rugo_shape* a = make_shape(pair == 0 ? ellipse_points(n) : bean_points(n), nullptr);
                rugo_shape* b = make_shape(pair == 0 ? ellipse_points(n) : bean_points(n), nullptr);
                if (!a || !b) return 1;
                const rugo_transform xa = rugo_make_transform(0.0, 0.0, 0.3);
                const rugo_transform xb = rugo_make_transform(0.0, 0.0, 2.0);
                const rugo_vec2 u = rugo_v2(std::cos(0.7), std::sin(0.7));
                sweep.push_back(sweep_point(ctx, "segments", pair == 0 ? "ellipse-ellipse" : "bean-bean", n,
                                            a, b, xa, xb, xa.p, u, 1, sreps));
                rugo_shape_destroy(a);
                rugo_shape_destroy(b);
            }
        }
        /* 34 teeth, so that even the widest slab (32 teeth) is narrower than the comb: equal widths
         * would put the walls on each other when the slab starts inside the comb, and coincident
         * curves are CONTACT, not INTERSECTING (contacts.md), which the bisection relies on */
        const int teeth = 34, nc = 1024;
        const double pitch = 0.03;
        rugo_shape* comb = make_shape(comb_points(teeth, pitch, 0.01, 16, 0.3, nc), nullptr);
        if (!comb) return 1;
        const std::vector<int> ks = quick ? std::vector<int>{1, 2, 4} : std::vector<int>{1, 2, 4, 8, 16, 32};
        for (int k : ks) {
            rugo_shape* slab = make_shape(slab_points(k * pitch, 0.1, nc), nullptr);
            if (!slab) return 1;
            /* under the middle k teeth (tips at x = -W/2 + (i + 1/2) pitch) */
            const int first = (teeth - k) / 2;
            const double xc = -0.5 * teeth * pitch + (first + 0.5 * k) * pitch;
            const rugo_transform xa = rugo_identity_transform();
            const rugo_transform xb = rugo_identity_transform();
            sweep.push_back(sweep_point(ctx, "contacts", "comb-slab", nc, comb, slab, xa, xb,
                                        rugo_v2(xc, 0.0), rugo_v2(0.0, -1.0), k, sreps));
            rugo_shape_destroy(slab);
        }
        rugo_shape_destroy(comb);
    }
    std::snprintf(path, sizeof path, "%s/bench_queries_sweep.csv", dir);
    FILE* sw = std::fopen(path, "w");
    if (!sw) return 1;
    std::fprintf(
        sw, "kind,shapes,segments,expected_contacts,contacts,box_tests,segment_pairs,time_ns_per_query\n");
    std::printf(
        "# sweep: "
        "kind,shapes,segments,expected_contacts,contacts,box_tests,segment_pairs,time_ns_per_query\n");
    for (const auto& s : sweep) {
        std::fprintf(sw, "%s,%s,%d,%d,%d,%ld,%ld,%.0f\n", s.kind.c_str(), s.shapes.c_str(), s.n, s.expected,
                     s.contacts, s.boxes, s.pairs, s.time_ns);
        std::printf("# sweep %s,%s,%d,%d,%d,%ld,%ld,%.0f\n", s.kind.c_str(), s.shapes.c_str(), s.n,
                    s.expected, s.contacts, s.boxes, s.pairs, s.time_ns);
    }
    io_ok &= std::fclose(sw) == 0;

    /* ---- hard cases ---- */
    std::vector<HardRow> hard;
    {
        const int mh = quick ? 256 : 1024;
        auto place = [&](const Body& A, rugo_transform xa, const Body& B, rugo_transform xb, rugo_vec2 u,
                         double gap) {
            const double d = touching(ctx, A.shape, xa, B.shape, xb, xa.p, u) + gap;
            xb.p = rugo_v2(xa.p.x + d * u.x, xa.p.y + d * u.y);
            return xb;
        };
        const Body &E = bodies[0], &ER = bodies[2];
        const rugo_transform x0 = rugo_make_transform(0.0, 0.0, 0.0),
                             x90 = rugo_make_transform(0.0, 0.0, 0.5 * kPi);
        const rugo_vec2 ux = rugo_v2(1.0, 0.0);
        hard.push_back(hard_case(ctx, "near-tangent, gap 1e-9", E, x0, E, place(E, x0, E, x90, ux, 1e-9), mh,
                                 &unrefined));
        hard.push_back(hard_case(ctx, "near-tangent, gap 1e-12", E, x0, E, place(E, x0, E, x90, ux, 1e-12),
                                 mh, &unrefined));
        hard.push_back(hard_case(ctx, "overlap 1e-9 (two close crossings)", E, x0, E,
                                 place(E, x0, E, x90, ux, -1e-9), mh, &unrefined));
        hard.push_back(hard_case(ctx, "rough on rough, gap 1e-9", ER, x0, ER,
                                 place(ER, x0, ER, x90, ux, 1e-9), mh, &unrefined));
        const rugo_transform far = rugo_make_transform(1000.0, -1000.0, 0.3);
        rugo_transform farb = far;
        farb.q = rugo_rot_from_angle(1.9);
        hard.push_back(hard_case(ctx, "1000 m from the origin, gap 1e-6", E, far, E,
                                 place(E, far, E, farb, rugo_v2(0.6, 0.8), 1e-6), mh, &unrefined));
        Body s1, s2;
        std::vector<rugo_vec2> p1 = slab_points(1.0, 0.2, 256), p2 = slab_points(0.6, 0.2, 256);
        normalise(p1);
        normalise(p2);
        if (make_smooth(s1, "slab", p1) && make_smooth(s2, "slab2", p2)) {
            hard.push_back(hard_case(ctx, "parallel straight sides, gap 1e-6", s1, x0, s2,
                                     place(s1, x0, s2, x0, rugo_v2(0.0, 1.0), 1e-6), mh, &unrefined));
            rugo_shape_destroy(s1.shape);
            rugo_shape_destroy(s2.shape);
        }
        std::snprintf(path, sizeof path, "%s/bench_queries_hard.csv", dir);
        FILE* hf = std::fopen(path, "w");
        if (!hf) return 1;
        std::fprintf(
            hf,
            "case,state,regions,rugo_max_sep_err,rugo_max_normal_err_rad,rugo_missed,rugo_spurious,box2d_m,"
            "box2d_max_sep_err,box2d_max_normal_err_rad,box2d_missed,box2d_spurious\n");
        std::printf(
            "# hard cases (librugo finest; box2d m = %d): case,state,regions,rugo sep err,normal err,missed,"
            "spurious | box2d sep err,normal err,missed,spurious\n",
            mh);
        for (const auto& h : hard) {
            std::fprintf(hf, "%s,%s,%ld,%.3e,%.3e,%ld,%ld,%d,%.3e,%.3e,%ld,%ld\n", h.name.c_str(),
                         rugo_contact_state_name((rugo_contact_state)h.state), h.regions, h.rugo.max_sep,
                         h.rugo.max_nrm, h.rugo.missed, h.rugo.spurious, mh, h.poly.max_sep, h.poly.max_nrm,
                         h.poly.missed, h.poly.spurious);
            std::printf("# hard %s: %s, %ld region(s); rugo %.2e, %.2e rad, %ld, %ld | box2d %.2e, %.2e rad, "
                        "%ld, %ld\n",
                        h.name.c_str(), rugo_contact_state_name((rugo_contact_state)h.state), h.regions,
                        h.rugo.max_sep, h.rugo.max_nrm, h.rugo.missed, h.rugo.spurious, h.poly.max_sep,
                        h.poly.max_nrm, h.poly.missed, h.poly.spurious);
        }
        io_ok &= std::fclose(hf) == 0;
    }

    /* ---- summary ---- */
    const Row* fin = nullptr;
    for (const auto& r : rows[0])
        if (r.method == "rugo" && r.param == 0) fin = &r;
    for (int k = 0; k < 3; ++k) {
        std::printf(k == 0 ? "summary:" : "# summary (%s pairs):", subset_name[k]);
        const double targets[2] = {1e-3, 1e-5}, goals[2] = {2.0, 10.0};
        for (int t = 0; t < 2; ++t) {
            const Row* rr = rugo_fastest_at(rows[k], targets[t]);
            if (!rr) {
                std::printf(" at %.0e: no librugo level reaches it;", targets[t]);
                continue;
            }
            double m_at = 0.0, m_at_n = 0.0;
            const double tb = baseline_time_at(rows[k], "box2d", targets[t], &m_at);
            const double tbn = baseline_time_at(rows[k], "box2d_narrow", targets[t], &m_at_n);
            if (tb < 0.0) {
                /* The baseline never got there. If its error still falls with m, the trend of its last
                 * two m values extrapolates; if it has a floor, "equal error" is out of its reach and the
                 * ratio against its largest m is only a lower bound. */
                const Row *last = nullptr, *lowest = nullptr;
                for (const auto& r : rows[k])
                    if (r.method == "box2d") {
                        if (!last || r.param > last->param) last = &r;
                        if (!lowest || eff_err(r) < eff_err(*lowest)) lowest = &r;
                    }
                const double lower = last->time_ns / rr->time_ns;
                std::printf(" at %.0e: rugo level %d %.0f ns; box2d does not reach it with m <= %d (its "
                            "smallest max error "
                            "is %.1e, at m = %d; at m = %d it takes %.0f ns, ratio %.2fx) (goal %.0fx: %s);",
                            targets[t], rr->param, rr->time_ns, last->param, eff_err(*lowest), lowest->param,
                            last->param, last->time_ns, lower, goals[t],
                            lower >= goals[t]
                                ? "met: no m tried reaches that error, and the largest is that much slower"
                                : "not shown");
                continue;
            }
            const double ratio = tb / rr->time_ns;
            std::printf(" at %.0e: rugo level %d %.0f ns vs box2d m~%.0f %.0f ns = %.2fx (goal %.0fx: %s; vs "
                        "box2d_narrow "
                        "m~%.0f %.0f ns: %.2fx);",
                        targets[t], rr->param, rr->time_ns, m_at, tb, ratio, goals[t],
                        ratio >= goals[t] ? "met" : "not met", m_at_n, tbn, tbn / rr->time_ns);
        }
        const Row* f = nullptr;
        for (const auto& r : rows[k])
            if (r.method == "rugo" && r.param == 0) f = &r;
        if (f)
            std::printf(" librugo finest max separation error %.1e of the size (%s both targets)\n",
                        f->m.max_sep, eff_err(*f) <= 1e-5 ? "beats" : "misses");
        else
            std::printf("\n");
    }

    /* ---- checks ---- */
    sample_expect("files written", io_ok);
    sample_expect("polygon decomposition succeeded for every m", poly_ok);
    sample_expect("every pose has a reference region with s <= D/2", poses_without_required == 0);
    bool finite = true;
    for (const auto& r : rows[0])
        finite &= r.m.finite && std::isfinite(r.time_ns) && r.time_ns > 0.0;
    sample_expect("every method ran with finite contacts and times", finite);
    const Row* brute = nullptr;
    for (const auto& r : rows[0])
        if (r.method == "brute") brute = &r;
    if (fin) {
        sample_expect("finest level: no missed contact", fin->m.missed == 0);
        sample_expect("finest level: no spurious contact", fin->m.spurious == 0);
        sample_expect_le("finest level: max separation error (size 1)", fin->m.max_sep, 1e-9);
        sample_expect_le("finest level: max normal error [rad]", fin->m.max_nrm, 1e-6);
        sample_expect_le("finest level: max point error (size 1)", fin->m.max_pt, 1e-5);
    }
    if (brute) {
        sample_expect("brute force: no missed or spurious contact",
                      brute->m.missed == 0 && brute->m.spurious == 0);
        sample_expect_le("brute force: max separation error", brute->m.max_sep, 1e-9);
        if (fin)
            sample_expect("brute force runs more narrow-phase pairs than the tree",
                          brute->pairs >= fin->pairs);
    }
    for (const auto& r : rows[0])
        if (r.method == "rugo" && r.param < 0) {
            char name[160];
            std::snprintf(name, sizeof name, "level %d: separation error / (beta_A + beta_B) of the contact",
                          r.param);
            sample_expect_le(name, r.m.max_bound_ratio, 1.0);
        }
    {
        const Row *lo = nullptr, *hi = nullptr;
        for (const auto& r : rows[0])
            if (r.method == "box2d") {
                if (!lo || r.param < lo->param) lo = &r;
                if (!hi || r.param > hi->param) hi = &r;
            }
        if (lo && hi) {
            sample_expect_le("box2d: max separation error falls with m (largest m / m = 16)",
                             hi->m.max_sep / lo->m.max_sep, 0.5);
            sample_expect_le("box2d: mean separation error falls with m (largest m / m = 16)",
                             (hi->m.sum_sep / (double)std::max(1L, hi->m.n_sep)) /
                                 (lo->m.sum_sep / (double)std::max(1L, lo->m.n_sep)),
                             0.1);
            sample_expect("box2d: no missed contact at the finest m", hi->m.missed == 0);
        }
    }
    long min_box = -1, max_box = -1;
    int min_n = 0, max_n = 0;
    bool counts = true;
    long pairs_k1 = -1, pairs_kmax = -1;
    int kmax = 0;
    double max_pairs_per_contact = 0.0;
    for (const auto& s : sweep) {
        counts &= s.contacts == s.expected;
        if (s.kind == "segments" && s.shapes == "ellipse-ellipse") {
            if (min_n == 0 || s.n < min_n) {
                min_n = s.n;
                min_box = s.boxes;
            }
            if (s.n > max_n) {
                max_n = s.n;
                max_box = s.boxes;
            }
        }
        if (s.kind == "contacts") {
            max_pairs_per_contact = std::max(max_pairs_per_contact, (double)s.pairs / s.expected);
            if (s.expected == 1) pairs_k1 = s.pairs;
            if (s.expected > kmax) {
                kmax = s.expected;
                pairs_kmax = s.pairs;
            }
        }
    }
    sample_expect("sweep: every situation has its expected number of contacts", counts);
    if (min_box > 0 && max_box > 0)
        sample_expect_le("sweep: box-test growth / segment growth (ellipses)",
                         ((double)max_box / (double)min_box) / ((double)max_n / (double)min_n), 0.5);
    if (pairs_k1 > 0 && pairs_kmax > 0) {
        sample_expect_le("sweep: segment pairs per contact (comb on slabs)", max_pairs_per_contact, 8.0);
        sample_expect_le("sweep: at least one more segment pair per extra contact", (double)(kmax - 1),
                         (double)(pairs_kmax - pairs_k1));
    }
    bool hard_ok = !hard.empty();
    for (const auto& h : hard)
        hard_ok &= h.rugo.finite && h.rugo.missed == 0 && h.rugo.spurious == 0 && h.rugo.max_sep <= 1e-9 &&
                   h.regions > 0;
    sample_expect("hard cases: librugo finest finds every region, nothing spurious, separation within 1e-9",
                  hard_ok);
    for (auto& b : bodies)
        rugo_shape_destroy(b.shape);
    rugo_collide_context_destroy(ctx);
    return sample_finish();
}
