// Internal to the Box2D 2.4 bridge (not installed): the records it keeps per body, proxy and query,
// and Bridge::Impl, the listener/filter that does the work. Its methods live in one file per concern:
//   bridge.cpp            the public API, listener chaining, body records
//   bridge_body.cpp       per-body facts: exact mass, levels of detail, bands, reach and speed
//   bridge_cache.cpp      the per-step query cache (one librugo query per body pair and poses)
//   bridge_presolve.cpp   PreSolve: librugo's contacts into Box2D's manifold (points, friction, CCD)
//   bridge_joints.cpp     joint points: Box2D-like second points on flat contacts
//   bridge_one_sided.cpp  one-sided edges (chains, b2EdgeShape) as Box2D 2.4.1 collides them
//   bridge_queries.cpp    ray cast, point test and AABB query on the curves
//   bridge_draw.cpp       debug drawing
#ifndef RUGO_BRIDGE_IMPL_HPP
#define RUGO_BRIDGE_IMPL_HPP

#include "rugo/box2d.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace rugo {
namespace detail {

struct BodyRec {
    b2Body* body = nullptr;
    const rugo_shape* shape = nullptr;
    double density = 1.0;
    int serial = 0;     // attach order: a deterministic canonical order for pair queries
    int relLevel = 0;   // contact level relative to the finest (<= 0)
    int level = 0;      // absolute contact level
    int proxyLevel = 0; // absolute proxy level
    std::vector<b2Fixture*> proxies;
    rugo_vec2 rootCorners[4]; // local frame, for the speed bound
    b2MassData applied;       // what GetMassData returned right after the bridge set the mass
    bool massValid = false;
    b2Transform stepStart;       // the pose when Bridge::Step began (a moved body means Box2D's TOI phase)
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

// The queries of this bridge: today's round-off contacts at minima of the distance (the thesis' rule),
// which its manifolds, joint points and speculative points are built around.
inline rugo_contact_query legacyQuery() {
    rugo_contact_query q = rugo_default_contact_query();
    q.resolution = 0.0;
    q.contact_rule = RUGO_CONTACT_THESIS;
    return q;
}

inline b2Vec2 toB2(rugo_vec2 v) { return b2Vec2(static_cast<float>(v.x), static_cast<float>(v.y)); }
inline rugo_vec2 toRv(b2Vec2 v) { return rugo_v2(static_cast<double>(v.x), static_cast<double>(v.y)); }

// The query a cache miss runs (bridge_cache.cpp): a reference to a callable, which must outlive the
// call, with no allocation (a capturing lambda in a std::function may allocate per query).
class QueryRun {
  public:
    template <class F>
    QueryRun(const F& f) // NOLINT: implicit, so that call sites pass their lambda as it is
        : m_fn(&f),
          m_call([](const void* fn, rugo_contact* out, int cap, int* n, rugo_query_stats* qs) -> rugo_status {
              return (*static_cast<const F*>(fn))(out, cap, n, qs);
          }) {}
    rugo_status operator()(rugo_contact* out, int cap, int* n, rugo_query_stats* qs) const {
        return m_call(m_fn, out, cap, n, qs);
    }

  private:
    const void* m_fn;
    rugo_status (*m_call)(const void*, rugo_contact*, int, int*, rugo_query_stats*);
};

} // namespace detail

using namespace detail; // NOLINT: the bridge's own sources only (this header is not installed)

// Not API: a nested class takes the visibility of its enclosing class, and Bridge is exported
// (RUGO_API), so without this the implementation's methods, vtable and typeinfo would be exported too.
#if defined(__GNUC__) || defined(__clang__)
#define RUGO_BRIDGE_HIDDEN __attribute__((visibility("hidden")))
#else
#define RUGO_BRIDGE_HIDDEN
#endif

struct RUGO_BRIDGE_HIDDEN Bridge::Impl : public b2ContactListener, public b2ContactFilter, public b2DestructionListener {
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
    std::vector<JointInfo> jointPool; // per step like pool (CacheEntry::joints)
    std::vector<JointChunk> jointChunks;
    size_t lastEntry = 0; // table index of the last cachedQuery's entry
    uint64_t gen = 1;
    size_t used = 0;
    std::vector<BPoint> cand;
    std::vector<BPoint> joints;
    std::vector<BPoint> apart; // TOI phase: joints of the owned piece that are apart but within the margin
    // All of the query's librugo contacts (any proxy pair) that touch: the regions joints attach to.
    std::vector<BPoint> regions;
    struct DrawnContact {
        b2Vec2 p, n;
    };
    std::vector<DrawnContact> lastContacts;
    // Inside Detach's DestroyFixture calls, or a user EndContact that Box2D raised outside Step
    // (DestroyBody, DestroyFixture, SetEnabled, SetType walk a contact list meanwhile): Attach and
    // Detach refuse (WORLD_LOCKED).
    bool removingProxies = false;
    // The contact each callback (Begin, End, Pre, Post) is being chained for. A user listener that
    // forwards to the listener it replaced (the bridge) is chained back by Step: bridge -> user ->
    // bridge -> ... would recurse without end. A callback re-entered for the contact it is chaining
    // returns at once (callbacks for other contacts, e.g. from a DestroyBody there, run as usual).
    enum Callback { kBegin = 0, kEnd = 1, kPre = 2, kPost = 3 };
    const b2Contact* chaining[4] = {nullptr, nullptr, nullptr, nullptr};
    bool rechained(Callback k, const b2Contact* c) const { return chaining[k] == c; }
    template <class F> void chain(Callback k, b2Contact* c, F&& call) {
        if (prevListener == nullptr) return;
        const b2Contact* was = chaining[k];
        chaining[k] = c;
        call();
        chaining[k] = was;
    }
    // Bodies destroyed since construction (SayGoodbye of any fixture): a callback of the bridge's own
    // (QueryAABB, Draw) that changed it may have destroyed bodies the bridge still holds.
    long destroyedFixtures = 0;
    // Per-step caches are reserved for this many joints (reserveFor), the point lists of one proxy
    // pair for this many joint points (reservePoints).
    size_t jointReserve = 0;
    size_t pointReserve = 0;
    size_t ncand = 0;         // cand[0, ncand) are librugo's contacts, the rest joints
    bool dropEndFlag = false; // gatherPrimitive: a chain child's second vertex belongs to the next child

