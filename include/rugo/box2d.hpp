/// @file rugo/box2d.hpp
/// librugo — the Box2D 2.4 bridge: rough curved bodies in an ordinary b2World.
///
/// One rugo::Bridge per b2World. Attaching a rugo_shape to a b2Body gives the body a few density-0 proxy
/// fixtures — convex polygons of at most 8 vertices (b2_maxPolygonVertices) whose core and skin enclose
/// convex runs of the curve and its tolerance band: one for a convex shape, a few for a concave one — and
/// the exact mass of the contour. Box2D uses the proxies only for its broad phase, its time of impact and
/// its sensors. The collision of every proxy pair is the bridge's: it registers a b2Contact subclass in
/// Box2D's contact registry for the shape-type pairs a proxy can be in, whose Evaluate writes librugo's
/// contacts into the manifold (one librugo query per body pair and pose, shared by the pair's proxy
/// contacts), with the friction and restitution of the surfaces at the points.
///
/// Semantics (docs/box2d.md has the full statement):
///  - Separation in the manifold is the curve distance minus the tolerance bands λ_A(t_A) + λ_B(t_B):
///    bodies rest on their asperities, like Box2D's polygon skin.
///  - A contact patch (a contact region of librugo's, regions with nearly the same normal merged, a
///    flat face on a flat face completed to the ends of the stretch they share) is owned by exactly one
///    proxy pair and becomes one b2Contact with one normal and at most two points, at the patch's ends,
///    as Box2D clips a face: its block solver then holds stacks.
///  - Box2D's own Begin/EndContact, PreSolve and PostSolve follow these manifolds: a contact touches when
///    the bridge wrote points. The user's PreSolve runs after the bridge's Evaluate and may change the
///    friction, the restitution, the tangent speed or disable the contact.
///  - Continuous collision: points apart but closing within the step are speculative (see Bridge::Step
///    and docs/box2d.md, "Continuous collision").
///  - Box2D is single precision; librugo computes in double and converts at the boundary.
///
/// Lifetime: shapes are shared, never copied, and must outlive every body they are attached to. Destroy
/// the bridge before its world (it restores the world's callbacks and removes its proxies); if the world
/// was destroyed first, call ReleaseWorld() before destroying the bridge (and before creating another
/// world). Destroying a rough body with b2World::DestroyBody is fine (the destruction listener forgets it).
///
/// Thread safety: as Box2D 2.4 — one thread drives every world and bridge of the process. Box2D's contact
/// registry is process-global: the first Bridge installs the bridge's contact functions there (for
/// every world; pairs without a proxy go to Box2D's own functions unchanged), and a process-global list
/// of live bridges by world tells the bridge's functions which bridge a fixture belongs to.
///
/// Units: Box2D's (metres, kilograms, seconds, radians); shapes are in metres. Errors are returned as
/// rugo_status (never thrown); only the constructor can throw (std::bad_alloc, as any C++ allocation).
#ifndef RUGO_BOX2D_HPP
#define RUGO_BOX2D_HPP

#include <box2d/box2d.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>

#include "rugo/rugo.h"

