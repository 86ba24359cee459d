/* Hard cases of the contact queries at a resolution (issue 20): conforming curves, where the work of a
 * query certified to round-off has no bound, timed against the resolution δ (rugo_contact_query.resolution).
 *
 * Usage: bench_hard_cases [--quick] [--repeats N] [OUTDIR]     (default OUTDIR out/bench_hard_cases)
 *
 * Cases (shapes of size ~1; "size" below is the smaller root box's diagonal, the size
 * RUGO_RESOLUTION_AUTO takes 1e-4 of; every case also translated by (6e5, 8e5), 1e6 from the origin):
 *  - disc_in_disc: a disc (128 control points on a circle of radius 0.5) resting in a block whose bay is
 *    the same disc's control points scaled by 1.0005 about its centre (a disc inside a disc 0.05 % larger,
 *    a wheel in a matching groove): the bay's curve is the disc's curve scaled exactly (B-splines are
 *    affine invariant). The disc sits 2.5e-4 × 0.5 − 1e-6 × size below the bay's centre, so the gap at the
 *    bottom is 1e-6 × size; both curves carry a constant band of 5e-4 × size (query.tolerance), so the
 *    whole bay (where the gap grows to ~2.5e-4) lies within the summed bands: a conforming stretch.
 *  - coincident_discs: two identical discs at the same pose, band 5e-4 × size.
 *  - coincident_rough: two identical roughened outlines (256 segments, tipo_5 bands varying along the
 *    curve) at the same pose, their own bands.
 *  - box_on_box: a block (corners of four coincident control points) lying on a slab, flat faces 1e-7 ×
 *    size apart, margin 1e-5 × size.
 *  - gear_in_gear: a 16-tooth gear (256 control points) in a block whose bay is the gear's own control
 *    points scaled by 1.0005, teeth in mesh, band 5e-4 × size.
 *  - concentric_arcs: a disc in a deep bay (270 degrees of arc) of radius 1 + 1e-4 times its own, its
 *    centre 3e-5 × radius off the bay's: two long nearly concentric arcs, band 5e-4 × size.
 *
 * Timing: the cases are run in turn (alternating, so that a disturbance of the shared machine spreads
 * over all of them), each query timed alone (CLOCK_MONOTONIC); µs/query is the median over the repeats
 * (default 9; the sweep 5). Resolutions: RUGO_RESOLUTION_AUTO (the default δ), 1e-6 × size, 0 (round-off,
 * the answers before issue 20), and the sweep δ = 1e-2 … 1e-9 × size. The goals (issue 20) are printed
 * with PASS/FAIL per case: ≤ 100 µs at the default δ, ≤ 1 ms at 1e-6 × size, and the cost growing no
 * faster than δ^-1/2 over the sweep (the slope of log cost against log 1/δ, least squares over 1e-2 … 1e-9
 * and from 1e-6 to 1e-9, both ≤ 0.5 + 0.1).
 *
 * Checks (the same in the full run and in --quick, the test sample_bench_hard_cases; none on a time), each
 * at the default δ and at 1e-6 × size, with the round-off allowance ε = 1e-12 × size + 8 ulp of the
 * translation (the relative pose of two far bodies is rounded at that scale):
 *  - every query returns RUGO_OK and a state other than APART, with at least one contact;
 *  - disc_in_disc: the smallest separation is the analytic 1.0005 ρ_b − ρ_b − o within δ + ε, where ρ_b
 *    is the disc curve's own radius at its bottom point (a control point lies below the centre, and the
 *    control points are mirror symmetric about the vertical, so the bottom point is at x = 0);
 *  - coincident_discs: every contact's separation is 0 within δ + ε, so its band-adjusted separation is
 *    −(λ_A + λ_B) within δ + ε;
 *  - coincident_rough: every contact's separation is 0 within δ + ε, and the smallest band-adjusted
 *    separation is at most −2 max_k λ_k + δ + ε (the interpolated band reaches its knots' values, and a
 *    band-adjusted contact sits where the bands reach farthest);
 *  - box_on_box: every contact's separation is the gap 1e-7 × size within δ + ε;
 *  - gear_in_gear, concentric_arcs: the smallest separation is that of the round-off query (δ = 0) within
 *    δ + ε.
 *
 * Output: OUTDIR/bench_hard_cases.csv (case,far,delta_rel,delta,us_median,us_min,repeats,state,contacts,
 * min_separation,box_tests,segment_pairs,newton_iterations,fallbacks; delta_rel -1 = RUGO_RESOLUTION_AUTO),
 * the tables on stdout; scripts/plot_benchmarks.py draws bench_hard_cases.svg from it. */
