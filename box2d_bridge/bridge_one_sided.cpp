// One-sided edges: chain children and b2EdgeShape with m_oneSided, as Box2D 2.4.1 collides them
// (see Bridge::Impl::OneSided in bridge_impl.hpp).
#include "bridge_impl.hpp"

#include <utility>

namespace rugo {

Bridge::Impl::OneSided Bridge::Impl::makeOneSided(const b2EdgeShape& e, const b2Transform& x, bool hasPrev,
                                                  bool hasNext) {
    OneSided o;
    o.on = true;
    o.v1 = b2Mul(x, e.m_vertex1);
    o.v2 = b2Mul(x, e.m_vertex2);
    const b2Vec2 v0 = b2Mul(x, e.m_vertex0), v3 = b2Mul(x, e.m_vertex3);
    b2Vec2 d1 = o.v2 - o.v1, d0 = o.v1 - v0, d2 = v3 - o.v2;
    o.len = d1.Normalize();
    const bool ghost0 = d0.Normalize() > 0.0f, ghost3 = d2.Normalize() > 0.0f;
    o.e0 = ghost0 ? d0 : d1;
    o.e1 = d1;
    o.n0.Set(o.e0.y, -o.e0.x);
    o.n1.Set(d1.y, -d1.x);
    o.n2 = ghost3 ? b2Vec2(d2.y, -d2.x) : o.n1;
    o.convex1 = ghost0 && b2Cross(d0, d1) > 0.0f;
    o.convex2 = ghost3 && b2Cross(d1, d2) > 0.0f;
    o.radius = e.m_radius;
    o.hasPrev = hasPrev;
    o.hasNext = hasNext;
    return o;
}

// A two-sided b2EdgeShape as the one-sided edge facing the body's centroid (the side Box2D's
// polygons collide with unless they are past the line), with round caps and no ghost vertices. Per
// body, not per contact: a thin tip that crossed the line is pushed back, not through (with a side
// per point, the crossed part of the curve got normals pushing it on through the edge).
Bridge::Impl::OneSided Bridge::Impl::makeTwoSided(const b2EdgeShape& e, const b2Transform& x,
                                                  b2Vec2 centroid) {
    OneSided o;
    o.on = true;
    o.roundEnds = true;
    o.v1 = b2Mul(x, e.m_vertex1);
    o.v2 = b2Mul(x, e.m_vertex2);
    b2Vec2 d1 = o.v2 - o.v1;
    o.len = d1.Normalize();
    o.n1.Set(d1.y, -d1.x);
    if (b2Dot(o.n1, centroid - o.v1) < 0.0f) { // face the centroid: run the edge the other way
        std::swap(o.v1, o.v2);
        d1 = -d1;
        o.n1 = -o.n1;
    }
    o.e0 = o.e1 = d1;
    o.n0 = o.n2 = o.n1;
    o.radius = e.m_radius;
    return o;
}

namespace {
// The normal beyond an end vertex v of the edge, toward p: a round cap's points from v to p; a convex
// vertex's lies between the normals of the faces before and after it (clamped to them); otherwise
// (a flat or concave vertex: "snap") *m is left as it is, the face normal.
void endNormal(b2Vec2 p, b2Vec2 v, bool round, bool convex, b2Vec2 nBefore, b2Vec2 nAfter, b2Vec2* m) {
    if (!round && !convex) return;
    b2Vec2 d = p - v;
    if (d.Normalize() > 0.0f)
        *m = round ? d : (b2Cross(nBefore, d) < 0.0f ? nBefore : (b2Cross(d, nAfter) < 0.0f ? nAfter : d));
}
} // namespace

// A curve point p (world) against the one-sided edge: false if another child reports it; else the
// normal out of the edge toward p (*m) and p's signed distance along it from the edge's skin.
bool Bridge::Impl::resolveOneSided(const OneSided& o, b2Vec2 p, b2Vec2* m, double* dist) {
    const float along = b2Dot(p - o.v1, o.e1);
    b2Vec2 base = o.v1;
    *m = o.n1;
    if (along < 0.0f) {
        if (o.hasPrev && b2Dot(p - o.v1, o.e0) < 0.0f) return false; // on the previous child's face
        endNormal(p, o.v1, o.roundEnds, o.convex1, o.n0, o.n1, m);
    } else if (along >= o.len) {
        if (o.hasNext) return false; // the next child's (its t = 0)
        base = o.v2;
        endNormal(p, o.v2, o.roundEnds, o.convex2, o.n1, o.n2, m);
    }
    *dist = static_cast<double>(b2Dot(p - base, *m)) - static_cast<double>(o.radius);
    return true;
}

} // namespace rugo
