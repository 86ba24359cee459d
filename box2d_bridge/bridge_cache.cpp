// The bridge's per-step cache of patches: every proxy contact of a body pair (and Box2D's continuous
// phase at the same poses) shares one librugo query, found by the bodies (or the body, fixture and
// child), the float poses, the margin and the level.
#include "bridge_impl.hpp"

#include <algorithm>
#include <cstring>

namespace rugo {

// Room for the per-step caches of n rough bodies, reserved when a body is attached so that steps do
// not allocate once librugo's query context has grown: per body 8 cached queries (at most half the
// table used) and 16 patches.
void Bridge::Impl::reserveFor(size_t n) {
    size_t want = table.size();
    while (want < 16 * n && want < 65536)
        want *= 2;
    if (want != table.size()) {
        table.assign(want, CacheEntry());
        ++gen;
        used = 0;
        patches.clear();
    }
    pairCaches.reserve(kPairCachesPerBody * n); // short of memory: the pairs beyond search every step
    patches.reserve(16 * n);
    patchScratch.reserve(scratch.size());
    lastContacts.reserve(std::max<size_t>(4096, 8 * n));
}

size_t Bridge::Impl::cacheSlot(const void* a, const void* b, int child, const float* xf, double margin,
                               int level, bool* found) {
    if (used * 2 >= table.size()) {
        if (table.size() < 65536) table.assign(table.size() * 2, CacheEntry());
        patches.clear();
        ++gen;
        used = 0;
    }
    if (patches.size() > (1u << 20)) {
        patches.clear();
        ++gen;
        used = 0;
    }
    const size_t mask = table.size() - 1;
    size_t i = static_cast<size_t>(cacheHash(a, b, child, xf)) & mask;
    for (;; i = (i + 1) & mask) {
        const CacheEntry& e = table[i];
        if (e.gen != gen) break;
        if (e.a == a && e.b == b && e.child == child && e.margin == margin && e.level == level &&
            std::memcmp(e.xf, xf, sizeof e.xf) == 0) {
            *found = true;
            return i;
        }
    }
    *found = false;
    return i;
}

void Bridge::Impl::cacheFill(size_t slot, const void* a, const void* b, int child, const float* xf,
                             double margin, int level, uint32_t start) {
    CacheEntry& e = table[slot];
    e.gen = gen;
    e.a = a;
    e.b = b;
    e.child = child;
    std::memcpy(e.xf, xf, sizeof e.xf);
    e.margin = margin;
    e.level = level;
    e.start = start;
    e.count = static_cast<uint32_t>(patches.size() - start);
    ++used;
}

// Has the query of (a, b, child) at these poses, margin and level run in this step? (No change.)
bool Bridge::Impl::cacheHas(const void* a, const void* b, int child, const b2Transform& xa,
                            const b2Transform& xb, double margin, int level) const {
    const float xf[8] = {xa.p.x, xa.p.y, xa.q.c, xa.q.s, xb.p.x, xb.p.y, xb.q.c, xb.q.s};
    const size_t mask = table.size() - 1;
    for (size_t i = static_cast<size_t>(cacheHash(a, b, child, xf)) & mask;; i = (i + 1) & mask) {
        const CacheEntry& e = table[i];
        if (e.gen != gen) return false;
        if (e.a == a && e.b == b && e.child == child && e.margin == margin && e.level == level &&
            std::memcmp(e.xf, xf, sizeof e.xf) == 0)
            return true;
    }
}

uint64_t Bridge::Impl::cacheHash(const void* a, const void* b, int child, const float* xf) {
    uint64_t h = mixHash(reinterpret_cast<uintptr_t>(a), reinterpret_cast<uintptr_t>(b));
    h = mixHash(h, static_cast<uint64_t>(child));
    for (int k = 0; k < 8; ++k)
        h = mixHash(h, floatBits(xf[k]));
    return h;
}

} // namespace rugo