#include "rugo/rugo.h"

extern "C" {
#include "sample_check.h"
}

#include "bench_outlines.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <vector>

namespace {

using namespace bench_outlines;

const double kFarX = 6e5, kFarY = 8e5; /* 1e6 from the origin */
const double kAuto = -1.0;             /* delta_rel of the RUGO_RESOLUTION_AUTO rows */

double now_ns() {
    timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
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
        std::fprintf(stderr, "rugo_shape_create (%d points): %s\n", d.count, rugo_status_string(st));
        return nullptr;
    }
    return s;
}

double root_size(const rugo_shape* s) {
    const rugo_obb* b = rugo_mobb_tree_root(rugo_shape_tree(s));
    return 2.0 * std::hypot(b->half[0], b->half[1]);
}

/* n control points on a circle of radius rho, the first at the bottom (angle -π/2), mirror symmetric
 * about the vertical axis bit for bit. */
std::vector<rugo_vec2> disc_bottom(int n, double rho) {
    std::vector<rugo_vec2> p((size_t)n);
    for (int k = 0; k <= n / 2; ++k) {
        const double th = 2.0 * kPi * k / n;
        const double x = rho * std::sin(th), y = -rho * std::cos(th);
        p[(size_t)k] = rugo_v2(x, y);
        if (k > 0 && k < n - k) p[(size_t)(n - k)] = rugo_v2(-x, y);
    }
    p[0].x = 0.0;
    if (n % 2 == 0) p[(size_t)(n / 2)].x = 0.0;
    return p;
}

/* A gear: n control points on r(θ) = R (1 + a cos(teeth θ)), the first at the bottom. */
std::vector<rugo_vec2> gear_bottom(int n, double R, double a, int teeth) {
    std::vector<rugo_vec2> p((size_t)n);
    for (int k = 0; k < n; ++k) {
        const double th = -kPi / 2 + 2.0 * kPi * k / n, r = R * (1.0 + a * std::cos(teeth * (th + kPi / 2)));
        p[(size_t)k] = rugo_v2(r * std::cos(th), r * std::sin(th));
    }
    return p;
}

/* A block of n control points (a power of two) whose top is a bay: the control points of `body`
 * (counter-clockwise, the first at the bottom) from index +half down to -half scaled by `scale` about the
 * origin (clockwise about the bay's centre: the block's boundary seen from the disc), closed by flat tops at
 * the rims' heights and a rectangle W wide reaching down to -H, the rest of the n points at equal spacing
 * along it. */
std::vector<rugo_vec2> bay_block(const std::vector<rugo_vec2>& body, int half, double scale, double W,
                                 double H, int n) {
    const int nb = (int)body.size();
    std::vector<rugo_vec2> p;
    for (int k = half; k >= -half; --k) {
        const rugo_vec2 q = body[(size_t)((k + nb) % nb)];
        p.push_back(rugo_v2(scale * q.x, scale * q.y));
    }
    const rugo_vec2 left = p.back(), right = p.front();
    const std::vector<rugo_vec2> poly = {left,           rugo_v2(-W, left.y), rugo_v2(-W, -H),
                                         rugo_v2(W, -H), rugo_v2(W, right.y), right};
    bench_outlines::append_along_open_polyline(poly, n - (int)p.size(), p);
    return p;
}

enum Check {
    CHECK_ANALYTIC_MIN,
    CHECK_COINCIDENT,
    CHECK_COINCIDENT_BANDS,
    CHECK_FLAT,
    CHECK_AGAINST_ROUNDOFF
};

struct Case {
    std::string name;
    rugo_shape* a = nullptr;
    rugo_shape* b = nullptr;
    rugo_transform xa, xb;
    bool far = false;
    double size = 0;
    double tolerance = -1; /* query.tolerance (-1: the shapes' own bands) */
    double margin = 0;
    Check check = CHECK_AGAINST_ROUNDOFF;
    double expected = 0; /* analytic separation (CHECK_ANALYTIC_MIN, CHECK_FLAT) or -2 max λ_k */
    double roundoff_min = 0;
};

