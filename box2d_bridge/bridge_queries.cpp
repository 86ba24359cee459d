// The bridge's scene queries on the rough bodies' curves: ray cast, point test, AABB query (box2d.hpp).
#include "bridge_impl.hpp"

#include <algorithm>
#include <functional>
#include <unordered_set>
#include <vector>

namespace rugo {

namespace {
struct CollectFixtures : public b2QueryCallback {
    std::vector<b2Fixture*>* out;
    bool ReportFixture(b2Fixture* f) override {
        out->push_back(f);
        return true;
    }
};
struct OrdinaryRay : public b2RayCastCallback {
    const Bridge* bridge;
    RayHit best;
    bool hit = false;
    float ReportFixture(b2Fixture* f, const b2Vec2& p, const b2Vec2& n, float fraction) override {
        if (bridge->IsProxy(f)) return -1.0f; // rough bodies are refined on their curves
        best.body = f->GetBody();
        best.fixture = f;
        best.point = p;
        best.normal = n;
        best.fraction = fraction;
        best.segment = -1;
        best.t = 0.0;
        hit = true;
        return fraction;
    }
};
} // namespace

bool Bridge::RayCast(const b2Vec2& p1, const b2Vec2& p2, RayHit* hit) const {
    const Impl& I = *m_impl;
    if (I.world == nullptr) return false;
    // b2World::RayCast asserts a finite ray of positive length (b2Assert is on in Debian's build).
    if (!p1.IsValid() || !p2.IsValid() || !(b2DistanceSquared(p1, p2) > 0.0f)) return false;
    OrdinaryRay ordinary;
    ordinary.bridge = this;
    I.world->RayCast(&ordinary, p1, p2);
    RayHit best = ordinary.best;
    bool found = ordinary.hit;
    // Candidates: proxies overlapping the ray's box (Box2D's polygon ray cast misses rays that start
    // inside a box, so its ray cast cannot be used to find them).
    b2AABB box;
    box.lowerBound = b2Min(p1, p2);
    box.upperBound = b2Max(p1, p2);
    std::vector<b2Fixture*> fx;
    CollectFixtures cf;
    cf.out = &fx;
    I.world->QueryAABB(&cf, box);
    std::vector<const BodyRec*> seen;
    for (b2Fixture* f : fx) {
        const ProxyRef* p = I.lookup(f);
        if (p == nullptr || std::find(seen.begin(), seen.end(), p->rec) != seen.end()) continue;
        seen.push_back(p->rec);
        const BodyRec* r = p->rec;
        rugo_contour curve;
        if (rugo_shape_level(r->shape, r->level, &curve) != RUGO_OK) continue;
        const rugo_transform x = toRugo(r->body->GetTransform());
        const rugo_vec2 o = rugo_inv_transform_point(x, toRv(p1));
        const rugo_vec2 d = rugo_inv_rotate(x.q, rugo_v2_sub(toRv(p2), toRv(p1)));
        if (d.x == 0.0 && d.y == 0.0) continue;
        double frac = 0.0;
        rugo_curve_point cp;
        rugo_vec2 nrm;
        if (!rugo_contour_ray_cast(curve, o, d, 1.0, &frac, &cp, &nrm)) continue;
        if (found && static_cast<float>(frac) >= best.fraction) continue;
        found = true;
        best.body = r->body;
        best.fixture = r->proxies[static_cast<size_t>(Impl::pieceOf(r->data, cp.segment, r->level))];
        best.point = toB2(rugo_transform_point(x, cp.point));
        best.normal = toB2(rugo_rotate(x.q, nrm));
        best.fraction = static_cast<float>(frac);
        best.segment = cp.segment;
        best.t = cp.t;
    }
    if (found && hit) *hit = best;
    return found;
}

bool Bridge::TestPoint(const b2Body* body, const b2Vec2& p) const {
    const BodyRec* r = m_impl->rec(body);
    if (r == nullptr) return false;
    bool inside = false;
    if (rugo_shape_contains(r->shape, r->level,
                            rugo_inv_transform_point(toRugo(body->GetTransform()), toRv(p)),
                            &inside) != RUGO_OK)
        return false;
    return inside;
}

void Bridge::QueryAABB(const b2AABB& aabb, const std::function<bool(b2Body*)>& callback) const {
    const Impl& I = *m_impl;
    if (I.world == nullptr || !callback) return;
    std::vector<b2Fixture*> fx;
    CollectFixtures cf;
    cf.out = &fx;
    I.world->QueryAABB(&cf, aabb);
    // Each body once, in the order Box2D reported its first fixture. The callback may attach, detach or
    // destroy bodies, so no fixture or record is held across it, only body pointers, and those are
    // checked against the world after a callback that destroyed or created any.
    std::vector<b2Body*> candidates;
    {
        std::unordered_set<const b2Body*> seen;
        for (b2Fixture* f : fx)
            if (seen.insert(f->GetBody()).second) candidates.push_back(f->GetBody());
    }
    rugo_vec2 v[4] = {
        rugo_v2(static_cast<double>(aabb.lowerBound.x), static_cast<double>(aabb.lowerBound.y)),
        rugo_v2(static_cast<double>(aabb.upperBound.x), static_cast<double>(aabb.lowerBound.y)),
        rugo_v2(static_cast<double>(aabb.upperBound.x), static_cast<double>(aabb.upperBound.y)),
        rugo_v2(static_cast<double>(aabb.lowerBound.x), static_cast<double>(aabb.upperBound.y))};
    const bool degenerate = !(v[2].x > v[0].x && v[2].y > v[0].y);
    long destroyed = I.destroyedFixtures;
    int32 bodyCount = I.world->GetBodyCount();
    const b2Body* head = I.world->GetBodyList();
    for (size_t i = 0; i < candidates.size(); ++i) {
        b2Body* b = candidates[i];
        if (b == nullptr) continue; // destroyed by an earlier callback
        const BodyRec* r = I.rec(b);
        if (r != nullptr && !queryOverlapsPolygon(I.query, r->shape, toRugo(b->GetTransform()), r->relLevel,
                                                  v, degenerate ? 1 : 4))
            continue; // decided by the curve
        if (!callback(b)) return;
        if (I.world == nullptr) return; // ReleaseWorld inside the callback
        // Creating a body changes the list's head, destroying one the count (and a destroyed body with
        // fixtures says goodbye): then drop the candidates that are no longer in the world.
        if (I.destroyedFixtures != destroyed || I.world->GetBodyCount() != bodyCount ||
            I.world->GetBodyList() != head) {
            std::unordered_set<const b2Body*> alive;
            for (const b2Body* w = I.world->GetBodyList(); w != nullptr; w = w->GetNext())
                alive.insert(w);
            for (size_t j = i + 1; j < candidates.size(); ++j)
                if (candidates[j] != nullptr && alive.count(candidates[j]) == 0) candidates[j] = nullptr;
            destroyed = I.destroyedFixtures;
            bodyCount = I.world->GetBodyCount();
            head = I.world->GetBodyList();
        }
    }
}

} // namespace rugo
