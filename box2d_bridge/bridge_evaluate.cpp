// RoughContact::Evaluate: Box2D's narrow phase for a proxy pair. The body pair's patches (one librugo
// query per pair and poses, cached for the pair's other proxy contacts and Box2D's continuous phase)
// give this proxy pair at most one patch; its points become the manifold, with the friction and
// restitution of the surfaces there and the speculative rules of docs/box2d.md ("Continuous
// collision"). Box2D then matches the points' ids for warm starting, raises Begin/EndContact and calls
// the user's PreSolve, which sees this manifold.
#include "bridge_impl.hpp"

#include <box2d/b2_distance.h>

#include <algorithm>
#include <cmath>

namespace rugo {

namespace {

// A body's velocity as Box2D's solver will first see it: in a normal step, after the step's gravity
// and damping (b2Island::Solve integrates velocities before it initialises the contact constraints);
// in the continuous phase, as it is.
struct Motion {
    b2Vec2 v, c;
    float w = 0.0f;
};

Motion predictedMotion(const b2Body* b, b2Vec2 gravity, float dt, bool toi) {
    Motion m;
    m.v = b->GetLinearVelocity();
    m.w = b->GetAngularVelocity();
    m.c = b->GetWorldCenter();
    if (!toi && b->GetType() == b2_dynamicBody) {
        m.v += dt * b->GetGravityScale() * gravity;
        m.v *= 1.0f / (1.0f + dt * b->GetLinearDamping());
        m.w *= 1.0f / (1.0f + dt * b->GetAngularDamping());
    }
    return m;
}

// Normal approach speed of B's point toward A's point along n (A -> B): > 0 when closing.
double approach(const Motion& a, b2Vec2 pa, const Motion& b, b2Vec2 pb, b2Vec2 n) {
    const b2Vec2 va = a.v + b2Cross(a.w, pa - a.c), vb = b.v + b2Cross(b.w, pb - b.c);
    return -static_cast<double>(b2Dot(vb - va, n));
}

// The primitive side of a rough-primitive query: the fixture's child in world coordinates.
PatchSide primitiveSide(const b2Fixture* f, int child, const b2Transform& x) {
    PatchSide s;
    s.x = toRugo(x);
    const b2Shape* sh = f->GetShape();
    s.type = sh->GetType();
    s.radius = sh->m_radius;
    s.mu = static_cast<double>(f->GetFriction());
    s.eps = static_cast<double>(f->GetRestitution());
    s.child = child;
    switch (s.type) {
    case b2Shape::e_circle:
        s.v[0] = b2Mul(x, static_cast<const b2CircleShape*>(sh)->m_p);
        s.n = 1;
        break;
    case b2Shape::e_polygon: {
        const b2PolygonShape* p = static_cast<const b2PolygonShape*>(sh);
        s.n = p->m_count;
        for (int i = 0; i < p->m_count; ++i) {
            s.v[i] = b2Mul(x, p->m_vertices[i]);
            s.normals[i] = b2Mul(x.q, p->m_normals[i]);
        }
        break;
    }
    case b2Shape::e_edge: {
        const b2EdgeShape* e = static_cast<const b2EdgeShape*>(sh);
        s.v[0] = b2Mul(x, e->m_vertex1);
        s.v[1] = b2Mul(x, e->m_vertex2);
        s.n = 2;
        break;
    }
    case b2Shape::e_chain: {
        b2EdgeShape e;
        static_cast<const b2ChainShape*>(sh)->GetChildEdge(&e, child);
        s.v[0] = b2Mul(x, e.m_vertex1);
        s.v[1] = b2Mul(x, e.m_vertex2);
        s.n = 2;
        break;
    }
    default:
        break;
    }
    return s;
}

} // namespace

// The patches of a rough body pair (query order: attach order) at poses xa, xb, cached per poses.
bool Bridge::Impl::roughPatches(BodyRec* QA, BodyRec* QB, const b2Transform& xa, const b2Transform& xb,
                                double margin, const RoughContact* current, uint32_t* start,
                                uint32_t* count) {
    const int level = std::max(QA->relLevel, QB->relLevel);
    return cachedPatches(
        QA, QB, -1, xa, xb, margin, level,
        [&]() {
            QueryParams qp;
            qp.level = level;
            qp.resolution = resolutionFor(QA, QB);
            qp.margin = searchMargin(margin);
            int n = 0, found = 0;
            const rugo_transform ta = toRugo(xa), tb = toRugo(xb);
            // The pair's kept answer, moved with the bodies, or a search kept for the next steps (not
            // at the poses a fast pair's turn is predicted at: the pair is not searched there next).
            PairCache* pc = current != nullptr && keepDistance() > 0.0
                                ? pairCaches.find(QA->serial, QB->serial, nullptr, -1, stepSerial)
                                : nullptr;
            const PrimitiveGeometry none;
            rugo_status st = RUGO_OK;
            if (keptAnswer(pc, none, ta, tb, qp, margin, scratch.data(), static_cast<int>(scratch.size()),
                           &n)) {
                ++stats.queriesReused;
            } else {
                st = queryShapes(query, QA->shape, ta, QB->shape, tb, qp, scratch.data(),
                                 static_cast<int>(scratch.size()), &n, &found, &stats);
                if (st == RUGO_OK && found > static_cast<int>(scratch.size())) {
                    scratch.resize(static_cast<size_t>(found) * 2); // a warm-up: the next such query fits
                    st = queryShapes(query, QA->shape, ta, QB->shape, tb, qp, scratch.data(),
                                     static_cast<int>(scratch.size()), &n, &found, &stats);
                }
                if (st == RUGO_OK)
                    keepAnswer(pc, originReach(QA), originReach(QB), none, ta, tb, qp, scratch.data(), n,
                               found);
            }
            ++stats.queries;
            if (st != RUGO_OK) return false;
            PatchSide A, B;
            A.data = QA->data;
            A.x = ta;
            A.serial = QA->serial;
            B.data = QB->data;
            B.x = tb;
            B.serial = QB->serial;
            const size_t before = patches.size();
            if (buildPatches(scratch.data(), n, A, B, &patches, &patchScratch) > 0 && current != nullptr)
                giveUnowned(static_cast<uint32_t>(before), QA, QB, -1, current);
            stats.patches += static_cast<long>(patches.size() - before);
            return true;
        },
        start, count);
}

// Patches of one query that every proxy pair of their points' pieces already had (ownerA -2) go to the
// body pair's proxy contacts that have none, in the order of their pieces; what is left is dropped. A
// manifold is in world points and the bodies' frames: Box2D's solver does not mind which two fixtures
// of the two bodies carry it. `other` is the second rough body's record, or the ordinary fixture with
// its child.
void Bridge::Impl::giveUnowned(uint32_t first, const BodyRec* qa, const void* other, int child,
                               const RoughContact* current) {
    const BodyRec* qb = child < 0 ? static_cast<const BodyRec*>(other) : nullptr;
    const b2Fixture* fo = child < 0 ? nullptr : static_cast<const b2Fixture*>(other);
    int freeA[64], freeB[64], nfree = 0;
    for (const b2ContactEdge* ce = qa->body->GetContactList(); ce != nullptr && nfree < 64; ce = ce->next) {
        const RoughContact* rc = dynamic_cast<const RoughContact*>(ce->contact);
        if (rc == nullptr) continue;
        int pa = -1, pb = -1;
        if (qb != nullptr) {
            if (rc->recA == qa && rc->recB == qb) {
                pa = rc->pieceA;
                pb = rc->pieceB;
            } else if (rc->recB == qa && rc->recA == qb) {
                pa = rc->pieceB;
                pb = rc->pieceA;
            } else {
                continue;
            }
        } else {
            const bool roughIsA = rc->recA == qa && rc->recB == nullptr;
            const bool roughIsB = rc->recB == qa && rc->recA == nullptr;
            if (roughIsA && rc->GetFixtureB() == fo && rc->GetChildIndexB() == child) {
                pa = rc->pieceA;
            } else if (roughIsB && rc->GetFixtureA() == fo && rc->GetChildIndexA() == child) {
                pa = rc->pieceB;
            } else {
                continue;
            }
        }
        bool taken = false;
        for (size_t i = first; i < patches.size() && !taken; ++i)
            taken = patches[i].ownerA == pa && patches[i].ownerB == pb;
        // Only a contact that is still to be evaluated at these poses in this step (it then finds its
        // patch in the cache), or the one being evaluated.
        if (!taken && rc != current && inStep && rc->lastStep == stepSerial) {
            const b2Transform& ta = rc->GetFixtureA()->GetBody()->GetTransform();
            const b2Transform& tb = rc->GetFixtureB()->GetBody()->GetTransform();
            const float pose[8] = {ta.p.x, ta.p.y, ta.q.c, ta.q.s, tb.p.x, tb.p.y, tb.q.c, tb.q.s};
            taken = std::memcmp(pose, rc->lastPose, sizeof pose) == 0;
        }
        if (taken) continue;
        // In piece order (the contact list's order depends on history).
        int at = nfree++;
        while (at > 0 && (freeA[at - 1] > pa || (freeA[at - 1] == pa && freeB[at - 1] > pb))) {
            freeA[at] = freeA[at - 1];
            freeB[at] = freeB[at - 1];
            --at;
        }
        freeA[at] = pa;
        freeB[at] = pb;
    }
    int next = 0;
    for (size_t i = first; i < patches.size(); ++i) {
        if (patches[i].ownerA != -2) continue;
        if (next < nfree) {
            patches[i].ownerA = freeA[next];
            patches[i].ownerB = freeB[next];
            ++next;
        } else {
            ++stats.patchesDropped;
        }
    }
}

// The patches of a rough body against an ordinary fixture's child, with Box2D 2.4.1's one-sided edge
// rules (bridge_one_sided.cpp).
bool Bridge::Impl::primitivePatches(BodyRec* R, b2Fixture* other, int child, const b2Transform& xr,
                                    const b2Transform& xo, double margin, const RoughContact* current,
                                    uint32_t* start, uint32_t* count) {
    const int level = R->relLevel;
    return cachedPatches(
        R, other, child, xr, xo, margin, level,
        [&]() {
            PatchSide B = primitiveSide(other, child, xo);
            const b2Vec2 centroid = b2Mul(xr, R->body->GetLocalCenter());
            OneSided os;
            const b2Shape* sh = other->GetShape();
            if (sh->GetType() == b2Shape::e_chain) {
                const b2ChainShape* ch = static_cast<const b2ChainShape*>(sh);
                b2EdgeShape edge;
                ch->GetChildEdge(&edge, child); // one-sided, with ghost vertices (Box2D 2.4.1)
                const bool loop = ch->m_count > 2 && ch->m_vertices[0] == ch->m_vertices[ch->m_count - 1];
                const bool hasNext = loop || child + 1 < ch->GetChildCount();
                os = makeOneSided(edge, xo, loop || child > 0, hasNext);
                B.chainNext = hasNext;
            } else if (sh->GetType() == b2Shape::e_edge) {
                const b2EdgeShape& es = *static_cast<const b2EdgeShape*>(sh);
                os = es.m_oneSided ? makeOneSided(es, xo, false, false) : makeTwoSided(es, xo, centroid);
            }
            // Box2D skips a one-sided edge when the other body's centroid is behind it.
            if (os.on && !os.roundEnds && b2Dot(os.n1, centroid - os.v1) < 0.0f) return true;
            QueryParams qp;
            qp.level = level;
            qp.resolution = resolutionFor(R, nullptr);
            qp.margin = searchMargin(margin);
            int n = 0, found = 0;
            const rugo_transform tr = toRugo(xr), to = toRugo(xo);
            // As roughPatches: the kept answer (of the edge's raw contacts: its rules apply below).
            PairCache* pc = current != nullptr && keepDistance() > 0.0
                                ? pairCaches.find(R->serial, -1, other, child, stepSerial)
                                : nullptr;
            const PrimitiveGeometry geometry =
                pc != nullptr ? primitiveGeometry(other, child) : PrimitiveGeometry();
            rugo_status st = RUGO_OK;
            if (keptAnswer(pc, geometry, tr, to, qp, margin, scratch.data(), static_cast<int>(scratch.size()),
                           &n)) {
                ++stats.queriesReused;
            } else {
                st = queryPrimitive(query, R->shape, tr, B, qp, scratch.data(),
                                    static_cast<int>(scratch.size()), &n, &found, &stats);
                if (st == RUGO_OK && found > static_cast<int>(scratch.size())) {
                    scratch.resize(static_cast<size_t>(found) * 2);
                    st = queryPrimitive(query, R->shape, tr, B, qp, scratch.data(),
                                        static_cast<int>(scratch.size()), &n, &found, &stats);
                }
                if (st == RUGO_OK)
                    keepAnswer(pc, originReach(R), originReach(geometry), geometry, tr, to, qp,
                               scratch.data(), n, found);
            }
            ++stats.queries;
            if (st != RUGO_OK) return false;
            if (os.on) { // the edge's rules decide the normal and the owner (see OneSided)
                int kept = 0;
                for (int i = 0; i < n; ++i) {
                    QContact k = scratch[static_cast<size_t>(i)];
                    b2Vec2 m;
                    double sep = 0.0;
                    if (!resolveOneSided(os, toB2(k.pa), &m, &sep)) {
                        // Another child's point; a face of the rough body there may still rest on
                        // this child too.
                        k.seed = true;
                        k.n = toRv(-os.n1);
                        scratch[static_cast<size_t>(kept++)] = k;
                        continue;
                    }
                    k.pb = rugo_v2_sub(k.pa, rugo_v2_scale(sep, toRv(m)));
                    k.n = rugo_v2_scale(-1.0, toRv(m)); // from the curve (the query's A) toward the edge
                    k.sep = sep;
                    scratch[static_cast<size_t>(kept++)] = k;
                }
                n = kept;
            }
            PatchSide A;
            A.data = R->data;
            A.x = tr;
            A.serial = R->serial;
            const size_t before = patches.size();
            if (buildPatches(scratch.data(), n, A, B, &patches, &patchScratch) > 0 && current != nullptr)
                giveUnowned(static_cast<uint32_t>(before), R, other, child, current);
            stats.patches += static_cast<long>(patches.size() - before);
            return true;
        },
        start, count);
}

void Bridge::Impl::evaluate(RoughContact* rc, b2Manifold* m, const b2Transform& xfA, const b2Transform& xfB) {
    ++stats.evaluations;
    b2Fixture* fA = rc->GetFixtureA();
    b2Fixture* fB = rc->GetFixtureB();
    const b2Body* bA = fA->GetBody();
    const b2Body* bB = fB->GetBody();
    BodyRec* RA = rc->recA;
    BodyRec* RB = rc->recB;
    // Box2D's continuous phase: a PostSolve was seen, or a rough body has moved since Step began
    // (islands without contacts report no PostSolve before the TOI phase).
    const bool toi = inStep && (afterSolve || (RA && moved(RA)) || (RB && moved(RB)));
    if (toi) ++stats.toiEvaluations;
    // How far the surfaces can approach within the step (velocities after the step's gravity), for
    // the query's speculative margin; and whether the pair is fast (turns by more than kFastTurn, or
    // moves by more than its reach, within the step).
    const b2Vec2 g = world != nullptr ? world->GetGravity() : b2Vec2(0.0f, 0.0f);
    const Motion mA = predictedMotion(bA, g, dt, toi), mB = predictedMotion(bB, g, dt, toi);
    const double reachA = RA ? roughReach(RA) : fixtureReach(fA, rc->GetChildIndexA());
    const double reachB = RB ? roughReach(RB) : fixtureReach(fB, rc->GetChildIndexB());
    const double h = static_cast<double>(dt);
    double margin = 0.0;
    if (def.speculative) {
        const double speed = static_cast<double>((mA.v - mB.v).Length()) +
                             std::fabs(static_cast<double>(mA.w)) * reachA +
                             std::fabs(static_cast<double>(mB.w)) * reachB;
        margin = speed * h;
    }
    const bool fast =
        std::fabs(static_cast<double>(mA.w - mB.w)) * h > kFastTurn || margin > std::max(reachA, reachB);
    // Evaluated before at these very poses in this step: Box2D's continuous phase is re-solving a
    // contact it has solved there already (a time of impact at the step's start, where the proxies
    // were within its target already, or the same event again after a solve that left them there).
    // The manifold stays as it was (its impulses warm-start the next step) and the contact is
    // disabled, which leaves it out of the continuous phase for the rest of the step. Not for a fast
    // pair: the step's solve with the start pose's points may not hold it (a spinning body turns
    // another part into the other body), so Box2D's continuous phase solves it again from there.
    const float pose[8] = {xfA.p.x, xfA.p.y, xfA.q.c, xfA.q.s, xfB.p.x, xfB.p.y, xfB.q.c, xfB.q.s};
    if (inStep && !(toi && fast) && rc->lastStep == stepSerial &&
        std::memcmp(pose, rc->lastPose, sizeof pose) == 0) {
        rc->SetEnabled(false);
        rc->repeated = true; // the user's PreSolve has seen this manifold already (Impl::PreSolve)
        return;
    }
    rc->repeated = false;
    rc->lastStep = stepSerial;
    std::memcpy(rc->lastPose, pose, sizeof pose);
    // The normal impulse of the last solve (Box2D hands Evaluate the previous manifold), for the rolling
    // resistance below.
    float lastImpulse = 0.0f;
    for (int i = 0; i < m->pointCount; ++i)
        lastImpulse += m->points[i].normalImpulse;
    m->pointCount = 0;

    // Which side of this contact is the query's A (rough-rough: attach order; rough-primitive: the
    // rough body), and this proxy pair's pieces in the query's orientation.
    int ownA = -1, ownB = -1;
    bool flip = false;
    if (RA && RB) {
        const bool swap = RB->serial < RA->serial;
        ownA = swap ? rc->pieceB : rc->pieceA;
        ownB = swap ? rc->pieceA : rc->pieceB;
        flip = swap;
    } else {
        ownA = RA ? rc->pieceA : rc->pieceB;
        ownB = -1;
        flip = RA == nullptr;
    }
    const b2Transform& xqa = flip ? xfB : xfA; // the query's A and B poses
    const b2Transform& xqb = flip ? xfA : xfB;

    // The patches at poses (xa, xb) of fixture A's and B's bodies.
    auto patchesAt = [&](const b2Transform& xa, const b2Transform& xb, const RoughContact* owner,
                         uint32_t* st, uint32_t* ct) {
        if (RA && RB) {
            const bool swap = RB->serial < RA->serial;
            roughPatches(swap ? RB : RA, swap ? RA : RB, swap ? xb : xa, swap ? xa : xb, margin, owner, st,
                         ct);
        } else {
            BodyRec* R = RA ? RA : RB;
            b2Fixture* other = RA ? fB : fA;
            const int child = RA ? rc->GetChildIndexB() : rc->GetChildIndexA();
            primitivePatches(R, other, child, RA ? xa : xb, RA ? xb : xa, margin, owner, st, ct);
        }
    };
    Patch carried;
    const Patch* patch = nullptr;
    // The proxies alone decide a pair that cannot touch within the step (no query), unless the pair's
    // query has run at these poses already: it may have given this contact a patch (giveUnowned).
    bool cached = false;
    if (RA && RB) {
        const bool swap = RB->serial < RA->serial;
        cached = cacheHas(swap ? RB : RA, swap ? RA : RB, -1, swap ? xfB : xfA, swap ? xfA : xfB, margin,
                          std::max(RA->relLevel, RB->relLevel));
    } else {
        const BodyRec* R = RA ? RA : RB;
        cached = cacheHas(R, RA ? fB : fA, RA ? rc->GetChildIndexB() : rc->GetChildIndexA(), RA ? xfA : xfB,
                          RA ? xfB : xfA, margin, R->relLevel);
    }
    if (!cached) {
        b2DistanceInput in;
        in.proxyA.Set(fA->GetShape(), rc->GetChildIndexA());
        in.proxyB.Set(fB->GetShape(), rc->GetChildIndexB());
        in.transformA = xfA;
        in.transformB = xfB;
        in.useRadii = false;
        b2SimplexCache cache;
        cache.count = 0;
        b2DistanceOutput out;
        b2Distance(&out, &cache, &in);
        const double gap = static_cast<double>(out.distance) - static_cast<double>(fA->GetShape()->m_radius) -
                           static_cast<double>(fB->GetShape()->m_radius);
        // A body with several proxies: another proxy contact of the pair may touch and owe this one a
        // patch of its query (giveUnowned); so the pair's query runs once the bodies' reaches meet.
        const bool several = (RA && RA->proxies.size() > 1) || (RB && RB->proxies.size() > 1);
        const double reach =
            static_cast<double>((bA->GetWorldCenter() - bB->GetWorldCenter()).Length()) - reachA - reachB;
        if (gap > margin && (!several || reach > margin)) {
            ++stats.proxyRejections;
            ++stats.emptyEvaluations;
            return;
        }
    }

    // This proxy pair's patch, in the query's orientation (rough-rough: attach order; rough-primitive:
    // the rough body first).
    uint32_t start = 0, count = 0;
    patchesAt(xfA, xfB, rc, &start, &count);
    // Held by value: a fast pair's second query below appends to `patches`, which may move it.
    for (uint32_t i = 0; i < count; ++i) {
        const Patch& p = patches[start + i];
        if (p.ownerA == ownA && p.ownerB == ownB) {
            carried = p;
            patch = &carried;
            break;
        }
    }
    if (patch == nullptr) {
        ++stats.emptyEvaluations;
        return;
    }
    // The patch's points; for a fast pair with one point, also the point of this proxy pair that would
    // be deepest if B kept turning relative to A about that point for the step, sliding along it (the
    // query at that pose, its material points brought back to these poses): a spinning body, or one
    // set spinning by the impact, hits with another part than the one closest now, and one normal
    // with two points holds both (Box2D's continuous phase would otherwise spend its sub-steps on the
    // first point while the body turns through).
    PatchPoint cand[3];
    int ncand = patch->count;
    const rugo_vec2 pn = patch->n;
    for (int i = 0; i < ncand; ++i)
        cand[i] = patch->p[i];
    if (fast && def.speculative && ncand == 1) {
        const b2Vec2 nAB = flip ? -toB2(pn) : toB2(pn);
        const b2Vec2 pivot = toB2(rugo_v2_scale(0.5, rugo_v2_add(cand[0].pa, cand[0].pb)));
        const float turn = b2Clamp((mB.w - mA.w) * dt, -0.5f * b2_pi, 0.5f * b2_pi);
        const b2Vec2 tangent(-nAB.y, nAB.x);
        const b2Vec2 slide = (dt * b2Dot(mB.v - mA.v, tangent)) * tangent;
        const b2Rot q(turn);
        b2Transform xb2;
        xb2.q = b2Mul(q, xfB.q);
        xb2.p = pivot + b2Mul(q, xfB.p - pivot) + slide;
        uint32_t ps = 0, pc = 0;
        patchesAt(xfA, xb2, nullptr, &ps, &pc);
        for (uint32_t i = 0; i < pc; ++i) {
            const Patch& p = patches[ps + i];
            if (p.ownerA != ownA || p.ownerB != ownB) continue;
            int d = 0;
            for (int k = 1; k < p.count; ++k)
                if (p.p[k].s < p.p[d].s) d = k;
            const PatchPoint& P = p.p[d];
            if (!(P.s < -static_cast<double>(b2_linearSlop))) break;
            PatchPoint now = P;
            now.pa = toRv(b2Mul(xqa, toB2(P.la)));
            now.pb = toRv(b2Mul(xqb, toB2(P.lb)));
            now.s = rugo_v2_dot(rugo_v2_sub(now.pb, now.pa), pn) - P.band;
            now.key = P.key ^ 0x5A5A5A5Au;
            const rugo_vec2 t = rugo_v2_perp(pn);
            const double apart =
                rugo_v2_dot(rugo_v2_sub(rugo_v2_add(now.pa, now.pb), rugo_v2_add(cand[0].pa, cand[0].pb)), t);
            if (std::fabs(0.5 * apart) >= static_cast<double>(b2_linearSlop)) cand[ncand++] = now;
            break;
        }
    }

    // The points in Box2D's orientation (fixture A -> fixture B), and which of them to submit: every
    // touching point; an apart one only if it closes within the step (its approach, with the step's
    // gravity, covers its gap), as a speculative point.
    struct Pt {
        b2Vec2 pA, pB;
        double s, mu, eps, closing, resist;
        uint32_t key;
        PointInfo info;
    };
    Pt pts[2];
    int np = 0;
    const b2Vec2 n = flip ? -toB2(pn) : toB2(pn);
    const float threshold =
        b2MixRestitutionThreshold(fA->GetRestitutionThreshold(), fB->GetRestitutionThreshold());
    bool speculative = false, bouncing = false;
    for (int i = 0; i < ncand && np < 2; ++i) {
        const PatchPoint& q = cand[i];
        Pt p;
        p.pA = toB2(flip ? q.pb : q.pa);
        p.pB = toB2(flip ? q.pa : q.pb);
        p.s = q.s;
        surfaceAt(rc, q, flip, &p.info);
        p.mu = p.info.friction;
        p.eps = p.info.restitution;
        // The rolling-resistance arm of the point: each rough side's band times its body's factor.
        p.resist = (RA ? RA->rollingResistance * p.info.a.lambda : 0.0) +
                   (RB ? RB->rollingResistance * p.info.b.lambda : 0.0);
        p.key = q.key;
        p.closing = approach(mA, p.pA, mB, p.pB, n);
        // A predicted point (i >= patch->count) counts whatever it does now: the impact at the first
        // point may turn the body onto it within the step.
        if (p.s > 0.0) {
            if (!def.speculative || (i < patch->count && (!(p.closing > 0.0) || p.s > p.closing * h)))
                continue;
            // An impact that will bounce (approach beyond the restitution threshold, ε > 0): a
            // speculative point would stop the body at the surface with what it has left of its
            // approach then, below the threshold, and eat the bounce. The point is submitted as a
            // touching one instead, so the solver's restitution turns the body round there, at most
            // the step's approach early.
            const bool bounce = p.eps > 0.0 && p.closing > static_cast<double>(threshold);
            if (!toi && bounce) {
                bouncing = true;
                pts[np++] = p;
                continue;
            }
            if (toi && (fast || bounce)) {
                // A fast pair's time of impact of the proxies where the curves are still apart (the
                // proxy is looser there than Box2D's target). Box2D's continuous phase goes on only once
                // its position solve has moved the proxies back out of its target; a point this deep is
                // pushed back by about half a linear slop there, and its approach is stopped, a gap
                // short of the impact, or it bounces there. The next step's speculative point closes
                // that gap. (A slow pair gets a speculative point: its step cannot carry it past the
                // other body.)
                p.s = -kToiDepth * static_cast<double>(b2_linearSlop);
            } else {
                speculative = true;
                ++stats.speculativePoints;
            }
        }
        pts[np++] = p;
    }
    if (np == 0) {
        ++stats.emptyEvaluations;
        return;
    }

    // The manifold, with the plane on the rough side (DESIGN.md's formulas): GetWorldManifold then
    // returns n and each point's separation exactly (to float precision).
    const float rA = fA->GetShape()->m_radius, rB = fB->GetShape()->m_radius;
    const bool planeOnA = RA != nullptr;
    if (planeOnA) {
        const b2Vec2 pA0 = pts[0].pA;
        m->type = b2Manifold::e_faceA;
        m->localNormal = b2MulT(xfA.q, n);
        m->localPoint = b2MulT(xfA, pA0 - rA * n);
        for (int i = 0; i < np; ++i) {
            const float k = rB + static_cast<float>(pts[i].s) - b2Dot(pts[i].pB - pA0, n);
            m->points[i].localPoint = b2MulT(xfB, pts[i].pB + k * n);
        }
    } else {
        const b2Vec2 pB0 = pts[0].pB;
        m->type = b2Manifold::e_faceB;
        m->localNormal = b2MulT(xfB.q, -n);
        m->localPoint = b2MulT(xfB, pB0 + rB * n);
        for (int i = 0; i < np; ++i) {
            const float k = rA + static_cast<float>(pts[i].s) + b2Dot(pts[i].pA - pB0, n);
            m->points[i].localPoint = b2MulT(xfA, pts[i].pA - k * n);
        }
    }
    m->pointCount = np;
    PointInfo* info = pointInfoOf(rc);
    for (int i = 0; i < np; ++i) {
        info[i] = pts[i].info;
        m->points[i].id.key = pts[i].key;
        m->points[i].normalImpulse = 0.0f; // Box2D copies the old impulses by id after Evaluate
        m->points[i].tangentImpulse = 0.0f;
        if (lastContacts.size() < lastContacts.capacity())
            lastContacts.push_back({0.5f * (pts[i].pA + pts[i].pB), n});
    }
    rc->SetFriction(
        static_cast<float>(np == 2 ? rugo_mix(def.pointFrictionMix, pts[0].mu, pts[1].mu) : pts[0].mu));
    if (speculative && !bouncing) {
        // Box2D 2.4's velocity solver targets vn >= -restitution * vn0 when vn0 < -threshold
        // (b2_contact_solver.cpp, InitializeVelocityConstraints), with one restitution per contact.
        // With threshold 0 and restitution -e, a point approaching at a may approach at e a, i.e. close
        // e a dt within the step: e is the largest value that lets no apart point close more than its
        // gap and no touching point sink more than to Box2D's resting penetration (a linear slop, at
        // least half a slop more).
        double e = kMaxSpeculativeRestitution;
        const double slop = static_cast<double>(b2_linearSlop);
        for (int i = 0; i < np; ++i) {
            if (!(pts[i].closing > 0.0)) continue;
            const double allowance = pts[i].s > 0.0 ? pts[i].s : std::max(pts[i].s + slop, 0.5 * slop);
            e = std::min(e, allowance / (pts[i].closing * h));
        }
        rc->SetRestitution(static_cast<float>(-e));
        rc->SetRestitutionThreshold(0.0f);
    } else {
        rc->SetRestitution(static_cast<float>(np == 2 ? std::min(pts[0].eps, pts[1].eps) : pts[0].eps));
        rc->ResetRestitutionThreshold();
    }
    stats.pointsSubmitted += np;
    if (!toi && lastImpulse > 0.0f)
        rollingResistance(rc, lastImpulse, 0.5 * (pts[0].resist + pts[np - 1].resist));
}

// The surfaces at a patch point (query orientation: A is rough; B rough or the contact's ordinary
// fixture), in the contact's orientation (fixture A's side, fixture B's side), and the point's μ and ε
// by the BridgeDef rule of the pair (docs/box2d.md, "Friction and restitution").
void Bridge::Impl::surfaceAt(const RoughContact* rc, const PatchPoint& q, bool flip, PointInfo* out) const {
    const BodyRec* qa = flip ? rc->recB : rc->recA; // the query's A: always rough
    const BodyRec* qb = flip ? rc->recA : rc->recB; // nullptr: an ordinary fixture
    SurfacePoint sa, sb;
    sa.rough = true;
    sa.segment = q.segA;
    sa.level = q.levelA;
    sa.t = static_cast<double>(q.tA);
    sa.lambda = q.lamA;
    sa.friction = rugo_friction(&qa->data->friction, q.lamA);
    sa.restitution = qa->data->restitution.epsilon;
    if (qb != nullptr) {
        sb.rough = true;
        sb.segment = q.segB;
        sb.level = q.levelB;
        sb.t = static_cast<double>(q.tB);
        sb.lambda = q.lamB;
        sb.friction = rugo_friction(&qb->data->friction, q.lamB);
        sb.restitution = qb->data->restitution.epsilon;
        out->friction = rugo_mix(def.roughFrictionMix, sa.friction, sb.friction);
        out->restitution = rugo_mix(def.roughRestitutionMix, sa.restitution, sb.restitution);
    } else {
        const b2Fixture* f = flip ? rc->GetFixtureA() : rc->GetFixtureB();
        sb.friction = static_cast<double>(f->GetFriction());
        sb.restitution = static_cast<double>(f->GetRestitution());
        out->friction = rugo_mix(def.fixtureFrictionMix, sa.friction, sb.friction);
        out->restitution = rugo_mix(def.fixtureRestitutionMix, sa.restitution, sb.restitution);
    }
    out->a = flip ? sb : sa;
    out->b = flip ? sa : sb;
}

// Rolling resistance from roughness (docs/roughness.md, "Rolling resistance"): a rough surface resists
// rolling in proportion to its band. The contact resists the two bodies' relative turning with a
// torque of its normal force times the arm k_A λ_A + k_B λ_B at its points (RoughBodyDef::
// rollingResistance), applied as an angular impulse before the solve from the last solve's normal
// impulse, never more than stops the relative turning. A smooth body (no band) rolls freely; a rough
// one settles instead of rocking on its asperities for ever (Box2D's solver has no rolling friction,
// and rolling on curved asperities does no work against its contact constraints).
void Bridge::Impl::rollingResistance(RoughContact* rc, float impulse, double arm) {
    if (!(arm > 0.0)) return;
    b2Body* a = rc->GetFixtureA()->GetBody();
    b2Body* b = rc->GetFixtureB()->GetBody();
    auto invInertia = [](const b2Body* body) {
        if (body->GetType() != b2_dynamicBody) return 0.0;
        const b2Vec2 lc = body->GetLocalCenter();
        const double ic = static_cast<double>(body->GetInertia()) -
                          static_cast<double>(body->GetMass()) * static_cast<double>(b2Dot(lc, lc));
        return ic > 0.0 ? 1.0 / ic : 0.0;
    };
    const double ia = invInertia(a), ib = invInertia(b);
    if (ia + ib <= 0.0) return;
    const double rel =
        static_cast<double>(b->GetAngularVelocity()) - static_cast<double>(a->GetAngularVelocity());
    if (rel == 0.0) return;
    const double j =
        std::min(static_cast<double>(impulse) * arm, std::fabs(rel) / (ia + ib)) * (rel > 0.0 ? 1.0 : -1.0);
    // As impulses that leave the bodies' sleep alone: SetAngularVelocity wakes a body and restarts its
    // sleep timer, and a contact evaluated every step would then keep its bodies awake for ever.
    if (ia > 0.0) a->ApplyAngularImpulse(static_cast<float>(j), false);
    if (ib > 0.0) b->ApplyAngularImpulse(static_cast<float>(-j), false);
}

} // namespace rugo
