// Adversarial scenes for the Box2D bridge, each stepped at 60 Hz through the public bridge API:
//   overlap    16 rough bodies spawned on top of each other (centres within 0.25 m, radius 0.5 m) in a box
//   far        the same box and 16 rough bodies, spaced, 1e4 m from the origin (x and y); the same box at
//              the origin runs first as its baseline (far@0)
//   sizes      1 cm rough pebbles (24) dropped on a 50 m rough boulder lying on a 200 m floor
//   squeeze    a rough body (radius 0.5 m) squeezed between two kinematic walls that close from 2.4 m
//              to 0.6 m apart at 0.5 m/s and then hold
//
//   b2_adversarial            600 steps per scene; checks per scene: no non-finite position, angle or
//                             velocity, no body lost or added, worst step <= 20x the median active step
//                             (the thread's CPU time per step, over the steps that began with a body
//                             awake; the median of all steps and the wall time are printed too); in the
//                             scenes nothing supplies energy to (far, sizes), no body's mechanical energy
//                             rises above its start by more than a 1 cm fall's (0.1 J/kg)
//   b2_adversarial --quick    120 steps per scene, 240 for the squeeze (the test suite): the same checks
//                             but the spike check (a loaded machine's timing is no verdict)
//   --scene NAME              one scene only
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
    // Step CPU times: the median of all steps, the median of the active steps (those that began with a
    // dynamic body awake), the worst step and its index; the wall time's median and worst.
    double median = 0.0, activeMedian = 0.0, worst = 0.0, wallMedian = 0.0, wallWorst = 0.0;
    long activeSteps = 0, worstStep = 0;
    // Bridge queries in the worst step, and the median over the active steps: a worst step that did no
    // more queries than usual is a spike of some other phase.
    long worstQueries = 0, activeMedianQueries = 0;
    // The fastest body: its speed and the speed a free fall from its start to where it was then gives.
    double maxSpeed = 0.0, freeFallSpeed = 0.0;
    // Largest rise of one body's mechanical energy per kg over its own start (J/kg): energy from nowhere
    // shows here even where a heavy body's losses hide it in the world's sum.
    double bodyRise = 0.0;
    rugo::BridgeStats stats;
};

// Mechanical energy of a body (J): kinetic (translation of the centre, rotation about it) plus
// potential in the world's gravity.
double Energy(const b2Body* b, b2Vec2 g) {
    const b2Vec2 v = b->GetLinearVelocity(), c = b->GetWorldCenter(), lc = b->GetLocalCenter();
    const double m = static_cast<double>(b->GetMass());
    const double ic = static_cast<double>(b->GetInertia()) - m * static_cast<double>(b2Dot(lc, lc));
    const double w = static_cast<double>(b->GetAngularVelocity());
    return 0.5 * m * static_cast<double>(b2Dot(v, v)) + 0.5 * ic * w * w -
           m * static_cast<double>(b2Dot(g, c));
}

