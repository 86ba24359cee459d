// The answers kept from step to step (BridgeDef::reuseDistance): one slot per rough body pair or rough
// body and ordinary fixture child, holding its last search's contacts, so that a pair at rest or creeping
// is searched again only once it has moved by the reuse distance (docs/box2d.md, "Kept answers").
#include "bridge_impl.hpp"

#include <algorithm>
#include <cmath>
#include <new>

namespace rugo {
namespace detail {

namespace {

uint64_t pairHash(int serialA, int serialB, const b2Fixture* fixture, int child) {
    uint64_t h = mixHash(static_cast<uint64_t>(static_cast<uint32_t>(serialA)),
                         static_cast<uint64_t>(static_cast<uint32_t>(serialB)));
    h = mixHash(h, reinterpret_cast<uintptr_t>(fixture));
    h = mixHash(h, static_cast<uint64_t>(static_cast<uint32_t>(child)));
    return hashId(h);
}

bool holds(const PairCache& c, int serialA, int serialB, const b2Fixture* fixture, int child) {
    return c.serialA == serialA && c.serialB == serialB && c.fixture == fixture && c.child == child;
}

} // namespace

bool PairCaches::reserve(size_t count) {
    if (count <= slots_.size()) return true;
    try {
        size_t buckets = std::max<size_t>(index_.size(), 16);
        while (buckets < 2 * count)
            buckets *= 2;
        slots_.reserve(count);
        free_.reserve(count);
        index_.reserve(buckets);
        while (slots_.size() < count) {
            free_.push_back(static_cast<int>(slots_.size()));
            slots_.emplace_back();
        }
        if (buckets != index_.size()) {
            index_.assign(buckets, -1);
            for (size_t i = 0; i < slots_.size(); ++i)
                if (slots_[i].serialA >= 0)
                    index_[at(slots_[i].serialA, slots_[i].serialB, slots_[i].fixture, slots_[i].child)] =
                        static_cast<int>(i);
        }
    } catch (const std::bad_alloc&) {
        return false;
    }
    return slots_.size() >= count;
}

// The bucket holding the pair, or the empty bucket where it would go.
size_t PairCaches::at(int serialA, int serialB, const b2Fixture* fixture, int child) const {
    const size_t mask = index_.size() - 1;
    size_t i = static_cast<size_t>(pairHash(serialA, serialB, fixture, child)) & mask;
    while (index_[i] >= 0 && !holds(slots_[static_cast<size_t>(index_[i])], serialA, serialB, fixture, child))
        i = (i + 1) & mask;
    return i;
}

// Takes back the slots of pairs not queried in this step or the last, and rebuilds the index.
void PairCaches::sweep(uint64_t step) {
    std::fill(index_.begin(), index_.end(), -1);
    free_.clear();
    for (size_t i = 0; i < slots_.size(); ++i) {
        PairCache& c = slots_[i];
        if (c.serialA >= 0 && c.lastUsed + 1 >= step) {
            index_[at(c.serialA, c.serialB, c.fixture, c.child)] = static_cast<int>(i);
        } else {
            c.serialA = -1;
            free_.push_back(static_cast<int>(i));
        }
    }
    // Lowest slots last: they are taken first (the order is deterministic either way).
    std::reverse(free_.begin(), free_.end());
}

PairCache* PairCaches::find(int serialA, int serialB, const b2Fixture* fixture, int child, uint64_t step) {
    if (slots_.empty()) return nullptr;
    size_t b = at(serialA, serialB, fixture, child);
    if (index_[b] < 0) {
        if (free_.empty()) {
            sweep(step);
            if (free_.empty()) return nullptr;
            b = at(serialA, serialB, fixture, child);
        }
        const int s = free_.back();
        free_.pop_back();
        PairCache& c = slots_[static_cast<size_t>(s)];
        c.serialA = serialA;
        c.serialB = serialB;
        c.fixture = fixture;
        c.child = child;
        c.valid = false;
        c.count = 0;
        index_[b] = s;
    }
    PairCache& c = slots_[static_cast<size_t>(index_[b])];
    c.lastUsed = step;
    return &c;
}

} // namespace detail

PrimitiveGeometry Bridge::Impl::primitiveGeometry(const b2Fixture* f, int child) {
    PrimitiveGeometry g;
    const b2Shape* sh = f->GetShape();
    g.type = static_cast<int>(sh->GetType());
    g.radius = sh->m_radius;
    switch (sh->GetType()) {
    case b2Shape::e_circle:
        g.v[0] = static_cast<const b2CircleShape*>(sh)->m_p;
        g.n = 1;
        break;
    case b2Shape::e_polygon: {
        const b2PolygonShape* p = static_cast<const b2PolygonShape*>(sh);
        g.n = p->m_count;
        for (int i = 0; i < p->m_count; ++i)
            g.v[i] = p->m_vertices[i];
        break;
    }
    case b2Shape::e_edge: {
        const b2EdgeShape* e = static_cast<const b2EdgeShape*>(sh);
        g.v[0] = e->m_vertex1;
        g.v[1] = e->m_vertex2;
        g.n = 2;
        break;
    }
    case b2Shape::e_chain: {
        b2EdgeShape e;
        static_cast<const b2ChainShape*>(sh)->GetChildEdge(&e, child);
        g.v[0] = e.m_vertex1;
        g.v[1] = e.m_vertex2;
        g.n = 2;
        break;
    }
    default:
        break;
    }
    return g;
}

double Bridge::Impl::originReach(const BodyRec* r) {
    double m = 0.0;
    for (const rugo_vec2& k : r->rootCorners) // the root box holds the curve and its band
        m = std::max(m, std::hypot(k.x, k.y));
    return m;
}

double Bridge::Impl::originReach(const PrimitiveGeometry& g) {
    double m = 0.0;
    for (int i = 0; i < g.n; ++i)
        m = std::max(m, static_cast<double>(g.v[i].Length()));
    return m + static_cast<double>(g.radius);
}

namespace {

bool sameGeometry(const PrimitiveGeometry& a, const PrimitiveGeometry& b) {
    if (a.type != b.type || a.radius != b.radius || a.n != b.n) return false;
    for (int i = 0; i < a.n; ++i)
        if (!(a.v[i] == b.v[i])) return false;
    return true;
}

// y's frame in x's frame.
rugo_transform relative(const rugo_transform& x, const rugo_transform& y) {
    rugo_transform r;
    r.p = rugo_inv_rotate(x.q, rugo_v2_sub(y.p, x.p));
    r.q.c = x.q.c * y.q.c + x.q.s * y.q.s;
    r.q.s = x.q.c * y.q.s - x.q.s * y.q.c;
    return r;
}

// How far any point of y (within `reachY` of its origin) has moved in x's frame from poses (x0, y0) to
// (x1, y1): |Δp| + |Δq| reachY, |Δq| the change of the relative rotation as a matrix (2 sin(Δθ/2)).
double motion(const rugo_transform& x0, const rugo_transform& y0, const rugo_transform& x1,
              const rugo_transform& y1, double reachY) {
    const rugo_transform r0 = relative(x0, y0), r1 = relative(x1, y1);
    return std::hypot(r1.p.x - r0.p.x, r1.p.y - r0.p.y) +
           std::hypot(r1.q.c - r0.q.c, r1.q.s - r0.q.s) * reachY;
}

rugo_vec2 carry(const rugo_transform& from, const rugo_transform& to, rugo_vec2 p) {
    return rugo_transform_point(to, rugo_inv_transform_point(from, p));
}

} // namespace

// Why a kept answer may stand for a search: the search (round-off, or certified to its resolution)
// found every contact whose separation was within its margin M. If every point of one body has moved
// by at most m <= r in the other's frame since, every separation has changed by at most m, so a contact
// now within M - r was within M then and is in the answer, and each carried contact's separation is
// within 2m of the contact's own (the curves' distance at its carried points moved by at most m; the
// minimum it stands for, by at most m). The motion is measured from the search's poses, never from the
// last reuse, so reuses do not add up. docs/contacts.md ("Coherence") states the same rule for librugo's
// own cache.
bool Bridge::Impl::keptAnswer(PairCache* pc, const PrimitiveGeometry& g, const rugo_transform& xa,
                              const rugo_transform& xb, const QueryParams& qp, double margin, QContact* out,
                              int cap, int* n) const {
    const double r = keepDistance();
    if (pc == nullptr || !pc->valid || !(r > 0.0) || pc->count > cap) return false;
    if (!(margin <= pc->covers) || pc->resolution != qp.resolution || pc->level != qp.level ||
        !sameGeometry(pc->geometry, g))
        return false;
    // Either body's points in the other's frame: the smaller bound holds for both.
    const double m =
        std::min(motion(pc->xa, pc->xb, xa, xb, pc->reachB), motion(pc->xb, pc->xa, xb, xa, pc->reachA));
    if (!(m <= r)) return false;
    for (int i = 0; i < pc->count; ++i) {
        QContact k = pc->contacts[i];
        k.pa = carry(pc->xa, xa, k.pa);
        k.pb = carry(pc->xb, xb, k.pb);
        k.n = rugo_rotate(xa.q, rugo_inv_rotate(pc->xa.q, k.n));
        out[i] = k;
    }
    *n = pc->count;
    return true;
}

void Bridge::Impl::keepAnswer(PairCache* pc, double reachA, double reachB, const PrimitiveGeometry& g,
                              const rugo_transform& xa, const rugo_transform& xb, const QueryParams& qp,
                              const QContact* c, int n, int found) const {
    if (pc == nullptr) return;
    const double r = keepDistance();
    pc->valid = r > 0.0 && n == found && n <= kPairCacheContacts;
    if (!pc->valid) return;
    pc->geometry = g;
    pc->covers = qp.margin - r;
    pc->resolution = qp.resolution;
    pc->level = qp.level;
    pc->xa = xa;
    pc->xb = xb;
    pc->reachA = reachA;
    pc->reachB = reachB;
    pc->count = n;
    std::copy(c, c + n, pc->contacts);
}

} // namespace rugo
