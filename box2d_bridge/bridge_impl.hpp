// Internal header of the Box2D 2.4 bridge (not installed). Records of the bridge and Bridge::Impl, one
// concern per source file:
//   bridge.cpp           the public API, chaining of the user's listener, filter and destruction
//                        listener, body records
//   bridge_body.cpp      exact mass, levels of detail, reach
//   bridge_shape.cpp     what the bridge derives once per shape and level: convex pieces (the proxies)
//                        and straight faces, shared by the bodies using them
//   bridge_contact.cpp   the bridge's b2Contact (RoughContact) in Box2D's contact registry, and the
//                        process-global list of live bridges by world
//   bridge_query.cpp     every call into librugo's contact query API
//   bridge_patch.cpp     a query's contacts into contact patches (one normal, at most two end points)
//   bridge_evaluate.cpp  RoughContact::Evaluate: a patch into Box2D's manifold, friction, restitution,
//                        speculative points
//   bridge_cache.cpp     the per-step cache of patches (one query per body pair and poses)
//   bridge_pair_cache.cpp the answers kept from step to step, one per body pair (or rough body and
//                        ordinary fixture child): resting and slow pairs skip their queries
//   bridge_one_sided.cpp one-sided edges as Box2D 2.4.1 collides them
//   bridge_queries.cpp   ray cast / point / AABB queries on the curves
//   bridge_draw.cpp      debug drawing
#ifndef RUGO_BOX2D_BRIDGE_IMPL_HPP
#define RUGO_BOX2D_BRIDGE_IMPL_HPP

#include "rugo/box2d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <map>
#include <memory>
#include <unordered_map>
#include <vector>