struct Result {
    rugo_status status = RUGO_OK;
    rugo_contact_state state = RUGO_STATE_APART;
    int count = 0;
    double min_sep = 0, min_band = 0, max_abs_sep = 0, max_flat_err = 0;
    rugo_query_stats stats = {};
};

std::vector<rugo_contact> g_buf(4096);

Result query(rugo_collide_context* ctx, const Case& c, double delta_rel, double* ns) {
    rugo_contact_query q = rugo_default_contact_query();
    q.lod = 0;
    q.resolution = delta_rel == kAuto ? RUGO_RESOLUTION_AUTO : delta_rel * c.size;
    q.tolerance = c.tolerance;
    q.margin = c.margin;
    rugo_contact_output out = rugo_contact_output_of(g_buf.data(), (int)g_buf.size());
    const double t0 = now_ns();
    Result r;
    r.status = rugo_collide_shapes(c.a, c.xa, c.b, c.xb, &q, ctx, &out);
    *ns = now_ns() - t0;
    r.state = out.state;
    r.count = out.count;
    r.stats = out.stats;
    r.min_sep = 1e300;
    r.min_band = 1e300;
    for (int k = 0; k < out.count; ++k) {
        const rugo_contact& k_ = g_buf[(size_t)k];
        r.min_sep = std::min(r.min_sep, k_.separation);
        r.min_band = std::min(r.min_band, k_.separation - k_.tolerance_a - k_.tolerance_b);
        r.max_abs_sep = std::max(r.max_abs_sep, std::fabs(k_.separation));
        r.max_flat_err = std::max(r.max_flat_err, std::fabs(k_.separation - c.expected));
    }
    return r;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

struct Timed {
    Result r;
    double med_us = 0, min_us = 0;
    int repeats = 0;
};

/* Each case in turn, `repeats` times, at one resolution; a case whose query took over 0.2 s stops
 * repeating after three. */
std::vector<Timed> time_all(rugo_collide_context* ctx, const std::vector<Case>& cases, double delta_rel,
                            int repeats) {
    std::vector<std::vector<double>> t(cases.size());
    std::vector<Timed> out(cases.size());
    for (int rep = 0; rep < repeats; ++rep)
        for (size_t i = 0; i < cases.size(); ++i) {
            if (rep >= 3 && median(t[i]) > 2e8) continue;
            double ns = 0;
            out[i].r = query(ctx, cases[i], delta_rel, &ns);
            t[i].push_back(ns);
        }
    for (size_t i = 0; i < cases.size(); ++i) {
        out[i].med_us = median(t[i]) * 1e-3;
        out[i].min_us = *std::min_element(t[i].begin(), t[i].end()) * 1e-3;
        out[i].repeats = (int)t[i].size();
    }
    return out;
}

const char* state_str(rugo_contact_state s) { return rugo_contact_state_name(s); }

struct Opt {
    bool quick = false;
    int repeats = 9;
    std::string out = "out/bench_hard_cases";
};

/* The correctness properties of one query (see the top of this file); prints what fails. */
bool check(const Case& c, const Result& r, double delta_rel) {
    const double delta = delta_rel == kAuto ? 1e-4 * c.size : delta_rel * c.size;
    const double eps = 1e-12 * c.size + (c.far ? 8.0 * 0x1p-52 * std::hypot(kFarX, kFarY) : 0.0);
    const double tol = delta + eps;
    char what[200] = "";
    bool ok = r.status == RUGO_OK && r.state != RUGO_STATE_APART && r.count > 0;
    if (!ok)
        std::snprintf(what, sizeof what, "status %s, state %s, %d contacts", rugo_status_string(r.status),
                      state_str(r.state), r.count);
    double err = 0;
    if (ok) switch (c.check) {
        case CHECK_ANALYTIC_MIN:
            err = std::fabs(r.min_sep - c.expected);
            ok = err <= tol;
            std::snprintf(what, sizeof what, "smallest separation %.17g, analytic %.17g", r.min_sep,
                          c.expected);
            break;
        case CHECK_COINCIDENT:
            err = r.max_abs_sep;
            ok = err <= tol;
            std::snprintf(what, sizeof what, "largest |separation| %.3e of coincident curves", r.max_abs_sep);
            break;
        case CHECK_COINCIDENT_BANDS:
            err = r.max_abs_sep;
            ok = err <= tol && r.min_band <= c.expected + tol;
            std::snprintf(what, sizeof what,
                          "largest |separation| %.3e; smallest band-adjusted %.9g, bound %.9g", r.max_abs_sep,
                          r.min_band, c.expected);
            break;
        case CHECK_FLAT:
            err = r.max_flat_err;
            ok = err <= tol;
            std::snprintf(what, sizeof what, "largest |separation - gap| %.3e (gap %.3e)", r.max_flat_err,
                          c.expected);
            break;
        case CHECK_AGAINST_ROUNDOFF:
            err = std::fabs(r.min_sep - c.roundoff_min);
            ok = err <= tol;
            std::snprintf(what, sizeof what, "smallest separation %.17g, round-off query's %.17g", r.min_sep,
                          c.roundoff_min);
            break;
        }
    char name[160];
    std::snprintf(name, sizeof name, "%s%s at δ = %s: error %.3e <= δ + ε = %.3e", c.name.c_str(),
                  c.far ? " (far)" : "", delta_rel == kAuto ? "default" : "1e-6 × size", err, tol);
    if (!ok) std::printf("  %s\n", what);
    return sample_expect(name, ok) != 0;
}

} // namespace