Figures Run(Scene& s, long steps) {
    Figures f;
    const b2Vec2 g = s.world->GetGravity();
    const double gn = static_cast<double>(g.Length());
    std::vector<double> y0, e0;
    for (const b2Body* b : s.dynamic) {
        y0.push_back(static_cast<double>(b->GetWorldCenter().y));
        e0.push_back(Energy(b, g) / static_cast<double>(b->GetMass()));
    }
    b2stress::StepTimes times;
    times.Reserve(static_cast<std::size_t>(steps));
    std::vector<double> active, activeQueries;
    active.reserve(static_cast<std::size_t>(steps));
    activeQueries.reserve(static_cast<std::size_t>(steps));
    std::vector<long> queries(static_cast<std::size_t>(steps), 0);
    for (long k = 0; k < steps; ++k) {
        if (s.beforeStep) s.beforeStep(k);
        bool awake = false;
        for (const b2Body* b : s.dynamic)
            awake = awake || b->IsAwake();
        const long q0 = s.bridge->GetStats().queries;
        times.Time([&] { s.bridge->Step(1.0f / 60.0f, 8, 3); });
        queries[static_cast<std::size_t>(k)] = s.bridge->GetStats().queries - q0;
        if (awake) {
            active.push_back(times.cpu[static_cast<std::size_t>(k)]);
            activeQueries.push_back(static_cast<double>(queries[static_cast<std::size_t>(k)]));
        }
        f.nonFinite += b2stress::NonFinite(*s.world);
        f.amiss += b2stress::BodiesAmiss(*s.world, s.alive);
        for (std::size_t i = 0; i < s.dynamic.size(); ++i) {
            const b2Body* b = s.dynamic[i];
            const b2Vec2 v = b->GetLinearVelocity();
            const double speed = std::sqrt(static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y);
            if (speed > f.maxSpeed) {
                f.maxSpeed = speed;
                f.freeFallSpeed =
                    std::sqrt(2.0 * gn * std::max(0.0, y0[i] - static_cast<double>(b->GetWorldCenter().y)));
            }
            f.bodyRise = std::max(f.bodyRise, Energy(b, g) / static_cast<double>(b->GetMass()) - e0[i]);
        }
    }
    f.steps = steps;
    const std::vector<double> cpu = times.Cpu(), wall = times.Wall();
    f.median = b2stress::StepTimes::Median(cpu);
    f.activeMedian = b2stress::StepTimes::Median(active);
    f.activeSteps = static_cast<long>(active.size());
    f.worst = b2stress::StepTimes::Worst(cpu);
    f.worstStep = static_cast<long>(std::max_element(cpu.begin(), cpu.end()) - cpu.begin());
    f.worstQueries = queries[static_cast<std::size_t>(f.worstStep)];
    f.activeMedianQueries = static_cast<long>(b2stress::StepTimes::Median(activeQueries));
    f.wallMedian = b2stress::StepTimes::Median(wall);
    f.wallWorst = b2stress::StepTimes::Worst(wall);
    f.stats = s.bridge->GetStats();
    return f;
}

double Ratio(double a, double b) { return b > 0.0 ? a / b : 0.0; }

// A scene's figures and checks. `closed`: nothing supplies energy (no kinematic body, no bodies spawned
// overlapping), so no body may end up with more mechanical energy than it started with, beyond what a
// 1 cm fall gives (float round-off of positions 1e4 m out is 1 mm).
void Report(const char* name, const char* what, const Figures& f, bool quick, bool closed) {
    std::printf(
        "%-8s %s\n         %ld steps (%ld active): step CPU time median %.1f us, active median %.1f us, "
        "worst %.1f us (step %ld, %ld queries against the active median's %ld; %.1fx the median, %.1fx the "
        "active median); wall median %.1f us, "
        "worst %.1f us\n         %ld queries; fastest body %.2f m/s (a free fall from its start: %.2f "
        "m/s); largest rise of a body's energy over its start %.3g J/kg\n",
        name, what, f.steps, f.activeSteps, 1e6 * f.median, 1e6 * f.activeMedian, 1e6 * f.worst, f.worstStep,
        f.worstQueries, f.activeMedianQueries, Ratio(f.worst, f.median), Ratio(f.worst, f.activeMedian),
        1e6 * f.wallMedian, 1e6 * f.wallWorst, f.stats.queries, f.maxSpeed, f.freeFallSpeed, f.bodyRise);
    const std::string n(name);
    sample_expect_le((n + ": non-finite positions, angles, velocities").c_str(),
                     static_cast<double>(f.nonFinite), 0.0);
    sample_expect_le((n + ": bodies lost or added (step-body pairs)").c_str(), static_cast<double>(f.amiss),
                     0.0);
    if (closed)
        sample_expect_le((n + ": rise of a body's mechanical energy over its start (J/kg)").c_str(),
                         f.bodyRise, 10.0 * 0.01);
    // The median of all steps is an empty step once the bodies sleep (a few us): the ratio to it
    // measures how long the scene slept, not a spike. The check is against the active steps' median.
    if (!quick)
        sample_expect_le((n + ": worst step / median active step (CPU time)").c_str(),
                         Ratio(f.worst, f.activeMedian), 20.0);
}

