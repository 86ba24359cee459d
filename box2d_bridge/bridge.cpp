// The Box2D 2.4 bridge (include/rugo/box2d.hpp; docs/box2d.md). The bridge only translates: Box2D's
// broad phase and proxy boxes pick candidate pairs, librugo decides the contacts, and PreSolve writes
// them into Box2D's manifold (DESIGN.md, "The Box2D 2.4 bridge", for the Box2D facts relied on).
#include "rugo/box2d.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace rugo {

namespace {

struct BodyRec {
    b2Body* body = nullptr;
    const rugo_shape* shape = nullptr;
    double density = 1.0;
    int serial = 0;         // attach order: a deterministic canonical order for pair queries
    int relLevel = 0;       // contact level relative to the finest (<= 0)
    int level = 0;          // absolute contact level
    int proxyLevel = 0;     // absolute proxy level
    std::vector<b2Fixture*> proxies;
    rugo_vec2 rootCorners[4]; // local frame, for the speed bound
    b2MassData applied;     // what GetMassData returned right after the bridge set the mass
    bool massValid = false;
    b2Transform stepStart;  // the pose when Bridge::Step began (a moved body means Box2D's TOI phase)
    std::vector<double> bandMax; // per absolute level J_min..J (index level - J_min): certified max of λ(t)
};

struct ProxyRef {
    BodyRec* rec;
    int node;
};

// One bridge point in Box2D's orientation (fixture A -> fixture B), world coordinates.
struct BPoint {
    b2Vec2 pA, pB; // on A's side and B's side (curves or primitive boundary)
    b2Vec2 n;      // unit, A -> B
    b2Vec2 m;      // joints: the rough curve's normal there, oriented A -> B (flatness test)
    double s;      // band-adjusted separation
    double mu, eps;
    uint32 key;
    bool edgeFace = false; // a joint whose closest point is inside an edge: n is that edge's face normal
};

struct CacheEntry {
    uint64_t gen = 0;
    const void* a = nullptr;
    const void* b = nullptr;
    int child = 0;
    float xf[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    double margin = 0.0;
    int level = 0;
    uint32_t start = 0, count = 0;
    bool toi = false; // run in Box2D's TOI phase
    // Rough pairs: the first JointChunk (Impl::jointChunks) of the joints of the query's shape A [0]
    // and B [1] (kNoJoints: none computed yet).
    uint32_t joints[2] = {0xFFFFFFFFu, 0xFFFFFFFFu};
};

constexpr uint32_t kNoJoints = 0xFFFFFFFFu;

// One joint's closest point on the other body's curve (same poses, same level): shared by every proxy
// pair of the body pair that offers the joint (each used to recompute it: measured ~70% of a step).
struct JointInfo {
    rugo_curve_point cp;
    signed char inside = -1; // rugo_contour_contains, -1 = not computed yet
    bool done = false;
};
// The joints of one proxy piece (node) of one side of a body pair's query: Impl::jointPool[base ..
// base + per] (its per joints and the piece's end), chained from CacheEntry::joints.
struct JointChunk {
    int node;
    uint32_t next, base;
};

// A joint point joins a contact region only if its own closest-point direction is within ~10° of the
// region's normal (it then takes that normal; attachJoint).
constexpr float kJointRegionCos = 0.985f;
// Largest |restitution| a speculative point gets (TOI phase): a point approaching 1000x slower than
// its gap per step is as good as not approaching.
constexpr double kMaxSpeculativeRestitution = 1000.0;
// Rotation per step (radians) from which a pair counts as fast for the TOI rule (docs/box2d.md).
constexpr double kFastTurn = 0.3;
// Contacts per query the librugo context is sized for when a body is attached (a body pair's query
// reports a handful; a pile's deepest pairs a few more): past it, librugo grows the context in a step.
constexpr int kQueryReserveContacts = 16;

inline uint32 hashId(uint64_t id) {
    // splitmix64 finaliser folded to 32 bits: distinct librugo ids rarely collide in a manifold.
    uint64_t z = id + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<uint32>(z ^ (z >> 32));
}

inline uint64_t mixHash(uint64_t h, uint64_t v) {
    h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    return h;
}

inline uint64_t floatBits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

inline rugo_transform toRugo(const b2Transform& x) {
    rugo_transform t;
    t.p = rugo_v2(static_cast<double>(x.p.x), static_cast<double>(x.p.y));
    t.q.c = static_cast<double>(x.q.c);
    t.q.s = static_cast<double>(x.q.s);
    // Box2D's float rotation is unit only to ~1e-7; librugo assumes unit rotations.
    const double len = std::sqrt(t.q.c * t.q.c + t.q.s * t.q.s);
    if (len > 0.0) {
        t.q.c /= len;
        t.q.s /= len;
    }
    return t;
}

inline b2Vec2 toB2(rugo_vec2 v) { return b2Vec2(static_cast<float>(v.x), static_cast<float>(v.y)); }
inline rugo_vec2 toRv(b2Vec2 v) { return rugo_v2(static_cast<double>(v.x), static_cast<double>(v.y)); }

} // namespace

struct Bridge::Impl : public b2ContactListener, public b2ContactFilter, public b2DestructionListener {
    b2World* world = nullptr;
    BridgeDef def;
    b2ContactListener* prevListener = nullptr;
    b2ContactFilter* prevFilter = nullptr;
    b2DestructionListener* userDestruction = nullptr;
    rugo_collide_context* ctx = nullptr;
    std::unordered_map<const b2Body*, BodyRec*> bodies;
    std::unordered_map<const b2Fixture*, ProxyRef> proxies;
    int nextSerial = 0;
    float dt = 1.0f / 60.0f;
    bool afterSolve = false; // a PostSolve was seen since the collide phase: later PreSolves are TOI
    bool inStep = false;     // inside Bridge::Step (the stepStart poses are current)
    bool toiPhase = false;   // the PreSolve being handled runs in Box2D's TOI phase
    double curMargin = 0.0;  // the margin of the current proxy pair's query
    double curReach = 0.0;   // the larger extent (from its centre of mass) of the pair's bodies
    bool fastPair = false;   // TOI phase and fast (kFastTurn, margin > reach): the TOI rule applies
    BridgeStats stats;

    // Query cache (open addressing; generation counter clears it in O(1)).
    std::vector<CacheEntry> table;
    std::vector<rugo_contact> pool;
    std::vector<rugo_contact> scratch;
    std::vector<JointInfo> jointPool;   // per step like pool (CacheEntry::joints)
    std::vector<JointChunk> jointChunks;
    size_t lastEntry = 0;             // table index of the last cachedQuery's entry
    uint64_t gen = 1;
    size_t used = 0;
    std::vector<BPoint> cand;
    std::vector<BPoint> joints;
    std::vector<BPoint> apart; // TOI phase: joints of the owned piece that are apart but within the margin
    std::vector<BPoint> regions; // all of the query's librugo contacts (any proxy pair) that touch: the regions
    struct DrawnContact {
        b2Vec2 p, n;
    };
    std::vector<DrawnContact> lastContacts;

    Impl() {
        table.resize(256);
        scratch.resize(64);
        for (std::vector<BPoint>* v : {&cand, &joints, &apart, &regions})
            v->reserve(64);
        lastContacts.reserve(4096); // its cap (write)
    }

    // Room for the per-step caches of n rough bodies, reserved when a body is attached so that steps
    // do not allocate once librugo's query context has grown (docs/box2d.md): per body 8 cached
    // queries (at most half the table used), 16 contacts and the joints of 8 proxy pieces (piece of
    // `per` joints). About 4 kB per body plus 0.4 kB per joint of a piece (table rounded up to a
    // power of two).
    size_t jointReserve = 0;
    void reserveFor(size_t n, int per) {
        jointReserve += 8 * (static_cast<size_t>(per) + 1);
        size_t want = table.size();
        while (want < 16 * n && want < 65536)
            want *= 2;
        if (want != table.size()) {
            table.assign(want, CacheEntry());
            ++gen;
            used = 0;
            pool.clear();
            jointPool.clear();
            jointChunks.clear();
        }
        pool.reserve(16 * n);
        jointPool.reserve(jointReserve);
        jointChunks.reserve(8 * n);
    }

