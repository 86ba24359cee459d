// The bridge's per-step query cache: every proxy pair of a body pair (and Box2D's TOI phase at the
// same poses) shares one librugo query, found by the bodies, the child and the float poses.
#include "bridge_impl.hpp"

#include <algorithm>
#include <cstring>

namespace rugo {

// Room for the per-step caches of n rough bodies, reserved when a body is attached so that steps
// do not allocate once librugo's query context has grown (docs/box2d.md): per body 8 cached
// queries (at most half the table used), 16 contacts and the joints of 8 proxy pieces (piece of
// `per` joints). About 4 kB per body plus 0.4 kB per joint of a piece (table rounded up to a
// power of two). The point lists of one proxy pair hold the joints of both sides' pieces (at most
// perFinest + 1 each: a pair's level is at most the finest) and the query's contacts.
void Bridge::Impl::reserveFor(size_t n, int per, int perFinest) {
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
    pointReserve = std::max(pointReserve, 2 * (static_cast<size_t>(perFinest) + 1));
    reservePoints();
}

// The point lists of one proxy pair: the joints of two pieces, and the contacts of a query (at most
// the scratch buffer's size) with those joints.
void Bridge::Impl::reservePoints() {
    joints.reserve(pointReserve);
    apart.reserve(pointReserve);
    cand.reserve(scratch.size() + pointReserve);
    regions.reserve(scratch.size());
}

// Runs (or finds) one librugo query; returns the contacts as [start, start+count) of pool. (run is a
// QueryRun, not a std::function: a capturing lambda in a std::function may allocate per query.)
bool Bridge::Impl::cachedQuery(const void* a, const void* b, int child, const b2Transform& xa,
                               const b2Transform& xb, double margin, int level, QueryRun run, uint32_t* start,
                               uint32_t* count) {
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
        reservePoints();                                            // now, not in a later step's PreSolve
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

uint64_t Bridge::Impl::cacheHash(const void* a, const void* b, int child, const float* xf) {
    uint64_t h = mixHash(reinterpret_cast<uintptr_t>(a), reinterpret_cast<uintptr_t>(b));
    h = mixHash(h, static_cast<uint64_t>(child));
    for (int k = 0; k < 8; ++k)
        h = mixHash(h, floatBits(xf[k]));
    return h;
}

// Was this pair queried in this step's collide phase at exactly these poses? (Box2D's TOI phase
// then handles an event at the step's start, alpha = 0.)
bool Bridge::Impl::seenInCollide(const void* a, const void* b, int child, const b2Transform& xa,
                                 const b2Transform& xb) const {
    const float xf[8] = {xa.p.x, xa.p.y, xa.q.c, xa.q.s, xb.p.x, xb.p.y, xb.q.c, xb.q.s};
    const size_t mask = table.size() - 1;
    for (size_t i = static_cast<size_t>(cacheHash(a, b, child, xf)) & mask;; i = (i + 1) & mask) {
        const CacheEntry& e = table[i];
        if (e.gen != gen) return false;
        if (!e.toi && e.a == a && e.b == b && e.child == child && std::memcmp(e.xf, xf, sizeof xf) == 0)
            return true;
    }
}

} // namespace rugo
