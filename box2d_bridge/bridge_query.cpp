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
    q.level = p.level;
    q.margin = p.margin;
    // p.resolution: today's queries answer to round-off; the resolution-aware query takes the budget.
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

// Runs `call` (librugo contacts into the engine's buffer, at most cap) and converts them. The buffer
// is sized by queryEngineReserve; a larger cap grows it (a warm-up, as librugo's own context).
template <class F>
rugo_status run(QueryEngine* e, F&& call, QContact* out, int cap, int* n, int* found, BridgeStats* qs) {
    if (static_cast<int>(e->buf.size()) < cap) e->buf.resize(static_cast<size_t>(cap));
    rugo_query_stats s;
    int count = 0;
    rugo_contact_state state;
    const rugo_status st = call(e->buf.data(), cap, &count, &state, &s);
    *found = st == RUGO_OK ? s.contacts_found : 0;
    if (st != RUGO_OK) count = 0;
    if (qs != nullptr) {
        qs->boxTests += s.box_tests;
        qs->segmentPairs += s.segment_pairs;
        qs->fallbacks += s.fallbacks;
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
        e,
        [&](rugo_contact* buf, int c, int* count, rugo_contact_state* state, rugo_query_stats* s) {
            return rugo_collide_shapes(e->ctx, a, xa, b, xb, &q, buf, c, count, state, s);
        },
        out, cap, n, found, qs);
}

rugo_status queryPrimitive(QueryEngine* e, const rugo_shape* a, const rugo_transform& xa,
                           const PatchSide& prim, const QueryParams& p, QContact* out, int cap, int* n,
                           int* found, BridgeStats* qs) {
    const rugo_contact_query q = makeQuery(p);
    return run(
        e,
        [&](rugo_contact* buf, int c, int* count, rugo_contact_state* state,
            rugo_query_stats* s) -> rugo_status {
            const double r = static_cast<double>(prim.radius);
            switch (prim.type) {
            case b2Shape::e_circle:
                return rugo_collide_circle(e->ctx, a, xa, toRv(prim.v[0]), r, &q, buf, c, count, state, s);
            case b2Shape::e_edge:
            case b2Shape::e_chain:
                return rugo_collide_segment(e->ctx, a, xa, toRv(prim.v[0]), toRv(prim.v[1]), r, &q, buf, c,
                                            count, state, s);
            case b2Shape::e_polygon: {
                rugo_vec2 v[b2_maxPolygonVertices];
                for (int i = 0; i < prim.n; ++i)
                    v[i] = toRv(prim.v[i]);
                return rugo_collide_polygon(e->ctx, a, xa, v, prim.n, r, &q, buf, c, count, state, s);
            }
            default:
                *count = 0;
                return RUGO_ERR_BAD_ARGUMENT;
            }
        },
        out, cap, n, found, qs);
}

bool queryOverlapsPolygon(QueryEngine* e, const rugo_shape* s, const rugo_transform& x, int level,
                          const rugo_vec2* v, int count) {
    rugo_contact_query q = rugo_default_contact_query();
    q.level = level;
    int n = 0;
    rugo_contact_state state = RUGO_STATE_APART;
    const rugo_status st =
        count == 1 ? rugo_collide_circle(e->ctx, s, x, v[0], 0.0, &q, nullptr, 0, &n, &state, nullptr)
                   : rugo_collide_polygon(e->ctx, s, x, v, count, 0.0, &q, nullptr, 0, &n, &state, nullptr);
    return st == RUGO_OK && state != RUGO_STATE_APART;
}

} // namespace detail
} // namespace rugo