    ~Impl() override {
        for (auto& kv : bodies)
            delete kv.second;
        rugo_collide_context_destroy(ctx);
    }

    // ---- chaining ----------------------------------------------------------------------------
    void BeginContact(b2Contact* c) override {
        if (prevListener) prevListener->BeginContact(c);
    }
    void EndContact(b2Contact* c) override {
        if (prevListener) prevListener->EndContact(c);
    }
    void PostSolve(b2Contact* c, const b2ContactImpulse* imp) override {
        afterSolve = true;
        if (prevListener) prevListener->PostSolve(c, imp);
    }
    bool ShouldCollide(b2Fixture* a, b2Fixture* b) override {
        return prevFilter ? prevFilter->ShouldCollide(a, b) : b2ContactFilter::ShouldCollide(a, b);
    }
    void SayGoodbye(b2Joint* j) override {
        if (userDestruction) userDestruction->SayGoodbye(j);
    }
    void SayGoodbye(b2Fixture* f) override {
        ++destroyedFixtures;
        auto it = proxies.find(f);
        // A proxy is destroyed by Box2D only with its body (Detach goes through the bridge).
        if (it != proxies.end()) forget(it->second.rec);
        if (userDestruction) userDestruction->SayGoodbye(f);
    }

    void forget(BodyRec* r) {
        for (b2Fixture* f : r->proxies)
            proxies.erase(f);
        bodies.erase(r->body);
        delete r;
        ++gen; // the cache may key on this record's address
    }