namespace rugo {

namespace detail {

class RoughContact;

// ---- per shape and level (bridge_shape.cpp) ---------------------------------------------------------

// One proxy: a convex polygon (local coordinates, counter-clockwise, 3..8 vertices) whose core pushed
// out by `radius` encloses the curve and band of the outline's segments [first, first + count) at the
// contact level and every finer level.
struct Piece {
    int first = 0, count = 0;
    b2Vec2 v[b2_maxPolygonVertices];
    int n = 0;
    float radius = 0.0f;
};

// A straight stretch of one level's curve: segments [first, first + count) (cyclic) whose Bezier
// points lie within a small tolerance of one line. joints[i] is the curve point at segment first + i,
// t = 0 (i = count: the stretch's end), in the shape's frame.
struct Face {
    int first = 0, count = 0;
    std::vector<rugo_vec2> joints;
};

struct LevelFaces {
    std::vector<int> faceOf; // per segment: index in faces, -1 if the segment is not straight
    std::vector<Face> faces;
};

// What the bridge derives from one shape at one contact level, shared by every body that uses it.
struct ShapeData {
    const rugo_shape* shape = nullptr;
    int level = 0;     // absolute contact level L
    int maxPieces = 8; // the cap it was built for
    int users = 0;     // bodies using it
    std::vector<Piece> pieces;
    std::vector<int> pieceOf;      // per segment of level L
    std::vector<LevelFaces> faces; // levels L .. J (index j - L)
    rugo_friction_map friction;    // the shape's
    rugo_restitution restitution;
};

// ---- records ------------------------------------------------------------------------------------------

struct BodyRec {
    b2Body* body = nullptr;
    const rugo_shape* shape = nullptr;
    ShapeData* data = nullptr;
    double density = 1.0;
    int serial = 0;      // attach order: queries run in this order (determinism)
    int level = 0;       // absolute contact level
    int relLevel = 0;    // relative contact level
    double budget = 0.0; // its error budget (m; RoughBodyDef's or the bridge's; < 0 or NaN: none)
    // RoughBodyDef::rollingResistance (k).
    double rollingResistance = 0.0;
    std::vector<b2Fixture*> proxies;
    rugo_vec2 rootCorners[4]; // local frame, for the speed bound
    b2MassData applied;       // what GetMassData returned right after the bridge set the mass
    bool massValid = false;
    b2Transform stepStart; // the pose when Bridge::Step began (a moved body means Box2D's TOI phase)
};

struct ProxyRef {
    BodyRec* rec;
    int piece;
};

// One contact of a librugo query as the bridge uses it (bridge_query.cpp converts librugo's), in the
// query's orientation: A is the query's first shape, normal from A to B.
struct QContact {
    rugo_vec2 pa, pb, n;
    double sep; // curve distance along n (negative: overlap)
    double tolA, tolB;
    int segA, segB; // segment at the level used (-1: primitive)
    double tA, tB;
    int levelA, levelB;
    double mu, eps; // mixed friction and restitution at the points
    int region;
    uint64_t id;
    // Not a contact of this pair (one-sided edges: a point another chain child reports), only where a
    // face of the rough body lies over this child: the patch builder completes that face on the child.
    bool seed;
};

// One end of a contact patch, query orientation.
// The Box2D ids of a patch's points: its lower end along the tangent (or its one point), its upper end.
constexpr uint32_t kPatchEndKey = 1;

struct PatchPoint {
    rugo_vec2 pa, pb;       // on A's curve and on B's (curve or primitive surface)
    rugo_vec2 la, lb;       // the same in A's and B's body frames (material points)
    double band;            // the bands there: s = (pb - pa) . n - band
    double s;               // band-adjusted separation along the patch normal
    double lamA, lamB;      // each side's band there (band = lamA + lamB; 0 on a primitive)
    int segA, segB;         // each side's segment at its contact level (-1: primitive)
    float tA, tB;           // each side's curve parameter in the segment (Bridge::GetPointInfo)
    uint32_t key;           // Box2D contact id (warm starting)
    int16_t levelA, levelB; // the absolute levels of segA and segB (the query may refine the body's)
};

// A contact patch: one normal, one or two points, owned by one proxy pair (pieces of A and B; -1 for
// a primitive side, whose b2Contact is its own per child).
struct Patch {
    rugo_vec2 n;
    int ownerA = -1, ownerB = -1;
    int count = 0;
    PatchPoint p[2];
};

// One side of a query, for the patch builder: a rough body (its shape data, pose and level) or a
// Box2D primitive (world geometry).
struct PatchSide {
    const ShapeData* data = nullptr; // rough side
    rugo_transform x;                // the side's body pose
    int serial = 0;
    // Primitive side: type, world vertices (polygon; edge: 2), their outward normals (polygon),
    // radius, material.
    b2Shape::Type type = b2Shape::e_typeCount;
    b2Vec2 v[b2_maxPolygonVertices];
    b2Vec2 normals[b2_maxPolygonVertices];
    int n = 0;
    float radius = 0.0f;
    double mu = 0.0, eps = 0.0;
    int child = 0;
    bool chainNext = false; // a chain child with a next child: its second vertex is the next child's
};

struct CacheEntry {
    uint64_t gen = 0;
    const void* a = nullptr;
    const void* b = nullptr;
    int child = 0;
    float xf[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    double margin = 0.0;
    int level = 0;
    uint32_t start = 0, count = 0; // Impl::patches[start, start + count)
};

// ---- answers kept from step to step (bridge_pair_cache.cpp) -------------------------------------------

// Contacts of an answer the bridge keeps (an answer with more is searched again every step).
constexpr int kPairCacheContacts = 8;
// Pair slots per rough body reserved when it is attached (a body in a pile touches about three others
// and the ground in the mean; a step that needs more searches the rest every step until some are free).
constexpr int kPairCachesPerBody = 4;
// A kept answer covers a speculative margin of at least this many reuse distances, so that a pair at
// rest or creeping (whose margin changes by a hair each step) is not searched again for its margin.
constexpr double kKeptMarginFloor = 4.0;

// An ordinary fixture's child in its body's frame, as a kept answer was asked for.
struct PrimitiveGeometry {
    int type = -1;
    float radius = 0.0f;
    int n = 0;
    b2Vec2 v[b2_maxPolygonVertices];
};

// One pair's last search, kept from step to step (BridgeDef::reuseDistance): a rough body pair's or a
// rough body and ordinary fixture child's contacts, in the query's orientation, with what was asked
// and where. Reused, moved with the bodies, while the bodies have moved relative to each other by at
// most the reuse distance since the search.
struct PairCache {
    int serialA = -1, serialB = -1; // query order; serialB -1: a rough body and an ordinary fixture
    const b2Fixture* fixture = nullptr;
    int child = 0;
    uint64_t lastUsed = 0; // Bridge::Impl::stepSerial
    bool valid = false;
    PrimitiveGeometry geometry; // the fixture's child (serialB -1)
    double covers = 0.0;        // the speculative margin the answer covers (its search's margin less r)
    double resolution = 0.0;
    int level = 0;
    rugo_transform xa, xb;         // the search's poses (query order: A rough; B rough or the fixture's body)
    double reachA = 0, reachB = 0; // farthest point of each side from its body's origin
    int count = 0;
    QContact contacts[kPairCacheContacts];
};

// The pair caches: a pool of slots found by pair (open addressing). Slots are made in reserve (when a
// body is attached), never in a step; a step that finds none free takes back the slots of pairs not
// queried in this step or the last.
class PairCaches {
  public:
    // Room for `count` pairs; false if memory runs out (the slots made so far are kept).
    bool reserve(size_t count);
    // The pair's slot (a fresh one, cleared, for a pair it does not hold), or nullptr if none is free.
    PairCache* find(int serialA, int serialB, const b2Fixture* fixture, int child, uint64_t step);