/// The Box2D 2.4 bridge of librugo (target rugo::box2d).
namespace rugo {

/// Settings of a Bridge, given to its constructor.
struct BridgeDef {
    /// Automatic level of detail: the coarsest level whose certified error against the finest level
    /// (rugo_shape_level_error: how far its curve plus band can lie from the finest curve plus band,
    /// anywhere on the outline, in metres) is at most this, at it and every finer level. A contact's
    /// band-adjusted separation then differs from the finest level's by at most the sum of the two
    /// bodies' budgets. Per body, see RoughBodyDef::errorBudget. A negative or NaN budget keeps every
    /// body at its finest level.
    double errorBudget = 0.005;
    /// Most proxy fixtures per body (1 .. 8; 0 or beyond: 8). A convex shape gets one; a concave one a
    /// convex piece per convex run of its outline, merged down to this many. Per body, see
    /// RoughBodyDef::maxProxies.
    int maxProxies = 8;
    /// Continuous collision policy (docs/box2d.md): a patch whose curves are apart by a gap that the
    /// bodies' approach closes within the step gets speculative points (positive separation) at its
    /// ends, which Box2D's solver lets close by their gap and no further, so fast rough bodies do not
    /// tunnel and flat faces land flat. false: only touching points (s <= 0) are ever submitted.
    bool speculative = true;
    /// Kept answers (docs/box2d.md, "Kept answers"): each rough body pair (and rough body and ordinary
    /// fixture child) keeps its last librugo search and answers from it, its contacts moved with the
    /// bodies, while the two have moved relative to each other by at most this distance since (metres: a
    /// bound on how far any point of one moved in the other's frame); its searches look this much farther
    /// and at least 4x this far (their margin), so the kept answer still holds every contact within the
    /// step's reach, each separation within 2x this distance of a search's. The default, a quarter of
    /// Box2D's linear slop (5 mm), keeps answers within half a slop: resting and creeping pairs skip their
    /// searches. 0 (or negative, NaN): every pair is searched every step.
    double reuseDistance = 0.25 * b2_linearSlop;
    /// Resolution of the bridge's librugo queries (rugo_contact_query.resolution) as a fraction of the
    /// pair's error budget (the smaller of the two bodies' errorBudget; Box2D's linear slop, 5 mm, when
    /// neither body has one): 0 = round-off answers (the default: librugo's answers at a resolution are
    /// not yet certified, docs/accuracy.md). Negative or NaN: 0. The contact rule is the thesis' (minima
    /// of the curves' distance) either way.
    double queryResolution = 0.0;
    /// Friction of a contact: how the per-point μ of its (at most 2) points are combined (a value that
    /// is not a rugo_mix_rule falls back to this default).
    rugo_mix_rule pointFrictionMix = RUGO_MIX_MEAN;
    /// Friction at a point of a rough body against an ordinary fixture: the rough surface's μ(λ(t)) at
    /// the point mixed with the fixture's friction. Default: the world's own rule, √(μ_rough μ_fixture)
    /// as b2MixFriction, so rough and ordinary bodies on one ramp follow one rule (a frictionless
    /// rough body slides on any floor). RUGO_MIX_MAX is the thesis' rule (7.2). A value that is not a
    /// rugo_mix_rule falls back to this default. (docs/box2d.md, "Friction and restitution".)
    rugo_mix_rule fixtureFrictionMix = RUGO_MIX_GEOMETRIC;
    /// Restitution at a point of a rough body against an ordinary fixture: the shape's ε mixed with the
    /// fixture's restitution. Default: the world's rule, max as b2MixRestitution; RUGO_MIX_MIN is the
    /// thesis'.
    rugo_mix_rule fixtureRestitutionMix = RUGO_MIX_MAX;
    /// Friction at a point of two rough bodies: μ_A(λ_A(t_A)) and μ_B(λ_B(t_B)) mixed. Default: the
    /// thesis' max (7.2: the rougher surface's asperities decide).
    rugo_mix_rule roughFrictionMix = RUGO_MIX_MAX;
    /// Restitution at a point of two rough bodies: the shapes' ε mixed. Default: the thesis' min.
    rugo_mix_rule roughRestitutionMix = RUGO_MIX_MIN;
    /// Box2D has no getter for the world's destruction listener: give the one you had set on the world
    /// here (or later with Bridge::SetDestructionListener); the bridge installs its own and chains to it.
    /// Not owned; must outlive the bridge.
    b2DestructionListener* destructionListener = nullptr;
};

/// RoughBodyDef::rollingResistance's default (docs/roughness.md, "Rolling resistance").
constexpr double kDefaultRollingResistance = 1.5;

/// How Bridge::Attach makes a b2Body rough.
struct RoughBodyDef {
    const rugo_shape* shape = nullptr; ///< shared, not copied; must outlive the attachment
    double density = 1.0;              ///< kg/m^2 (> 0 for a dynamic body)
    /// Level of detail of this body's contacts, as rugo_contact_query::lod counts it: 0 = finest, -1 =
    /// one level coarser, ... (clamped to the shape's coarsest level); RUGO_LOD_AUTO = from errorBudget
    /// (rugo_shape_level_for_error). A positive value is BAD_ARGUMENT. A body pair uses the finer of its
    /// two levels.
    int lod = RUGO_LOD_AUTO;
    double errorBudget = -1.0; ///< metres; < 0 or NaN = BridgeDef::errorBudget
    /// Most proxy fixtures of this body (1 .. 8); 0 = BridgeDef::maxProxies.
    int maxProxies = 0;
    /// Rolling resistance from roughness (docs/roughness.md, "Rolling resistance"): k >= 0, a
    /// dimensionless factor on this body's own band. At each contact the bridge resists the two bodies'
    /// relative turning with a torque of at most N (k_A λ_A + k_B λ_B) (N the normal force, λ the bands at
    /// the contact; an ordinary fixture has no band), never more than stops the turning. 0 switches it
    /// off for this body (a smooth curve then rolls and rocks on its asperities as Box2D 2.4 lets it).
    /// The default is calibrated so that a rough rock dropped on a floor comes to rest about as soon as
    /// its polygon twin (samples/box2d/b2_surface). Errors: BAD_ARGUMENT if negative or not finite.
    double rollingResistance = kDefaultRollingResistance;
    /// Given to every proxy fixture, as b2FixtureDef would.
    b2Filter filter;
    bool isSensor = false;      ///< makes every proxy fixture a sensor (Box2D reports, no contact response)
    b2FixtureUserData userData; ///< given to every proxy fixture (the bridge does not use it)
};

/// Debug drawing flags (Bridge::Draw).
enum DrawFlags : unsigned {
    kDrawCurve = 1u,   ///< the curve at the body's contact level (b2Draw::DrawSegment polylines)
    kDrawBand = 2u,    ///< the tolerance band's two offset curves
    kDrawProxies = 4u, ///< the proxies: each core polygon pushed out by its skin (DrawPolygon)
    kDrawContacts = 8u ///< the last step's rough manifold points and normals
};

/// The closest hit of Bridge::RayCast.
struct RayHit {
    b2Body* body = nullptr;       ///< the body hit
    b2Fixture* fixture = nullptr; ///< the proxy (rough body) or the ordinary fixture hit
    b2Vec2 point;                 ///< world point on the true curve (or on the ordinary fixture)
    b2Vec2 normal;                ///< unit outward normal there
    float fraction = 1.0f;        ///< along p1 -> p2
    int segment = -1;             ///< curve segment at the body's contact level (-1: ordinary fixture)
    double t = 0.0;               ///< curve parameter in [0, 1)
};

/// One side of a manifold point of a rough contact (PointInfo): the surface of fixture A's or B's body.
struct SurfacePoint {
    bool rough = false; ///< a rough body's curve (false: an ordinary fixture)
    /// Absolute level of detail of segment and t: the body's contact level (Bridge::GetLevel), or a
    /// finer one where the query refined it (-1: ordinary fixture).
    int level = -1;
    int segment = -1;         ///< curve segment at that level (-1: ordinary fixture)
    double t = 0.0;           ///< curve parameter in [0, 1] within the segment (0: ordinary fixture)
    double lambda = 0.0;      ///< tolerance band λ(t) there, metres (0: ordinary fixture)
    double friction = 0.0;    ///< μ(λ) of the body's friction map there, or the fixture's friction
    double restitution = 0.0; ///< the shape's base ε (rugo_restitution::epsilon), or the fixture's
};

/// The surface data of one manifold point of a rough contact (Bridge::GetPointInfo).
struct PointInfo {
    /// The point's μ: a.friction and b.friction mixed by the BridgeDef rule of the pair (rough against
    /// rough: roughFrictionMix; against an ordinary fixture: fixtureFrictionMix). The contact's friction
    /// (b2Contact::GetFriction before your PreSolve changes it) is these mixed over its points by
    /// BridgeDef::pointFrictionMix.
    double friction = 0.0;
    /// The point's ε, mixed likewise (roughRestitutionMix, fixtureRestitutionMix). The contact's
    /// restitution is the smaller of its points', except on speculative manifolds (docs/box2d.md).
    double restitution = 0.0;
    SurfacePoint a; ///< the surface of b2Contact::GetFixtureA()'s body at the point
    SurfacePoint b; ///< the surface of b2Contact::GetFixtureB()'s body at the point
};

/// Counters since construction or ResetStats().
struct BridgeStats {
    long evaluations = 0;       ///< Evaluate calls of the bridge's contacts (Box2D's narrow phase)
    long toiEvaluations = 0;    ///< of those, during Box2D's continuous (TOI) phase
    long emptyEvaluations = 0;  ///< of those, with no manifold point (not touching)
    long proxyRejections = 0;   ///< of those, decided by the proxies' distance alone (no query)
    long reusedEvaluations = 0; ///< not counted any more (see queriesReused); kept for source compatibility
    long preSolves = 0;         ///< PreSolve calls Box2D made on contacts with a proxy (chained to yours)
    long queries = 0;           ///< librugo collision queries run (one per body pair and pose)
    long queriesReused = 0;     ///< of those, answered from the pair's kept answer (reuseDistance; no search)
    long cacheHits = 0;         ///< proxy contacts answered from a query already run for the same poses
    long patches = 0;           ///< contact patches built from the queries
    long patchesDropped = 0;    ///< patches whose proxy pair already owned a deeper one (not submitted)
    long pointsSubmitted = 0;   ///< manifold points written
    long speculativePoints = 0; ///< of those, with positive separation (CCD policy)
    /// librugo query statistics, summed (rugo_query_stats). @{
    long boxTests = 0, segmentPairs = 0, fallbacks = 0;
    /// @}
    long massReapplied = 0;      ///< times Box2D had reset a rough body's mass and the bridge fixed it
    long listenersRechained = 0; ///< times Step() found a replaced listener/filter and chained to it
};

/// Memory held for one rough body (shapes are shared and counted separately).
struct BodyMemory {
    std::size_t bridgeBytes = 0;      ///< the bridge's own record for the body
    std::size_t box2dBytes = 0;       ///< proxy fixtures, their shapes and broad-phase proxies inside Box2D
    int proxyCount = 0;               ///< number of proxy fixtures
    std::size_t sharedShapeBytes = 0; ///< the rugo_shape (shared by every body using it; not per body)
};

/// Rough curved bodies in one b2World (see the top of this file). Not copyable.
class RUGO_API Bridge {
  public:
    /// Installs the bridge's contact listener, contact filter and destruction listener on `world`,
    /// chaining to those the world had (world is not owned; nullptr makes an inert bridge, and so does a
    /// world that already has a bridge: one bridge per world). Create it after setting your own listener
    /// and filter. Throws std::bad_alloc if memory runs out.
    explicit Bridge(b2World* world, const BridgeDef& def = BridgeDef());
    /// Removes every proxy and restores the world's listener, filter and destruction listener (unless
    /// ReleaseWorld() was called). Must run before the world is destroyed.
    ~Bridge();
    /// Not copyable: one bridge per world.
    Bridge(const Bridge&) = delete;
    /// Not assignable.
    Bridge& operator=(const Bridge&) = delete;