    Impl();
    ~Impl() override;

    const ProxyRef* lookup(const b2Fixture* f) const {
        auto it = proxies.find(f);
        return it == proxies.end() ? nullptr : &it->second;
    }
    BodyRec* rec(const b2Body* b) const {
        auto it = bodies.find(b);
        return it == bodies.end() ? nullptr : it->second;
    }
    static int ownerNode(int segment, int level, int proxyLevel) { return segment >> (level - proxyLevel); }

    // bridge.cpp: listener chaining and body records
    void BeginContact(b2Contact* c) override;
    void EndContact(b2Contact* c) override;
    void PostSolve(b2Contact* c, const b2ContactImpulse* imp) override;
    bool ShouldCollide(b2Fixture* a, b2Fixture* b) override;
    void SayGoodbye(b2Joint* j) override;
    void SayGoodbye(b2Fixture* f) override;
    void forget(BodyRec* r);
    void rechain();
    std::vector<b2Body*> bodiesInAttachOrder() const;

    // bridge_body.cpp: mass, levels, bands, reach and speed
    // The rough part's mass at a density: kg, local centroid, inertia about it and about the body origin.
    struct RoughMass {
        double mass;
        rugo_vec2 centroid;
        double inertiaCentre, inertiaOrigin;
    };
    static RoughMass roughMass(const rugo_shape* s, double density);
    b2MassData exactMass(const BodyRec* r) const;
    static bool sameMass(const b2MassData& a, const b2MassData& b);
    void applyMass(BodyRec* r);
    bool massStale(const BodyRec* r) const;
    static double bandExcess(const rugo_shape* s, int from);
    static std::vector<double> bandMaxima(const rugo_shape* s);
    static int absLevel(const rugo_shape* s, int rel);
    static double roughReach(const BodyRec* r);
    static double fixtureReach(const b2Fixture* f, int child);
    static double speedBound(const b2Body* a, double ra, const b2Body* b, double rb);
    static double approach(const b2Body* a, b2Vec2 pa, const b2Body* b, b2Vec2 pb, b2Vec2 n);
    static bool moved(const BodyRec* r);

    // bridge_cache.cpp: the query cache. cachedQuery runs `run` unless the same query (bodies or
    // fixture, child, float poses, margin, level) ran this step; the contacts are pool[start, start+count).
    void reserveFor(size_t n, int per, int perFinest);
    void reservePoints();
    bool cachedQuery(const void* a, const void* b, int child, const b2Transform& xa, const b2Transform& xb,
                     double margin, int level, QueryRun run, uint32_t* start, uint32_t* count);
    static uint64_t cacheHash(const void* a, const void* b, int child, const float* xf);
    bool seenInCollide(const void* a, const void* b, int child, const b2Transform& xa,
                       const b2Transform& xb) const;

    // bridge_presolve.cpp: PreSolve
    void PreSolve(b2Contact* c, const b2Manifold* old) override;
    bool atCollidePoses(const ProxyRef* ra, const ProxyRef* rb, b2Fixture* fa, b2Fixture* fb,
                        b2Contact* c) const;
    void gatherRough(const ProxyRef* ra, const ProxyRef* rb);
    void gatherPrimitive(const ProxyRef* r, bool roughIsA, b2Fixture* other, int child);
    void disable(b2Contact* c);
    void write(b2Contact* c, const b2Manifold* old, bool roughIsA, const b2Body* bA, const b2Body* bB);

    // bridge_joints.cpp: joint points
    static double obbDistance(const rugo_obb* b, rugo_vec2 p);
    static bool primitiveDistance(const b2Fixture* f, int child, b2Vec2 p, double* sd, b2Vec2* q,
                                  double* tEdge);
    template <class F> static void forJoints(const BodyRec* r, int node, int L, bool withEnd, F&& fn);
    void jointsVsPrimitive(const ProxyRef* r, bool roughIsA, const b2Fixture* other, int child, bool dropEnd);
    void jointsVsRough(const ProxyRef* self, const ProxyRef* oth, bool selfIsA, int pairRel);
    void pushJoint(b2Vec2 pa, b2Vec2 pb, bool inside, b2Vec2 surfaceNormal, double s, float mu, float eps,
                   const BodyRec* R, int k, uint32 tag, std::vector<BPoint>* out);
    bool attachJoint(BPoint* j) const;

    // bridge_one_sided.cpp: one-sided edges, chain children and b2EdgeShape with m_oneSided.
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
        bool roundEnds = false;                // a two-sided edge: beyond its ends, its round caps
    };
    OneSided oneSided; // of the fixture child being gathered (gatherPrimitive)
    static OneSided makeOneSided(const b2EdgeShape& e, const b2Transform& x, bool hasPrev, bool hasNext);
    static OneSided makeTwoSided(const b2EdgeShape& e, const b2Transform& x, b2Vec2 centroid);
    static bool resolveOneSided(const OneSided& o, b2Vec2 p, b2Vec2* m, double* dist);
};

} // namespace rugo

#endif