  private:
    std::vector<PairCache> slots_;
    std::vector<int> index_; // slot of each hash bucket, -1 empty; size a power of two >= 2 slots
    std::vector<int> free_;
    size_t at(int serialA, int serialB, const b2Fixture* fixture, int child) const;
    void sweep(uint64_t step);
};

// Largest |restitution| a speculative manifold gets: a point approaching 1000x slower than its gap
// per step is as good as not approaching.
constexpr double kMaxSpeculativeRestitution = 1000.0;
// A pair turning by more than this (radians) in a step is fast: Box2D's continuous phase re-solves it
// even at the poses its step solve had (bridge_evaluate.cpp).
constexpr double kFastTurn = 0.3;
// Depth (in linear slops) given to a point of a time of impact whose curves are still apart: Box2D's
// position solve of the continuous phase stops at 1.5 slops, so it moves the bodies back by half a
// slop, out of the target of its next time-of-impact search.
constexpr double kToiDepth = 2.0;
// Contacts per query the librugo context is sized for when a body is attached (a body pair's query
// reports a handful; a pile's deepest pairs a few more): past it, librugo grows the context in a step.
constexpr int kQueryReserveContacts = 16;
// Regions whose normals agree within 30 degrees form one patch (a face resting on several bumps, a
// body resting on two feet or on two crests of a wavy ground): their extreme points become the
// manifold's two points, with the mean of their normals.
constexpr double kMergeCos = 0.866;
// A face of one body is the contact face only if its direction is within ~10 degrees of the patch's
// tangent (otherwise the contact is at the face's end, against another feature).
constexpr double kFaceSin = 0.17;

inline uint32_t hashId(uint64_t id) {
    // splitmix64 finaliser folded to 32 bits: distinct ids rarely collide in a manifold.
    uint64_t z = id + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<uint32_t>(z ^ (z >> 32));
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

// ---- librugo's query API (bridge_query.cpp: the only file that calls it) ---------------------------

struct QueryParams {
    int level = 0;           // relative level (0 finest)
    double margin = 0.0;     // speculative reach beyond the bands (m)
    double resolution = 0.0; // the resolution δ librugo certifies its answer to (m; 0: round-off)
};
// librugo's query context and a buffer of its contacts; opaque outside bridge_query.cpp.
struct QueryEngine;
QueryEngine* queryEngineCreate(); // nullptr if memory runs out
void queryEngineDestroy(QueryEngine* e);
// Room for queries of shapes up to `shape` with `contacts` contacts, now rather than in a step.
rugo_status queryEngineReserve(QueryEngine* e, const rugo_shape* shape, int contacts);
// Contacts of shape a against b (or a primitive), converted into out[0, *n) (at most cap; *found =
// how many librugo found). Statistics are added to *qs.
rugo_status queryShapes(QueryEngine* e, const rugo_shape* a, const rugo_transform& xa, const rugo_shape* b,
                        const rugo_transform& xb, const QueryParams& p, QContact* out, int cap, int* n,
                        int* found, BridgeStats* qs);
rugo_status queryPrimitive(QueryEngine* e, const rugo_shape* a, const rugo_transform& xa,
                           const PatchSide& prim, const QueryParams& p, QContact* out, int cap, int* n,
                           int* found, BridgeStats* qs);
// Does the shape's curve (at relative level `level`) touch or cross the convex polygon (world
// vertices, counter-clockwise; count 1 = a point)?
bool queryOverlapsPolygon(QueryEngine* e, const rugo_shape* s, const rugo_transform& x, int level,
                          const rugo_vec2* v, int count);

// ---- patches (bridge_patch.cpp) ----------------------------------------------------------------------

// Builds the patches of one query: contacts c[0, n) (query orientation, already resolved against
// one-sided edges) into out (appended). Returns how many were left unowned (ownerA -2) because every
// proxy pair of their points had a deeper patch already.
int buildPatches(const QContact* c, int n, const PatchSide& A, const PatchSide& B, std::vector<Patch>* out,
                 std::vector<int>* scratch);

// ---- shapes (bridge_shape.cpp) ----------------------------------------------------------------------

// Pieces and faces of a shape at absolute contact level `level`, at most maxPieces pieces; false if
// memory runs out.
bool buildShapeData(const rugo_shape* s, int level, int maxPieces, ShapeData* out);

} // namespace detail

using namespace detail; // NOLINT: the bridge's own sources only (this header is not installed)

// Not API: a nested class takes the visibility of its enclosing class, and Bridge is exported
// (RUGO_API), so without this the implementation's methods, vtable and typeinfo would be exported too.
#if defined(__GNUC__) || defined(__clang__)
#define RUGO_BRIDGE_HIDDEN __attribute__((visibility("hidden")))
#else
#define RUGO_BRIDGE_HIDDEN
#endif

struct RUGO_BRIDGE_HIDDEN Bridge::Impl : public b2ContactListener,
                                         public b2ContactFilter,
                                         public b2DestructionListener {
    b2World* world = nullptr;
    BridgeDef def;
    std::string lastError; // Bridge::LastError
    b2ContactListener* prevListener = nullptr;
    b2ContactFilter* prevFilter = nullptr;
    b2DestructionListener* userDestruction = nullptr;
    QueryEngine* query = nullptr;
    std::unordered_map<const b2Body*, BodyRec*> bodies;
    std::unordered_map<const b2Fixture*, ProxyRef> proxies;
    // Shape data by (shape, level, maxPieces), shared by the bodies using it (ShapeData::users).
    std::map<std::tuple<const rugo_shape*, int, int>, std::unique_ptr<ShapeData>> shapes;
    int nextSerial = 0;
    float dt = 1.0f / 60.0f;
    uint64_t stepSerial = 0; // Bridge::Step count: a RoughContact evaluated twice at one pose in a step
    bool afterSolve = false; // a PostSolve was seen since the collide phase: later evaluations are TOI
    bool inStep = false;     // inside Bridge::Step (the stepStart poses are current)
    BridgeStats stats;

    // Patch cache (open addressing; the generation counter clears it in O(1)).
    std::vector<CacheEntry> table;
    std::vector<Patch> patches;
    std::vector<QContact> scratch; // one query's contacts
    std::vector<int> patchScratch; // buildPatches' work list
    uint64_t gen = 1;
    size_t used = 0;
    PairCaches pairCaches; // the answers kept from step to step
    struct DrawnContact {
        b2Vec2 p, n;
    };
    std::vector<DrawnContact> lastContacts;
    // Bridge::GetPointInfo's data: two PointInfo per slot, a slot per RoughContact that has written
    // points (RoughContact::infoSlot), free slots chained through infoNext (bridge_contact.cpp).
    std::vector<PointInfo> pointInfo;
    std::vector<int> infoNext;
    int infoFree = -1;
    PointInfo* pointInfoOf(RoughContact* rc);
    void reservePointInfo(size_t bodyCount); // room for the slots of that many bodies' contacts
    void releasePointInfo(RoughContact* rc);
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
    // The piece of `data` holding segment `segment` of absolute level `level` (>= the data's level).
    static int pieceOf(const ShapeData* data, int segment, int level) {
        return data->pieceOf[static_cast<size_t>(segment >> (level - data->level))];
    }

    // bridge.cpp: listener chaining and body records
    void BeginContact(b2Contact* c) override;
    void EndContact(b2Contact* c) override;
    void PreSolve(b2Contact* c, const b2Manifold* old) override;
    void PostSolve(b2Contact* c, const b2ContactImpulse* imp) override;
    bool ShouldCollide(b2Fixture* a, b2Fixture* b) override;
    void SayGoodbye(b2Joint* j) override;
    void SayGoodbye(b2Fixture* f) override;
    void forget(BodyRec* r);
    void releaseShapeData(ShapeData* d);
    void rechain();
    std::vector<b2Body*> bodiesInAttachOrder() const;

    // bridge_body.cpp: mass, levels, reach
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
    static double roughReach(const BodyRec* r);
    static double fixtureReach(const b2Fixture* f, int child);
    static bool moved(const BodyRec* r);

    // bridge_cache.cpp: the patch cache. Finds the patches of a query (bodies or fixture, child, float
    // poses, margin, level) run this step, or runs `run` (which appends them to `patches`).
    void reserveFor(size_t bodyCount);
    template <class F>
    bool cachedPatches(const void* a, const void* b, int child, const b2Transform& xa, const b2Transform& xb,
                       double margin, int level, F&& run, uint32_t* start, uint32_t* count);
    bool cacheHas(const void* a, const void* b, int child, const b2Transform& xa, const b2Transform& xb,
                  double margin, int level) const;
    size_t cacheSlot(const void* a, const void* b, int child, const float* xf, double margin, int level,
                     bool* found);
    void cacheFill(size_t slot, const void* a, const void* b, int child, const float* xf, double margin,
                   int level, uint32_t start);
    static uint64_t cacheHash(const void* a, const void* b, int child, const float* xf);

    // bridge_pair_cache.cpp: the pair's kept answer. keptAnswer puts it, moved with the bodies, into
    // out[0, *n) if it was asked the same (level, resolution, the fixture's geometry), covers `margin`
    // and the bodies have moved by at most the reuse distance since; keepAnswer stores a search's answer
    // (whole answers that fit only).
    bool keptAnswer(PairCache* pc, const PrimitiveGeometry& g, const rugo_transform& xa,
                    const rugo_transform& xb, const QueryParams& qp, double margin, QContact* out, int cap,
                    int* n) const;
    void keepAnswer(PairCache* pc, double reachA, double reachB, const PrimitiveGeometry& g,
                    const rugo_transform& xa, const rugo_transform& xb, const QueryParams& qp,
                    const QContact* c, int n, int found) const;
    static PrimitiveGeometry primitiveGeometry(const b2Fixture* f, int child);
    static double originReach(const BodyRec* r);
    static double originReach(const PrimitiveGeometry& g);
    // The reuse distance r (BridgeDef::reuseDistance; 0: every pair is searched every step).
    double keepDistance() const {
        return def.reuseDistance > 0.0 && std::isfinite(def.reuseDistance) ? def.reuseDistance : 0.0;
    }
    // A search's margin: the speculative margin, at least kKeptMarginFloor r, plus r, so that its answer
    // covers the margin of the next steps while they move by at most r.
    double searchMargin(double margin) const {
        const double r = keepDistance();
        return r > 0.0 ? std::max(margin, kKeptMarginFloor * r) + r : margin;
    }

    // bridge_evaluate.cpp: the patches of a pair, into a manifold.
    bool roughPatches(BodyRec* qa, BodyRec* qb, const b2Transform& xa, const b2Transform& xb, double margin,
                      const RoughContact* current, uint32_t* start, uint32_t* count);
    bool primitivePatches(BodyRec* r, b2Fixture* other, int child, const b2Transform& xr,
                          const b2Transform& xo, double margin, const RoughContact* current, uint32_t* start,
                          uint32_t* count);
    void evaluate(RoughContact* c, b2Manifold* m, const b2Transform& xfA, const b2Transform& xfB);
    // The resolution of a query between a and b (b nullptr: an ordinary fixture): queryResolution times
    // the smaller error budget of the two, or times Box2D's linear slop when neither body has one (a
    // world's positions are good to a slop: Box2D lets resting bodies overlap by that much); 0 when
    // queryResolution is 0 (round-off answers, searched every step).
    double resolutionFor(const BodyRec* a, const BodyRec* b) const {
        const double f = def.queryResolution;
        if (!(f > 0.0) || !std::isfinite(f)) return 0.0;
        double budget = a->budget > 0.0 && std::isfinite(a->budget) ? a->budget : 0.0;
        if (b != nullptr && b->budget > 0.0 && std::isfinite(b->budget) &&
            (budget == 0.0 || b->budget < budget))
            budget = b->budget;
        return f * (budget > 0.0 ? budget : static_cast<double>(b2_linearSlop));
    }
    void rollingResistance(RoughContact* rc, float impulse, double arm);
    void surfaceAt(const RoughContact* rc, const PatchPoint& q, bool flip, PointInfo* out) const;
    void giveUnowned(uint32_t first, const BodyRec* qa, const void* other, int child,
                     const RoughContact* current);

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
    static OneSided makeOneSided(const b2EdgeShape& e, const b2Transform& x, bool hasPrev, bool hasNext);
    static OneSided makeTwoSided(const b2EdgeShape& e, const b2Transform& x, b2Vec2 centroid);
    static bool resolveOneSided(const OneSided& o, b2Vec2 p, b2Vec2* m, double* dist);
};

namespace detail {

// The bridge's contact for every pair of fixtures of which one is a proxy (bridge_contact.cpp). Box2D
// creates and destroys it through the registry; it holds no resource of its own (a world destroyed
// first frees it without running its destructor).
class RUGO_BRIDGE_HIDDEN RoughContact : public b2Contact {
  public:
    RoughContact(b2Fixture* fA, int32 iA, b2Fixture* fB, int32 iB, Bridge::Impl* impl, const ProxyRef* ra,
                 const ProxyRef* rb);
    void Evaluate(b2Manifold* manifold, const b2Transform& xfA, const b2Transform& xfB) override;

