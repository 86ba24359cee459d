/* The polygon baseline of the query benchmarks (bench_queries, bench_accuracy): a curve approximated by
 * the polygon of m vertices on it at equal arc length (in floats), decomposed into convex pieces of at
 * most 8 vertices, each a Box2D 2.4.1 b2PolygonShape; contacts by Box2D's own b2DynamicTree and
 * b2CollidePolygons (bench_queries.cpp's header has the method and docs/accuracy.md its error model).
 * Header-only. */
#ifndef RUGO_BENCH_POLYGON_BASELINE_HPP
#define RUGO_BENCH_POLYGON_BASELINE_HPP

#include "rugo/rugo.h"

#include <box2d/box2d.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace polygon_baseline {

/* ------------------------------------------------------------------------------------------------
 * Contacts as compared: world points, unit normal from A to B, separation (core separation for Box2D). */

struct Cnt {
    double ax, ay, bx, by, nx, ny, s;
    double bound; /* librugo: β_A + β_B of the contact's segments at its level (else 0) */
};

/* ------------------------------------------------------------------------------------------------
 * Polygon baseline */

struct DV {
    double x, y;
};

/* x rounded to float and back. Through a volatile on purpose: gcc 12 at -O2 folds a vectorised pair of
 * (double)(float) round trips into nothing (seen with -ftree-slp-vectorize; a 6-line reproducer is in
 * docs/accuracy.md), and the polygons must hold exactly the coordinates Box2D's floats will. */
inline double to_float(double x) {
    volatile float f = static_cast<float>(x);
    return static_cast<double>(f);
}

