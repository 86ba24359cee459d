// Per-body facts of the bridge: the exact mass Box2D is given, the automatic level of detail, the
// bands the proxies and joints must cover, and the reach and speed bounds of the speculative margin.
#include "bridge_impl.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rugo {

Bridge::Impl::RoughMass Bridge::Impl::roughMass(const rugo_shape* s, double density) {
    const rugo_mass_properties mp = rugo_shape_mass(s);
    RoughMass out;
    out.mass = mp.area * density;
    out.centroid = mp.centroid;
    out.inertiaCentre = density * mp.inertia;
    out.inertiaOrigin =
        out.inertiaCentre + out.mass * (mp.centroid.x * mp.centroid.x + mp.centroid.y * mp.centroid.y);
    return out;
}

b2MassData Bridge::Impl::exactMass(const BodyRec* r) const {
    const RoughMass rm = roughMass(r->shape, r->density);
    double m = rm.mass;
    double cx = m * rm.centroid.x, cy = m * rm.centroid.y;
    double iOrigin = rm.inertiaOrigin;
    for (const b2Fixture* f = r->body->GetFixtureList(); f; f = f->GetNext()) {
        if (proxies.count(f) || f->GetDensity() <= 0.0f) continue;
        b2MassData md;
        f->GetShape()->ComputeMass(&md, f->GetDensity());
        m += static_cast<double>(md.mass);
        cx += static_cast<double>(md.mass) * static_cast<double>(md.center.x);
        cy += static_cast<double>(md.mass) * static_cast<double>(md.center.y);
        iOrigin += static_cast<double>(md.I);
    }
    b2MassData out;
    out.mass = static_cast<float>(m);
    out.center =
        m > 0.0 ? b2Vec2(static_cast<float>(cx / m), static_cast<float>(cy / m)) : b2Vec2(0.0f, 0.0f);
    out.I = static_cast<float>(iOrigin);
    return out;
}

bool Bridge::Impl::sameMass(const b2MassData& a, const b2MassData& b) {
    return a.mass == b.mass && a.I == b.I && a.center.x == b.center.x && a.center.y == b.center.y;
}

void Bridge::Impl::applyMass(BodyRec* r) {
    if (r->body->GetType() != b2_dynamicBody) {
        r->massValid = false; // Box2D keeps no mass for static/kinematic; repaired when dynamic again
        return;
    }
    const b2MassData md = exactMass(r);
    r->body->SetMassData(&md);
    r->body->GetMassData(&r->applied);
    r->massValid = true;
}

bool Bridge::Impl::massStale(const BodyRec* r) const {
    if (r->body->GetType() != b2_dynamicBody) return false;
    if (!r->massValid) return true;
    b2MassData now;
    r->body->GetMassData(&now);
    return !sameMass(now, r->applied);
}

// Largest excess of λ(t) over the segment value λ^j_k at levels from..J: queries at those levels
// grow boxes by it, so the proxies must too.
double Bridge::Impl::bandExcess(const rugo_shape* s, int from) {
    double e = 0.0;
    for (int j = from; j <= rugo_shape_finest_level(s); ++j) {
        rugo_tolerance_level tl;
        if (rugo_shape_tolerance_level(s, j, &tl) != RUGO_OK) continue;
        for (int k = 0; k < tl.count; ++k)
            e = std::max(e, rugo_tolerance_bound_on_segment(tl.total, tl.count, k, 0.0) - tl.total[k]);
    }
    return e;
}

// Certified largest λ(t) over each level's curve, levels J_min..J (index level - J_min).
std::vector<double> Bridge::Impl::bandMaxima(const rugo_shape* s) {
    const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
    std::vector<double> m(static_cast<size_t>(J - Jmin + 1), 0.0);
    for (int j = Jmin; j <= J; ++j) {
        rugo_tolerance_level tl;
        if (rugo_shape_tolerance_level(s, j, &tl) != RUGO_OK) continue;
        for (int k = 0; k < tl.count; ++k)
            m[static_cast<size_t>(j - Jmin)] =
                std::max(m[static_cast<size_t>(j - Jmin)],
                         rugo_tolerance_bound_on_segment(tl.total, tl.count, k, 0.0));
    }
    return m;
}

// The absolute level of a relative one (0 finest, < 0 coarser), clamped to the shape's levels.
int Bridge::Impl::absLevel(const rugo_shape* s, int rel) {
    const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
    return std::max(Jmin, std::min(J, J + rel));
}

double Bridge::Impl::roughReach(const BodyRec* r) {
    const b2Vec2 lc = r->body->GetLocalCenter();
    double m = 0.0;
    for (const rugo_vec2& c : r->rootCorners)
        m = std::max(m, std::hypot(c.x - static_cast<double>(lc.x), c.y - static_cast<double>(lc.y)));
    return m;
}

double Bridge::Impl::fixtureReach(const b2Fixture* f, int child) {
    const b2Vec2 lc = f->GetBody()->GetLocalCenter();
    const b2Shape* s = f->GetShape();
    double m = 0.0;
    auto upd = [&](b2Vec2 v) { m = std::max(m, static_cast<double>((v - lc).Length())); };
    switch (s->GetType()) {
    case b2Shape::e_circle:
        upd(static_cast<const b2CircleShape*>(s)->m_p);
        break;
    case b2Shape::e_polygon: {
        const b2PolygonShape* p = static_cast<const b2PolygonShape*>(s);
        for (int i = 0; i < p->m_count; ++i)
            upd(p->m_vertices[i]);
        break;
    }
    case b2Shape::e_edge: {
        const b2EdgeShape* e = static_cast<const b2EdgeShape*>(s);
        upd(e->m_vertex1);
        upd(e->m_vertex2);
        break;
    }
    case b2Shape::e_chain: {
        b2EdgeShape e;
        static_cast<const b2ChainShape*>(s)->GetChildEdge(&e, child);
        upd(e.m_vertex1);
        upd(e.m_vertex2);
        break;
    }
    default:
        break;
    }
    return m + static_cast<double>(s->m_radius);
}

double Bridge::Impl::speedBound(const b2Body* a, double ra, const b2Body* b, double rb) {
    const b2Vec2 dv = a->GetLinearVelocity() - b->GetLinearVelocity();
    return static_cast<double>(dv.Length()) + std::fabs(static_cast<double>(a->GetAngularVelocity())) * ra +
           std::fabs(static_cast<double>(b->GetAngularVelocity())) * rb;
}

// Normal approach speed of B's point toward A's point along n (A -> B).
double Bridge::Impl::approach(const b2Body* a, b2Vec2 pa, const b2Body* b, b2Vec2 pb, b2Vec2 n) {
    const b2Vec2 va = a->GetLinearVelocityFromWorldPoint(pa), vb = b->GetLinearVelocityFromWorldPoint(pb);
    return -static_cast<double>(b2Dot(vb - va, n));
}

bool Bridge::Impl::moved(const BodyRec* r) {
    const b2Transform& x = r->body->GetTransform();
    return x.p.x != r->stepStart.p.x || x.p.y != r->stepStart.p.y || x.q.s != r->stepStart.q.s ||
           x.q.c != r->stepStart.q.c;
}

} // namespace rugo