// The far scene's box and bodies with the box's floor centred at (o, o).
void FarBox(Scene& s, double o, const rugo_shape* rock) {
    b2stress::Rng rng{8};
    s.Container(o, o, 8.0);
    for (int i = 0; i < 16; ++i)
        s.Rough(s.Body(b2_dynamicBody, o - 3.0 + 1.2 * (i % 6), o + 1.0 + 1.2 * (i / 6), rng.Uniform(-3, 3)),
                rock);
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false;
    const char* only = nullptr;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            quick = true;
        } else if (std::strcmp(argv[i], "--scene") == 0 && i + 1 < argc) {
            only = argv[++i];
        } else {
            std::fprintf(stderr, "usage: b2_adversarial [--quick] [--scene overlap|far|sizes|squeeze]\n");
            return 2;
        }
    }
    auto runs = [only](const char* name) { return only == nullptr || std::strcmp(only, name) == 0; };
    const long steps = quick ? 120 : 600;
    const ShapePtr rock = b2stress::RoughShape(64, 0.5, 0.01);
    const ShapePtr pebble = b2stress::RoughShape(32, 0.005, 0.01);
    const ShapePtr boulder = b2stress::RoughShape(128, 25.0, 0.005);
    if (!rock || !pebble || !boulder) return 1;

    if (runs("overlap")) {
        b2stress::Rng rng{7};
        Scene s;
        s.Container(0.0, 0.0, 8.0);
        for (int i = 0; i < 16; ++i)
            s.Rough(s.Body(b2_dynamicBody, rng.Uniform(-0.25, 0.25), 3.0 + rng.Uniform(-0.25, 0.25),
                           rng.Uniform(-3, 3)),
                    rock.get());
        Report("overlap", "16 rough bodies (r = 0.5 m) spawned within 0.25 m of one point", Run(s, steps),
               quick, false);
    }
    if (runs("far")) {
        // The same box at the origin first: the baseline a spike far out would stand out from.
        Figures atOrigin, far;
        {
            Scene s;
            FarBox(s, 0.0, rock.get());
            atOrigin = Run(s, steps);
        }
        {
            Scene s;
            FarBox(s, 1e4, rock.get());
            far = Run(s, steps);
        }
        Report("far@0", "the far scene's box and bodies at the origin (the baseline)", atOrigin, quick, true);
        Report("far", "16 rough bodies in a box 1e4 m from the origin (x and y)", far, quick, true);
        std::printf(
            "         far / at the origin: active median step %.2fx, worst step %.2fx, queries %.2fx\n",
            Ratio(far.activeMedian, atOrigin.activeMedian), Ratio(far.worst, atOrigin.worst),
            Ratio(static_cast<double>(far.stats.queries), static_cast<double>(atOrigin.stats.queries)));
    }
    if (runs("sizes")) {
        b2stress::Rng rng{9};
        Scene s;
        b2Body* floor = s.Body(b2_staticBody, 0.0, 0.0);
        s.Box(floor, 100.0, 1.0, 0.0, -1.0);
        s.Rough(s.Body(b2_dynamicBody, 0.0, 26.0), boulder.get());
        for (int i = 0; i < 24; ++i)
            s.Rough(s.Body(b2_dynamicBody, rng.Uniform(-8.0, 8.0), 53.0 + 0.05 * i, rng.Uniform(-3, 3)),
                    pebble.get());
        Report("sizes", "24 rough pebbles of 1 cm dropped on a 50 m rough boulder on a floor", Run(s, steps),
               quick, true);
    }
    if (runs("squeeze")) {
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
               Run(s, quick ? 240 : steps), quick, false);
    }
    return sample_finish();
}
