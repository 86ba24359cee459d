// The bridge's debug drawing (Bridge::Draw): curves, bands, proxies, last step's manifold points.
#include "bridge_impl.hpp"

#include <vector>

namespace rugo {

void Bridge::Draw(b2Draw* draw, unsigned flags) const {
    const Impl& I = *m_impl;
    if (draw == nullptr) return;
    const b2Color curveColor(0.9f, 0.9f, 0.3f), bandColor(0.5f, 0.5f, 0.2f), boxColor(0.4f, 0.6f, 0.9f),
        contactColor(1.0f, 0.2f, 0.2f);
    // Each body's picture is computed before any of its b2Draw calls and the next body is looked up
    // again after them: a b2Draw may attach, detach or destroy bodies (or free a detached shape)
    // without leaving the bridge holding anything stale. A debug path: it allocates.
    struct Seg {
        b2Vec2 a, b;
        const b2Color* color;
    };
    std::vector<Seg> segs;
    std::vector<b2Vec2> polys; // b2_maxPolygonVertices per proxy box, then its vertex count
    std::vector<int> polyCounts;
    const std::vector<Impl::DrawnContact> contacts = I.lastContacts;
    for (b2Body* body : I.bodiesInAttachOrder()) {
        const BodyRec* r = I.rec(body);
        if (r == nullptr) continue; // gone during an earlier body's drawing
        segs.clear();
        polys.clear();
        polyCounts.clear();
        const rugo_transform x = toRugo(body->GetTransform());
        rugo_contour curve;
        if (rugo_shape_level(r->shape, r->level, &curve) != RUGO_OK) continue;
        rugo_tolerance_level tl;
        const bool haveTol = rugo_shape_tolerance_level(r->shape, r->level, &tl) == RUGO_OK;
        const int perSeg = 8;
        for (int k = 0; k < curve.count; ++k)
            for (int i = 0; i < perSeg; ++i) {
                const double t0 = static_cast<double>(i) / perSeg, t1 = static_cast<double>(i + 1) / perSeg;
                const rugo_vec2 a = rugo_contour_point(curve, k, t0), b = rugo_contour_point(curve, k, t1);
                if (flags & kDrawCurve)
                    segs.push_back(
                        {toB2(rugo_transform_point(x, a)), toB2(rugo_transform_point(x, b)), &curveColor});
                if ((flags & kDrawBand) && haveTol)
                    for (int side = -1; side <= 1; side += 2) {
                        const double la = rugo_tolerance_at(tl.total, tl.count, k, t0, 0.0) * side;
                        const double lb = rugo_tolerance_at(tl.total, tl.count, k, t1, 0.0) * side;
                        const rugo_vec2 oa =
                            rugo_v2_add(a, rugo_v2_scale(la, rugo_contour_normal(curve, k, t0)));
                        const rugo_vec2 ob =
                            rugo_v2_add(b, rugo_v2_scale(lb, rugo_contour_normal(curve, k, t1)));
                        segs.push_back({toB2(rugo_transform_point(x, oa)), toB2(rugo_transform_point(x, ob)),
                                        &bandColor});
                    }
            }
        if (flags & kDrawProxies)
            for (const b2Fixture* f : r->proxies) {
                // The region Box2D's polygon covers: its core pushed out by its skin (the polygon
                // through the offset edges' meeting points, which holds the rounded corners too).
                const b2PolygonShape* p = static_cast<const b2PolygonShape*>(f->GetShape());
                for (int i = 0; i < p->m_count; ++i) {
                    const b2Vec2 n0 = p->m_normals[(i + p->m_count - 1) % p->m_count], n1 = p->m_normals[i];
                    const float k = p->m_radius / (1.0f + b2Dot(n0, n1));
                    polys.push_back(b2Mul(body->GetTransform(), p->m_vertices[i] + k * (n0 + n1)));
                }
                polyCounts.push_back(p->m_count);
            }
        for (const Seg& sg : segs)
            draw->DrawSegment(sg.a, sg.b, *sg.color);
        size_t at = 0;
        for (int n : polyCounts) {
            draw->DrawPolygon(polys.data() + at, n, boxColor);
            at += static_cast<size_t>(n);
        }
    }
    if (flags & kDrawContacts)
        for (const auto& c : contacts) {
            draw->DrawPoint(c.p, 4.0f, contactColor);
            draw->DrawSegment(c.p, c.p + 0.2f * c.n, contactColor);
        }
}

} // namespace rugo
