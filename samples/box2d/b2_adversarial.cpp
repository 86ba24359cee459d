// Adversarial scenes for the Box2D bridge, each stepped at 60 Hz through the public bridge API:
//   overlap    16 rough bodies spawned on top of each other (centres within 0.25 m, radius 0.5 m) in a box
//   far        the same box and 16 rough bodies, spaced, 1e4 m from the origin (x and y)
//   sizes      1 cm rough pebbles (24) dropped on a 50 m rough boulder lying on a 200 m floor
//   squeeze    a rough body (radius 0.5 m) squeezed between two kinematic walls that close from 2.4 m
//              to 0.6 m apart at 0.5 m/s and then hold
//
//   b2_adversarial            600 steps per scene; checks per scene: no non-finite position, angle or
//                             velocity, no body lost or added, worst step <= 20x the median step (the
//                             thread's CPU time per step; the wall time is printed too)
//   b2_adversarial --quick    120 steps per scene (the test suite): the finiteness and body checks
//                             only; the step times are printed, not checked
#include "b2_stress.hpp"

extern "C" {
#include "sample_check.h"
}

#include <cstring>
#include <functional>
#include <string>

namespace {

using b2stress::ShapePtr;

struct Scene {
    std::unique_ptr<b2World> world;
    std::unique_ptr<rugo::Bridge> bridge;
    std::set<const b2Body*> alive;
    std::vector<b2Body*> dynamic;
    std::function<void(long step)> beforeStep; // the squeeze's walls

    Scene() : world(new b2World(b2Vec2(0.0f, -10.0f))), bridge(new rugo::Bridge(world.get())) {}
    ~Scene() {
        bridge.reset();
        world.reset();
    }

