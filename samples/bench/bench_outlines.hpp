/* Outlines (control points) for the resolution benchmarks (bench_accuracy, bench_hard_cases): smooth,
 * concave, straight, sharp-cornered, bowl-like and roughened shapes of size ~1. Header-only. */
#ifndef RUGO_BENCH_OUTLINES_HPP
#define RUGO_BENCH_OUTLINES_HPP

#include "rugo/rugo.h"

extern "C" {
#include "sample_shapes.h"
}

#include <cmath>
#include <cstdint>
#include <vector>

namespace bench_outlines {

const double kPi = 3.14159265358979323846;

inline std::vector<rugo_vec2> ellipse_pts(int n, double a, double b) {
    std::vector<rugo_vec2> p((size_t)n);
    for (int k = 0; k < n; ++k) {
        const double th = 2.0 * kPi * k / n;
        p[(size_t)k] = rugo_v2(a * std::cos(th), b * std::sin(th));
    }
    return p;
}

/* Control points on a circle such that the curve passes through radius r at the joints. */
inline std::vector<rugo_vec2> disc_pts(int n, double r) {
    const double rho = r * 6.0 / (4.0 + 2.0 * std::cos(2.0 * kPi / n));
    return ellipse_pts(n, rho, rho);
}

inline std::vector<rugo_vec2> star_pts(int n, double r, double k, int arms) {
    std::vector<rugo_vec2> p((size_t)n);
    for (int i = 0; i < n; ++i) {
        const double th = 2.0 * kPi * i / n, rr = r * (1.0 + k * std::cos(arms * th));
        p[(size_t)i] = rugo_v2(rr * std::cos(th), rr * std::sin(th));
    }
    return p;
}

inline std::vector<rugo_vec2> bean_pts(int n, double r) {
    std::vector<rugo_vec2> p((size_t)n);
    sample_object(n, rugo_v2(0.0, 0.0), r, p.data());
    return p;
}

/* n points at equal spacing along a closed polyline (counter-clockwise), the first at its first vertex. */
inline std::vector<rugo_vec2> along_polyline(const std::vector<rugo_vec2>& v, int n) {
    std::vector<double> cum(v.size() + 1, 0.0);
    for (size_t i = 0; i < v.size(); ++i) {
        const rugo_vec2 a = v[i], b = v[(i + 1) % v.size()];
        cum[i + 1] = cum[i] + std::hypot(b.x - a.x, b.y - a.y);
    }
    std::vector<rugo_vec2> p((size_t)n);
    size_t e = 0;
    for (int k = 0; k < n; ++k) {
        const double s = cum.back() * k / n;
        while (e + 1 < v.size() && cum[e + 1] <= s)
            ++e;
        const rugo_vec2 a = v[e], b = v[(e + 1) % v.size()];
        const double w = (s - cum[e]) / (cum[e + 1] - cum[e]);
        p[(size_t)k] = rugo_v2(a.x + w * (b.x - a.x), a.y + w * (b.y - a.y));
    }
    return p;
}

/* A box w x h with rounded corners: n points at equal spacing, corners among them when the spacing
 * divides the sides (straight segments where four consecutive points are collinear). */
inline std::vector<rugo_vec2> rbox_pts(int n, double w, double h) {
    return along_polyline(
        {rugo_v2(-w / 2, -h / 2), rugo_v2(w / 2, -h / 2), rugo_v2(w / 2, h / 2), rugo_v2(-w / 2, h / 2)}, n);
}

/* A polygon with sharp corners: vertex k repeated mult[k] times, `inner` equally spaced points on each
 * side between the vertices. */
inline std::vector<rugo_vec2> sharp_pts(const std::vector<rugo_vec2>& v, const std::vector<int>& mult,
                                        int inner) {
    std::vector<rugo_vec2> p;
    for (size_t k = 0; k < v.size(); ++k) {
        for (int m = 0; m < mult[k]; ++m)
            p.push_back(v[k]);
        const rugo_vec2 a = v[k], b = v[(k + 1) % v.size()];
        for (int i = 1; i <= inner; ++i) {
            const double w = (double)i / (inner + 1);
            p.push_back(rugo_v2(a.x + w * (b.x - a.x), a.y + w * (b.y - a.y)));
        }
    }
    return p;
}

/* Appends `count` points at equal arc-length spacing along the open polyline `poly`, its ends excluded
 * (the bay blocks close their rims this way). */
inline void append_along_open_polyline(const std::vector<rugo_vec2>& poly, int count,
                                       std::vector<rugo_vec2>& p) {
    std::vector<double> cum(poly.size(), 0.0);
    for (size_t i = 1; i < poly.size(); ++i)
        cum[i] = cum[i - 1] + std::hypot(poly[i].x - poly[i - 1].x, poly[i].y - poly[i - 1].y);
    size_t e = 0;
    for (int k = 1; k <= count; ++k) {
        const double s = cum.back() * k / (count + 1);
        while (e + 2 < poly.size() && cum[e + 1] <= s)
            ++e;
        const double w = (s - cum[e]) / (cum[e + 1] - cum[e]);
        p.push_back(rugo_v2(poly[e].x + w * (poly[e + 1].x - poly[e].x),
                            poly[e].y + w * (poly[e + 1].y - poly[e].y)));
    }
}

/* A bowl: a block whose top has a circular bay of (curve) radius rb about the origin, 25 control points
 * at spacing 2π/64 on the bay (the disc's spacing), the rest (n - 25) along the block's other sides. */
inline std::vector<rugo_vec2> bowl_pts(int n, double rb) {
    const int arc = 25;
    const double al = 2.0 * kPi / 64.0, rho = rb * 6.0 / (4.0 + 2.0 * std::cos(al));
    std::vector<rugo_vec2> p;
    const double a0 = -kPi / 2 + 12 * al; /* right rim; the bay runs clockwise about its centre */
    for (int k = 0; k < arc; ++k)
        p.push_back(rugo_v2(rho * std::cos(a0 - k * al), rho * std::sin(a0 - k * al)));
    const rugo_vec2 left = p.back(), right = p.front();
    const double W = 0.8, H = 0.9;
    /* the rest: left rim, left side, bottom, right side, right rim (open polyline from left to right) */
    std::vector<rugo_vec2> poly = {left,           rugo_v2(-W, left.y), rugo_v2(-W, -H),
                                   rugo_v2(W, -H), rugo_v2(W, right.y), right};
    append_along_open_polyline(poly, n - arc, p);
    return p;
}

/* A roughened outline: `base` (count a power of two) roughened by two wavelet levels with tipo_3 x amp
 * details (geometry), seeded. */
inline std::vector<rugo_vec2> rough_pts(const std::vector<rugo_vec2>& base, double amp, uint64_t seed) {
    const int n0 = (int)base.size();
    std::vector<double> lam0((size_t)n0);
    rugo_tolerances_preset(RUGO_PRESET_TIPO_3, 0, n0, lam0.data());
    for (auto& v : lam0)
        v *= amp;
    std::vector<rugo_vec2> out((size_t)(n0 << 2));
    rugo_roughen_def d = rugo_default_roughen_def();
    d.points = base.data();
    d.count = n0;
    d.tolerances = lam0.data();
    d.method = RUGO_ROUGHEN_WAVELET;
    d.levels = 2;
    d.seed = seed;
    if (rugo_roughen(&d, out.data()) != RUGO_OK) out.clear();
    return out;
}

} // namespace bench_outlines

#endif
