// Joint points: Box2D-like second points on flat contacts. librugo reports one contact per local
// minimum or overlap region; a slightly tilted flat face has one minimum (its lower end), so a block
// would rock on one point. Like Box2D's clipping, the joints (t = 0) of the owned segments that also
// touch (band-adjusted separation <= 0) are offered as manifold points; the reduction keeps the
// deepest and the farthest (write, bridge_presolve.cpp).
#include "bridge_impl.hpp"

#include <algorithm>
#include <cmath>

namespace rugo {

// Distance from p to box b (0 inside), in the box's frame.
double Bridge::Impl::obbDistance(const rugo_obb* b, rugo_vec2 p) {
    const rugo_vec2 d = rugo_v2_sub(p, b->center);
    const double u = std::max(std::fabs(rugo_v2_dot(d, b->axis[0])) - b->half[0], 0.0);
    const double v = std::max(std::fabs(rugo_v2_dot(d, b->axis[1])) - b->half[1], 0.0);
    return std::hypot(u, v);
}

// Signed distance from world point p to an ordinary fixture's boundary (core grown by m_radius),
// closest boundary point in *q. Returns false for unsupported shapes.
bool Bridge::Impl::primitiveDistance(const b2Fixture* f, int child, b2Vec2 p, double* sd, b2Vec2* q,
                                     double* tEdge) {
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
template <class F> void Bridge::Impl::forJoints(const BodyRec* r, int node, int L, bool withEnd, F&& fn) {
    rugo_contour curve;
    rugo_tolerance_level tl;
    if (rugo_shape_level(r->shape, L, &curve) != RUGO_OK ||
        rugo_shape_tolerance_level(r->shape, L, &tl) != RUGO_OK)
        return;
    const int per = 1 << (L - r->proxyLevel);
    const rugo_transform x = toRugo(r->body->GetTransform());
    const int last = (node + 1) * per + (withEnd ? 1 : 0);
    for (int k = node * per; k < last; ++k) {
        const int kk = k % curve.count;
        const rugo_vec2 pl = rugo_contour_point(curve, kk, 0.0);
        const auto normal = [&curve, &x, kk]() {
            return toB2(rugo_rotate(x.q, rugo_contour_normal(curve, kk, 0.0)));
        };
        fn(k, toB2(rugo_transform_point(x, pl)), rugo_tolerance_at(tl.total, tl.count, kk, 0.0, 0.0), normal);
    }
}

void Bridge::Impl::jointsVsPrimitive(const ProxyRef* r, bool roughIsA, const b2Fixture* other, int child,
                                     bool dropEnd) {
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
                pushJoint(roughIsA ? p : q, roughIsA ? q : p, sd < 0.0, roughIsA ? out() : -out(), s,
                          other->GetFriction(), other->GetRestitution(), R, k, 0x1000000u, &apart);
            return;
        }
        const size_t before = joints.size();
        pushJoint(roughIsA ? p : q, roughIsA ? q : p, sd < 0.0, roughIsA ? out() : -out(), s,
                  other->GetFriction(), other->GetRestitution(), R, k, 0x1000000u, &joints);
        const b2Shape::Type ty = other->GetShape()->GetType();
        if (joints.size() > before && (ty == b2Shape::e_edge || ty == b2Shape::e_chain) && tEdge > 0.0 &&
            tEdge < 1.0)
            joints.back().edgeFace = true;
    });
}

void Bridge::Impl::jointsVsRough(const ProxyRef* self, const ProxyRef* oth, bool selfIsA, int pairRel) {
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
    const double reachO = (fastPair ? std::max(curMargin, 0.0) : 0.0) +
                          O->bandMax[static_cast<size_t>(LO - rugo_shape_coarsest_level(O->shape))];
    forJoints(S, self->node, LS, fastPair, [&](int k, b2Vec2 p, double lam, const auto& out) {
        const rugo_vec2 pl = rugo_inv_transform_point(xo, toRv(p));
        if (known == nullptr) unkept = JointInfo();
        JointInfo& ji = known ? known[k - firstK] : unkept;
        // Whether the joint is inside O (level LO's curve, through the tree), computed once.
        const auto isInside = [&]() {
            if (ji.inside < 0) {
                bool in = false;
                rugo_shape_contains(O->shape, LO, pl, &in);
                ji.inside = in ? 1 : 0;
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
        pushJoint(selfIsA ? p : q, selfIsA ? q : p, inside, selfIsA ? out() : -out(), s,
                  static_cast<float>(mu), static_cast<float>(std::min(eS.epsilon, eO.epsilon)), S, k,
                  selfIsA ? 0x2000000u : 0x3000000u, isApart ? &apart : &joints);
    });
}

// A joint point: pa on A's side, pb on B's; `inside`: the rough joint is inside the other body.
void Bridge::Impl::pushJoint(b2Vec2 pa, b2Vec2 pb, bool inside, b2Vec2 surfaceNormal, double s, float mu,
                             float eps, const BodyRec* R, int k, uint32 tag, std::vector<BPoint>* out) {
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
    bp.key = hashId((static_cast<uint64_t>(tag) << 32) ^ (static_cast<uint64_t>(R->serial) << 20) ^
                    static_cast<uint64_t>(k));
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
bool Bridge::Impl::attachJoint(BPoint* j) const {
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

} // namespace rugo
