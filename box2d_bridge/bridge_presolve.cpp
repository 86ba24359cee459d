// The bridge's PreSolve: the proxy pair's librugo contacts (and joint points) become Box2D's manifold,
// with the friction and restitution of the surfaces at the points and the speculative-contact rules of
// the TOI phase (docs/box2d.md).
#include "bridge_impl.hpp"

#include <algorithm>
#include <cmath>

namespace rugo {

void Bridge::Impl::PreSolve(b2Contact* c, const b2Manifold* old) {
    if (rechained(kPre, c)) return;
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
            chain(kPre, c, [&] { prevListener->PreSolve(c, old); });
            return;
        }
        cand.clear();
        joints.clear();
        apart.clear();
        regions.clear();
        if (ra && rb)
            gatherRough(ra, rb);
        else
            gatherPrimitive(ra ? ra : rb, ra != nullptr, ra ? fb : fa,
                            ra ? c->GetChildIndexB() : c->GetChildIndexA());
        ncand = cand.size();
        {
            const b2Body* b1 = fa->GetBody();
            const b2Body* b2 = fb->GetBody();
            const double turn =
                std::fabs(static_cast<double>(b1->GetAngularVelocity() - b2->GetAngularVelocity())) *
                static_cast<double>(dt);
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
                jointsVsPrimitive(ra ? ra : rb, ra != nullptr, ra ? fb : fa,
                                  ra ? c->GetChildIndexB() : c->GetChildIndexA(), dropEndFlag);
            }
            // Joints only add points to a contact region librugo reported (in this or another proxy
            // pair), with that region's normal; see attachJoint.
            for (BPoint& j : joints)
                if (attachJoint(&j)) cand.push_back(j);
        }
        write(c, old, ra != nullptr, ra ? ra->rec->body : fa->GetBody(), rb ? rb->rec->body : fb->GetBody());
    }
    chain(kPre, c, [&] { prevListener->PreSolve(c, old); });
}

bool Bridge::Impl::atCollidePoses(const ProxyRef* ra, const ProxyRef* rb, b2Fixture* fa, b2Fixture* fb,
                                  b2Contact* c) const {
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
    return seenInCollide(r->rec, other, child, r->rec->body->GetTransform(),
                         other->GetBody()->GetTransform());
}

