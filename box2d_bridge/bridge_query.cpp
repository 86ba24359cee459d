// Every call of the bridge into librugo's contact query API (collide.h), and the conversion of its
// contacts into the bridge's QContact. librugo's query API is changing (a resolution, contact patches,
// a warm-start cache per body pair, one output struct): keeping its calls here makes that a change of
// this file only.
#include "bridge_impl.hpp"

#include <new>
#include <vector>

namespace rugo {
namespace detail {

// librugo's context and a buffer of its contacts (rugo_contact stays inside this file).
struct QueryEngine {
    rugo_collide_context* ctx = nullptr;
    std::vector<rugo_contact> buf;
};

namespace {

rugo_contact_query makeQuery(const QueryParams& p) {
    rugo_contact_query q = rugo_default_contact_query();
    q.lod = p.level;
    q.margin = p.margin;
    // At minima of the curves' distance (the thesis' rule); round-off answers unless the bridge gives a
    // resolution (BridgeDef::queryResolution).
    q.resolution = p.resolution > 0.0 ? p.resolution : 0.0;
    q.contact_rule = RUGO_CONTACT_THESIS;
    return q;
}

QContact convert(const rugo_contact& k) {
    QContact q;
    q.pa = k.point_a;
    q.pb = k.point_b;
    q.n = k.normal;
    q.sep = k.separation;
    q.tolA = k.tolerance_a;
    q.tolB = k.tolerance_b;
    q.segA = k.segment_a;
    q.segB = k.segment_b;
    q.tA = k.t_a;
    q.tB = k.t_b;
    q.levelA = k.level_a;
    q.levelB = k.level_b;
    q.mu = k.friction;
    q.eps = k.restitution;
    q.region = k.region;
    q.id = k.id;
    q.seed = false;
    return q;
}

// Runs `call` (librugo contacts into an output over the engine's buffer, at most cap) and converts
// them. The buffer is sized by queryEngineReserve; a larger cap grows it (a warm-up, as librugo's own
// context).
template <class F>
rugo_status run(QueryEngine* e, F&& call, QContact* out, int cap, int* n, int* found, BridgeStats* qs) {
    if (static_cast<int>(e->buf.size()) < cap) e->buf.resize(static_cast<size_t>(cap));
    rugo_contact_output o = rugo_contact_output_of(e->buf.data(), cap);
    const rugo_status st = call(&o);
    *found = st == RUGO_OK ? o.stats.contacts_found : 0;
    const int count = st == RUGO_OK ? o.count : 0;
    if (qs != nullptr) {
        qs->boxTests += o.stats.box_tests;
        qs->segmentPairs += o.stats.segment_pairs;
        qs->fallbacks += o.stats.fallbacks;
    }
    for (int i = 0; i < count; ++i)
        out[i] = convert(e->buf[static_cast<size_t>(i)]);
    *n = count;
    return st;
}

} // namespace

QueryEngine* queryEngineCreate() {
    QueryEngine* e = new (std::nothrow) QueryEngine;
    if (e == nullptr) return nullptr;
    if (rugo_collide_context_create(nullptr, &e->ctx) != RUGO_OK) {
        delete e;
        return nullptr;
    }
    return e;
}

void queryEngineDestroy(QueryEngine* e) {
    if (e == nullptr) return;
    rugo_collide_context_destroy(e->ctx);
    delete e;
}

rugo_status queryEngineReserve(QueryEngine* e, const rugo_shape* shape, int contacts) {
    try {
        if (static_cast<int>(e->buf.size()) < contacts) e->buf.resize(static_cast<size_t>(contacts));
    } catch (const std::bad_alloc&) {
        return RUGO_ERR_OUT_OF_MEMORY;
    }
    return rugo_collide_context_reserve(e->ctx, shape, contacts);
}

rugo_status queryShapes(QueryEngine* e, const rugo_shape* a, const rugo_transform& xa, const rugo_shape* b,
                        const rugo_transform& xb, const QueryParams& p, QContact* out, int cap, int* n,
                        int* found, BridgeStats* qs) {
    const rugo_contact_query q = makeQuery(p);
    return run(
        e, [&](rugo_contact_output* o) { return rugo_collide_shapes(a, xa, b, xb, &q, e->ctx, o); }, out, cap,
        n, found, qs);
}

rugo_status queryPrimitive(QueryEngine* e, const rugo_shape* a, const rugo_transform& xa,
                           const PatchSide& prim, const QueryParams& p, QContact* out, int cap, int* n,
                           int* found, BridgeStats* qs) {
    const rugo_contact_query q = makeQuery(p);
    // The primitive in world coordinates (PatchSide's), so with the identity transform.
    rugo_primitive pr = rugo_make_circle(toRv(prim.v[0]), static_cast<double>(prim.radius));
    switch (prim.type) {
    case b2Shape::e_circle:
        break;
    case b2Shape::e_edge:
    case b2Shape::e_chain:
        pr = rugo_make_capsule(toRv(prim.v[0]), toRv(prim.v[1]), static_cast<double>(prim.radius));
        break;
    case b2Shape::e_polygon:
        pr.count = prim.n;
        for (int i = 0; i < prim.n; ++i)
            pr.points[i] = toRv(prim.v[i]);
        break;
    default:
        *n = 0;
        *found = 0;
        return RUGO_ERR_BAD_ARGUMENT;
    }
    return run(
        e,
        [&](rugo_contact_output* o) {
            return rugo_collide_primitive(a, xa, &pr, rugo_identity_transform(), &q, e->ctx, o);
        },
        out, cap, n, found, qs);
}

bool queryOverlapsPolygon(QueryEngine* e, const rugo_shape* s, const rugo_transform& x, int level,
                          const rugo_vec2* v, int count) {
    QueryParams p;
    p.level = level;
    const rugo_contact_query q = makeQuery(p);
    rugo_primitive pr = rugo_make_circle(v[0], 0.0);
    if (count > 1) {
        pr.count = count;
        for (int i = 0; i < count; ++i)
            pr.points[i] = v[i];
    }
    rugo_contact_output o = rugo_contact_output_of(nullptr, 0); // the state only
    const rugo_status st = rugo_collide_primitive(s, x, &pr, rugo_identity_transform(), &q, e->ctx, &o);
    return st == RUGO_OK && o.state != RUGO_STATE_APART;
}

} // namespace detail
} // namespace rugo