    b2Body* Body(b2BodyType type, double x, double y, double angle = 0.0) {
        b2BodyDef bd;
        bd.type = type;
        bd.position.Set(static_cast<float>(x), static_cast<float>(y));
        bd.angle = static_cast<float>(angle);
        b2Body* b = world->CreateBody(&bd);
        alive.insert(b);
        if (type == b2_dynamicBody) dynamic.push_back(b);
        return b;
    }
    void Box(b2Body* b, double hx, double hy, double cx = 0.0, double cy = 0.0) {
        b2PolygonShape box;
        box.SetAsBox(static_cast<float>(hx), static_cast<float>(hy),
                     b2Vec2(static_cast<float>(cx), static_cast<float>(cy)), 0.0f);
        b->CreateFixture(&box, 1.0f);
    }
    bool Rough(b2Body* b, const rugo_shape* shape) {
        rugo::RoughBodyDef rd;
        rd.shape = shape;
        rd.density = 1.0;
        const rugo_status st = bridge->Attach(b, rd);
        if (st == RUGO_OK) return true;
        std::fprintf(stderr, "Attach: %s\n", rugo_status_string(st));
        return sample_expect("Attach", 0);
    }
    // A static box container: floor and two walls, inner width w, around (x, y) at the floor's top.
    void Container(double x, double y, double w) {
        b2Body* g = Body(b2_staticBody, x, y);
        Box(g, 0.5 * w + 0.5, 0.5, 0.0, -0.5);
        Box(g, 0.5, 0.5 * w, -0.5 * w - 0.5, 0.5 * w);
        Box(g, 0.5, 0.5 * w, 0.5 * w + 0.5, 0.5 * w);
    }
};

struct Figures {
    long steps = 0, nonFinite = 0, amiss = 0;
    double median = 0.0, worst = 0.0, wallMedian = 0.0, wallWorst = 0.0, maxSpeed = 0.0;
    rugo::BridgeStats stats;
};

Figures Run(Scene& s, long steps) {
    Figures f;
    b2stress::StepTimes times;
    for (long k = 0; k < steps; ++k) {
        if (s.beforeStep) s.beforeStep(k);
        times.Time([&] { s.bridge->Step(1.0f / 60.0f, 8, 3); });
        f.nonFinite += b2stress::NonFinite(*s.world);
        f.amiss += b2stress::BodiesAmiss(*s.world, s.alive);
        for (const b2Body* b : s.dynamic) {
            const b2Vec2 v = b->GetLinearVelocity();
            f.maxSpeed = std::max(f.maxSpeed,
                                  std::sqrt(static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y));
        }
    }
    f.steps = steps;
    f.median = b2stress::StepTimes::Median(times.cpu);
    f.worst = b2stress::StepTimes::Worst(times.cpu);
    f.wallMedian = b2stress::StepTimes::Median(times.wall);
    f.wallWorst = b2stress::StepTimes::Worst(times.wall);
    f.stats = s.bridge->GetStats();
    return f;
}

void Report(const char* name, const char* what, const Figures& f, bool quick) {
    std::printf(
        "%-8s %s\n         %ld steps: step CPU time median %.1f us, worst %.1f us (%.1fx); wall median "
        "%.1f us, worst %.1f us; %ld queries, fastest body %.2f m/s\n",
        name, what, f.steps, 1e6 * f.median, 1e6 * f.worst, f.median > 0 ? f.worst / f.median : 0.0,
        1e6 * f.wallMedian, 1e6 * f.wallWorst, f.stats.queries, f.maxSpeed);
    const std::string n(name);
    sample_expect_le((n + ": non-finite positions, angles, velocities").c_str(),
                     static_cast<double>(f.nonFinite), 0.0);
    sample_expect_le((n + ": bodies lost or added (step-body pairs)").c_str(), static_cast<double>(f.amiss),
                     0.0);
    if (!quick)
        sample_expect_le((n + ": worst step / median step (CPU time)").c_str(),
                         f.median > 0 ? f.worst / f.median : 0.0, 20.0);
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            quick = true;
        } else {
            std::fprintf(stderr, "usage: b2_adversarial [--quick]\n");
            return 2;
        }
    }
    const long steps = quick ? 120 : 600;
    const ShapePtr rock = b2stress::RoughShape(64, 0.5, 0.01);
    const ShapePtr pebble = b2stress::RoughShape(32, 0.005, 0.01);
    const ShapePtr boulder = b2stress::RoughShape(128, 25.0, 0.005);
    if (!rock || !pebble || !boulder) return 1;
    b2stress::Rng rng{7};

    {
        Scene s;
        s.Container(0.0, 0.0, 8.0);
        for (int i = 0; i < 16; ++i)
            s.Rough(s.Body(b2_dynamicBody, rng.Uniform(-0.25, 0.25), 3.0 + rng.Uniform(-0.25, 0.25),
                           rng.Uniform(-3, 3)),
                    rock.get());
        Report("overlap", "16 rough bodies (r = 0.5 m) spawned within 0.25 m of one point", Run(s, steps),
               quick);
    }
    {
        Scene s;
        const double o = 1e4;
        s.Container(o, o, 8.0);
        for (int i = 0; i < 16; ++i)
            s.Rough(
                s.Body(b2_dynamicBody, o - 3.0 + 1.2 * (i % 6), o + 1.0 + 1.2 * (i / 6), rng.Uniform(-3, 3)),
                rock.get());
        Report("far", "16 rough bodies in a box 1e4 m from the origin (x and y)", Run(s, steps), quick);
    }
    {
        Scene s;
        b2Body* floor = s.Body(b2_staticBody, 0.0, 0.0);
        s.Box(floor, 100.0, 1.0, 0.0, -1.0);
        s.Rough(s.Body(b2_dynamicBody, 0.0, 26.0), boulder.get());
        for (int i = 0; i < 24; ++i)
            s.Rough(s.Body(b2_dynamicBody, rng.Uniform(-8.0, 8.0), 53.0 + 0.05 * i, rng.Uniform(-3, 3)),
                    pebble.get());
        Report("sizes", "24 rough pebbles of 1 cm dropped on a 50 m rough boulder on a floor", Run(s, steps),
               quick);
    }
    {
        Scene s;
        b2Body* floor = s.Body(b2_staticBody, 0.0, 0.0);
        s.Box(floor, 5.0, 0.5, 0.0, -0.5);
        b2Body* left = s.Body(b2_kinematicBody, -1.3, 1.5);
        b2Body* right = s.Body(b2_kinematicBody, 1.3, 1.5);
        s.Box(left, 0.1, 1.5);
        s.Box(right, 0.1, 1.5);
        s.Rough(s.Body(b2_dynamicBody, 0.0, 0.6, 0.3), rock.get());
        s.beforeStep = [left, right](long) {
            // Inner faces at x = +-(|x| - 0.1): close at 0.5 m/s to 0.6 m apart, then hold.
            const float gap = 2.0f * (right->GetPosition().x - 0.1f);
            const float v = gap > 0.6f ? 0.5f : 0.0f;
            left->SetLinearVelocity(b2Vec2(v, 0.0f));
            right->SetLinearVelocity(b2Vec2(-v, 0.0f));
        };
        Report("squeeze",
               "a rough body (r = 0.5 m) between kinematic walls closing from 2.4 m to 0.6 m apart",
               Run(s, quick ? 240 : steps), quick);
    }
    return sample_finish();
}