void Bridge::Impl::gatherRough(const ProxyRef* ra, const ProxyRef* rb) {
    BodyRec* A = ra->rec;
    BodyRec* B = rb->rec;
    const bool swap = B->serial < A->serial; // query in attach order (deterministic)
    BodyRec* QA = swap ? B : A;
    BodyRec* QB = swap ? A : B;
    const b2Transform& xa = QA->body->GetTransform();
    const b2Transform& xb = QB->body->GetTransform();
    const int level = std::max(QA->relLevel, QB->relLevel);
    const double margin = def.speculative ? speedBound(QA->body, roughReach(QA), QB->body, roughReach(QB)) *
                                                static_cast<double>(dt)
                                          : 0.0;
    curMargin = margin;
    curReach = std::max(roughReach(QA), roughReach(QB));
    uint32_t start = 0, count = 0;
    const rugo_transform ta = toRugo(xa), tb = toRugo(xb);
    cachedQuery(
        QA, QB, -1, xa, xb, margin, level,
        [&](rugo_contact* out, int cap, int* n, rugo_query_stats* qs) {
            rugo_contact_query q = legacyQuery();
            q.lod = level;
            q.margin = margin;
            rugo_contact_output o = rugo_contact_output_of(out, cap);
            const rugo_status st = rugo_collide_shapes(QA->shape, ta, QB->shape, tb, &q, ctx, &o);
            *n = o.count;
            *qs = o.stats;
            return st;
        },
        &start, &count);
    for (uint32_t i = 0; i < count; ++i) {
        const rugo_contact& k = pool[start + i];
        const int na =
            ownerNode(swap ? k.segment_b : k.segment_a, swap ? k.level_b : k.level_a, A->proxyLevel);
        const int nb =
            ownerNode(swap ? k.segment_a : k.segment_b, swap ? k.level_a : k.level_b, B->proxyLevel);
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

void Bridge::Impl::gatherPrimitive(const ProxyRef* r, bool roughIsA, b2Fixture* other, int child) {
    BodyRec* R = r->rec;
    const b2Shape* sh = other->GetShape();
    const b2Body* ob = other->GetBody();
    const b2Transform& xr = R->body->GetTransform();
    const b2Transform& xo = ob->GetTransform();
    const int level = R->relLevel;
    const double margin =
        def.speculative
            ? speedBound(R->body, roughReach(R), ob, fixtureReach(other, child)) * static_cast<double>(dt)
            : 0.0;
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
        oneSided = es.m_oneSided ? makeOneSided(es, xo, false, false)
                                 : makeTwoSided(es, xo, R->body->GetWorldCenter());
    }
    // Box2D skips a one-sided edge when the other body's centroid is behind it.
    if (oneSided.on && b2Dot(oneSided.n1, R->body->GetWorldCenter() - oneSided.v1) < 0.0f) return;
    uint32_t start = 0, count = 0;
    cachedQuery(
        R, other, child, xr, xo, margin, level,
        [&](rugo_contact* out, int cap, int* n, rugo_query_stats* qs) -> rugo_status {
            rugo_contact_query q = legacyQuery();
            q.lod = level;
            q.margin = margin;
            rugo_primitive p = rugo_make_circle(rugo_v2(0.0, 0.0), 0.0);
            switch (sh->GetType()) {
            case b2Shape::e_circle: {
                const b2CircleShape* cs = static_cast<const b2CircleShape*>(sh);
                p = rugo_make_circle(toRv(cs->m_p), static_cast<double>(cs->m_radius));
                break;
            }
            case b2Shape::e_polygon: {
                const b2PolygonShape* ps = static_cast<const b2PolygonShape*>(sh);
                p.count = ps->m_count;
                p.radius = static_cast<double>(ps->m_radius);
                for (int i = 0; i < ps->m_count; ++i)
                    p.points[i] = toRv(ps->m_vertices[i]);
                break;
            }
            case b2Shape::e_edge:
            case b2Shape::e_chain: {
                const b2EdgeShape* es =
                    sh->GetType() == b2Shape::e_edge ? static_cast<const b2EdgeShape*>(sh) : &edge;
                p = rugo_make_capsule(toRv(es->m_vertex1), toRv(es->m_vertex2), static_cast<double>(es->m_radius));
                break;
            }
            default:
                *n = 0;
                return RUGO_ERR_BAD_ARGUMENT;
            }
            rugo_contact_output o = rugo_contact_output_of(out, cap);
            const rugo_status st = rugo_collide_primitive(R->shape, tr, &p, to, &q, ctx, &o);
            *n = o.count;
            *qs = o.stats;
            return st;
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
        p.mu = std::max(k.friction, mu);      // thesis 7.2: max for friction
        p.eps = std::min(k.restitution, eps); // and min for restitution
        p.key = hashId(k.id ^ (static_cast<uint64_t>(static_cast<uint32_t>(child)) << 40));
        p.m = p.n;
        regions.push_back(p); // a region for joints (attachJoint), whichever pair reports it
        if (keep) cand.push_back(p);
    }
}

void Bridge::Impl::disable(b2Contact* c) {
    c->GetManifold()->pointCount = 0;
    c->SetEnabled(false);
    ++stats.disabledContacts;
}

void Bridge::Impl::write(b2Contact* c, const b2Manifold* old, bool roughIsA, const b2Body* bA,
                         const b2Body* bB) {
    // Touching points first: the deepest librugo contact fixes the normal; the second point is the
    // farthest touching one (another librugo contact, or a joint of a flat piece: its own normal
    // within ~2.6° of the first, else it is no flat contact and would only resist rolling).
    int deepest = -1;
    for (int pass = 0; pass < 2 && deepest < 0; ++pass) // librugo's points first, then joints
        for (int i = pass == 0 ? 0 : static_cast<int>(ncand);
             i < static_cast<int>(pass == 0 ? ncand : cand.size()); ++i)
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
            if ((i >= static_cast<int>(ncand) || deepest >= static_cast<int>(ncand)) &&
                b2Dot(p.m, pts[0].n) < 0.999f)
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
        const double wA = static_cast<double>(bA->GetAngularVelocity()),
                     wB = static_cast<double>(bB->GetAngularVelocity());
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
                               (wA * wA * static_cast<double>((p.pA - cA).Length()) +
                                wB * wB * static_cast<double>((p.pB - cB).Length()));
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
            if (lastContacts.size() < lastContacts.capacity() || lastContacts.size() < 4096)
                lastContacts.push_back(dc);
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

} // namespace rugo