inline double cross3(const DV& a, const DV& b, const DV& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/* m vertices on the finest curve at equal arc length (from 64 chords per segment), from u = 0, rounded to
 * float. */
inline std::vector<DV> polygon_on_curve(const std::vector<rugo_vec2>& pts, int m) {
    rugo_contour c = {pts.data(), (int)pts.size()};
    const int S = 64, N = c.count * S;
    std::vector<double> cum((size_t)N + 1, 0.0);
    rugo_vec2 prev = rugo_contour_point(c, 0, 0.0);
    for (int i = 1; i <= N; ++i) {
        const rugo_vec2 p = rugo_contour_point_at(c, (double)i / S);
        cum[(size_t)i] = cum[(size_t)i - 1] + std::hypot(p.x - prev.x, p.y - prev.y);
        prev = p;
    }
    std::vector<DV> v((size_t)m);
    for (int k = 0; k < m; ++k) {
        const double target = cum[(size_t)N] * k / m;
        const size_t i = (size_t)(std::upper_bound(cum.begin(), cum.end(), target) - cum.begin());
        const size_t i0 = i == 0 ? 0 : std::min((size_t)N - 1, i - 1);
        const double seg = cum[i0 + 1] - cum[i0];
        const double f = seg > 0.0 ? (target - cum[i0]) / seg : 0.0;
        const rugo_vec2 p = rugo_contour_point_at(c, ((double)i0 + f) / S);
        /* rounded to Box2D's floats here, so that convexity is decided on the coordinates it uses */
        v[(size_t)k] = {to_float(p.x), to_float(p.y)};
    }
    return v;
}

/* Ear clipping then Hertel-Mehlhorn merging (pieces of at most 8 vertices, strictly convex). Pieces
 * are index lists, counter-clockwise. Empty on failure (not a simple polygon).
 * Compact pieces matter for collision (a fan of long slivers would pair every piece with many): the
 * ear with the shortest diagonal is clipped first, which peels the polygon in layers from its boundary,
 * and diagonals are merged shortest first, so the boundary is covered by small pieces of up to 8
 * vertices and the interior by a few large ones. */
inline std::vector<std::vector<int>> decompose_hm(const std::vector<DV>& v) {
    const int n = (int)v.size();
    std::vector<int> prev((size_t)n), next((size_t)n), version((size_t)n, 0);
    std::vector<char> alive((size_t)n, 1), isreflex((size_t)n, 0);
    for (int i = 0; i < n; ++i) {
        prev[(size_t)i] = (i + n - 1) % n;
        next[(size_t)i] = (i + 1) % n;
    }
    auto reflex = [&](int i) {
        return cross3(v[(size_t)prev[(size_t)i]], v[(size_t)i], v[(size_t)next[(size_t)i]]) <= 0.0;
    };
    std::vector<int> reflexes;
    for (int i = 0; i < n; ++i)
        if (reflex(i)) {
            isreflex[(size_t)i] = 1;
            reflexes.push_back(i);
        }
    auto is_ear = [&](int b) {
        if (isreflex[(size_t)b]) return false;
        const int a = prev[(size_t)b], c = next[(size_t)b];
        const DV &pa = v[(size_t)a], &pb = v[(size_t)b], &pc = v[(size_t)c];
        const double lx = std::min(pa.x, std::min(pb.x, pc.x)), hx = std::max(pa.x, std::max(pb.x, pc.x));
        const double ly = std::min(pa.y, std::min(pb.y, pc.y)), hy = std::max(pa.y, std::max(pb.y, pc.y));
        for (int r : reflexes) {
            if (!alive[(size_t)r] || !isreflex[(size_t)r] || r == a || r == c) continue;
            const DV& p = v[(size_t)r];
            if (p.x < lx || p.x > hx || p.y < ly || p.y > hy) continue;
            if (cross3(pa, pb, p) >= 0.0 && cross3(pb, pc, p) >= 0.0 && cross3(pc, pa, p) >= 0.0)
                return false;
        }
        return true;
    };
    auto diag = [&](int b) {
        const DV &pa = v[(size_t)prev[(size_t)b]], &pc = v[(size_t)next[(size_t)b]];
        return std::hypot(pc.x - pa.x, pc.y - pa.y);
    };
    /* min-heap of (diagonal length, vertex, version); stale entries are skipped */
    typedef std::pair<double, std::pair<int, int>> Entry;
    std::vector<Entry> heap;
    auto push = [&](int b) {
        heap.push_back({diag(b), {b, version[(size_t)b]}});
        std::push_heap(heap.begin(), heap.end(), std::greater<Entry>());
    };
    for (int i = 0; i < n; ++i)
        push(i);
    std::vector<std::array<int, 3>> tris;
    int remaining = n;
    while (remaining > 3) {
        int b = -1;
        while (!heap.empty() && b < 0) {
            std::pop_heap(heap.begin(), heap.end(), std::greater<Entry>());
            const Entry e = heap.back();
            heap.pop_back();
            const int k = e.second.first;
            if (alive[(size_t)k] && e.second.second == version[(size_t)k] && is_ear(k)) b = k;
        }
        if (b < 0) { /* ears blocked by reflex vertices that have since gone: scan, then refill the heap */
            for (int k = 0; k < n && b < 0; ++k)
                if (alive[(size_t)k] && is_ear(k)) b = k;
            if (b < 0) return {};
            for (int k = 0; k < n; ++k)
                if (alive[(size_t)k] && k != b) {
                    ++version[(size_t)k];
                    push(k);
                }
        }
        const int a = prev[(size_t)b], c = next[(size_t)b];
        tris.push_back({a, b, c});
        alive[(size_t)b] = 0;
        next[(size_t)a] = c;
        prev[(size_t)c] = a;
        --remaining;
        for (int w : {a, c}) {
            const bool r = reflex(w);
            if (r && !isreflex[(size_t)w]) reflexes.push_back(w);
            isreflex[(size_t)w] = r ? 1 : 0;
            ++version[(size_t)w];
            push(w);
        }
        if (reflexes.size() > (size_t)(4 * n)) { /* compact */
            std::vector<int> keep;
            for (int r : reflexes)
                if (alive[(size_t)r] && isreflex[(size_t)r]) keep.push_back(r);
            std::sort(keep.begin(), keep.end());
            keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
            reflexes.swap(keep);
        }
    }
    for (int k = 0; k < n; ++k)
        if (alive[(size_t)k]) {
            tris.push_back({prev[(size_t)k], k, next[(size_t)k]});
            break;
        }
    /* Hertel-Mehlhorn: merge across diagonals while convex and <= 8 vertices */
    std::vector<std::vector<int>> poly;
    std::vector<int> owner;
    for (const auto& t : tris) {
        poly.push_back({t[0], t[1], t[2]});
        owner.push_back((int)owner.size());
    }
    std::function<int(int)> find = [&](int k) {
        return owner[(size_t)k] == k ? k : owner[(size_t)k] = find(owner[(size_t)k]);
    };
    /* diagonal (u, v) -> the triangle holding u->v and the one holding v->u */
    struct Diag {
        int u, w, t1, t2;
    };
    std::vector<Diag> diags;
    {
        std::vector<std::array<int, 3>> edges; /* (min, max, tri) for directed internal edges */
        for (size_t t = 0; t < tris.size(); ++t)
            for (int e = 0; e < 3; ++e) {
                const int u = tris[t][(size_t)e], w = tris[t][(size_t)((e + 1) % 3)];
                if ((u + 1) % n == w || (w + 1) % n == u) continue; /* boundary edge */
                edges.push_back({std::min(u, w), std::max(u, w), (int)t});
            }
        std::sort(edges.begin(), edges.end());
        for (size_t k = 0; k + 1 < edges.size(); ++k)
            if (edges[k][0] == edges[k + 1][0] && edges[k][1] == edges[k + 1][1]) {
                diags.push_back({edges[k][0], edges[k][1], edges[k][2], edges[k + 1][2]});
                ++k;
            }
        auto len = [&](const Diag& d) {
            return std::hypot(v[(size_t)d.u].x - v[(size_t)d.w].x, v[(size_t)d.u].y - v[(size_t)d.w].y);
        };
        std::stable_sort(diags.begin(), diags.end(),
                         [&](const Diag& x, const Diag& y) { return len(x) < len(y); });
    }
    auto rotate_to = [](std::vector<int> p, int start) {
        const auto it = std::find(p.begin(), p.end(), start);
        std::rotate(p.begin(), it, p.end());
        return p;
    };
    for (const auto& d : diags) {
        const int p1 = find(d.t1), p2 = find(d.t2);
        if (p1 == p2) continue;
        const std::vector<int>&P1 = poly[(size_t)p1], &P2 = poly[(size_t)p2];
        if (P1.size() + P2.size() - 2 > 8) continue;
        /* which of P1, P2 holds u->w */
        auto holds = [](const std::vector<int>& p, int a, int b) {
            for (size_t k = 0; k < p.size(); ++k)
                if (p[k] == a && p[(k + 1) % p.size()] == b) return true;
            return false;
        };
        int u = d.u, w = d.w;
        const std::vector<int>* X = &P1;
        const std::vector<int>* Y = &P2;
        if (!holds(*X, u, w)) std::swap(u, w);
        if (!holds(*X, u, w)) std::swap(X, Y), std::swap(u, w);
        if (!holds(*X, u, w) || !holds(*Y, w, u)) continue;
        std::vector<int> a = rotate_to(*X, w); /* w ... u */
        std::vector<int> b = rotate_to(*Y, u); /* u ... w */
        std::vector<int> merged(a);
        merged.insert(merged.end(), b.begin() + 1, b.end() - 1);
        /* convex at u and at w */
        const size_t L = merged.size();
        bool convex = true;
        for (size_t k = 0; k < L && convex; ++k) {
            if (merged[k] != u && merged[k] != w) continue;
            convex = cross3(v[(size_t)merged[(k + L - 1) % L]], v[(size_t)merged[k]],
                            v[(size_t)merged[(k + 1) % L]]) > 0.0;
        }
        if (!convex) continue;
        poly[(size_t)p1] = merged;
        poly[(size_t)p2].clear();
        owner[(size_t)p2] = p1;
    }
    std::vector<std::vector<int>> out;
    for (size_t k = 0; k < poly.size(); ++k)
        if (find((int)k) == (int)k && poly[k].size() >= 3) out.push_back(poly[k]);
    return out;
}

/* For an outline star-shaped about c (every edge seen counter-clockwise from c): a boundary strip of
 * truncated wedges (a convex run of at most 5 boundary edges, the two radial edges down to the scaled
 * copy c + alpha (v - c), and the inner chord), and a fan from c over the strip's inner corners. Every
 * internal edge is radial or lies deep inside (1 - alpha of the radius, ~0.1 of the size here), so
 * none lies just under the boundary where Box2D's skin would make contacts with it ("ghost" contacts
 * on internal faces). Empty if the outline is not star-shaped about c. */
inline std::vector<std::vector<DV>> decompose_strip(const std::vector<DV>& v, DV c, double alpha) {
    const int n = (int)v.size();
    for (int i = 0; i < n; ++i)
        if (!(cross3(c, v[(size_t)i], v[(size_t)((i + 1) % n)]) > 0.0)) return {};
    auto at = [&](int i) { return v[(size_t)(((i % n) + n) % n)]; };
    auto inner = [&](const DV& p) {
        return DV{to_float(c.x + alpha * (p.x - c.x)), to_float(c.y + alpha * (p.y - c.y))};
    };
    std::vector<std::vector<DV>> out;
    std::vector<DV> core;
    int s0 = 0; /* start runs at a reflex vertex if there is one, so no run straddles it */
    for (int i = 0; i < n; ++i)
        if (cross3(at(i - 1), at(i), at(i + 1)) <= 0.0) {
            s0 = i;
            break;
        }
    for (int s = s0; s < s0 + n;) {
        int e = s + 1;
        while (e - s < 5 && e < s0 + n && cross3(at(e - 1), at(e), at(e + 1)) > 0.0)
            ++e;
        std::vector<DV> piece;
        for (int k = s; k <= e; ++k)
            piece.push_back(at(k));
        piece.push_back(inner(at(e)));
        piece.push_back(inner(at(s)));
        out.push_back(piece);
        core.push_back(inner(at(s)));
        s = e;
    }
    const int q = (int)core.size();
    auto cat = [&](int i) { return core[(size_t)(((i % q) + q) % q)]; };
    for (int s = 0; s < q;) {
        int e = s + 1;
        while (e - s < 6 && e < q && cross3(cat(e - 1), cat(e), cat(e + 1)) > 0.0 &&
               cross3(c, cat(s), cat(e + 1)) > 0.0)
            ++e;
        std::vector<DV> piece{c};
        for (int k = s; k <= e; ++k)
            piece.push_back(cat(k));
        out.push_back(piece);
        s = e;
    }
    return out;
}

/* The pieces as coordinate lists: the strip decomposition when the outline is star-shaped about the
 * origin (the centroid) and strip is asked for, else ear clipping + Hertel-Mehlhorn. */
inline std::vector<std::vector<DV>> decompose(const std::vector<DV>& v, bool strip, bool* used_strip) {
    *used_strip = false;
    if (strip) {
        auto p = decompose_strip(v, DV{0.0, 0.0}, 0.75);
        if (!p.empty()) {
            *used_strip = true;
            return p;
        }
    }
    std::vector<std::vector<DV>> out;
    for (const auto& idx : decompose_hm(v)) {
        std::vector<DV> piece;
        for (int k : idx)
            piece.push_back(v[(size_t)k]);
        out.push_back(piece);
    }
    return out;
}

struct PolyBody {
    std::vector<b2PolygonShape> pieces;
    std::vector<b2AABB> box; /* tight, local, skin included */
    std::vector<b2Vec2> cc;  /* bounding circle of each piece, local */
    std::vector<float> cr;
    float radius = 0.0f; /* bounding radius of the body about its origin, skin included */
    b2DynamicTree tree;  /* the pieces' boxes in the body's frame */
    int vertices = 0;
    bool ok = false;
    bool strip = false; /* decomposed by decompose_strip */
};

inline void build_poly(const std::vector<rugo_vec2>& pts, int m, bool strip, PolyBody& pb) {
    const std::vector<DV> v = polygon_on_curve(pts, m);
    const auto parts = decompose(v, strip, &pb.strip);
    if (parts.empty()) return;
    pb.vertices = m;
    for (const auto& part : parts) {
        /* every piece a strictly convex counter-clockwise polygon of 3..8 vertices, also in floats */
        const int L = (int)part.size();
        if (L < 3 || L > b2_maxPolygonVertices) return;
        for (int k = 0; k < L; ++k) {
            const DV &p0 = part[(size_t)k], &p1 = part[(size_t)((k + 1) % L)],
                     &p2 = part[(size_t)((k + 2) % L)];
            const DV f0{to_float(p0.x), to_float(p0.y)}, f1{to_float(p1.x), to_float(p1.y)},
                f2{to_float(p2.x), to_float(p2.y)};
            if (!(cross3(p0, p1, p2) > 0.0) || !(cross3(f0, f1, f2) > 0.0)) return;
        }
        b2PolygonShape s;
        s.m_count = (int32)part.size();
        for (size_t k = 0; k < part.size(); ++k)
            s.m_vertices[k].Set((float)part[k].x, (float)part[k].y);
        double ax = 0, ay = 0, area = 0;
        for (int k = 0; k < s.m_count; ++k) {
            const b2Vec2 e = s.m_vertices[(k + 1) % s.m_count] - s.m_vertices[k];
            b2Vec2 nrm(e.y, -e.x);
            nrm.Normalize();
            s.m_normals[k] = nrm;
            const double cr = (double)s.m_vertices[k].x * s.m_vertices[(k + 1) % s.m_count].y -
                              (double)s.m_vertices[(k + 1) % s.m_count].x * s.m_vertices[k].y;
            area += cr;
            ax += cr * (s.m_vertices[k].x + s.m_vertices[(k + 1) % s.m_count].x);
            ay += cr * (s.m_vertices[k].y + s.m_vertices[(k + 1) % s.m_count].y);
        }
        s.m_centroid.Set((float)(ax / (3.0 * area)), (float)(ay / (3.0 * area)));
        b2AABB bx;
        s.ComputeAABB(&bx, b2Transform(b2Vec2(0.0f, 0.0f), b2Rot(0.0f)), 0);
        b2Vec2 c(0.0f, 0.0f);
        for (int k = 0; k < s.m_count; ++k)
            c += s.m_vertices[k];
        c *= 1.0f / (float)s.m_count;
        float r = 0.0f;
        for (int k = 0; k < s.m_count; ++k)
            r = std::max(r, b2Distance(c, s.m_vertices[k]));
        r += s.m_radius;
        pb.radius = std::max(pb.radius, c.Length() + r);
        pb.pieces.push_back(s);
        pb.box.push_back(bx);
        pb.cc.push_back(c);
        pb.cr.push_back(r);
        /* proxy ids are the tree's node indices: the piece index rides in the user data */
        pb.tree.CreateProxy(bx, reinterpret_cast<void*>((intptr_t)pb.pieces.size() - 1));
    }
    pb.ok = true;
}

inline b2Transform b2xf(rugo_transform x) {
    b2Transform t;
    t.p.Set((float)x.p.x, (float)x.p.y);
    t.q.s = (float)x.q.s;
    t.q.c = (float)x.q.c;
    return t;
}

/* Candidate piece pairs: A's pieces whose circles reach B's, their boxes in B's frame through B's tree,
 * then the tight boxes. */
struct TreeHits {
    const PolyBody* B;
    b2AABB box;
    int ia;
    std::vector<std::pair<int, int>>* out;
    bool QueryCallback(int32 id) {
        const int k = (int)reinterpret_cast<intptr_t>(B->tree.GetUserData(id));
        if (b2TestOverlap(box, B->box[(size_t)k])) out->push_back({ia, k});
        return true;
    }
};

inline void box2d_pairs(const PolyBody& A, const b2Transform& xa, const PolyBody& B, const b2Transform& xb,
                        std::vector<std::pair<int, int>>& out) {
    out.clear();
    const b2Vec2 cb = b2MulT(xa, xb.p);    /* B's origin in A's frame */
    const b2Transform ab = b2MulT(xb, xa); /* A's frame -> B's frame */
    TreeHits th{&B, b2AABB(), 0, &out};
    for (size_t i = 0; i < A.pieces.size(); ++i) {
        const float reach = A.cr[i] + B.radius;
        if (b2DistanceSquared(A.cc[i], cb) > reach * reach) continue;
        const b2PolygonShape& p = A.pieces[i];
        b2Vec2 lo = b2Mul(ab, p.m_vertices[0]), hi = lo;
        for (int k = 1; k < p.m_count; ++k) {
            const b2Vec2 q = b2Mul(ab, p.m_vertices[k]);
            lo = b2Min(lo, q);
            hi = b2Max(hi, q);
        }
        const b2Vec2 r(p.m_radius, p.m_radius);
        th.box.lowerBound = lo - r;
        th.box.upperBound = hi + r;
        th.ia = (int)i;
        B.tree.Query(&th, th.box);
    }
}

inline void box2d_collide(const PolyBody& A, const b2Transform& xa, const PolyBody& B, const b2Transform& xb,
                          int i, int j, std::vector<Cnt>* out, int* points) {
    b2Manifold man;
    b2CollidePolygons(&man, &A.pieces[(size_t)i], xa, &B.pieces[(size_t)j], xb);
    if (man.pointCount == 0) return;
    b2WorldManifold wm;
    wm.Initialize(&man, xa, A.pieces[(size_t)i].m_radius, xb, B.pieces[(size_t)j].m_radius);
    *points += man.pointCount;
    if (!out) return;
    const double skin = (double)A.pieces[(size_t)i].m_radius + (double)B.pieces[(size_t)j].m_radius;
    for (int k = 0; k < man.pointCount; ++k) {
        Cnt c;
        c.s = (double)wm.separations[k] + skin; /* the cores' separation */
        c.nx = wm.normal.x;
        c.ny = wm.normal.y;
        /* the world point is the middle of the two skins' surfaces = middle of the cores' points */
        c.ax = wm.points[k].x - 0.5 * c.s * c.nx;
        c.ay = wm.points[k].y - 0.5 * c.s * c.ny;
        c.bx = wm.points[k].x + 0.5 * c.s * c.nx;
        c.by = wm.points[k].y + 0.5 * c.s * c.ny;
        c.bound = 0.0;
        out->push_back(c);
    }
}

} // namespace polygon_baseline

#endif
