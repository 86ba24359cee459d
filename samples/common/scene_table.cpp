// The scene table (scene_table.hpp): the scenes.h scenes built through the bridge, and the rows.
#include "scene_table.hpp"

#include "pile_scene.hpp"
extern "C" {
#include "sample_check.h"
}

#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdint>

namespace scene_table {

namespace {

constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;

// Every body of a scenes.h scene in a new b2World through the bridge (its defaults); false, with a
// message, if the bridge refuses one.
bool BuildBodies(const scene& s, World* w) {
    w->world =
        std::make_unique<b2World>(b2Vec2(static_cast<float>(s.gravity.x), static_cast<float>(s.gravity.y)));
    w->bridge = std::make_unique<rugo::Bridge>(w->world.get(), rugo::BridgeDef());
    for (int i = 0; i < s.body_count; ++i) {
        const scene_body& sb = s.bodies[i];
        b2BodyDef bd;
        bd.type = sb.is_static ? b2_staticBody : b2_dynamicBody;
        bd.position.Set(static_cast<float>(sb.transform.p.x), static_cast<float>(sb.transform.p.y));
        bd.angle = static_cast<float>(std::atan2(sb.transform.q.s, sb.transform.q.c));
        b2Body* body = w->world->CreateBody(&bd);
        double band = 0.0;
        if (sb.kind == SCENE_ROUGH) {
            rugo::RoughBodyDef rd;
            rd.shape = sb.shape;
            rd.density = sb.density;
            rd.lod = sb.level;
            const rugo_status st = w->bridge->Attach(body, rd);
            if (st != RUGO_OK) {
                std::fprintf(stderr, "Attach(%s): %s\n", sb.name, rugo_status_string(st));
                return false;
            }
            band = scene_max_band(sb.shape, sb.level);
        } else {
            b2FixtureDef fd;
            fd.density = static_cast<float>(sb.density);
            fd.friction = static_cast<float>(sb.friction);
            fd.restitution = static_cast<float>(sb.restitution);
            b2PolygonShape box;
            b2CircleShape circle;
            b2ChainShape chain;
            std::vector<b2Vec2> v;
            if (sb.kind == SCENE_BOX) {
                box.SetAsBox(static_cast<float>(sb.half_extents.x), static_cast<float>(sb.half_extents.y));
                fd.shape = &box;
            } else if (sb.kind == SCENE_CIRCLE) {
                circle.m_radius = static_cast<float>(sb.radius);
                fd.shape = &circle;
            } else {
                for (int k = 0; k < sb.chain_count; ++k)
                    v.emplace_back(static_cast<float>(sb.chain[k].x), static_cast<float>(sb.chain[k].y));
                const b2Vec2 prev = v[0] + (v[0] - v[1]), next = v.back() + (v.back() - v[v.size() - 2]);
                chain.CreateChain(v.data(), static_cast<int32>(v.size()), prev, next);
                fd.shape = &chain;
            }
            body->CreateFixture(&fd);
        }
        body->SetLinearVelocity(
            b2Vec2(static_cast<float>(sb.linear_velocity.x), static_cast<float>(sb.linear_velocity.y)));
        body->SetAngularVelocity(static_cast<float>(sb.angular_velocity));
        w->bodies.push_back(body);
        w->bands.push_back(band);
    }
    return true;
}

// A scenes.h scene, id Id: its description (owned by the world) and its bodies.
template <scene_id Id> bool CreateFromScenes(const Args& args, World* w) {
    if (args.variant < 0 || args.variant >= scene_variant_count(Id)) {
        std::fprintf(stderr, "scene %d has no variant %d\n", static_cast<int>(Id), args.variant);
        return false;
    }
    std::shared_ptr<scene> s(new scene(), [](scene* p) {
        scene_destroy(p);
        delete p;
    });
    const rugo_status st = scene_create(Id, args.variant, s.get());
    if (st != RUGO_OK) {
        std::fprintf(stderr, "scene %d variant %d: %s\n", static_cast<int>(Id), args.variant,
                     rugo_status_string(st));
        return false;
    }
    w->description = s;
    w->sc = s.get();
    return BuildBodies(*s, w);
}

// A step of a scenes.h scene: its time step, 8 velocity and 3 position iterations.
void StepScenes(World* w) {
    w->bridge->Step(static_cast<float>(w->sc->time_step), kVelocityIterations, kPositionIterations);
    w->time += w->sc->time_step;
    ++w->steps;
}

} // namespace

// Step counts are the scenes' durations at their 60 Hz (scenes.c); the determinism test checks that
// they agree.
const Entry kScenes[] = {
    {"demo", 1, CreateFromScenes<SCENE_DEMO>, StepScenes, 360},
    {"fig7_5_ball", 6, CreateFromScenes<SCENE_BALL>, StepScenes, 210},
    {"fig7_8_thrown", 2, CreateFromScenes<SCENE_THROWN>, StepScenes, 240},
    {"fig7_9_four_bodies", 1, CreateFromScenes<SCENE_FOUR_BODIES>, StepScenes, 480},
    {"fig7_10_grafica", 2, CreateFromScenes<SCENE_GRAFICA>, StepScenes, 300},
    {"fig7_13_levels", 3, CreateFromScenes<SCENE_LEVELS>, StepScenes, 240},
    // The Box2D scenes benchmark's default run is 300 steps (its --steps).
    {"rock_pile", pile::kVariants, pile::Create, pile::Step, 300},
};
const int kSceneCount = static_cast<int>(sizeof kScenes / sizeof kScenes[0]);

const Entry* Find(const char* name) {
    for (const Entry& e : kScenes)
        if (std::strcmp(e.name, name) == 0) return &e;
    return nullptr;
}

bool Create(const Entry& entry, const Args& args, World* world) {
    world->entry = &entry;
    return entry.create(args, world);
}

bool Create(const char* name, int variant, World* world) {
    const Entry* e = Find(name);
    if (e == nullptr) {
        std::fprintf(stderr, "no scene called %s\n", name);
        return false;
    }
    Args args;
    args.variant = variant;
    return Create(*e, args, world);
}

void World::Step() { entry->step(this); }

int World::Index(const b2Body* b) const {
    for (std::size_t i = 0; i < bodies.size(); ++i)
        if (bodies[i] == b) return static_cast<int>(i);
    return -1;
}

int World::Find(scene_role role, int nth) const {
    for (int i = 0; i < sc->body_count; ++i)
        if (sc->bodies[i].role == role && nth-- == 0) return i;
    return -1;
}

std::uint64_t HashBodies(std::uint64_t h, const World& world) {
    for (const b2Body* b : world.bodies) {
        const float f[3] = {b->GetPosition().x, b->GetPosition().y, b->GetAngle()};
        h = sample_fnv1a(h, f, sizeof f);
    }
    return h;
}

} // namespace scene_table