    /// The largest rough body Attach accepts, in metres across (the diagonal of the shape's bounds).
    static constexpr double kMaxBodySize = 1000.0;
    /// Makes `body` rough: adds density-0 proxy fixtures (owned by the body, removed by Detach or by
    /// destroying the body) and applies the exact mass. The shape is borrowed (see RoughBodyDef).
    /// Errors: RUGO_ERR_NULL_ARGUMENT (body or def.shape), RUGO_ERR_BAD_ARGUMENT (body of another world,
    /// density not finite or < 0, or 0 on a dynamic body, or so large or small that the shape's mass or
    /// inertia leaves [1e6 FLT_MIN, 1e-6 FLT_MAX] (Box2D's floats need room for products and inverses),
    /// maxProxies < 0 or > 8, lod > 0), RUGO_ERR_BAD_SIZE (more than kMaxBodySize across),
    /// RUGO_ERR_ALREADY_ATTACHED, RUGO_ERR_WORLD_LOCKED (inside Step or a
    /// callback, or an EndContact that Box2D raises outside Step), RUGO_ERR_OUT_OF_MEMORY.
    rugo_status Attach(b2Body* body, const RoughBodyDef& def);
    /// Why the last Attach failed, for people: the field, its value and a way out (e.g. "density: is 0;
    /// a dynamic body needs a density > 0 in kg/m^2 ..."); "" after a successful Attach. Bodies more
    /// than kMaxBodySize across are refused (RUGO_ERR_BAD_SIZE): Box2D is tuned for 0.1-10 m.
    const char* LastError() const;
    /// Removes the proxies and the rough mass (Box2D recomputes the mass from the remaining fixtures).
    /// Errors: RUGO_ERR_NULL_ARGUMENT, RUGO_ERR_NOT_ATTACHED, RUGO_ERR_WORLD_LOCKED.
    rugo_status Detach(b2Body* body);

