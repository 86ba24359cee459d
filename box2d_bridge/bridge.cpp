// The Box2D 2.4 bridge (include/rugo/box2d.hpp; docs/box2d.md). The bridge only translates: Box2D's
// broad phase pairs the proxy polygons, the bridge's b2Contact asks librugo for the contacts and writes
// them into Box2D's manifold (DESIGN.md, "The Box2D 2.4 bridge" and "Decisions of the second round",
// for the Box2D facts relied on). This file: the public API, the chaining of the user's listener and
// filter, and the body records; bridge_impl.hpp lists the files of the rest.
#include "bridge_impl.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>

namespace rugo {

Bridge::Impl::Impl() {
    table.resize(256);
    scratch.resize(64);
    patchScratch.reserve(64);
    lastContacts.reserve(4096);
}

Bridge::Impl::~Impl() {
    unregisterBridge(this);
    for (auto& kv : bodies)
        delete kv.second;
    queryEngineDestroy(query);
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

void Bridge::Impl::PreSolve(b2Contact* c, const b2Manifold* old) {
    if (rechained(kPre, c)) return;
    if (const RoughContact* rc = dynamic_cast<const RoughContact*>(c)) {
        // Box2D's continuous phase re-evaluating a manifold at the poses it was solved at: the bridge
        // disabled it (bridge_evaluate.cpp) and the user's PreSolve has seen it in this step.
        if (rc->repeated) return;
        ++stats.preSolves;
    }
    chain(kPre, c, [&] { prevListener->PreSolve(c, old); });
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
    releaseShapeData(r->data);
    delete r;
    ++gen; // the cache may key on this record's address
}

void Bridge::Impl::releaseShapeData(ShapeData* d) {
    if (d == nullptr || --d->users > 0) return;
    shapes.erase(std::make_tuple(d->shape, d->level, d->maxPieces));
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
        const BridgeDef defaults;
        auto sane = [](const rugo_mix_rule& given, rugo_mix_rule fallback) {
            int mix = 0;
            static_assert(sizeof mix == sizeof given, "rugo_mix_rule is an int");
            std::memcpy(&mix, &given, sizeof mix);
            return mix < RUGO_MIX_MAX || mix > RUGO_MIX_GEOMETRIC ? fallback : given;
        };
        I.def.pointFrictionMix = sane(def.pointFrictionMix, defaults.pointFrictionMix);
        I.def.fixtureFrictionMix = sane(def.fixtureFrictionMix, defaults.fixtureFrictionMix);
        I.def.fixtureRestitutionMix = sane(def.fixtureRestitutionMix, defaults.fixtureRestitutionMix);
        I.def.roughFrictionMix = sane(def.roughFrictionMix, defaults.roughFrictionMix);
        I.def.roughRestitutionMix = sane(def.roughRestitutionMix, defaults.roughRestitutionMix);
    }
    I.userDestruction = def.destructionListener;
    I.query = queryEngineCreate();
    if (world) {
        registerBridge(world, m_impl.get());
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
    unregisterBridge(m_impl.get());
}

const char* Bridge::LastError() const { return m_impl->lastError.c_str(); }

// Attach's refusals, each with the field, its value and a way out in LastError.
static rugo_status refuse(std::string& out, rugo_status st, const char* field, const char* message) {
    out = std::string(field) + ": " + message;
    return st;
}

// The same with the field's value: fmt has exactly one double conversion (%g, %.17g, %.6g).
static rugo_status refuse(std::string& out, rugo_status st, const char* field, const char* fmt,
                          double value) {
    char msg[320];
    std::snprintf(msg, sizeof msg, fmt, value);
    return refuse(out, st, field, msg);
}

rugo_status Bridge::Attach(b2Body* body, const RoughBodyDef& def) {
    Impl& I = *m_impl;
    std::string& e = I.lastError;
    e.clear();
    if (body == nullptr) return refuse(e, RUGO_ERR_NULL_ARGUMENT, "body", "is null");
    if (def.shape == nullptr)
        return refuse(e, RUGO_ERR_NULL_ARGUMENT, "RoughBodyDef::shape",
                      "is null; build one with rugo_shape_create "
                      "or load one with rugo_shape_load_file");
    if (I.world == nullptr || body->GetWorld() != I.world)
        return refuse(e, RUGO_ERR_BAD_ARGUMENT, "body", "belongs to another b2World than this bridge's");
    if (I.world->IsLocked() || I.removingProxies)
        return refuse(e, RUGO_ERR_WORLD_LOCKED, "body",
                      "the world is inside Step or a callback; attach after "
                      "the step");
    if (I.bodies.count(body))
        return refuse(e, RUGO_ERR_ALREADY_ATTACHED, "body", "already has a rough shape; Detach it first");
    if (!std::isfinite(def.density) || def.density < 0.0)
        return refuse(e, RUGO_ERR_BAD_ARGUMENT, "RoughBodyDef::density",
                      "is %.17g; give a finite density >= 0 "
                      "in kg/m^2 (e.g. 2500 for rock)",
                      def.density);
    if (def.density == 0.0 && body->GetType() == b2_dynamicBody)
        return refuse(e, RUGO_ERR_BAD_ARGUMENT, "RoughBodyDef::density",
                      "is %g; a dynamic body needs a density "
                      "> 0 in kg/m^2 (e.g. 2500 for rock, 1 for a toy)",
                      def.density);
    {
        const rugo_obb* root = rugo_mobb_tree_root(rugo_shape_tree(def.shape));
        const double size = root != nullptr ? 2.0 * std::hypot(root->half[0], root->half[1]) : 0.0;
        if (!(size <= kMaxBodySize))
            return refuse(e, RUGO_ERR_BAD_SIZE, "RoughBodyDef::shape",
                          "is %.6g m across, more than "
                          "Bridge::kMaxBodySize (1000 m); Box2D works in metres (0.1-10 m bodies): scale the "
                          "outline (rugo import --px-per-metre) or split the terrain",
                          size);
    }
    if (def.density > 0.0) {
        // Box2D keeps mass and inertia in floats and asserts a positive inertia (b2Assert is on in
        // Debian's build): a density that puts them out of [1e6 FLT_MIN, 1e-6 FLT_MAX] (room for the
        // products with speeds and gravity, and for the inverses) is refused now, not in SetMassData or
        // as NaN poses later.
        const Impl::RoughMass rm = Impl::roughMass(def.shape, def.density);
        const double lo = 1e6 * static_cast<double>(FLT_MIN), hi = 1e-6 * static_cast<double>(FLT_MAX);
        if (!(rm.mass >= lo && rm.mass <= hi && rm.inertiaCentre >= lo && rm.inertiaCentre <= hi &&
              rm.inertiaOrigin <= hi))
            return refuse(e, RUGO_ERR_BAD_ARGUMENT, "RoughBodyDef::density",
                          "is %.17g, which puts the body's "
                          "mass or inertia beyond Box2D's floats; use kg/m^2 and a shape in metres",
                          def.density);
    }
    if (I.query == nullptr) return RUGO_ERR_OUT_OF_MEMORY;
    if (def.maxProxies < 0 || def.maxProxies > b2_maxPolygonVertices)
        return refuse(e, RUGO_ERR_BAD_ARGUMENT, "RoughBodyDef::maxProxies",
                      "is %g; give 0 (the bridge's) or "
                      "1..8",
                      def.maxProxies);
    if (!std::isfinite(def.rollingResistance) || def.rollingResistance < 0.0)
        return refuse(e, RUGO_ERR_BAD_ARGUMENT, "RoughBodyDef::rollingResistance",
                      "is %.17g; give a factor >= 0 (0 switches rolling resistance off, "
                      "rugo::kDefaultRollingResistance is calibrated)",
                      def.rollingResistance);
    const int cap = def.maxProxies > 0
                        ? def.maxProxies
                        : (I.def.maxProxies >= 1 && I.def.maxProxies <= 8 ? I.def.maxProxies : 8);
    const rugo_shape* s = def.shape;
    const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
    int level;
    const double budget = def.errorBudget >= 0.0 ? def.errorBudget : I.def.errorBudget;
    if (def.lod == RUGO_LOD_AUTO) {
        level = rugo_shape_level_for_error(s, budget);
    } else if (def.lod > 0) {
        return refuse(e, RUGO_ERR_BAD_ARGUMENT, "RoughBodyDef::lod",
                      "is %g; give 0 (finest), a negative "
                      "level of detail or RUGO_LOD_AUTO",
                      def.lod);
    } else {
        level = std::max(Jmin, J + std::max(def.lod, Jmin - J));
    }
    // The query engine's room for this shape's queries, now rather than during a step (librugo grows
    // its context to a new high-water mark otherwise). kQueryReserveContacts: see its comment.
    const rugo_status reserved = queryEngineReserve(I.query, s, kQueryReserveContacts);
    if (reserved != RUGO_OK) return reserved;
    // The shape's pieces and faces at this level, shared with other bodies of the same shape.
    ShapeData* data = nullptr;
    {
        const auto key = std::make_tuple(s, level, cap);
        auto it = I.shapes.find(key);
        if (it == I.shapes.end()) {
            std::unique_ptr<ShapeData> d(new (std::nothrow) ShapeData);
            if (!d || !buildShapeData(s, level, cap, d.get())) return RUGO_ERR_OUT_OF_MEMORY;
            it = I.shapes.emplace(key, std::move(d)).first;
        }
        data = it->second.get();
    }
    const rugo_mobb_tree* tree = rugo_shape_tree(s);
    BodyRec* r = new (std::nothrow) BodyRec;
    if (r == nullptr) {
        if (data->users == 0) I.shapes.erase(std::make_tuple(s, level, cap));
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    ++data->users;
    r->body = body;
    r->shape = s;
    r->data = data;
    r->density = def.density;
    r->rollingResistance = def.rollingResistance;
    r->serial = I.nextSerial++;
    r->level = level;
    r->budget = budget;
    r->relLevel = level - J;
    rugo_obb_corners(rugo_mobb_tree_root(tree), r->rootCorners);
    r->proxies.reserve(data->pieces.size());
    for (size_t k = 0; k < data->pieces.size(); ++k) {
        const Piece& pc = data->pieces[k];
        b2PolygonShape poly;
        poly.Set(pc.v, pc.n);
        poly.m_radius = pc.radius; // the skin that, around the core, encloses the curve and its band
        b2FixtureDef fd;
        fd.shape = &poly;
        fd.density = 0.0f;
        fd.filter = def.filter;
        fd.isSensor = def.isSensor;
        fd.userData = def.userData;
        b2Fixture* f = body->CreateFixture(&fd);
        r->proxies.push_back(f);
        I.proxies[f] = ProxyRef{r, static_cast<int>(k)};
    }
    I.bodies[body] = r;
    I.reserveFor(I.bodies.size());
    I.reservePointInfo(I.bodies.size());
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
    I.releaseShapeData(r->data);
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
int Bridge::GetProxyCount(const b2Body* body) const {
    const BodyRec* r = m_impl->rec(body);
    return r ? static_cast<int>(r->proxies.size()) : 0;
}
bool Bridge::IsProxy(const b2Fixture* fixture, int* piece) const {
    const ProxyRef* p = m_impl->lookup(fixture);
    if (p && piece) *piece = p->piece;
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
    ++I.stepSerial;
    I.used = 0;
    I.patches.clear();
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
    I.shapes.clear();
    ++I.gen;
    unregisterBridge(m_impl.get());
}

} // namespace rugo
