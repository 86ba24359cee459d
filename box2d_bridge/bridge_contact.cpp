// The bridge's b2Contact in Box2D 2.4.1's contact registry, and the live bridges by world.
//
// Box2D creates a contact for a fixture pair through b2Contact::s_registers[typeA][typeB], a
// process-global table that b2Contact::InitializeRegisters fills on first use. A proxy is a polygon, so
// the pairs a proxy can be in are polygon-polygon, polygon-circle, edge-polygon and chain-polygon: for
// those the bridge installs its own create and destroy functions (AddType, a protected static member,
// reached from RoughContact, a class derived from b2Contact). Its create function asks the bridge of
// the fixtures' world whether either fixture is a proxy: then it makes a RoughContact, otherwise it
// calls Box2D's own function for the pair, saved when the bridge's was installed, with the same
// arguments. Its destroy function tells a RoughContact from Box2D's own contacts by dynamic_cast.
//
// Thread safety: the registry and the list of bridges are process-global and unguarded. Box2D 2.4 is
// single-threaded per process here (one thread steps every world), and so is the bridge.
#include "bridge_impl.hpp"

#include <new>
#include <utility>
#include <vector>

namespace rugo {
namespace detail {

namespace {

// The live bridges, by world (a handful: a linear scan is the fastest lookup). Contacts are created
// rarely (when proxies' AABBs start to overlap), so this is not on a per-step path.
std::vector<std::pair<const b2World*, Bridge::Impl*>>& bridges() {
    static std::vector<std::pair<const b2World*, Bridge::Impl*>> list;
    return list;
}

Bridge::Impl* bridgeOf(const b2World* w) {
    for (const auto& e : bridges())
        if (e.first == w) return e.second;
    return nullptr;
}

// Box2D's own functions for the pairs the bridge took over, in the registry's [typeA][typeB] layout.
b2ContactRegister g_original[b2Shape::e_typeCount][b2Shape::e_typeCount];

b2Contact* createContact(b2Fixture* fA, int32 iA, b2Fixture* fB, int32 iB, b2BlockAllocator* allocator) {
    Bridge::Impl* impl = bridgeOf(fA->GetBody()->GetWorld());
    if (impl != nullptr) {
        const ProxyRef* ra = impl->lookup(fA);
        const ProxyRef* rb = impl->lookup(fB);
        if (ra != nullptr || rb != nullptr) {
            // Box2D's block allocator serves blocks up to 640 bytes (b2_maxBlockSize); beyond, each would be
            // a malloc.
            static_assert(sizeof(RoughContact) <= 640, "RoughContact outgrew Box2D's blocks");
            void* mem = allocator->Allocate(sizeof(RoughContact));
            return new (mem) RoughContact(fA, iA, fB, iB, impl, ra, rb);
        }
    }
    // The registry hands this function the fixtures in the order of the pair's primary entry; Box2D's
    // own function for that entry expects the same order.
    return g_original[fA->GetType()][fB->GetType()].createFcn(fA, iA, fB, iB, allocator);
}

void destroyContact(b2Contact* contact, b2BlockAllocator* allocator) {
    if (RoughContact* rc = dynamic_cast<RoughContact*>(contact)) {
        rc->impl->releasePointInfo(rc);
        rc->~RoughContact();
        allocator->Free(rc, sizeof(RoughContact));
        return;
    }
    g_original[contact->GetFixtureA()->GetType()][contact->GetFixtureB()->GetType()].destroyFcn(contact,
                                                                                                allocator);
}

} // namespace

RoughContact::RoughContact(b2Fixture* fA, int32 iA, b2Fixture* fB, int32 iB, Bridge::Impl* owner,
                           const ProxyRef* ra, const ProxyRef* rb)
    : b2Contact(fA, iA, fB, iB), impl(owner), recA(ra ? ra->rec : nullptr), recB(rb ? rb->rec : nullptr),
      pieceA(ra ? ra->piece : -1), pieceB(rb ? rb->piece : -1) {}

void RoughContact::Evaluate(b2Manifold* manifold, const b2Transform& xfA, const b2Transform& xfB) {
    impl->evaluate(this, manifold, xfA, xfB);
}

void RoughContact::install() {
    static bool installed = false;
    if (installed) return;
    installed = true;
    // Box2D fills the registry on its first contact unless it is initialised: it would then overwrite
    // the bridge's functions.
    if (!s_initialized) {
        InitializeRegisters();
        s_initialized = true;
    }
    const std::pair<b2Shape::Type, b2Shape::Type> pairs[] = {{b2Shape::e_polygon, b2Shape::e_polygon},
                                                             {b2Shape::e_polygon, b2Shape::e_circle},
                                                             {b2Shape::e_edge, b2Shape::e_polygon},
                                                             {b2Shape::e_chain, b2Shape::e_polygon}};
    for (const auto& p : pairs) {
        g_original[p.first][p.second] = s_registers[p.first][p.second];
        g_original[p.second][p.first] = s_registers[p.second][p.first];
        AddType(createContact, destroyContact, p.first, p.second);
    }
}

} // namespace detail

// A contact's two PointInfo (allocated on its first points; a free slot first).
PointInfo* Bridge::Impl::pointInfoOf(RoughContact* rc) {
    if (rc->infoSlot < 0) {
        if (infoFree >= 0) {
            rc->infoSlot = infoFree;
            infoFree = infoNext[static_cast<size_t>(infoFree)];
        } else {
            rc->infoSlot = static_cast<int>(infoNext.size());
            infoNext.push_back(-1);
            pointInfo.resize(pointInfo.size() + 2);
        }
    }
    return &pointInfo[2 * static_cast<size_t>(rc->infoSlot)];
}

// Slots for 16 touching proxy contacts a body (a body in a pile touches a handful of others, a few proxy
// pairs each), now rather than in a step: the bridge allocates nothing in a step once warm.
void Bridge::Impl::reservePointInfo(size_t bodyCount) {
    infoNext.reserve(16 * bodyCount);
    pointInfo.reserve(2 * 16 * bodyCount);
}

void Bridge::Impl::releasePointInfo(RoughContact* rc) {
    if (rc->infoSlot < 0) return;
    infoNext[static_cast<size_t>(rc->infoSlot)] = infoFree;
    infoFree = rc->infoSlot;
    rc->infoSlot = -1;
}

rugo_status Bridge::GetPointInfo(const b2Contact* contact, int index, PointInfo* out) const {
    if (contact == nullptr || out == nullptr) return RUGO_ERR_NULL_ARGUMENT;
    const RoughContact* rc = dynamic_cast<const RoughContact*>(contact);
    if (rc == nullptr || rc->impl != m_impl.get()) return RUGO_ERR_NOT_ATTACHED;
    // The manifold and its surface data are written together (Impl::evaluate); a contact evaluated
    // without points has a manifold of none.
    if (index < 0 || index >= contact->GetManifold()->pointCount || rc->infoSlot < 0)
        return RUGO_ERR_BAD_ARGUMENT;
    *out = m_impl->pointInfo[2 * static_cast<size_t>(rc->infoSlot) + static_cast<size_t>(index)];
    return RUGO_OK;
}

namespace detail {

void registerBridge(const b2World* world, Bridge::Impl* impl) {
    RoughContact::install();
    bridges().emplace_back(world, impl);
}

void unregisterBridge(const Bridge::Impl* impl) {
    auto& list = bridges();
    for (size_t i = 0; i < list.size(); ++i)
        if (list[i].second == impl) {
            list.erase(list.begin() + static_cast<std::ptrdiff_t>(i));
            return;
        }
}

} // namespace detail
} // namespace rugo
