// libFuzzer target: the Box2D bridge driven by random scenes, through its public API only
// (include/rugo/box2d.hpp). The input chooses up to three rough shapes (star-shaped outlines of 8..32
// points at sizes 0.02..4 m, random tolerances), then a script of operations between steps: create a
// body (dynamic, kinematic or static; with an ordinary box or circle or none; rough or not), attach,
// detach, destroy, set velocities, change the type, teleport, sync the mass, and step. Properties, after
// every operation and step: no crash or sanitizer report; every body's position, angle and velocities
// finite; the world holds exactly the bodies created and not destroyed (none lost, none added); the
// bridge's IsRough agrees with the attachments that succeeded; Attach, Detach and SyncMass return
// statuses their documentation lists.
#include "rugo/box2d.hpp"

#include <box2d/box2d.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <set>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

#define FUZZ_CHECK(cond)                                                                                     \
    do {                                                                                                     \
        if (!(cond)) {                                                                                       \
            std::fprintf(stderr, "%s:%d: FUZZ_CHECK(%s) failed\n", __FILE__, __LINE__, #cond);               \
            std::abort();                                                                                    \
        }                                                                                                    \
    } while (0)

struct Bytes {
    const std::uint8_t* p;
    std::size_t n;
    unsigned Next() {
        if (n == 0) return 0;
        --n;
        return *p++;
    }
    // [0, 1] from two bytes.
    double Unit() {
        const unsigned v = Next() | (Next() << 8);
        return static_cast<double>(v) / 65535.0;
    }
    double Range(double lo, double hi) { return lo + (hi - lo) * Unit(); }
};

struct ShapeDeleter {
    void operator()(rugo_shape* s) const { rugo_shape_destroy(s); }
};
using ShapePtr = std::unique_ptr<rugo_shape, ShapeDeleter>;

const double kSizes[4] = {0.02, 0.3, 1.0, 4.0};

ShapePtr MakeShape(Bytes* b) {
    const unsigned head = b->Next();
    const int count = 8 << (head % 3); // 8, 16, 32
    const double size = kSizes[(head >> 2) % 4];
    rugo_vec2 pts[32];
    rugo_real lam[32];
    const double lamScale = (head >> 4) % 4 == 0 ? 0.0 : 0.02 * size;
    for (int i = 0; i < count; ++i) {
        const double r = size * (0.4 + 0.6 * b->Unit());
        const double a = 6.283185307179586 * (i + 0.8 * (b->Unit() - 0.5)) / count;
        pts[i] = rugo_v2(r * std::cos(a), r * std::sin(a));
        lam[i] = lamScale * b->Next() / 255.0;
    }
    rugo_shape_def def = rugo_default_shape_def();
    def.points = pts;
    def.count = count;
    def.tolerances = lam;
    rugo_shape* s = nullptr;
    if (rugo_shape_create(&def, &s, nullptr) != RUGO_OK) return nullptr;
    return ShapePtr(s);
}

bool Finite(float x) { return std::isfinite(x); }

struct Scene {
    std::vector<ShapePtr> shapes;
    std::unique_ptr<b2World> world;
    std::unique_ptr<rugo::Bridge> bridge;
    std::vector<b2Body*> live;     // created, not destroyed (the ground first)
    std::set<const b2Body*> rough; // attached and not detached

    ~Scene() {
        bridge.reset(); // before the world, both before the shapes
        world.reset();
    }

    b2Body* Pick(Bytes* b) {
        if (live.size() <= 1) return nullptr;
        return live[1 + b->Next() % (live.size() - 1)];
    }

    void Check() const {
        std::set<const b2Body*> inWorld;
        for (const b2Body* x = world->GetBodyList(); x; x = x->GetNext())
            inWorld.insert(x);
        FUZZ_CHECK(inWorld.size() == live.size());
        FUZZ_CHECK(static_cast<std::size_t>(world->GetBodyCount()) == live.size());
        for (const b2Body* x : live) {
            FUZZ_CHECK(inWorld.count(x) == 1);
            const b2Vec2 p = x->GetPosition(), v = x->GetLinearVelocity();
            FUZZ_CHECK(Finite(p.x) && Finite(p.y) && Finite(x->GetAngle()));
            FUZZ_CHECK(Finite(v.x) && Finite(v.y) && Finite(x->GetAngularVelocity()));
            FUZZ_CHECK(bridge->IsRough(x) == (rough.count(x) == 1));
            FUZZ_CHECK((bridge->GetShape(x) != nullptr) == (rough.count(x) == 1));
        }
    }

    void Attach(b2Body* body, Bytes* b) {
        if (body == nullptr || shapes.empty()) return;
        rugo::RoughBodyDef def;
        def.shape = shapes[b->Next() % shapes.size()].get();
        const unsigned opt = b->Next();
        def.density = (opt & 3) == 0 ? 0.0 : ((opt & 3) == 1 ? 0.5 : 2.0);
        def.lod = (opt & 4) ? RUGO_LOD_AUTO : -static_cast<int>((opt >> 3) % 3);
        const rugo_status st = bridge->Attach(body, def);
        FUZZ_CHECK(st == RUGO_OK || st == RUGO_ERR_BAD_ARGUMENT || st == RUGO_ERR_ALREADY_ATTACHED);
        FUZZ_CHECK((st == RUGO_ERR_ALREADY_ATTACHED) == (rough.count(body) == 1));
        if (st == RUGO_OK) rough.insert(body);
    }

    void Create(Bytes* b) {
        if (live.size() >= 9) return;
        const unsigned opt = b->Next();
        b2BodyDef bd;
        bd.type = (opt % 4) == 0 ? b2_staticBody : ((opt % 4) == 1 ? b2_kinematicBody : b2_dynamicBody);
        bd.position.Set(static_cast<float>(b->Range(-6.0, 6.0)), static_cast<float>(b->Range(-2.0, 10.0)));
        bd.angle = static_cast<float>(b->Range(-3.2, 3.2));
        bd.bullet = (opt & 64) != 0;
        b2Body* body = world->CreateBody(&bd);
        live.push_back(body);
        const unsigned fixture = (opt >> 2) % 3;
        if (fixture == 1) {
            b2PolygonShape box;
            box.SetAsBox(static_cast<float>(b->Range(0.05, 1.0)), static_cast<float>(b->Range(0.05, 1.0)));
            body->CreateFixture(&box, 1.0f);
        } else if (fixture == 2) {
            b2CircleShape circle;
            circle.m_radius = static_cast<float>(b->Range(0.05, 1.0));
            body->CreateFixture(&circle, 1.0f);
        }
        if (opt & 16) Attach(body, b);
    }

    void Op(Bytes* b) {
        const unsigned op = b->Next() % 10;
        b2Body* body = Pick(b);
        switch (op) {
        case 0:
            Create(b);
            break;
        case 1:
            Attach(body, b);
            break;
        case 2:
            if (body != nullptr) {
                const rugo_status st = bridge->Detach(body);
                FUZZ_CHECK(st == (rough.count(body) ? RUGO_OK : RUGO_ERR_NOT_ATTACHED));
                rough.erase(body);
            }
            break;
        case 3:
            if (body != nullptr) {
                rough.erase(body);
                for (std::size_t i = 1; i < live.size(); ++i)
                    if (live[i] == body) {
                        live.erase(live.begin() + static_cast<std::ptrdiff_t>(i));
                        break;
                    }
                world->DestroyBody(body);
            }
            break;
        case 4:
            if (body != nullptr) {
                body->SetLinearVelocity(b2Vec2(static_cast<float>(b->Range(-60.0, 60.0)),
                                               static_cast<float>(b->Range(-60.0, 60.0))));
                body->SetAngularVelocity(static_cast<float>(b->Range(-30.0, 30.0)));
            }
            break;
        case 5:
            if (body != nullptr) {
                const unsigned t = b->Next() % 3;
                body->SetType(t == 0 ? b2_staticBody : (t == 1 ? b2_kinematicBody : b2_dynamicBody));
            }
            break;
        case 6:
            if (body != nullptr)
                body->SetTransform(
                    b2Vec2(static_cast<float>(b->Range(-6.0, 6.0)), static_cast<float>(b->Range(-2.0, 10.0))),
                    static_cast<float>(b->Range(-3.2, 3.2)));
            break;
        case 7:
            if (body != nullptr) {
                const rugo_status st = bridge->SyncMass(body);
                FUZZ_CHECK(st == (rough.count(body) ? RUGO_OK : RUGO_ERR_NOT_ATTACHED));
            }
            break;
        default: {
            const int steps = 1 + static_cast<int>(b->Next() % 4);
            for (int i = 0; i < steps; ++i) {
                bridge->Step(1.0f / 60.0f, 8, 3);
                Check();
            }
            break;
        }
        }
        Check();
    }
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    Bytes b{data, size};
    Scene s;
    const int nshapes = 1 + static_cast<int>(b.Next() % 3);
    for (int i = 0; i < nshapes; ++i) {
        ShapePtr shape = MakeShape(&b);
        if (shape) s.shapes.push_back(std::move(shape));
    }
    s.world.reset(new b2World(b2Vec2(0.0f, -10.0f)));
    s.bridge.reset(new rugo::Bridge(s.world.get()));
    b2BodyDef gd;
    b2Body* ground = s.world->CreateBody(&gd);
    b2PolygonShape floor;
    floor.SetAsBox(20.0f, 0.5f, b2Vec2(0.0f, -3.0f), 0.0f);
    ground->CreateFixture(&floor, 0.0f);
    s.live.push_back(ground);
    for (int op = 0; op < 48 && b.n > 0; ++op)
        s.Op(&b);
    // A few steps at the end so that every scene is stepped at least once.
    for (int i = 0; i < 2; ++i) {
        s.bridge->Step(1.0f / 60.0f, 8, 3);
        s.Check();
    }
    return 0;
}
