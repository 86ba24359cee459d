// The Box2D 2.4 bridge (include/rugo/box2d.hpp; docs/box2d.md). The bridge only translates: Box2D's
// broad phase and proxy boxes pick candidate pairs, librugo decides the contacts, and PreSolve writes
// them into Box2D's manifold (DESIGN.md, "The Box2D 2.4 bridge", for the Box2D facts relied on).
// This file: the public API, the chaining of the user's listener and filter, and the body records;
// bridge_impl.hpp lists the files of the rest.
#include "bridge_impl.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <new>

namespace rugo {

Bridge::Impl::Impl() {
    table.resize(256);
    scratch.resize(64);
    for (std::vector<BPoint>* v : {&cand, &joints, &apart, &regions})
        v->reserve(64);
    lastContacts.reserve(4096); // its cap (write)
}

Bridge::Impl::~Impl() {
    for (auto& kv : bodies)
        delete kv.second;
    rugo_collide_context_destroy(ctx);
}

// ---- chaining ----------------------------------------------------------------------------
void Bridge::Impl::BeginContact(b2Contact* c) {
    if (rechained(kBegin, c)) return;
    chain(kBegin, c, [&] { prevListener->BeginContact(c); });
}

void Bridge::Impl::EndContact(b2Contact* c) {
    if (rechained(kEnd, c)) return;
    const bool was = removingProxies;
    if (world != nullptr && !world->IsLocked()) removingProxies = true; // see removingProxies
    chain(kEnd, c, [&] { prevListener->EndContact(c); });
    removingProxies = was;
}

void Bridge::Impl::PostSolve(b2Contact* c, const b2ContactImpulse* imp) {
    if (rechained(kPost, c)) return;
    afterSolve = true;
    chain(kPost, c, [&] { prevListener->PostSolve(c, imp); });
}

bool Bridge::Impl::ShouldCollide(b2Fixture* a, b2Fixture* b) {
    return prevFilter ? prevFilter->ShouldCollide(a, b) : b2ContactFilter::ShouldCollide(a, b);
}

void Bridge::Impl::SayGoodbye(b2Joint* j) {
    if (userDestruction) userDestruction->SayGoodbye(j);
}

void Bridge::Impl::SayGoodbye(b2Fixture* f) {
    ++destroyedFixtures;
    auto it = proxies.find(f);
    // A proxy is destroyed by Box2D only with its body (Detach goes through the bridge).
    if (it != proxies.end()) forget(it->second.rec);
    if (userDestruction) userDestruction->SayGoodbye(f);
}

void Bridge::Impl::forget(BodyRec* r) {
    for (b2Fixture* f : r->proxies)
        proxies.erase(f);
    bodies.erase(r->body);
    delete r;
    ++gen; // the cache may key on this record's address
}

void Bridge::Impl::rechain() {
    const b2ContactManager& cm = world->GetContactManager();
    if (cm.m_contactListener != this) {
        prevListener = cm.m_contactListener;
        world->SetContactListener(this);
        ++stats.listenersRechained;
    }
    if (cm.m_contactFilter != this) {
        prevFilter = cm.m_contactFilter;
        world->SetContactFilter(this);
        ++stats.listenersRechained;
    }
}

// The rough bodies in attach order (deterministic, unlike the hash map's order).
std::vector<b2Body*> Bridge::Impl::bodiesInAttachOrder() const {
    std::vector<const BodyRec*> recs;
    for (const auto& kv : bodies)
        recs.push_back(kv.second);
    std::sort(recs.begin(), recs.end(),
              [](const BodyRec* a, const BodyRec* b) { return a->serial < b->serial; });
    std::vector<b2Body*> out;
    for (const BodyRec* r : recs)
        out.push_back(r->body);
    return out;
}

// ---- Bridge --------------------------------------------------------------------------------------

Bridge::Bridge(b2World* world, const BridgeDef& def) : m_impl(new Impl) {
    Impl& I = *m_impl;
    // One bridge per world: a second one would take over the listeners and keep records of bodies the
    // first one's world destroys. It is made inert instead (Attach: BAD_ARGUMENT).
    if (world != nullptr && dynamic_cast<Impl*>(world->GetContactManager().m_contactListener) != nullptr)
        world = nullptr;
    I.world = world;
    I.def = def;
    {
        // An unknown mixing rule would give NaN friction (rugo_mix); read as an int, since loading an
        // out-of-range enum value is undefined in C++.
        int mix = 0;
        static_assert(sizeof mix == sizeof def.pointFrictionMix, "rugo_mix_rule is an int");
        std::memcpy(&mix, &def.pointFrictionMix, sizeof mix);
        if (mix < RUGO_MIX_MAX || mix > RUGO_MIX_GEOMETRIC)
            I.def.pointFrictionMix = BridgeDef().pointFrictionMix;
    }
    I.userDestruction = def.destructionListener;
    if (rugo_collide_context_create(nullptr, &I.ctx) != RUGO_OK) I.ctx = nullptr;
    if (world) {
        const b2ContactManager& cm = world->GetContactManager();
        I.prevListener = cm.m_contactListener;
        I.prevFilter = cm.m_contactFilter;
        world->SetContactListener(m_impl.get());
        world->SetContactFilter(m_impl.get());
        world->SetDestructionListener(m_impl.get());
    }
}

Bridge::~Bridge() {
    Impl& I = *m_impl;
    if (I.world) {
        // Remove the proxies while our listener still chains EndContact to the user's. That listener
        // may detach or destroy other rough bodies meanwhile: hold bodies, not records, and look
        // each up again (a destroyed body's record is gone; its pointer is only a key then).
        for (b2Body* b : I.bodiesInAttachOrder())
            if (I.rec(b) != nullptr && !I.world->IsLocked()) Detach(b);
        const b2ContactManager& cm = I.world->GetContactManager();
        if (cm.m_contactListener == m_impl.get()) I.world->SetContactListener(I.prevListener);
        if (cm.m_contactFilter == m_impl.get()) I.world->SetContactFilter(I.prevFilter);
        I.world->SetDestructionListener(I.userDestruction);
    }
}

rugo_status Bridge::Attach(b2Body* body, const RoughBodyDef& def) {
    Impl& I = *m_impl;
    if (body == nullptr || def.shape == nullptr) return RUGO_ERR_NULL_ARGUMENT;
    if (I.world == nullptr || body->GetWorld() != I.world) return RUGO_ERR_BAD_ARGUMENT;
    if (I.world->IsLocked() || I.removingProxies) return RUGO_ERR_WORLD_LOCKED;
    if (I.bodies.count(body)) return RUGO_ERR_ALREADY_ATTACHED;
    if (!std::isfinite(def.density) || def.density < 0.0) return RUGO_ERR_BAD_ARGUMENT;
    if (def.density == 0.0 && body->GetType() == b2_dynamicBody) return RUGO_ERR_BAD_ARGUMENT;
    if (def.density > 0.0) {
        // Box2D keeps mass and inertia in floats and asserts a positive inertia (b2Assert is on in
        // Debian's build): a density that puts them out of [1e6 FLT_MIN, 1e-6 FLT_MAX] (room for the
        // products with speeds and gravity, and for the inverses) is refused now, not in SetMassData or
        // as NaN poses later.
        const Impl::RoughMass rm = Impl::roughMass(def.shape, def.density);
        const double lo = 1e6 * static_cast<double>(FLT_MIN), hi = 1e-6 * static_cast<double>(FLT_MAX);
        if (!(rm.mass >= lo && rm.mass <= hi && rm.inertiaCentre >= lo && rm.inertiaCentre <= hi &&
              rm.inertiaOrigin <= hi))
            return RUGO_ERR_BAD_ARGUMENT;
    }
    if (I.ctx == nullptr) return RUGO_ERR_OUT_OF_MEMORY;
    const rugo_shape* s = def.shape;
    const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
    int level;
    if (def.lod == RUGO_LOD_AUTO) {
        const double budget = def.errorBudget >= 0.0 ? def.errorBudget : I.def.errorBudget;
        level = rugo_shape_level_for_error(s, budget);
    } else if (def.lod > 0) {
        return RUGO_ERR_BAD_ARGUMENT;
    } else {
        level = std::max(Jmin, J + std::max(def.lod, Jmin - J));
    }
    int proxyLevel;
    if (def.proxyLevel == RUGO_LOD_AUTO) {
        proxyLevel = std::max(Jmin, std::min(level, I.def.maxProxyLevel));
    } else {
        if (def.proxyLevel < Jmin || def.proxyLevel > J || def.proxyLevel > level)
            return RUGO_ERR_BAD_ARGUMENT;
        proxyLevel = def.proxyLevel;
    }
    // The query context's room for this shape's queries, now rather than during a step (librugo grows
    // the context to a new high-water mark otherwise). kQueryReserveContacts: see its comment.
    const rugo_status reserved = rugo_collide_context_reserve(I.ctx, s, kQueryReserveContacts);
    if (reserved != RUGO_OK) return reserved;
    const rugo_mobb_tree* tree = rugo_shape_tree(s);
    BodyRec* r = new (std::nothrow) BodyRec;
    if (r == nullptr) return RUGO_ERR_OUT_OF_MEMORY;
    r->body = body;
    r->shape = s;
    r->density = def.density;
    r->serial = I.nextSerial++;
    r->level = level;
    r->relLevel = level - J;
    r->proxyLevel = proxyLevel;
    r->bandMax = Impl::bandMaxima(s);
    rugo_obb_corners(rugo_mobb_tree_root(tree), r->rootCorners);
    const double excess = Impl::bandExcess(s, proxyLevel);
    const int nk = 1 << proxyLevel;
    r->proxies.reserve(static_cast<size_t>(nk));
    for (int k = 0; k < nk; ++k) {
        const rugo_obb* b = rugo_mobb_tree_node(tree, proxyLevel, k);
        b2PolygonShape box;
        // Rounding to float must not shrink the box: pad by a relative 1e-6 (Box2D's skin adds 1 cm more).
        const double pad =
            excess + 1e-6 * (std::fabs(b->center.x) + std::fabs(b->center.y) + b->half[0] + b->half[1]);
        const float hx = std::max(static_cast<float>(b->half[0] + pad), b2_linearSlop);
        const float hy = std::max(static_cast<float>(b->half[1] + pad), b2_linearSlop);
        box.SetAsBox(hx, hy, toB2(b->center), static_cast<float>(std::atan2(b->axis[0].y, b->axis[0].x)));
        b2FixtureDef fd;
        fd.shape = &box;
        fd.density = 0.0f;
        fd.filter = def.filter;
        fd.isSensor = def.isSensor;
        fd.userData = def.userData;
        b2Fixture* f = body->CreateFixture(&fd);
        r->proxies.push_back(f);
        I.proxies[f] = ProxyRef{r, k};
    }
    I.bodies[body] = r;
    I.reserveFor(I.bodies.size(), 1 << (level - proxyLevel), 1 << (J - proxyLevel));
    I.applyMass(r);
    return RUGO_OK;
}

rugo_status Bridge::Detach(b2Body* body) {
    Impl& I = *m_impl;
    if (body == nullptr) return RUGO_ERR_NULL_ARGUMENT;
    BodyRec* r = I.rec(body);
    if (r == nullptr) return RUGO_ERR_NOT_ATTACHED;
    if ((I.world && I.world->IsLocked()) || I.removingProxies) return RUGO_ERR_WORLD_LOCKED;
    std::vector<b2Fixture*> fx;
    fx.swap(r->proxies);
    for (b2Fixture* f : fx)
        I.proxies.erase(f);
    I.bodies.erase(body);
    delete r;
    ++I.gen;
    // Box2D calls EndContact from DestroyFixture while it walks the body's contact list: a listener
    // that detached another body there would destroy contacts under that walk. Attach and Detach
    // refuse meanwhile (WORLD_LOCKED), as they do inside Step.
    I.removingProxies = true;
    for (b2Fixture* f : fx)
        body->DestroyFixture(f); // each resets the mass from the remaining fixtures
    I.removingProxies = false;
    return RUGO_OK;
}

bool Bridge::IsRough(const b2Body* body) const { return m_impl->rec(body) != nullptr; }
const rugo_shape* Bridge::GetShape(const b2Body* body) const {
    const BodyRec* r = m_impl->rec(body);
    return r ? r->shape : nullptr;
}
int Bridge::GetLevel(const b2Body* body) const {
    const BodyRec* r = m_impl->rec(body);
    return r ? r->level : -1;
}
int Bridge::GetProxyLevel(const b2Body* body) const {
    const BodyRec* r = m_impl->rec(body);
    return r ? r->proxyLevel : -1;
}
bool Bridge::IsProxy(const b2Fixture* fixture, int* node) const {
    const ProxyRef* p = m_impl->lookup(fixture);
    if (p && node) *node = p->node;
    return p != nullptr;
}

void Bridge::Step(float timeStep, int32 velocityIterations, int32 positionIterations) {
    Impl& I = *m_impl;
    if (I.world == nullptr || I.world->IsLocked()) return;
    I.rechain();
    for (auto& kv : I.bodies)
        if (I.massStale(kv.second)) {
            I.applyMass(kv.second);
            ++I.stats.massReapplied;
        }
    if (timeStep > 0.0f) I.dt = timeStep;
    ++I.gen; // new poses: the cache of the last step is of no use
    I.used = 0;
    I.pool.clear();
    I.jointPool.clear();
    I.jointChunks.clear();
    I.lastContacts.clear();
    I.afterSolve = false;
    for (auto& kv : I.bodies)
        kv.second->stepStart = kv.second->body->GetTransform();
    I.inStep = true;
    I.world->Step(timeStep, velocityIterations, positionIterations);
    I.inStep = false;
    I.afterSolve = false;
}

rugo_status Bridge::SyncMass(b2Body* body) {
    Impl& I = *m_impl;
    if (body == nullptr) return RUGO_ERR_NULL_ARGUMENT;
    BodyRec* r = I.rec(body);
    if (r == nullptr) return RUGO_ERR_NOT_ATTACHED;
    if (I.world && I.world->IsLocked()) return RUGO_ERR_WORLD_LOCKED;
    I.applyMass(r);
    return RUGO_OK;
}

rugo_status Bridge::GetExactMass(const b2Body* body, b2MassData* out) const {
    if (body == nullptr || out == nullptr) return RUGO_ERR_NULL_ARGUMENT;
    const BodyRec* r = m_impl->rec(body);
    if (r == nullptr) return RUGO_ERR_NOT_ATTACHED;
    *out = m_impl->exactMass(r);
    return RUGO_OK;
}

BodyMemory Bridge::GetBodyMemory(const b2Body* body) const {
    BodyMemory m;
    const BodyRec* r = m_impl->rec(body);
    if (r == nullptr) return m;
    m.proxyCount = static_cast<int>(r->proxies.size());
    // Record + proxy list + the two hash-map entries (node: key, value, next pointer, cached hash).
    m.bridgeBytes = sizeof(BodyRec) + r->proxies.capacity() * sizeof(b2Fixture*) +
                    r->proxies.size() * (sizeof(const b2Fixture*) + sizeof(ProxyRef) + 2 * sizeof(void*)) +
                    sizeof(const b2Body*) + sizeof(BodyRec*) + 2 * sizeof(void*);
    // Per proxy: the fixture, its polygon (cloned into Box2D's block allocator), its b2FixtureProxy and
    // one dynamic-tree node of the broad phase.
    m.box2dBytes = r->proxies.size() *
                   (sizeof(b2Fixture) + sizeof(b2PolygonShape) + sizeof(b2FixtureProxy) + sizeof(b2TreeNode));
    // The shared shape, estimated from its arrays: per segment of each level the control point, λ own,
    // total, bound, band bound and one tree box.
    const int J = rugo_shape_finest_level(r->shape), Jmin = rugo_shape_coarsest_level(r->shape);
    size_t bytes = 0;
    for (int j = Jmin; j <= J; ++j)
        bytes +=
            (static_cast<size_t>(1) << j) * (sizeof(rugo_vec2) + 4 * sizeof(rugo_real) + sizeof(rugo_obb));
    m.sharedShapeBytes = bytes;
    return m;
}

BridgeStats Bridge::GetStats() const { return m_impl->stats; }
void Bridge::ResetStats() { m_impl->stats = BridgeStats(); }
b2World* Bridge::GetWorld() const { return m_impl->world; }
void Bridge::SetDestructionListener(b2DestructionListener* listener) { m_impl->userDestruction = listener; }

void Bridge::ReleaseWorld() {
    Impl& I = *m_impl;
    I.world = nullptr;
    for (auto& kv : I.bodies)
        delete kv.second;
    I.bodies.clear();
    I.proxies.clear();
    ++I.gen;
}

} // namespace rugo