    Bridge::Impl* impl;
    BodyRec* recA; // the proxy's body record on fixture A's side (nullptr: an ordinary fixture)
    BodyRec* recB;
    int pieceA, pieceB;
    // The last evaluation: Bridge::Impl::stepSerial and the two float poses.
    uint64_t lastStep = 0;
    float lastPose[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    bool repeated = false; // the last evaluation repeated the one before at the same poses (disabled)
    int infoSlot = -1;     // its points' surface data in Impl::pointInfo (-1: none written yet)

    // Installs the bridge's create and destroy functions in Box2D's registry (once per process).
    static void install();
};

// The live bridges by world (bridge_contact.cpp).
void registerBridge(const b2World* world, Bridge::Impl* impl);
void unregisterBridge(const Bridge::Impl* impl);

} // namespace detail

// ---- the cache's template (bridge_cache.cpp has the rest) --------------------------------------------
template <class F>
bool Bridge::Impl::cachedPatches(const void* a, const void* b, int child, const b2Transform& xa,
                                 const b2Transform& xb, double margin, int level, F&& run, uint32_t* start,
                                 uint32_t* count) {
    const float xf[8] = {xa.p.x, xa.p.y, xa.q.c, xa.q.s, xb.p.x, xb.p.y, xb.q.c, xb.q.s};
    bool found = false;
    const size_t slot = cacheSlot(a, b, child, xf, margin, level, &found);
    if (found) {
        ++stats.cacheHits;
        *start = table[slot].start;
        *count = table[slot].count;
        return true;
    }
    const uint32_t first = static_cast<uint32_t>(patches.size());
    const bool ok = run();
    cacheFill(slot, a, b, child, xf, margin, level, first);
    *start = first;
    *count = table[slot].count;
    return ok;
}

} // namespace rugo

#endif