int main(int argc, char** argv) {
    Opt opt;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick")
            opt.quick = true;
        else if (a == "--repeats" && i + 1 < argc)
            opt.repeats = std::max(1, std::atoi(argv[++i]));
        else if (!a.empty() && a[0] != '-')
            opt.out = a;
        else {
            std::fprintf(stderr, "usage: bench_hard_cases [--quick] [--repeats N] [OUTDIR]\n");
            return 2;
        }
    }
    if (opt.quick) opt.repeats = 1;

    /* shapes */
    const double rdisc = 0.5, grow = 1.0005;
    const int ndisc = 128;
    const double rho =
        rdisc * 6.0 / (4.0 + 2.0 * std::cos(2.0 * kPi / ndisc)); /* curve through r at joints */
    const std::vector<rugo_vec2> disc = disc_bottom(ndisc, rho);
    rugo_shape* s_disc = make_shape(disc, nullptr);
    rugo_shape* s_bay = make_shape(bay_block(disc, 24, grow, 0.8, 0.9, 128), nullptr);
    const std::vector<rugo_vec2> gear = gear_bottom(256, 0.5, 0.04, 16);
    rugo_shape* s_gear = make_shape(gear, nullptr);
    rugo_shape* s_gear_bay = make_shape(bay_block(gear, 48, grow, 0.8, 0.9, 256), nullptr);
    rugo_shape* s_deep = make_shape(bay_block(disc, 48, 1.0001, 0.8, 0.9, 256), nullptr);
    std::vector<rugo_vec2> rough = rough_pts(bean_pts(64, 0.45), 0.004, 20);
    std::vector<double> lam(rough.size());
    rugo_tolerances_preset(RUGO_PRESET_TIPO_5, 0, (int)lam.size(), lam.data());
    for (double& v : lam)
        v *= 0.01;
    rugo_shape* s_rough = make_shape(rough, &lam);
    rugo_shape* s_block = make_shape(
        sharp_pts({rugo_v2(-0.3, -0.15), rugo_v2(0.3, -0.15), rugo_v2(0.3, 0.15), rugo_v2(-0.3, 0.15)},
                  {4, 4, 4, 4}, 28),
        nullptr);
    rugo_shape* s_slab =
        make_shape(sharp_pts({rugo_v2(-1.0, -0.2), rugo_v2(1.0, -0.2), rugo_v2(1.0, 0.2), rugo_v2(-1.0, 0.2)},
                             {4, 4, 4, 4}, 60),
                   nullptr);
    if (!s_disc || !s_bay || !s_gear || !s_gear_bay || !s_deep || !s_rough || !s_block || !s_slab) {
        std::fprintf(stderr, "bench_hard_cases: a shape could not be created\n");
        return 2;
    }
    /* the disc curve's radius at its bottom point (u = 0: control points p[-1], p[0], p[1]) */
    rugo_contour dc;
    rugo_shape_level(s_disc, rugo_shape_finest_level(s_disc), &dc);
    const rugo_vec2 bottom = rugo_contour_point(dc, 0, 0.0);
    const double rho_b = -bottom.y;
    double lam_max = 0;
    {
        rugo_tolerance_level tl;
        rugo_shape_tolerance_level(s_rough, rugo_shape_finest_level(s_rough), &tl);
        for (int k = 0; k < tl.count; ++k)
            lam_max = std::max(lam_max, tl.total[k]);
    }

    std::vector<Case> cases;
    auto add = [&](const std::string& name, rugo_shape* a, rugo_transform xa, rugo_shape* b,
                   rugo_transform xb, double band_rel, double margin_rel, Check ck, double expected) {
        for (int far = 0; far < 2; ++far) {
            Case c;
            c.name = name;
            c.a = a;
            c.b = b;
            c.xa = xa;
            c.xb = xb;
            c.far = far != 0;
            if (c.far) {
                c.xa.p = rugo_v2(xa.p.x + kFarX, xa.p.y + kFarY);
                c.xb.p = rugo_v2(xb.p.x + kFarX, xb.p.y + kFarY);
            }
            c.size = std::min(root_size(a), root_size(b));
            c.tolerance = band_rel < 0 ? -1.0 : band_rel * c.size;
            c.margin = margin_rel * c.size;
            c.check = ck;
            c.expected = expected;
            cases.push_back(c);
        }
    };
    const rugo_transform I = rugo_identity_transform();
    const double size_disc = std::min(root_size(s_bay), root_size(s_disc));
    /* the disc below the bay's centre by o: gap at the bottom grow ρ_b − ρ_b − o = 1e-6 × size */
    const double gap_disc = 1e-6 * size_disc;
    const double o = (grow - 1.0) * rho_b - gap_disc;
    add("disc_in_disc", s_bay, I, s_disc, rugo_make_transform(0.0, -o, 0.0), 5e-4, 0.0, CHECK_ANALYTIC_MIN,
        (grow * rho_b - rho_b) - o);
    add("coincident_discs", s_disc, I, s_disc, I, 5e-4, 0.0, CHECK_COINCIDENT, 0.0);
    add("coincident_rough", s_rough, I, s_rough, I, -1.0, 0.0, CHECK_COINCIDENT_BANDS, -2.0 * lam_max);
    const double size_box = std::min(root_size(s_block), root_size(s_slab));
    add("box_on_box", s_slab, I, s_block, rugo_make_transform(0.1, 0.35 + 1e-7 * size_box, 0.0), -1.0, 1e-5,
        CHECK_FLAT, 1e-7 * size_box);
    add("gear_in_gear", s_gear_bay, I, s_gear,
        rugo_make_transform(0.0, -(grow - 1.0) * 0.5 * 0.96 + 1e-6, 0.0), 5e-4, 0.0, CHECK_AGAINST_ROUNDOFF,
        0.0);
    add("concentric_arcs", s_deep, I, s_disc, rugo_make_transform(1e-5 * rdisc, -3e-5 * rdisc, 0.0), 5e-4,
        0.0, CHECK_AGAINST_ROUNDOFF, 0.0);

    rugo_collide_context* ctx = nullptr;
    if (rugo_collide_context_create(nullptr, &ctx) != RUGO_OK) return 2;
    std::printf("bench_hard_cases: %s run, %d repeats (medians; cases alternating)\n",
                opt.quick ? "quick" : "full", opt.repeats);

    /* the round-off answers (δ = 0), the reference of two checks and the cost before issue 20 */
    const int rep0 = opt.quick ? 1 : std::min(opt.repeats, 3);
    const std::vector<Timed> t0 = time_all(ctx, cases, 0.0, rep0);
    for (size_t i = 0; i < cases.size(); ++i)
        cases[i].roundoff_min = t0[i].r.min_sep;
    const std::vector<Timed> tdef = time_all(ctx, cases, kAuto, opt.repeats);
    const std::vector<Timed> t6 = time_all(ctx, cases, 1e-6, opt.repeats);

    if (sample_mkdir(opt.out.c_str()) != 0) {
        std::fprintf(stderr, "cannot create %s\n", opt.out.c_str());
        return 2;
    }
    const std::string csv = opt.out + "/bench_hard_cases.csv";
    FILE* f = std::fopen(csv.c_str(), "w");
    if (!f) return 2;
    std::fprintf(f,
                 "case,far,delta_rel,delta,us_median,us_min,repeats,state,contacts,min_separation,box_tests,"
                 "segment_pairs,newton_iterations,fallbacks\n");
    auto row = [&](const Case& c, double dr, const Timed& t) {
        const double d = dr == kAuto ? 1e-4 * c.size : dr * c.size;
        std::fprintf(f, "%s,%d,%g,%.6e,%.3f,%.3f,%d,%s,%d,%.17g,%ld,%ld,%ld,%ld\n", c.name.c_str(),
                     c.far ? 1 : 0, dr, d, t.med_us, t.min_us, t.repeats, state_str(t.r.state), t.r.count,
                     t.r.count ? t.r.min_sep : 0.0, t.r.stats.box_tests, t.r.stats.segment_pairs,
                     t.r.stats.newton_iterations, t.r.stats.fallbacks);
    };

    std::printf("\nµs per query (median) and contacts; goals: <= 100 µs at the default δ (1e-4 × size), <= "
                "1000 µs at "
                "1e-6 × size\n");
    std::printf("%-18s %4s %12s %9s %12s %5s %9s %5s %12s %5s\n", "case", "far", "δ=0 µs", "contacts",
                "default µs", "goal", "contacts", "", "1e-6 µs", "goal");
    int pass_def = 0, pass_6 = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        const Case& c = cases[i];
        const bool gd = tdef[i].med_us <= 100.0, g6 = t6[i].med_us <= 1000.0;
        pass_def += gd;
        pass_6 += g6;
        std::printf("%-18s %4s %12.1f %9d %12.1f %5s %9d %5s %12.1f %5s\n", c.name.c_str(),
                    c.far ? "yes" : "no", t0[i].med_us, t0[i].r.count, tdef[i].med_us, gd ? "PASS" : "FAIL",
                    tdef[i].r.count, "", t6[i].med_us, g6 ? "PASS" : "FAIL");
        row(c, 0.0, t0[i]);
        row(c, kAuto, tdef[i]);
        row(c, 1e-6, t6[i]);
    }
    std::printf("goals met: %d of %zu cases at the default δ, %d of %zu at 1e-6 × size\n", pass_def,
                cases.size(), pass_6, cases.size());

    /* the sweep */
    if (!opt.quick) {
        const double sweep[8] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
        std::vector<std::vector<Timed>> ts;
        for (double dr : sweep)
            ts.push_back(time_all(ctx, cases, dr, std::max(3, opt.repeats / 2 + 1)));
        std::printf("\nsweep: µs per query (median) against δ / size; slope of log µs against log 1/δ (goal "
                    "<= 0.5)\n");
        std::printf("%-18s %4s", "case", "far");
        for (double dr : sweep)
            std::printf(" %8.0e", dr);
        std::printf(" %7s %6s %5s\n", "slope", "tail", "goal");
        int pass_slope = 0;
        for (size_t i = 0; i < cases.size(); ++i) {
            const Case& c = cases[i];
            std::printf("%-18s %4s", c.name.c_str(), c.far ? "yes" : "no");
            double sx = 0, sy = 0, sxx = 0, sxy = 0;
            for (size_t k = 0; k < 8; ++k) {
                const double x = std::log10(1.0 / sweep[k]), y = std::log10(std::max(ts[k][i].med_us, 1e-3));
                sx += x;
                sy += y;
                sxx += x * x;
                sxy += x * y;
                std::printf(" %8.1f", ts[k][i].med_us);
                row(c, sweep[k], ts[k][i]);
            }
            const double slope = (8 * sxy - sx * sy) / (8 * sxx - sx * sx);
            /* the tail: 1e-6 -> 1e-9 (three decades), where a growth faster than δ^-1/2 shows first */
            const double tail =
                std::log10(std::max(ts[7][i].med_us, 1e-3) / std::max(ts[4][i].med_us, 1e-3)) / 3.0;
            const bool ok = slope <= 0.6 && tail <= 0.6;
            pass_slope += ok;
            std::printf(" %7.2f %6.2f %5s\n", slope, tail, ok ? "PASS" : "FAIL");
        }
        std::printf("cost growing no faster than δ^-1/2 (slope over 1e-2..1e-9 and over 1e-6..1e-9 <= 0.5 + "
                    "0.1): %d of %zu cases\n",
                    pass_slope, cases.size());
    }
    std::fclose(f);
    std::printf("(%s written)\n\nchecks (correctness only, no time):\n", csv.c_str());
    for (size_t i = 0; i < cases.size(); ++i) {
        check(cases[i], tdef[i].r, kAuto);
        check(cases[i], t6[i].r, 1e-6);
    }
    rugo_collide_context_destroy(ctx);
    for (rugo_shape* s : {s_disc, s_bay, s_gear, s_gear_bay, s_deep, s_rough, s_block, s_slab})
        rugo_shape_destroy(s);
    return sample_finish();
}