    /// Is a rough shape attached to this body? (false for nullptr)
    bool IsRough(const b2Body* body) const;
    /// The attached shape (borrowed); nullptr if not rough.
    const rugo_shape* GetShape(const b2Body* body) const;
    /// The body's absolute contact level; -1 if not rough.
    int GetLevel(const b2Body* body) const;
    /// The number of the body's proxy fixtures; 0 if not rough.
    int GetProxyCount(const b2Body* body) const;
    /// Is this fixture one of the bridge's proxies? If so and piece is not nullptr, *piece = which of
    /// the body's proxies it is (0 .. GetProxyCount - 1, in outline order).
    bool IsProxy(const b2Fixture* fixture, int* piece = nullptr) const;

    /// The step wrapper: re-chains a listener or filter the user replaced, re-applies the exact mass of
    /// every rough body whose mass Box2D has reset (SetType, fixture changes, SetFixedRotation), then
    /// calls b2World::Step (timeStep in seconds, iteration counts as Box2D's). Calling b2World::Step
    /// directly also works, but then mass resets are only repaired by SyncMass, speculative points
    /// assume a 1/60 s step, and Box2D's continuous phase re-solves contacts it has already solved
    /// (docs/box2d.md, "Continuous collision").
    void Step(float timeStep, int32 velocityIterations, int32 positionIterations);
    /// Re-applies the exact mass now: the rough contour's integrals times density, plus the mass of the
    /// body's ordinary fixtures. Errors: NULL_ARGUMENT, NOT_ATTACHED, WORLD_LOCKED.
    rugo_status SyncMass(b2Body* body);
    /// The exact mass data the bridge gives a body (what SyncMass applies: kg, local centre in metres,
    /// rotational inertia about the body origin in kg m^2) into *out. Errors: NULL_ARGUMENT,
    /// NOT_ATTACHED.
    rugo_status GetExactMass(const b2Body* body, b2MassData* out) const;

