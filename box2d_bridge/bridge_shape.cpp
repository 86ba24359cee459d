// What the bridge derives once from a shape at a contact level, shared by the bodies that use it:
//  - the convex pieces whose polygons become the body's proxy fixtures (few and tight: one for a convex
//    outline, one per convex or concave run of a concave one, merged down to a cap), each enclosing
//    its run's curve and band at the contact level and every finer level, certified;
//  - the straight faces of each level from the contact level to the finest, which the patch builder
//    uses to give a flat contact its two ends.
#include "bridge_impl.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <new>
#include <vector>

namespace rugo {
namespace detail {

namespace {

using Poly = std::vector<rugo_vec2>;

double length(rugo_vec2 v) { return std::hypot(v.x, v.y); }

double cross(rugo_vec2 o, rugo_vec2 a, rugo_vec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Convex hull, counter-clockwise, no collinear points (Andrew's monotone chain).
Poly hull(Poly p) {
    std::sort(p.begin(), p.end(),
              [](rugo_vec2 a, rugo_vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    p.erase(
        std::unique(p.begin(), p.end(), [](rugo_vec2 a, rugo_vec2 b) { return a.x == b.x && a.y == b.y; }),
        p.end());
    if (p.size() < 3) return p;
    Poly h(2 * p.size());
    size_t k = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0.0)
            --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0.0)
            --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

rugo_vec2 lerpPoint(rugo_vec2 a, rugo_vec2 b, double t) {
    return rugo_v2(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y));
}

double area(const Poly& p) {
    double a = 0.0;
    for (size_t i = 0; i < p.size(); ++i) {
        const rugo_vec2 u = p[i], v = p[(i + 1) % p.size()];
        a += u.x * v.y - u.y * v.x;
    }
    return 0.5 * a;
}

// Where the lines through a1-a2 and b1-b2 meet; false if parallel.
bool meet(rugo_vec2 a1, rugo_vec2 a2, rugo_vec2 b1, rugo_vec2 b2, rugo_vec2* x) {
    const rugo_vec2 d = rugo_v2_sub(a2, a1), e = rugo_v2_sub(b2, b1);
    const double den = d.x * e.y - d.y * e.x;
    if (std::fabs(den) <= 1e-300) return false;
    const rugo_vec2 w = rugo_v2_sub(b1, a1);
    const double t = (w.x * e.y - w.y * e.x) / den;
    *x = rugo_v2(a1.x + t * d.x, a1.y + t * d.y);
    return true;
}

// Removes edges of a convex polygon (extending its neighbours to meet) until it has at most `most`
// vertices and no edge shorter than `minEdge`, each time the edge whose removal adds the least area.
// The result contains the input.
void reduce(Poly* p, size_t most, double minEdge) {
    for (;;) {
        const size_t m = p->size();
        if (m <= 3) return;
        bool shortEdge = false;
        for (size_t k = 0; k < m && !shortEdge; ++k)
            shortEdge = length(rugo_v2_sub((*p)[(k + 1) % m], (*p)[k])) < minEdge;
        if (m <= most && !shortEdge) return;
        // Edge k runs from vertex k to k + 1; removing it joins edge k - 1 (k - 1 -> k) and edge k + 1
        // (k + 1 -> k + 2) at their lines' meeting point, which must lie beyond edge k (they turn by less
        // than 180 degrees together).
        size_t best = m;
        double bestCost = DBL_MAX;
        rugo_vec2 bestX = rugo_v2(0, 0);
        for (size_t k = 0; k < m; ++k) {
            const rugo_vec2 a = (*p)[(k + m - 1) % m], b = (*p)[k], c = (*p)[(k + 1) % m],
                            d = (*p)[(k + 2) % m];
            const rugo_vec2 d1 = rugo_v2_sub(b, a), d2 = rugo_v2_sub(d, c);
            if (d1.x * d2.y - d1.y * d2.x <= 1e-14 * length(d1) * length(d2)) continue;
            rugo_vec2 x;
            if (!meet(a, b, c, d, &x)) continue;
            double cost = 0.5 * std::fabs(cross(b, x, c));
            // Short edges go first whatever they add (Box2D welds vertices closer than half a slop).
            if (length(rugo_v2_sub(c, b)) < minEdge) cost -= 1e30;
            if (cost < bestCost) {
                bestCost = cost;
                best = k;
                bestX = x;
            }
        }
        if (best == m) return;
        Poly q;
        for (size_t i = 0; i < m; ++i) {
            if (i == best) {
                q.push_back(bestX);
            } else if (i == (best + 1) % m) {
                continue;
            } else {
                q.push_back((*p)[i]);
            }
        }
        *p = q;
    }
}

// The convex polygon {x : n_k . x <= o_k}, clipped out of a box of half-size `big`.
Poly intersect(const std::vector<rugo_vec2>& n, const std::vector<double>& o, double big) {
    Poly p = {rugo_v2(-big, -big), rugo_v2(big, -big), rugo_v2(big, big), rugo_v2(-big, big)};
    for (size_t k = 0; k < n.size() && !p.empty(); ++k) {
        Poly q;
        for (size_t i = 0; i < p.size(); ++i) {
            const rugo_vec2 a = p[i], b = p[(i + 1) % p.size()];
            const double da = rugo_v2_dot(n[k], a) - o[k], db = rugo_v2_dot(n[k], b) - o[k];
            if (da <= 0.0) q.push_back(a);
            if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
                const double t = da / (da - db);
                q.push_back(rugo_v2(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)));
            }
        }
        p = q;
    }
    return p;
}

// Distance from p to a convex counter-clockwise polygon (0 inside), and the polygon's nearest edge (its
// start vertex index) or vertex (-1 - index).
double polyDistance(const Poly& poly, rugo_vec2 p, int* feature) {
    const size_t m = poly.size();
    bool inside = true;
    double best = DBL_MAX;
    *feature = 0;
    for (size_t k = 0; k < m; ++k) {
        const rugo_vec2 a = poly[k], b = poly[(k + 1) % m];
        if (cross(a, b, p) < 0.0) inside = false;
        const rugo_vec2 d = rugo_v2_sub(b, a), w = rugo_v2_sub(p, a);
        const double l2 = rugo_v2_dot(d, d);
        const double t = l2 > 0.0 ? std::min(1.0, std::max(0.0, rugo_v2_dot(w, d) / l2)) : 0.0;
        const double dist = std::hypot(w.x - t * d.x, w.y - t * d.y);
        if (dist < best) {
            best = dist;
            *feature = t <= 0.0 ? -1 - static_cast<int>(k)
                                : (t >= 1.0 ? -1 - static_cast<int>((k + 1) % m) : static_cast<int>(k));
        }
    }
    return inside ? 0.0 : best;
}

// A core polygon of at most 8 vertices with every point p_i within radius - reach_i of it, so that
// the core pushed out by `radius` holds every disc (p_i, reach_i) and so (the points being Bezier
// control points) every segment with its band. False if no such polygon fits Box2D's rules (3..8
// vertices, edges of at least two linear slops).
bool makeCore(const Poly& pts, const std::vector<double>& reach, double radius, Poly* out) {
    const double minEdge = 2.0 * static_cast<double>(b2_linearSlop);
    Poly h = hull(pts);
    if (h.size() < 3) return false;
    double extent = 0.0;
    for (const rugo_vec2& p : pts)
        extent = std::max(extent, std::fabs(p.x) + std::fabs(p.y));
    reduce(&h, b2_maxPolygonVertices, minEdge);
    const size_t m = h.size();
    std::vector<rugo_vec2> nrm(m);
    std::vector<double> off(m);
    for (size_t k = 0; k < m; ++k) {
        const rugo_vec2 d = rugo_v2_sub(h[(k + 1) % m], h[k]);
        const double l = length(d);
        nrm[k] = l > 0.0 ? rugo_v2(d.y / l, -d.x / l) : rugo_v2(0.0, 0.0);
        off[k] = -DBL_MAX;
        for (size_t i = 0; i < pts.size(); ++i)
            off[k] = std::max(off[k], rugo_v2_dot(nrm[k], pts[i]) - (radius - reach[i]));
    }
    // Each point is within its allowance of every edge's line; at the core's corners it may not be:
    // push the edges next to the nearest feature out by the shortfall until every point fits.
    const double big = 4.0 * (extent + radius) + 1.0;
    Poly core;
    for (int iter = 0; iter < 64; ++iter) {
        core = intersect(nrm, off, big);
        if (core.size() < 3) return false;
        bool fits = true;
        for (size_t i = 0; i < pts.size(); ++i) {
            int f = 0;
            const double lack = polyDistance(core, pts[i], &f) - (radius - reach[i]);
            if (lack <= 0.0) continue;
            fits = false;
            // The halfplanes whose lines pass through the nearest feature: one for an edge (its
            // midpoint), both for a vertex.
            const size_t fi = static_cast<size_t>(f >= 0 ? f : -1 - f);
            const rugo_vec2 a =
                f >= 0 ? rugo_v2_scale(0.5, rugo_v2_add(core[fi], core[(fi + 1) % core.size()])) : core[fi];
            for (size_t k = 0; k < m; ++k)
                if (std::fabs(rugo_v2_dot(nrm[k], a) - off[k]) <= 1e-9 * big) off[k] += lack * (1.0 + 1e-9);
        }
        if (fits) break;
    }
    reduce(&core, b2_maxPolygonVertices, minEdge);
    if (core.size() < 3 || area(core) < minEdge * minEdge) return false;
    for (size_t i = 0; i < pts.size(); ++i) {
        int f = 0;
        if (polyDistance(core, pts[i], &f) > radius - reach[i] + 1e-12 * big) return false;
    }
    *out = core;
    return true;
}

// Removes the corners of a convex counter-clockwise polygon that lie within `tol` of the chord of their
// neighbours, and returns by how much the polygon may have shrunk (the sum of their distances): Box2D
// 2.4's b2PolygonShape::Set wraps the hull in floats and can cycle between two nearly collinear
// corners (it then asserts; fuzz_bridge found one 4e-10 m off its chord), so no corner may be that flat.
double dropFlatCorners(Poly* p, double tol) {
    double shrink = 0.0;
    for (bool again = true; again && p->size() > 3;) {
        again = false;
        const size_t m = p->size();
        for (size_t k = 0; k < m; ++k) {
            const rugo_vec2 a = (*p)[(k + m - 1) % m], b = (*p)[k], c = (*p)[(k + 1) % m];
            const double chord = length(rugo_v2_sub(c, a));
            const double off = chord > 0.0 ? cross(a, b, c) / chord : 0.0;
            if (off < tol) {
                shrink += std::max(off, 0.0);
                p->erase(p->begin() + static_cast<std::ptrdiff_t>(k));
                again = true;
                break;
            }
        }
    }
    return shrink;
}

// How far the proxy (core pushed out by radius) reaches beyond the run's curve and band, sampled on its
// boundary: the mean distance of a boundary point to the nearest curve sample minus the band there
// (the mean, because the chord side of an open run may span a bay whatever the skin). For an open
// run, boundary points inside the shape do not count (the run's chord side lies inside).
double looseness(const Poly& core, double radius, const Poly& curve, const std::vector<double>& band,
                 const rugo_contour* inside) {
    double sum = 0.0;
    int count = 0;
    const size_t m = core.size();
    auto probe = [&](rugo_vec2 q) {
        if (inside != nullptr && rugo_contour_contains(*inside, q)) return;
        double d = DBL_MAX;
        for (size_t i = 0; i < curve.size(); ++i)
            d = std::min(d, length(rugo_v2_sub(q, curve[i])) - band[i]);
        sum += std::max(d, 0.0);
        ++count;
    };
    for (size_t k = 0; k < m; ++k) {
        const rugo_vec2 a = core[k], b = core[(k + 1) % m], c = core[(k + 2) % m];
        const rugo_vec2 d = rugo_v2_sub(b, a);
        const double l = length(d);
        if (!(l > 0.0)) continue;
        const rugo_vec2 n = rugo_v2(d.y / l, -d.x / l);
        for (int i = 0; i <= 8; ++i)
            probe(rugo_v2_add(lerpPoint(a, b, i / 8.0), rugo_v2_scale(radius, n)));
        // The rounded corner at b, between this edge's normal and the next one's.
        const rugo_vec2 e = rugo_v2_sub(c, b);
        const double le = length(e);
        if (!(le > 0.0)) continue;
        const rugo_vec2 n2 = rugo_v2(e.y / le, -e.x / le);
        for (int i = 1; i < 4; ++i) {
            rugo_vec2 u = lerpPoint(n, n2, i / 4.0);
            const double lu = length(u);
            if (lu > 0.0) probe(rugo_v2_add(b, rugo_v2_scale(radius / lu, u)));
        }
    }
    return count > 0 ? sum / count : 0.0;
}

// The piece's polygon: the core and skin radius (at least the largest band, and Box2D's polygon skin)
// whose proxy reaches least beyond the run's curve and band. A rounded outline wants a large skin
// around a small core, a boxy one a skin as small as its corners: Box2D's continuous collision stops
// a body where the two proxies' skins overlap by three linear slops, so a proxy much looser than that
// leaves the curves apart there.
bool enclose(const Poly& pts, const std::vector<double>& reach, double minRadius, const Poly& curve,
             const std::vector<double>& band, const rugo_contour* inside, Piece* out) {
    double extent = 0.0;
    rugo_vec2 lo = pts[0], hi = pts[0];
    for (const rugo_vec2& p : pts) {
        extent = std::max(extent, std::fabs(p.x) + std::fabs(p.y));
        lo = rugo_v2(std::min(lo.x, p.x), std::min(lo.y, p.y));
        hi = rugo_v2(std::max(hi.x, p.x), std::max(hi.y, p.y));
    }
    Poly best;
    double bestRadius = minRadius, bestLoose = DBL_MAX;
    const double most = 0.5 * std::min(hi.x - lo.x, hi.y - lo.y);
    for (double r = minRadius; r <= std::max(minRadius, most); r *= 1.4) {
        Poly core;
        if (!makeCore(pts, reach, r, &core)) continue;
        const double loose = looseness(core, r, curve, band, inside);
        if (loose < bestLoose - 1e-4) { // a larger skin only when it is clearly tighter
            bestLoose = loose;
            best = core;
            bestRadius = r;
        }
    }
    if (best.empty()) {
        // Too small or thin for a polygon of Box2D's: the points' bounding box, at least two slops wide,
        // with the smallest skin.
        const double minEdge = 2.0 * static_cast<double>(b2_linearSlop);
        const double cx = 0.5 * (lo.x + hi.x), cy = 0.5 * (lo.y + hi.y);
        const double hx = std::max(0.5 * (hi.x - lo.x), minEdge), hy = std::max(0.5 * (hi.y - lo.y), minEdge);
        best = {rugo_v2(cx - hx, cy - hy), rugo_v2(cx + hx, cy - hy), rugo_v2(cx + hx, cy + hy),
                rugo_v2(cx - hx, cy + hy)};
        bestRadius = minRadius;
    }
    // Flat corners go (see dropFlatCorners); the skin grows by what that cut off. The tolerance is far
    // above the float rounding of the corners (a relative 64 FLT_EPSILON of the extent).
    const double flatTol =
        std::max(1e-3 * static_cast<double>(b2_linearSlop), 64.0 * static_cast<double>(FLT_EPSILON) * extent);
    bestRadius += dropFlatCorners(&best, flatTol);
    out->n = static_cast<int>(best.size());
    for (int i = 0; i < out->n; ++i)
        out->v[i] = toB2(best[static_cast<size_t>(i)]);
    // Rounding the vertices to float must not shrink the enclosure: pad the skin by a relative 1e-6.
    out->radius = static_cast<float>(bestRadius + 1e-6 * (extent + bestRadius));
    return true;
}

// Turning angle of one segment of a contour (tangents at t = 0, 1/2, 1), radians, left positive.
double turning(rugo_contour c, int k) {
    const rugo_vec2 t0 = rugo_contour_tangent(c, k, 0.0), t1 = rugo_contour_tangent(c, k, 0.5),
                    t2 = rugo_contour_tangent(c, k, 1.0);
    return std::atan2(t0.x * t1.y - t0.y * t1.x, rugo_v2_dot(t0, t1)) +
           std::atan2(t1.x * t2.y - t1.y * t2.x, rugo_v2_dot(t1, t2));
}

// How far the run's sample points (joints and midpoints of segments [first, first + count) of c) lie
// inside the hull of those points: 0 for a convex run, the depth of a concavity otherwise.
double runDepth(rugo_contour c, int first, int count) {
    Poly s;
    for (int i = 0; i < count; ++i) {
        const int k = (first + i) % c.count;
        s.push_back(rugo_contour_point(c, k, 0.0));
        s.push_back(rugo_contour_point(c, k, 0.5));
    }
    if (count < c.count) s.push_back(rugo_contour_point(c, (first + count) % c.count, 0.0));
    const Poly h = hull(s);
    if (h.size() < 3) return 0.0;
    double depth = 0.0;
    for (const rugo_vec2& p : s) {
        double d = DBL_MAX;
        for (size_t k = 0; k < h.size(); ++k) {
            const rugo_vec2 a = h[k], b = h[(k + 1) % h.size()];
            const double l = length(rugo_v2_sub(b, a));
            if (l > 0.0) d = std::min(d, cross(a, b, p) / l);
        }
        depth = std::max(depth, d);
    }
    return depth;
}

// How often the contour's turning changes sign from segment to segment.
int signChanges(rugo_contour c) {
    int changes = 0;
    bool prev = turning(c, c.count - 1) < -1e-3;
    for (int k = 0; k < c.count; ++k) {
        const bool neg = turning(c, k) < -1e-3;
        changes += neg != prev;
        prev = neg;
    }
    return changes;
}

// The outline's runs at level Lp (segments [first, first + count)): single segments merged, pair by
// pair, where the merged run stays within `loose` of its hull, then further until at most maxPieces.
std::vector<std::pair<int, int>> runs(rugo_contour c, int maxPieces, double loose) {
    std::vector<std::pair<int, int>> r;
    // Start from the runs of one turning sign (so that merges never have to undo a concavity), then
    // agglomerate.
    const int n = c.count;
    std::vector<int> sign(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k)
        sign[static_cast<size_t>(k)] = turning(c, k) < -1e-3 ? -1 : 1;
    int start = 0;
    while (start < n && sign[static_cast<size_t>(start)] == sign[static_cast<size_t>((start + n - 1) % n)])
        ++start;
    if (start == n) {
        r.emplace_back(0, n);
    } else {
        for (int i = 0; i < n;) {
            const int first = (start + i) % n;
            int len = 1;
            while (i + len < n &&
                   sign[static_cast<size_t>((first + len) % n)] == sign[static_cast<size_t>(first)])
                ++len;
            r.emplace_back(first, len);
            i += len;
        }
    }
    while (r.size() > 1) {
        size_t best = r.size();
        double bestCost = DBL_MAX;
        for (size_t i = 0; i < r.size(); ++i) {
            const size_t j = (i + 1) % r.size();
            if (r.size() == 2 && i == 1) break; // the same pair twice
            const double cost = runDepth(c, r[i].first, r[i].second + r[j].second);
            if (cost < bestCost) {
                bestCost = cost;
                best = i;
            }
        }
        if (best == r.size() || (bestCost > loose && static_cast<int>(r.size()) <= maxPieces)) break;
        const size_t j = (best + 1) % r.size();
        r[best].second += r[j].second;
        r.erase(r.begin() + static_cast<std::ptrdiff_t>(j));
    }
    return r;
}

// The straight faces of one level (see Face).
void findFaces(rugo_contour c, LevelFaces* out) {
    const int n = c.count;
    out->faceOf.assign(static_cast<size_t>(n), -1);
    out->faces.clear();
    std::vector<char> straight(static_cast<size_t>(n), 0);
    auto tol = [](double len) { return std::min(1e-3, 5e-3 * len); };
    for (int k = 0; k < n; ++k) {
        rugo_vec2 b[4];
        rugo_contour_bezier(c, k, b);
        const rugo_vec2 d = rugo_v2_sub(b[3], b[0]);
        const double l = length(d);
        if (!(l > 0.0)) continue;
        const double e = tol(l);
        straight[static_cast<size_t>(k)] =
            std::fabs(cross(b[0], b[3], b[1])) / l <= e && std::fabs(cross(b[0], b[3], b[2])) / l <= e;
    }
    int start = 0;
    while (start < n && straight[static_cast<size_t>(start)])
        ++start;
    if (start == n) return; // every segment straight: a degenerate outline, no faces
    for (int i = 0; i < n;) {
        const int k = (start + i) % n;
        if (!straight[static_cast<size_t>(k)]) {
            ++i;
            continue;
        }
        // Extend while the next straight segment keeps every joint of the run on one line.
        Face f;
        f.first = k;
        f.joints.push_back(rugo_contour_point(c, k, 0.0));
        f.joints.push_back(rugo_contour_point(c, (k + 1) % n, 0.0));
        int len = 1;
        while (i + len < n && straight[static_cast<size_t>((k + len) % n)]) {
            const rugo_vec2 e = rugo_contour_point(c, (k + len + 1) % n, 0.0);
            const double l = length(rugo_v2_sub(e, f.joints[0]));
            bool on = l > 0.0;
            for (size_t j = 1; j < f.joints.size() && on; ++j)
                on = std::fabs(cross(f.joints[0], e, f.joints[j])) / l <= tol(l);
            if (!on) break;
            f.joints.push_back(e);
            ++len;
        }
        f.count = len;
        for (int j = 0; j < len; ++j)
            out->faceOf[static_cast<size_t>((k + j) % n)] = static_cast<int>(out->faces.size());
        out->faces.push_back(f);
        i += len;
    }
}

} // namespace

bool buildShapeData(const rugo_shape* s, int level, int maxPieces, ShapeData* out) {
    try {
        out->shape = s;
        out->level = level;
        out->maxPieces = maxPieces;
        out->friction = rugo_shape_friction_map(s);
        out->restitution = rugo_shape_restitution(s);
        const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
        out->faces.assign(static_cast<size_t>(J - level + 1), LevelFaces());
        for (int j = level; j <= J; ++j) {
            rugo_contour c;
            if (rugo_shape_level(s, j, &c) != RUGO_OK) return false;
            findFaces(c, &out->faces[static_cast<size_t>(j - level)]);
        }
        // Runs at the contact level, or at a coarser one when the outline turns back and forth too
        // often there for the agglomeration (quadratic in the runs) to stay cheap; the runs' looseness
        // is a heuristic, the enclosure below is certified for every level from the contact level down.
        int Lp = level;
        rugo_contour cp;
        for (;; --Lp) {
            if (rugo_shape_level(s, Lp, &cp) != RUGO_OK) return false;
            if (Lp <= Jmin || signChanges(cp) <= 64) break;
        }
        rugo_vec2 lo, hi;
        rugo_contour_bounds(cp, &lo, &hi);
        const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
        const std::vector<std::pair<int, int>> rs = runs(cp, maxPieces, std::min(0.01, 0.05 * extent));
        const int per = 1 << (level - Lp);
        const int nL = 1 << level;
        out->pieceOf.assign(static_cast<size_t>(nL), 0);
        out->pieces.clear();
        for (size_t r = 0; r < rs.size(); ++r) {
            Piece pc;
            pc.first = rs[r].first * per;
            pc.count = rs[r].second * per;
            for (int i = 0; i < pc.count; ++i)
                out->pieceOf[static_cast<size_t>((pc.first + i) % nL)] = static_cast<int>(r);
            // Every level from the contact level to the finest: the Bezier points of the run's segments,
            // each with the certified largest band of its segment.
            Poly pts;
            std::vector<double> reach;
            double most = 0.0;
            for (int j = level; j <= J; ++j) {
                rugo_contour c;
                rugo_tolerance_level tl;
                if (rugo_shape_level(s, j, &c) != RUGO_OK || rugo_shape_tolerance_level(s, j, &tl) != RUGO_OK)
                    return false;
                const int scale = 1 << (j - level);
                for (int i = 0; i < pc.count * scale; ++i) {
                    const int k = (pc.first * scale + i) % c.count;
                    rugo_vec2 b[4];
                    rugo_contour_bezier(c, k, b);
                    const double lam = rugo_tolerance_bound_on_segment(tl.total, tl.count, k, 0.0);
                    if (!std::isfinite(lam)) return false;
                    for (const rugo_vec2& q : b) {
                        pts.push_back(q);
                        reach.push_back(lam);
                    }
                    most = std::max(most, lam);
                }
            }
            // The run's curve at the contact level, densely, with its band, for the looseness measure.
            Poly curve;
            std::vector<double> band;
            rugo_contour cl;
            rugo_tolerance_level tll;
            if (rugo_shape_level(s, level, &cl) != RUGO_OK ||
                rugo_shape_tolerance_level(s, level, &tll) != RUGO_OK)
                return false;
            for (int i = 0; i < pc.count; ++i)
                for (int q = 0; q < 8; ++q) {
                    const int k = (pc.first + i) % cl.count;
                    curve.push_back(rugo_contour_point(cl, k, q / 8.0));
                    band.push_back(rugo_tolerance_at(tll.total, tll.count, k, q / 8.0, 0.0));
                }
            const bool closed = pc.count == nL;
            if (!enclose(pts, reach, std::max(static_cast<double>(b2_polygonRadius), most), curve, band,
                         closed ? nullptr : &cl, &pc))
                return false;
            out->pieces.push_back(pc);
        }
        return true;
    } catch (const std::bad_alloc&) {
        return false;
    }
}

} // namespace detail
} // namespace rugo