    void rechain() {
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

    const ProxyRef* lookup(const b2Fixture* f) const {
        auto it = proxies.find(f);
        return it == proxies.end() ? nullptr : &it->second;
    }
    BodyRec* rec(const b2Body* b) const {
        auto it = bodies.find(b);
        return it == bodies.end() ? nullptr : it->second;
    }
    // The rough bodies in attach order (deterministic, unlike the hash map's order).
    std::vector<b2Body*> bodiesInAttachOrder() const {
        std::vector<const BodyRec*> recs;
        for (const auto& kv : bodies)
            recs.push_back(kv.second);
        std::sort(recs.begin(), recs.end(), [](const BodyRec* a, const BodyRec* b) { return a->serial < b->serial; });
        std::vector<b2Body*> out;
        for (const BodyRec* r : recs)
            out.push_back(r->body);
        return out;
    }
    bool removingProxies = false; // inside Detach's DestroyFixture calls (EndContact may run)
    // Bodies destroyed since construction (SayGoodbye of any fixture): a callback of the bridge's own
    // (QueryAABB, Draw) that changed it may have destroyed bodies the bridge still holds.
    long destroyedFixtures = 0;

    // ---- mass ------------------------------------------------------------------------------------
    b2MassData exactMass(const BodyRec* r) const {
        const rugo_mass_properties mp = rugo_shape_mass(r->shape);
        double m = mp.area * r->density;
        double cx = m * mp.centroid.x, cy = m * mp.centroid.y;
        double iOrigin = r->density * mp.inertia + m * (mp.centroid.x * mp.centroid.x + mp.centroid.y * mp.centroid.y);
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
        out.center = m > 0.0 ? b2Vec2(static_cast<float>(cx / m), static_cast<float>(cy / m)) : b2Vec2(0.0f, 0.0f);
        out.I = static_cast<float>(iOrigin);
        return out;
    }

    static bool sameMass(const b2MassData& a, const b2MassData& b) {
        return a.mass == b.mass && a.I == b.I && a.center.x == b.center.x && a.center.y == b.center.y;
    }

    void applyMass(BodyRec* r) {
        if (r->body->GetType() != b2_dynamicBody) {
            r->massValid = false; // Box2D keeps no mass for static/kinematic; repaired when dynamic again
            return;
        }
        const b2MassData md = exactMass(r);
        r->body->SetMassData(&md);
        r->body->GetMassData(&r->applied);
        r->massValid = true;
    }

    bool massStale(const BodyRec* r) const {
        if (r->body->GetType() != b2_dynamicBody) return false;
        if (!r->massValid) return true;
        b2MassData now;
        r->body->GetMassData(&now);
        return !sameMass(now, r->applied);
    }

    // ---- levels --------------------------------------------------------------------------------
    // The coarsest level whose certified level-of-detail error (rugo_shape_level_error: how far its
    // curve-plus-band can lie from the finest one's, anywhere on the outline) is within the budget at
    // it and at every finer level, so a pair evaluated at the finer of its two levels keeps each body's
    // share of the error within its budget too.
    static int autoLevel(const rugo_shape* s, double budget) {
        const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
        int level = J;
        for (int j = J - 1; j >= Jmin; --j) {
            double e = 0.0;
            if (rugo_shape_level_error(s, j, nullptr, &e) != RUGO_OK || !(e <= budget)) break;
            level = j;
        }
        return level;
    }

    // Largest excess of λ(t) over the segment value λ^j_k at levels from..J: queries at those levels
    // grow boxes by it, so the proxies must too.
    static double bandExcess(const rugo_shape* s, int from) {
        double e = 0.0;
        for (int j = from; j <= rugo_shape_finest_level(s); ++j) {
            rugo_tolerance_level tl;
            if (rugo_shape_tolerance_level(s, j, &tl) != RUGO_OK) continue;
            for (int k = 0; k < tl.count; ++k)
                e = std::max(e, rugo_tolerance_bound_on_segment(tl.total, tl.count, k, 0.0) - tl.total[k]);
        }
        return e;
    }

    // Distance from p to box b (0 inside), in the box's frame.
    static double obbDistance(const rugo_obb* b, rugo_vec2 p) {
        const rugo_vec2 d = rugo_v2_sub(p, b->center);
        const double u = std::max(std::fabs(rugo_v2_dot(d, b->axis[0])) - b->half[0], 0.0);
        const double v = std::max(std::fabs(rugo_v2_dot(d, b->axis[1])) - b->half[1], 0.0);
        return std::hypot(u, v);
    }

    // Certified largest λ(t) over each level's curve, levels J_min..J (index level - J_min).
    static std::vector<double> bandMaxima(const rugo_shape* s) {
        const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
        std::vector<double> m(static_cast<size_t>(J - Jmin + 1), 0.0);
        for (int j = Jmin; j <= J; ++j) {
            rugo_tolerance_level tl;
            if (rugo_shape_tolerance_level(s, j, &tl) != RUGO_OK) continue;
            for (int k = 0; k < tl.count; ++k)
                m[static_cast<size_t>(j - Jmin)] = std::max(m[static_cast<size_t>(j - Jmin)], rugo_tolerance_bound_on_segment(tl.total, tl.count, k, 0.0));
        }
        return m;
    }

    // ---- query cache --------------------------------------------------------------------------
    // Runs (or finds) one librugo query; returns the contacts as [start, start+count) of pool.
    // (A template, not std::function: a capturing lambda in a std::function may allocate per query.)
    template <class Run>
    bool cachedQuery(const void* a, const void* b, int child, const b2Transform& xa, const b2Transform& xb,
                     double margin, int level, Run&& run, uint32_t* start, uint32_t* count) {
        if (used * 2 >= table.size()) {
            if (table.size() < 65536) {
                table.assign(table.size() * 2, CacheEntry());
                pool.clear();
                jointPool.clear();
                jointChunks.clear();
            }
            ++gen;
            used = 0;
        }
        if (pool.size() > (1u << 20) || jointPool.size() > (1u << 20)) {
            pool.clear();
            jointPool.clear();
            jointChunks.clear();
            ++gen;
            used = 0;
        }
        const float xf[8] = {xa.p.x, xa.p.y, xa.q.c, xa.q.s, xb.p.x, xb.p.y, xb.q.c, xb.q.s};
        const size_t mask = table.size() - 1;
        size_t i = static_cast<size_t>(cacheHash(a, b, child, xf)) & mask;
        for (;; i = (i + 1) & mask) {
            CacheEntry& e = table[i];
            if (e.gen != gen) break;
            if (e.a == a && e.b == b && e.child == child && e.margin == margin && e.level == level &&
                std::memcmp(e.xf, xf, sizeof xf) == 0) {
                ++stats.cacheHits;
                lastEntry = i;
                *start = e.start;
                *count = e.count;
                return true;
            }
        }
        int n = 0;
        rugo_query_stats qs;
        rugo_status st = run(scratch.data(), static_cast<int>(scratch.size()), &n, &qs);
        if (st == RUGO_OK && qs.contacts_found > static_cast<int>(scratch.size())) {
            scratch.resize(static_cast<size_t>(qs.contacts_found) * 2); // warm-up only
            st = run(scratch.data(), static_cast<int>(scratch.size()), &n, &qs);
        }
        ++stats.queries;
        stats.boxTests += qs.box_tests;
        stats.segmentPairs += qs.segment_pairs;
        stats.fallbacks += qs.fallbacks;
        if (st != RUGO_OK) n = 0;
        CacheEntry& e = table[i];
        e.gen = gen;
        e.a = a;
        e.b = b;
        e.child = child;
        std::memcpy(e.xf, xf, sizeof xf);
        e.margin = margin;
        e.level = level;
        e.toi = toiPhase;
        e.joints[0] = e.joints[1] = kNoJoints;
        lastEntry = i;
        e.start = static_cast<uint32_t>(pool.size());
        e.count = static_cast<uint32_t>(n);
        pool.insert(pool.end(), scratch.begin(), scratch.begin() + n);
        ++used;
        *start = e.start;
        *count = e.count;
        return st == RUGO_OK;
    }

    static uint64_t cacheHash(const void* a, const void* b, int child, const float* xf) {
        uint64_t h = mixHash(reinterpret_cast<uintptr_t>(a), reinterpret_cast<uintptr_t>(b));
        h = mixHash(h, static_cast<uint64_t>(child));
        for (int k = 0; k < 8; ++k)
            h = mixHash(h, floatBits(xf[k]));
        return h;
    }

    // Was this pair queried in this step's collide phase at exactly these poses? (Box2D's TOI phase
    // then handles an event at the step's start, alpha = 0.)
    bool seenInCollide(const void* a, const void* b, int child, const b2Transform& xa, const b2Transform& xb) const {
        const float xf[8] = {xa.p.x, xa.p.y, xa.q.c, xa.q.s, xb.p.x, xb.p.y, xb.q.c, xb.q.s};
        const size_t mask = table.size() - 1;
        for (size_t i = static_cast<size_t>(cacheHash(a, b, child, xf)) & mask;; i = (i + 1) & mask) {
            const CacheEntry& e = table[i];
            if (e.gen != gen) return false;
            if (!e.toi && e.a == a && e.b == b && e.child == child && std::memcmp(e.xf, xf, sizeof xf) == 0) return true;
        }
    }

    // ---- speed bound --------------------------------------------------------------------------
    static double roughReach(const BodyRec* r) {
        const b2Vec2 lc = r->body->GetLocalCenter();
        double m = 0.0;
        for (const rugo_vec2& c : r->rootCorners)
            m = std::max(m, std::hypot(c.x - static_cast<double>(lc.x), c.y - static_cast<double>(lc.y)));
        return m;
    }
    static double fixtureReach(const b2Fixture* f, int child) {
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
    static double speedBound(const b2Body* a, double ra, const b2Body* b, double rb) {
        const b2Vec2 dv = a->GetLinearVelocity() - b->GetLinearVelocity();
        return static_cast<double>(dv.Length()) + std::fabs(static_cast<double>(a->GetAngularVelocity())) * ra +
               std::fabs(static_cast<double>(b->GetAngularVelocity())) * rb;
    }
    // Normal approach speed of B's point toward A's point along n (A -> B).
    static double approach(const b2Body* a, b2Vec2 pa, const b2Body* b, b2Vec2 pb, b2Vec2 n) {
        const b2Vec2 va = a->GetLinearVelocityFromWorldPoint(pa), vb = b->GetLinearVelocityFromWorldPoint(pb);
        return -static_cast<double>(b2Dot(vb - va, n));
    }


    // ---- joint points: Box2D-like second points on flat contacts ---------------------------------
    // librugo reports one contact per local minimum or overlap region; a slightly tilted flat face has
    // one minimum (its lower end), so a block would rock on one point. Like Box2D's clipping, the
    // joints (t = 0) of the owned segments that also touch (band-adjusted separation <= 0) are offered
    // as manifold points; the reduction keeps the deepest and the farthest.
    static int absLevel(const rugo_shape* s, int rel) {
        const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
        return std::max(Jmin, std::min(J, J + rel));
    }

    // Signed distance from world point p to an ordinary fixture's boundary (core grown by m_radius),
    // closest boundary point in *q. Returns false for unsupported shapes.
    static bool primitiveDistance(const b2Fixture* f, int child, b2Vec2 p, double* sd, b2Vec2* q, double* tEdge) {
        const b2Transform& x = f->GetBody()->GetTransform();
        const b2Shape* sh = f->GetShape();
        const float r = sh->m_radius;
        *tEdge = 0.0;
        auto fromFoot = [&](b2Vec2 foot, bool inside) {
            b2Vec2 d = p - foot;
            float len = d.Length();
            b2Vec2 u = len > 0.0f ? (1.0f / len) * d : b2Vec2(0.0f, 1.0f);
            if (inside) u = -u;
            *q = foot + r * u;
            *sd = static_cast<double>(inside ? -len : len) - static_cast<double>(r);
        };
        switch (sh->GetType()) {
        case b2Shape::e_circle:
            fromFoot(b2Mul(x, static_cast<const b2CircleShape*>(sh)->m_p), false);
            return true;
        case b2Shape::e_edge:
        case b2Shape::e_chain: {
            b2EdgeShape e;
            if (sh->GetType() == b2Shape::e_chain)
                static_cast<const b2ChainShape*>(sh)->GetChildEdge(&e, child);
            else
                e = *static_cast<const b2EdgeShape*>(sh);
            const b2Vec2 a = b2Mul(x, e.m_vertex1), b = b2Mul(x, e.m_vertex2), d = b - a;
            const float l2 = b2Dot(d, d);
            float t = l2 > 0.0f ? b2Dot(p - a, d) / l2 : 0.0f;
            *tEdge = static_cast<double>(t);
            t = b2Clamp(t, 0.0f, 1.0f);
            fromFoot(a + t * d, false);
            return true;
        }
        case b2Shape::e_polygon: {
            const b2PolygonShape* ps = static_cast<const b2PolygonShape*>(sh);
            const b2Vec2 pl = b2MulT(x, p);
            float maxSep = -b2_maxFloat;
            int face = 0;
            for (int i = 0; i < ps->m_count; ++i) {
                const float sep = b2Dot(ps->m_normals[i], pl - ps->m_vertices[i]);
                if (sep > maxSep) {
                    maxSep = sep;
                    face = i;
                }
            }
            if (maxSep <= 0.0f) { // inside the core: out through the nearest face
                *sd = static_cast<double>(maxSep) - static_cast<double>(r);
                *q = b2Mul(x, pl + (r - maxSep) * ps->m_normals[face]);
                return true;
            }
            float best = b2_maxFloat;
            b2Vec2 foot = pl;
            for (int i = 0; i < ps->m_count; ++i) {
                const b2Vec2 a = ps->m_vertices[i], b = ps->m_vertices[(i + 1) % ps->m_count], d = b - a;
                const float l2 = b2Dot(d, d);
                const float t = l2 > 0.0f ? b2Clamp(b2Dot(pl - a, d) / l2, 0.0f, 1.0f) : 0.0f;
                const b2Vec2 ft = a + t * d;
                const float dd = b2DistanceSquared(pl, ft);
                if (dd < best) {
                    best = dd;
                    foot = ft;
                }
            }
            fromFoot(b2Mul(x, foot), false);
            return true;
        }
        default:
            return false;
        }
    }

    // Joints of the segments of `r` owned by proxy `node` at absolute level L (world points, λ there).
    // With withEnd, also the piece's end (the next piece's first joint) as k = (node + 1) * per, so
    // that the joints bound the piece's closest point from both sides. The curve's normal there comes
    // as a callable (computed only for the joints that are kept).
    template <class F>
    static void forJoints(const BodyRec* r, int node, int L, bool withEnd, F&& fn) {
        rugo_contour curve;
        rugo_tolerance_level tl;
        if (rugo_shape_level(r->shape, L, &curve) != RUGO_OK || rugo_shape_tolerance_level(r->shape, L, &tl) != RUGO_OK) return;
        const int per = 1 << (L - r->proxyLevel);
        const rugo_transform x = toRugo(r->body->GetTransform());
        const int last = (node + 1) * per + (withEnd ? 1 : 0);
        for (int k = node * per; k < last; ++k) {
            const int kk = k % curve.count;
            const rugo_vec2 pl = rugo_contour_point(curve, kk, 0.0);
            const auto normal = [&curve, &x, kk]() { return toB2(rugo_rotate(x.q, rugo_contour_normal(curve, kk, 0.0))); };
            fn(k, toB2(rugo_transform_point(x, pl)), rugo_tolerance_at(tl.total, tl.count, kk, 0.0, 0.0), normal);
        }
    }

    // ---- one-sided edges: chain children and b2EdgeShape with m_oneSided --------------------------
    // Box2D 2.4.1 (b2_collide_edge.cpp) collides a one-sided edge only with a body whose centroid is in
    // front of it (on the right of v1 -> v2), and keeps the normal in the edge's Gauss map set by its
    // ghost vertices: the face normal along the edge; at a convex vertex a normal between the two
    // edges' normals; at a flat or concave vertex the face normal ("snap"). That is what keeps bodies
    // from catching on a chain's inner vertices (ghost collisions); the bridge applies the same rules to
    // the curve's points. A point beyond a vertex that a real neighbouring child also covers is that
    // child's (the previous child's face before v1; the next child's from v2 on, its t = 0).
    struct OneSided {
        bool on = false;
        b2Vec2 v1, v2, e0, e1, n0, n1, n2; // world; e* unit directions, n* front normals
        float len = 0.0f, radius = 0.0f;
        bool convex1 = false, convex2 = false;
        bool hasPrev = false, hasNext = false; // a real neighbouring child, not only a ghost vertex
        bool roundEnds = false; // a two-sided edge: beyond its ends, its round caps
    };
    OneSided oneSided; // of the fixture child being gathered (gatherPrimitive)

    static OneSided makeOneSided(const b2EdgeShape& e, const b2Transform& x, bool hasPrev, bool hasNext) {
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
    static OneSided makeTwoSided(const b2EdgeShape& e, const b2Transform& x, b2Vec2 centroid) {
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

    // A curve point p (world) against the one-sided edge: false if another child reports it; else the
    // normal out of the edge toward p (*m) and p's signed distance along it from the edge's skin.
    static bool resolveOneSided(const OneSided& o, b2Vec2 p, b2Vec2* m, double* dist) {
        const float along = b2Dot(p - o.v1, o.e1);
        b2Vec2 base = o.v1;
        *m = o.n1;
        if (along < 0.0f) {
            if (o.hasPrev && b2Dot(p - o.v1, o.e0) < 0.0f) return false; // on the previous child's face
            if (o.roundEnds) {
                b2Vec2 d = p - o.v1;
                if (d.Normalize() > 0.0f) *m = d;
            } else if (o.convex1) {
                b2Vec2 d = p - o.v1;
                if (d.Normalize() > 0.0f) *m = b2Cross(o.n0, d) < 0.0f ? o.n0 : (b2Cross(d, o.n1) < 0.0f ? o.n1 : d);
            }
        } else if (along >= o.len) {
            if (o.hasNext) return false; // the next child's (its t = 0)
            base = o.v2;
            if (o.roundEnds) {
                b2Vec2 d = p - o.v2;
                if (d.Normalize() > 0.0f) *m = d;
            } else if (o.convex2) {
                b2Vec2 d = p - o.v2;
                if (d.Normalize() > 0.0f) *m = b2Cross(o.n1, d) < 0.0f ? o.n1 : (b2Cross(d, o.n2) < 0.0f ? o.n2 : d);
            }
        }
        *dist = static_cast<double>(b2Dot(p - base, *m)) - static_cast<double>(o.radius);
        return true;
    }

    void jointsVsPrimitive(const ProxyRef* r, bool roughIsA, const b2Fixture* other, int child, bool dropEnd) {
        const BodyRec* R = r->rec;
        const int L = absLevel(R->shape, R->relLevel);
        const int endK = (r->node + 1) << (L - R->proxyLevel);
        forJoints(R, r->node, L, fastPair, [&](int k, b2Vec2 p, double lam, const auto& out) {
            double sd, tEdge;
            b2Vec2 q;
            if (oneSided.on) {
                b2Vec2 m;
                if (!resolveOneSided(oneSided, p, &m, &sd)) return;
                q = p - static_cast<float>(sd) * m; // on the edge's skin
                tEdge = static_cast<double>(b2Dot(p - oneSided.v1, oneSided.e1) / oneSided.len);
            } else {
                if (!primitiveDistance(other, child, p, &sd, &q, &tEdge)) return;
                if (dropEnd && tEdge >= 1.0 - 1e-7) return;
            }
            const double s = sd - lam;
            if (s > 0.0 || k == endK) {
                if (fastPair && s <= curMargin)
                    pushJoint(roughIsA ? p : q, roughIsA ? q : p, sd < 0.0, roughIsA ? out() : -out(), s, other->GetFriction(),
                              other->GetRestitution(), R, k, 0x1000000u, &apart);
                return;
            }
            const size_t before = joints.size();
            pushJoint(roughIsA ? p : q, roughIsA ? q : p, sd < 0.0, roughIsA ? out() : -out(), s, other->GetFriction(),
                      other->GetRestitution(), R, k, 0x1000000u, &joints);
            const b2Shape::Type ty = other->GetShape()->GetType();
            if (joints.size() > before && (ty == b2Shape::e_edge || ty == b2Shape::e_chain) && tEdge > 0.0 && tEdge < 1.0)
                joints.back().edgeFace = true;
        });
    }

    void jointsVsRough(const ProxyRef* self, const ProxyRef* oth, bool selfIsA, int pairRel) {
        const BodyRec* S = self->rec;
        const BodyRec* O = oth->rec;
        const int LS = absLevel(S->shape, pairRel), LO = absLevel(O->shape, pairRel);
        rugo_tolerance_level otl;
        if (rugo_shape_tolerance_level(O->shape, LO, &otl) != RUGO_OK) return;
        const rugo_transform xo = toRugo(O->body->GetTransform());
        const rugo_friction_map fmO = rugo_shape_friction_map(O->shape), fmS = rugo_shape_friction_map(S->shape);
        const rugo_restitution eO = rugo_shape_restitution(O->shape), eS = rugo_shape_restitution(S->shape);
        const int endK = (self->node + 1) << (LS - S->proxyLevel);
        // The joints' closest points are kept with the body pair's query (gatherRough ran it just
        // before: table[lastEntry]), per piece of S; S is the query's A when it comes first in attach order.
        const int per = 1 << (LS - S->proxyLevel);
        uint32_t& head = table[lastEntry].joints[S->serial < O->serial ? 0 : 1];
        uint32_t chunk = head;
        while (chunk != kNoJoints && jointChunks[chunk].node != self->node)
            chunk = jointChunks[chunk].next;
        // Only within the capacity reserved in Attach: beyond it the joints are computed without being
        // kept (same results, more work), so that a step never allocates here.
        if (chunk == kNoJoints && jointChunks.size() < jointChunks.capacity() &&
            jointPool.size() + static_cast<size_t>(per) + 1 <= jointPool.capacity()) {
            chunk = static_cast<uint32_t>(jointChunks.size());
            jointChunks.push_back(JointChunk{self->node, head, static_cast<uint32_t>(jointPool.size())});
            head = chunk;
            jointPool.resize(jointPool.size() + static_cast<size_t>(per) + 1);
        }
        JointInfo* known = chunk == kNoJoints ? nullptr : jointPool.data() + jointChunks[chunk].base;
        JointInfo unkept;
        const int firstK = self->node * per;
        // A joint outside O and farther from the other piece's box than the bands plus the margin a
        // pushed joint may have cannot be pushed below (its closest point is on another piece, or on
        // this one and apart): its closest point is not needed for this proxy pair. The box holds the
        // piece's curve at level LO (mobb.h); the pad covers rounding.
        const rugo_obb* othBox = rugo_mobb_tree_node(rugo_shape_tree(O->shape), O->proxyLevel, oth->node);
        const double reachO = (fastPair ? std::max(curMargin, 0.0) : 0.0) + O->bandMax[static_cast<size_t>(LO - rugo_shape_coarsest_level(O->shape))];
        forJoints(S, self->node, LS, fastPair, [&](int k, b2Vec2 p, double lam, const auto& out) {
            const rugo_vec2 pl = rugo_inv_transform_point(xo, toRv(p));
            if (known == nullptr) unkept = JointInfo();
            JointInfo& ji = known ? known[k - firstK] : unkept;
            // Whether the joint is inside O (level LO's curve, through the tree), computed once.
            const auto isInside = [&]() {
                if (ji.inside < 0) {
                    int in = 0;
                    rugo_shape_contains(O->shape, LO, pl, &in);
                    ji.inside = in != 0 ? 1 : 0;
                }
                return ji.inside != 0;
            };
            if (!ji.done && othBox != nullptr) {
                const double reach = (reachO + lam) * (1.0 + 1e-9) + 1e-9 * (othBox->half[0] + othBox->half[1]);
                if (obbDistance(othBox, pl) > reach && !isInside()) return;
            }
            if (!ji.done) {
                rugo_shape_closest_point(O->shape, LO, pl, &ji.cp); // level LO's curve, through the tree
                ji.done = true;
            }
            const rugo_curve_point cp = ji.cp;
            if ((cp.segment >> (LO - O->proxyLevel)) != oth->node) return; // another proxy pair's point
            const bool inside = isInside();
            const double lamO = rugo_tolerance_at(otl.total, otl.count, cp.segment, cp.t, 0.0);
            const double s = (inside ? -cp.distance : cp.distance) - lam - lamO;
            const bool isApart = s > 0.0 || k == endK;
            if (isApart && !(fastPair && s <= curMargin)) return;
            const b2Vec2 q = toB2(rugo_transform_point(xo, cp.point));
            const double mu = rugo_mix(RUGO_MIX_MAX, rugo_friction(&fmS, lam), rugo_friction(&fmO, lamO));
            pushJoint(selfIsA ? p : q, selfIsA ? q : p, inside, selfIsA ? out() : -out(), s, static_cast<float>(mu),
                      static_cast<float>(std::min(eS.epsilon, eO.epsilon)), S, k, selfIsA ? 0x2000000u : 0x3000000u,
                      isApart ? &apart : &joints);
        });
    }

    // A joint point: pa on A's side, pb on B's; `inside`: the rough joint is inside the other body.
    void pushJoint(b2Vec2 pa, b2Vec2 pb, bool inside, b2Vec2 surfaceNormal, double s, float mu, float eps, const BodyRec* R,
                   int k, uint32 tag, std::vector<BPoint>* out) {
        b2Vec2 d = pb - pa;
        const float len = d.Length();
        if (len <= 0.0f) return; // no direction: the librugo contacts cover it
        b2Vec2 n = (1.0f / len) * d;
        // A penetrating joint: the way out is from the boundary point back to the joint.
        if (inside) n = -n;
        BPoint bp;
        bp.pA = pa;
        bp.pB = pb;
        bp.n = n;
        bp.s = s;
        bp.mu = static_cast<double>(mu);
        bp.eps = static_cast<double>(eps);
        bp.key = hashId((static_cast<uint64_t>(tag) << 32) ^ (static_cast<uint64_t>(R->serial) << 20) ^ static_cast<uint64_t>(k));
        bp.m = surfaceNormal;
        out->push_back(bp);
    }

    // A touching joint belongs to one of the query's contact regions (librugo's contacts of the body
    // pair or the fixture child, whichever proxy pair owns them): the one whose normal its own
    // closest-point direction matches within ~10° (kJointRegionCos). It then takes that region's
    // normal and its separation is measured along it; a joint deeper along it than the region itself
    // (a joint inside an overlap) or no longer touching along it is dropped, as is a joint matching no
    // region (but see edgeFace). Before, each proxy pair overlapping a region made its own manifold from
    // its joints' closest-point directions; inside an overlap (a rough body and a circle) those point
    // every way (up to ~45° off librugo's normal in test_circle_overlap_one_normal). The flatness test
    // for second points (m against the first point's normal, in write) still applies.
    bool attachJoint(BPoint* j) const {
        const BPoint* best = nullptr;
        float bestDot = kJointRegionCos;
        for (const BPoint& r : regions) {
            const float d = b2Dot(j->n, r.n);
            if (d >= bestDot) {
                bestDot = d;
                best = &r;
            }
        }
        // A joint against the inside of an edge has the edge's face normal (every such joint of the
        // edge the same one): where librugo's region normal differs (a body crossing the edge deeply
        // gets an intersecting region with another way out), the face normal is kept, like Box2D's
        // own edge manifolds.
        if (best == nullptr) return j->edgeFace;
        const b2Vec2 d = j->pB - j->pA;
        const double band = static_cast<double>(b2Dot(d, j->n)) - j->s; // the bands at the joint
        const double s = static_cast<double>(b2Dot(d, best->n)) - band;
        if (s > 0.0 || s < best->s - static_cast<double>(b2_linearSlop)) return false;
        j->n = best->n;
        j->s = s;
        return true;
    }

    // ---- PreSolve ---------------------------------------------------------------------------------
    void PreSolve(b2Contact* c, const b2Manifold* old) override {
        b2Fixture* fa = c->GetFixtureA();
        b2Fixture* fb = c->GetFixtureB();
        const ProxyRef* ra = lookup(fa);
        const ProxyRef* rb = lookup(fb);
        if (ra || rb) {
            ++stats.preSolves;
            // TOI phase: a PostSolve was seen, or a rough body of the pair has moved since Step began
            // (islands without contacts report no PostSolve before Box2D's TOI phase).
            toiPhase = (afterSolve || (inStep && ((ra && moved(ra->rec)) || (rb && moved(rb->rec)))));
            if (toiPhase) ++stats.toiPreSolves;
            if (toiPhase && c->GetRestitution() < 0.0f && atCollidePoses(ra, rb, fa, fb, c)) {
                // A TOI event at the step's start (Box2D's proxies are within its TOI target there) on
                // a pair that got a speculative point in the collide phase: the step's solve already
                // limited its approach to the gap. Re-solving it here from the start pose would redo
                // the whole step without gravity and the other contacts (a rolling disc would hover),
                // so it leaves the TOI phase.
                disable(c);
                if (prevListener) prevListener->PreSolve(c, old);
                return;
            }
            cand.clear();
            joints.clear();
            apart.clear();
            regions.clear();
            if (ra && rb)
                gatherRough(ra, rb);
            else
                gatherPrimitive(ra ? ra : rb, ra != nullptr, ra ? fb : fa, ra ? c->GetChildIndexB() : c->GetChildIndexA());
            ncand = cand.size();
            {
                const b2Body* b1 = fa->GetBody();
                const b2Body* b2 = fb->GetBody();
                const double turn = std::fabs(static_cast<double>(b1->GetAngularVelocity() - b2->GetAngularVelocity())) * static_cast<double>(dt);
                fastPair = def.speculative && toiPhase && (turn > kFastTurn || curMargin > curReach);
            }
            // Joints are offered even without a librugo point in this proxy pair: on a tilted flat face
            // the one minimum may belong to a neighbouring proxy, and this pair's part of the face
            // still carries load.
            {
                if (ra && rb) {
                    // A rough joint is used only by attaching it to one of the query's regions, or as
                    // an apart candidate of a fast pair: without either, its closest points (most of
                    // a step's time) would be computed for nothing.
                    if (!regions.empty() || fastPair) {
                        const int rel = std::max(ra->rec->relLevel, rb->rec->relLevel);
                        jointsVsRough(ra, rb, true, rel);
                        jointsVsRough(rb, ra, false, rel);
                    }
                } else {
                    jointsVsPrimitive(ra ? ra : rb, ra != nullptr, ra ? fb : fa, ra ? c->GetChildIndexB() : c->GetChildIndexA(),
                                      dropEndFlag);
                }
                // Joints only add points to a contact region librugo reported (in this or another proxy
                // pair), with that region's normal; see attachJoint.
                for (BPoint& j : joints)
                    if (attachJoint(&j)) cand.push_back(j);
            }
            write(c, old, ra != nullptr, ra ? ra->rec->body : fa->GetBody(), rb ? rb->rec->body : fb->GetBody());
        }
        if (prevListener) prevListener->PreSolve(c, old);
    }

    bool atCollidePoses(const ProxyRef* ra, const ProxyRef* rb, b2Fixture* fa, b2Fixture* fb, b2Contact* c) const {
        if (ra && rb) {
            const BodyRec* A = ra->rec;
            const BodyRec* B = rb->rec;
            const bool swap = B->serial < A->serial;
            const BodyRec* QA = swap ? B : A;
            const BodyRec* QB = swap ? A : B;
            return seenInCollide(QA, QB, -1, QA->body->GetTransform(), QB->body->GetTransform());
        }
        const ProxyRef* r = ra ? ra : rb;
        const b2Fixture* other = ra ? fb : fa;
        const int child = ra ? c->GetChildIndexB() : c->GetChildIndexA();
        return seenInCollide(r->rec, other, child, r->rec->body->GetTransform(), other->GetBody()->GetTransform());
    }

    static int ownerNode(int segment, int level, int proxyLevel) { return segment >> (level - proxyLevel); }
    static bool moved(const BodyRec* r) {
        const b2Transform& x = r->body->GetTransform();
        return x.p.x != r->stepStart.p.x || x.p.y != r->stepStart.p.y || x.q.s != r->stepStart.q.s || x.q.c != r->stepStart.q.c;
    }

    void gatherRough(const ProxyRef* ra, const ProxyRef* rb) {
        BodyRec* A = ra->rec;
        BodyRec* B = rb->rec;
        const bool swap = B->serial < A->serial; // query in attach order (deterministic)
        BodyRec* QA = swap ? B : A;
        BodyRec* QB = swap ? A : B;
        const b2Transform& xa = QA->body->GetTransform();
        const b2Transform& xb = QB->body->GetTransform();
        const int level = std::max(QA->relLevel, QB->relLevel);
        const double margin =
            def.speculative ? speedBound(QA->body, roughReach(QA), QB->body, roughReach(QB)) * static_cast<double>(dt) : 0.0;
        curMargin = margin;
        curReach = std::max(roughReach(QA), roughReach(QB));
        uint32_t start = 0, count = 0;
        const rugo_transform ta = toRugo(xa), tb = toRugo(xb);
        cachedQuery(QA, QB, -1, xa, xb, margin, level,
                    [&](rugo_contact* out, int cap, int* n, rugo_query_stats* qs) {
                        rugo_contact_query q = rugo_default_contact_query();
                        q.level = level;
                        q.margin = margin;
                        rugo_contact_state state;
                        return rugo_collide_shapes(ctx, QA->shape, ta, QB->shape, tb, &q, out, cap, n, &state, qs);
                    },
                    &start, &count);
        for (uint32_t i = 0; i < count; ++i) {
            const rugo_contact& k = pool[start + i];
            const int na = ownerNode(swap ? k.segment_b : k.segment_a, swap ? k.level_b : k.level_a, A->proxyLevel);
            const int nb = ownerNode(swap ? k.segment_a : k.segment_b, swap ? k.level_a : k.level_b, B->proxyLevel);
            BPoint p;
            p.pA = toB2(swap ? k.point_b : k.point_a);
            p.pB = toB2(swap ? k.point_a : k.point_b);
            p.n = swap ? -toB2(k.normal) : toB2(k.normal);
            p.s = k.separation - k.tolerance_a - k.tolerance_b;
            p.mu = k.friction;
            p.eps = k.restitution;
            p.key = hashId(k.id);
            p.m = p.n;
            regions.push_back(p);
            if (na != ra->node || nb != rb->node) continue;
            cand.push_back(p);
        }
    }

    bool dropEndFlag = false;
    void gatherPrimitive(const ProxyRef* r, bool roughIsA, b2Fixture* other, int child) {
        BodyRec* R = r->rec;
        const b2Shape* sh = other->GetShape();
        const b2Body* ob = other->GetBody();
        const b2Transform& xr = R->body->GetTransform();
        const b2Transform& xo = ob->GetTransform();
        const int level = R->relLevel;
        const double margin =
            def.speculative ? speedBound(R->body, roughReach(R), ob, fixtureReach(other, child)) * static_cast<double>(dt) : 0.0;
        curMargin = margin;
        curReach = std::max(roughReach(R), fixtureReach(other, child));
        const rugo_transform tr = toRugo(xr);
        const rugo_transform to = toRugo(xo);
        // Chain children: a point at an edge's second vertex belongs to the next edge (as t = 1 in librugo).
        bool dropEnd = false;
        dropEndFlag = false;
        oneSided = OneSided();
        b2EdgeShape edge;
        if (sh->GetType() == b2Shape::e_chain) {
            const b2ChainShape* ch = static_cast<const b2ChainShape*>(sh);
            ch->GetChildEdge(&edge, child); // one-sided, with ghost vertices (Box2D 2.4.1)
            const bool loop = ch->m_count > 2 && ch->m_vertices[0] == ch->m_vertices[ch->m_count - 1];
            dropEnd = loop || child + 1 < ch->GetChildCount();
            dropEndFlag = dropEnd;
            oneSided = makeOneSided(edge, xo, loop || child > 0, dropEnd);
        } else if (sh->GetType() == b2Shape::e_edge) {
            const b2EdgeShape& es = *static_cast<const b2EdgeShape*>(sh);
            oneSided = es.m_oneSided ? makeOneSided(es, xo, false, false) : makeTwoSided(es, xo, R->body->GetWorldCenter());
        }
        // Box2D skips a one-sided edge when the other body's centroid is behind it.
        if (oneSided.on && b2Dot(oneSided.n1, R->body->GetWorldCenter() - oneSided.v1) < 0.0f) return;
        uint32_t start = 0, count = 0;
        cachedQuery(R, other, child, xr, xo, margin, level,
                    [&](rugo_contact* out, int cap, int* n, rugo_query_stats* qs) -> rugo_status {
                        rugo_contact_query q = rugo_default_contact_query();
                        q.level = level;
                        q.margin = margin;
                        rugo_contact_state state;
                        switch (sh->GetType()) {
                        case b2Shape::e_circle: {
                            const b2CircleShape* cs = static_cast<const b2CircleShape*>(sh);
                            return rugo_collide_circle(ctx, R->shape, tr, rugo_transform_point(to, toRv(cs->m_p)),
                                                       static_cast<double>(cs->m_radius), &q, out, cap, n, &state, qs);
                        }
                        case b2Shape::e_polygon: {
                            const b2PolygonShape* ps = static_cast<const b2PolygonShape*>(sh);
                            rugo_vec2 v[b2_maxPolygonVertices];
                            for (int i = 0; i < ps->m_count; ++i)
                                v[i] = rugo_transform_point(to, toRv(ps->m_vertices[i]));
                            return rugo_collide_polygon(ctx, R->shape, tr, v, ps->m_count,
                                                        static_cast<double>(ps->m_radius), &q, out, cap, n, &state, qs);
                        }
                        case b2Shape::e_edge:
                        case b2Shape::e_chain: {
                            const b2EdgeShape* es = sh->GetType() == b2Shape::e_edge
                                                        ? static_cast<const b2EdgeShape*>(sh)
                                                        : &edge;
                            return rugo_collide_segment(ctx, R->shape, tr, rugo_transform_point(to, toRv(es->m_vertex1)),
                                                        rugo_transform_point(to, toRv(es->m_vertex2)),
                                                        static_cast<double>(es->m_radius), &q, out, cap, n, &state, qs);
                        }
                        default:
                            *n = 0;
                            return RUGO_ERR_BAD_ARGUMENT;
                        }
                    },
                    &start, &count);
        const double mu = static_cast<double>(other->GetFriction());
        const double eps = static_cast<double>(other->GetRestitution());
        for (uint32_t i = 0; i < count; ++i) {
            const rugo_contact& k = pool[start + i];
            const bool owned = ownerNode(k.segment_a, k.level_a, R->proxyLevel) == r->node;
            bool keep = owned;
            BPoint p;
            const b2Vec2 pr = toB2(k.point_a);
            b2Vec2 po = toB2(k.point_b), n = toB2(k.normal);
            double sep = k.separation;
            if (oneSided.on) { // the edge's rules decide the normal and the owner (see OneSided)
                b2Vec2 m;
                if (!resolveOneSided(oneSided, pr, &m, &sep)) continue;
                po = pr - static_cast<float>(sep) * m;
                n = -m; // librugo's orientation: from the curve (its A) toward the edge
            }
            p.pA = roughIsA ? pr : po;
            p.pB = roughIsA ? po : pr;
            p.n = roughIsA ? n : -n;
            p.s = sep - k.tolerance_a - k.tolerance_b;
            p.mu = std::max(k.friction, mu);  // thesis 7.2: max for friction
            p.eps = std::min(k.restitution, eps); // and min for restitution
            p.key = hashId(k.id ^ (static_cast<uint64_t>(static_cast<uint32_t>(child)) << 40));
            p.m = p.n;
            regions.push_back(p); // a region for joints (attachJoint), whichever pair reports it
            if (keep) cand.push_back(p);
        }
    }

    void disable(b2Contact* c) {
        c->GetManifold()->pointCount = 0;
        c->SetEnabled(false);
        ++stats.disabledContacts;
    }

    size_t ncand = 0; // cand[0, ncand) are librugo's contacts, the rest joints
    void write(b2Contact* c, const b2Manifold* old, bool roughIsA, const b2Body* bA, const b2Body* bB) {
        // Touching points first: the deepest librugo contact fixes the normal; the second point is the
        // farthest touching one (another librugo contact, or a joint of a flat piece: its own normal
        // within ~2.6° of the first, else it is no flat contact and would only resist rolling).
        int deepest = -1;
        for (int pass = 0; pass < 2 && deepest < 0; ++pass) // librugo's points first, then joints
            for (int i = pass == 0 ? 0 : static_cast<int>(ncand); i < static_cast<int>(pass == 0 ? ncand : cand.size()); ++i)
                if (cand[static_cast<size_t>(i)].s <= 0.0 &&
                    (deepest < 0 || cand[static_cast<size_t>(i)].s < cand[static_cast<size_t>(deepest)].s))
                    deepest = i;
        BPoint pts[2];
        int np = 0;
        bool speculative = false;
        double specApproach = 0.0;
        if (deepest >= 0) {
            pts[np++] = cand[static_cast<size_t>(deepest)];
            int far = -1;
            float best = -1.0f;
            for (int i = 0; i < static_cast<int>(cand.size()); ++i) {
                const BPoint& p = cand[static_cast<size_t>(i)];
                if (i == deepest || p.s > 0.0) continue;
                if ((i >= static_cast<int>(ncand) || deepest >= static_cast<int>(ncand)) && b2Dot(p.m, pts[0].n) < 0.999f)
                    continue;
                const float d = b2DistanceSquared(p.pA, pts[0].pA);
                if (d > best) {
                    best = d;
                    far = i;
                }
            }
            // A second point closer than linear slop adds nothing but solver noise.
            if (far >= 0 && best > b2_linearSlop * b2_linearSlop) pts[np++] = cand[static_cast<size_t>(far)];
        } else if (def.speculative) {
            // "Speculative within the step" (docs/box2d.md): no touching point, but the owned piece may
            // reach the other body within the step (gap <= margin). Disabling would also take the pair
            // out of Box2D's TOI phase for the rest of the step (SolveTOI skips disabled contacts), so
            // the candidate predicted deepest at the end of the step (linear approach plus the arc of
            // the rotation) becomes a speculative point; its negative restitution (below) lets it
            // approach by its gap but no further, like Box2D v3's speculative contacts.
            const double h = static_cast<double>(dt);
            const double wA = static_cast<double>(bA->GetAngularVelocity()), wB = static_cast<double>(bB->GetAngularVelocity());
            const b2Vec2 cA = bA->GetWorldCenter(), cB = bB->GetWorldCenter();
            // "Fast": the bodies turn by more than kFastTurn radians or move by more than their
            // reach (the margin exceeds the proxy pair's size) within the step.
            const bool fastRule = fastPair;
            double bestPred = 0.0;
            const BPoint* best = nullptr;
            auto consider = [&](const BPoint& p) {
                if (p.s > curMargin) return;
                // Linear approach plus the arc of the rotation (a point's path bends toward the other
                // body by up to ω² r h² / 2; a linear test misses that on a spinning body).
                const double arc = 0.5 * h * h *
                                   (wA * wA * static_cast<double>((p.pA - cA).Length()) + wB * wB * static_cast<double>((p.pB - cB).Length()));
                const double pred = p.s - approach(bA, p.pA, bB, p.pB, p.n) * h - (fastRule ? arc : 0.0);
                // Fast pairs in the TOI phase: only a point predicted deeper than Box2D's linear slop
                // (which the position solver removes in the next step anyway); otherwise any point
                // that closes within the step (the rule for slow pairs, as a TOI solve also re-solves
                // the pair's touching contacts without warm start: a rolling disc would be braked).
                if (pred > (fastRule ? -static_cast<double>(b2_linearSlop) : 0.0)) return;
                if (best == nullptr || pred < bestPred) {
                    best = &p;
                    bestPred = pred;
                }
            };
            if (fastRule) {
                for (size_t i = 0; i < ncand; ++i)
                    consider(cand[i]);
                for (const BPoint& p : apart)
                    consider(p);
            } else {
                // Slow pairs (and the collide phase): the closest librugo point, if its approach
                // closes the gap within the step.
                size_t closest = ncand;
                for (size_t i = 0; i < ncand; ++i)
                    if (closest == ncand || cand[i].s < cand[closest].s) closest = i;
                if (closest < ncand) consider(cand[closest]);
            }
            if (best != nullptr) {
                pts[np++] = *best;
                speculative = true;
                specApproach = approach(bA, best->pA, bB, best->pB, best->n);
            }
        }
        if (np == 0) {
            disable(c);
            return;
        }
        b2Manifold* m = c->GetManifold();
        const b2Transform& xA = bA->GetTransform();
        const b2Transform& xB = bB->GetTransform();
        const float rA = c->GetFixtureA()->GetShape()->m_radius;
        const float rB = c->GetFixtureB()->GetShape()->m_radius;
        const b2Vec2 n = pts[0].n;
        // The second point's separation along the manifold's one normal.
        double s[2];
        s[0] = pts[0].s;
        if (np == 2) {
            const double sOwn = pts[1].s, dOwn = static_cast<double>(b2Dot(pts[1].pB - pts[1].pA, pts[1].n));
            s[1] = static_cast<double>(b2Dot(pts[1].pB - pts[1].pA, n)) - (dOwn - sOwn);
        }
        if (roughIsA) {
            // Plane on A (DESIGN.md formulas): GetWorldManifold then returns n and s_i.
            const b2Vec2 pA0 = pts[0].pA;
            m->type = b2Manifold::e_faceA;
            m->localNormal = b2MulT(xA.q, n);
            m->localPoint = b2MulT(xA, pA0 - rA * n);
            for (int i = 0; i < np; ++i) {
                const b2Vec2 pB = pts[i].pB;
                const float k = rB + static_cast<float>(s[i]) - b2Dot(pB - pA0, n);
                m->points[i].localPoint = b2MulT(xB, pB + k * n);
            }
        } else {
            const b2Vec2 pB0 = pts[0].pB;
            m->type = b2Manifold::e_faceB;
            m->localNormal = b2MulT(xB.q, -n);
            m->localPoint = b2MulT(xB, pB0 + rB * n);
            for (int i = 0; i < np; ++i) {
                const b2Vec2 pA = pts[i].pA;
                const float k = rA + static_cast<float>(s[i]) + b2Dot(pA - pB0, n);
                m->points[i].localPoint = b2MulT(xA, pA - k * n);
            }
        }
        m->pointCount = np;
        double mu[2], eps[2];
        for (int i = 0; i < np; ++i) {
            b2ManifoldPoint& mp = m->points[i];
            mp.id.key = pts[i].key;
            mp.normalImpulse = 0.0f;
            mp.tangentImpulse = 0.0f;
            for (int j = 0; j < old->pointCount; ++j)
                if (old->points[j].id.key == mp.id.key) {
                    mp.normalImpulse = old->points[j].normalImpulse;
                    mp.tangentImpulse = old->points[j].tangentImpulse;
                    break;
                }
            mu[i] = pts[i].mu;
            eps[i] = pts[i].eps;
            if (i == 0) {
                DrawnContact dc;
                dc.p = 0.5f * (pts[i].pA + pts[i].pB);
                dc.n = n;
                if (lastContacts.size() < lastContacts.capacity() || lastContacts.size() < 4096) lastContacts.push_back(dc);
            }
        }
        c->SetFriction(static_cast<float>(np == 2 ? rugo_mix(def.pointFrictionMix, mu[0], mu[1]) : mu[0]));
        if (speculative && fastPair) {
            // Box2D 2.4's velocity solver targets vn >= -restitution * vn0 when vn0 < -threshold
            // (b2_contact_solver.cpp:217). With restitution -min(1, (s / dt) / approach) and threshold 0
            // an approaching speculative point may close its gap s within the step and no more; a
            // receding one keeps vn >= 0.
            // In the TOI phase the solver starts from exactly these velocities, so e may exceed 1 (a
            // point approaching slower than s / dt may still speed up by that much); in the normal
            // phase gravity is integrated first, so e <= 1 (the point closes within the step anyway).
            const double gapSpeed = std::max(pts[0].s, 0.0) / static_cast<double>(dt);
            const double e = specApproach * kMaxSpeculativeRestitution > gapSpeed
                                 ? std::min(gapSpeed / specApproach, toiPhase ? kMaxSpeculativeRestitution : 1.0)
                                 : (toiPhase ? kMaxSpeculativeRestitution : 1.0);
            c->SetRestitution(static_cast<float>(-e));
            c->SetRestitutionThreshold(0.0f);
        } else {
            c->SetRestitution(static_cast<float>(np == 2 ? std::min(eps[0], eps[1]) : eps[0]));
            c->ResetRestitutionThreshold();
        }
        c->SetEnabled(true);
        stats.pointsSubmitted += np;
        if (speculative) ++stats.speculativePoints;
    }
};

// ---- Bridge --------------------------------------------------------------------------------------

Bridge::Bridge(b2World* world, const BridgeDef& def) : m_impl(new Impl) {
    Impl& I = *m_impl;
    I.world = world;
    I.def = def;
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
    if (I.ctx == nullptr) return RUGO_ERR_OUT_OF_MEMORY;
    const rugo_shape* s = def.shape;
    const int J = rugo_shape_finest_level(s), Jmin = rugo_shape_coarsest_level(s);
    int level;
    if (def.level == kAutoLevel) {
        const double budget = def.errorBudget >= 0.0 ? def.errorBudget : I.def.errorBudget;
        level = Impl::autoLevel(s, budget);
    } else {
        level = def.level > 0 ? J : std::max(Jmin, J + std::max(def.level, Jmin - J));
    }
    int proxyLevel;
    if (def.proxyLevel == kAutoLevel) {
        proxyLevel = std::max(Jmin, std::min(level, I.def.maxProxyLevel));
    } else {
        if (def.proxyLevel < Jmin || def.proxyLevel > J || def.proxyLevel > level) return RUGO_ERR_BAD_ARGUMENT;
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
        const double pad = excess + 1e-6 * (std::fabs(b->center.x) + std::fabs(b->center.y) + b->half[0] + b->half[1]);
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
    I.reserveFor(I.bodies.size(), 1 << (level - proxyLevel));
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
        best.fixture = r->proxies[static_cast<size_t>(cp.segment >> (r->level - r->proxyLevel))];
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
    int inside = 0;
    if (rugo_shape_contains(r->shape, r->level, rugo_inv_transform_point(toRugo(body->GetTransform()), toRv(p)), &inside) != RUGO_OK)
        return false;
    return inside != 0;
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
    rugo_vec2 v[4] = {rugo_v2(static_cast<double>(aabb.lowerBound.x), static_cast<double>(aabb.lowerBound.y)),
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
        if (r != nullptr) { // decided by the curve
            int n = 0;
            rugo_contact_state state = RUGO_STATE_APART;
            rugo_contact_query q = rugo_default_contact_query();
            q.level = r->relLevel;
            const rugo_transform x = toRugo(b->GetTransform());
            rugo_status st = degenerate ? rugo_collide_circle(I.ctx, r->shape, x, v[0], 0.0, &q, nullptr, 0, &n, &state, nullptr)
                                        : rugo_collide_polygon(I.ctx, r->shape, x, v, 4, 0.0, &q, nullptr, 0, &n, &state, nullptr);
            if (st != RUGO_OK || state == RUGO_STATE_APART) continue;
        }
        if (!callback(b)) return;
        if (I.world == nullptr) return; // ReleaseWorld inside the callback
        // Creating a body changes the list's head, destroying one the count (and a destroyed body with
        // fixtures says goodbye): then drop the candidates that are no longer in the world.
        if (I.destroyedFixtures != destroyed || I.world->GetBodyCount() != bodyCount || I.world->GetBodyList() != head) {
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
                if (flags & kDrawCurve) segs.push_back({toB2(rugo_transform_point(x, a)), toB2(rugo_transform_point(x, b)), &curveColor});
                if ((flags & kDrawBand) && haveTol)
                    for (int side = -1; side <= 1; side += 2) {
                        const double la = rugo_tolerance_at(tl.total, tl.count, k, t0, 0.0) * side;
                        const double lb = rugo_tolerance_at(tl.total, tl.count, k, t1, 0.0) * side;
                        const rugo_vec2 oa = rugo_v2_add(a, rugo_v2_scale(la, rugo_contour_normal(curve, k, t0)));
                        const rugo_vec2 ob = rugo_v2_add(b, rugo_v2_scale(lb, rugo_contour_normal(curve, k, t1)));
                        segs.push_back({toB2(rugo_transform_point(x, oa)), toB2(rugo_transform_point(x, ob)), &bandColor});
                    }
            }
        if (flags & kDrawProxies)
            for (const b2Fixture* f : r->proxies) {
                const b2PolygonShape* p = static_cast<const b2PolygonShape*>(f->GetShape());
                for (int i = 0; i < p->m_count; ++i)
                    polys.push_back(b2Mul(body->GetTransform(), p->m_vertices[i]));
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
    m.box2dBytes = r->proxies.size() * (sizeof(b2Fixture) + sizeof(b2PolygonShape) + sizeof(b2FixtureProxy) + sizeof(b2TreeNode));
    // The shared shape, estimated from its arrays: per segment of each level the control point, λ own,
    // total, bound, band bound and one tree box.
    const int J = rugo_shape_finest_level(r->shape), Jmin = rugo_shape_coarsest_level(r->shape);
    size_t bytes = 0;
    for (int j = Jmin; j <= J; ++j)
        bytes += (static_cast<size_t>(1) << j) * (sizeof(rugo_vec2) + 4 * sizeof(rugo_real) + sizeof(rugo_obb));
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