    /// Closest hit along p1 -> p2 (world, metres) over all fixtures: rough bodies are hit on their true
    /// curve (at their contact level, band ignored), ordinary fixtures as Box2D reports them. Returns
    /// false if none (also for a ray of zero length or with a non-finite end, which Box2D's own ray cast
    /// would assert on); on a hit fills *hit unless it is nullptr. Allocates a small temporary vector.
    bool RayCast(const b2Vec2& p1, const b2Vec2& p2, RayHit* hit) const;
    /// Is the world point inside the rough body's true curve? (false if not rough)
    bool TestPoint(const b2Body* body, const b2Vec2& p) const;
    /// Bodies whose true geometry overlaps the box: rough bodies by their curve (plus band), ordinary
    /// bodies by their fixtures' AABBs as Box2D would. Each body reported once; return false to stop.
    void QueryAABB(const b2AABB& aabb, const std::function<bool(b2Body*)>& callback) const;

    /// The surface data of manifold point `index` (0 .. GetManifold()->pointCount - 1, as
    /// b2WorldManifold numbers the points) of a contact the bridge wrote (one with a rough body): μ, ε,
    /// λ, segment and t on each side, into *out. Valid in BeginContact, PreSolve and PostSolve and until
    /// the contact is next evaluated (the manifold it describes). Errors (*out untouched):
    /// RUGO_ERR_NULL_ARGUMENT (contact or out), RUGO_ERR_NOT_ATTACHED (a contact without a rough body
    /// of this bridge: IsProxy tells), RUGO_ERR_BAD_ARGUMENT (index outside the manifold's points; a
    /// contact that does not touch has none).
    rugo_status GetPointInfo(const b2Contact* contact, int index, PointInfo* out) const;

    /// Draws every rough body through any b2Draw (flags: DrawFlags); nothing for nullptr.
    void Draw(b2Draw* draw, unsigned flags = kDrawCurve) const;

    /// Memory held for one rough body (all zero if not rough).
    BodyMemory GetBodyMemory(const b2Body* body) const;
    /// The counters since construction or the last ResetStats().
    BridgeStats GetStats() const;
    /// Sets every counter to 0.
    void ResetStats();
    /// The world given to the constructor (nullptr after ReleaseWorld()).
    b2World* GetWorld() const;
    /// The destruction listener the bridge chains to (b2World::SetDestructionListener would replace the
    /// bridge's own, which must stay installed so that destroyed rough bodies are forgotten). Not owned.
    void SetDestructionListener(b2DestructionListener* listener);
    /// The world was destroyed before the bridge: forget it without touching it.
    void ReleaseWorld();

    /// The implementation (box2d_bridge/), also the listener and filter installed on the world.
    struct Impl;

  private:
    std::unique_ptr<Impl> m_impl;
};

} // namespace rugo

#endif
