// The bridge's contact goals (issue 21; docs/box2d.md, "What the bridge holds"): ordinary Box2D 2.4.1
// scenes with their boxes and discs made rough (same outline, same mass, bands of 1-3 mm, constant
// friction), each run natively and through the bridge in the same program, 60 Hz, 8/3 iterations.
//
//   stack      15 boxes (1 m, created 10 cm apart) stand 10 s: drift of any box (m); ten 1 m boxes
//              created touching: drift
//   overlap    two discs (r 0.5 m) and two 1 m boxes created with centres 0.7 m apart, no gravity:
//              their distance after 1 s
//   tumbler    small boxes (0.25 m) spawned 2 cm apart in a kinematic container turning at 0.05 pi
//              rad/s: deepest contact and ms/step against native boxes
//   landing    a 1 m box dropped flat from 10 cm: largest |omega| after it lands; a box dropped onto
//              a conveyor belt (tangent speed 5 m/s in the user's PreSolve): largest |angle|
//   tunnel     seeded runs: a bullet box (400 m/s) and a spinning rod (4 x 0.2 m, 100 m/s, |omega|
//              <= 50 rad/s) against a 1 cm static box, a two-sided edge and a static rod (0.1 x 2 m):
//              runs through; an ordinary box at 20 m/s onto a static rough slab: its dip
//   pile       200 bodies (convex rocks, concave pebbles, gears, ~0.5 m, density 2) in a one-sided
//              chain container and in a box container, 10 s: escapes, deepest resting contact and
//              ms/step, against polygon compounds (5 mm chords) and circles in the same run
//
// Usage: b2_goals [--quick] [--only stack,overlap,tumbler,landing,tunnel,pile] [--runs R]
//                 [--pile-n N] [--pile-seconds T] [--tumbler-n N]
// Every figure is printed with its native (or polygon) counterpart. The checks are the goals;
// a goal that fails is printed as FAIL and counted (the exit status is 1). --quick (the test suite):
// 20 runs per tunnelling case, a 60-body pile for 4 s, a 150-box tumbler; the same tolerances.
#include "rugo/box2d.hpp"

#include "pile_scene.hpp"
extern "C" {
#include "sample_check.h"
}

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr float kDt = 1.0f / 60.0f;
constexpr int kVel = 8, kPos = 3;
constexpr double kPi = 3.14159265358979323846;
const double kSlop = static_cast<double>(b2_linearSlop);

struct Options {
    bool quick = false;
    std::string only;
    int runs = 100, pileN = 200, tumblerN = 600;
    double pileSeconds = 10.0;
    bool want(const char* name) const {
        if (only.empty()) return true;
        return (',' + only + ',').find(std::string(",") + name + ",") != std::string::npos;
    }
};

double nowMs() {
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// Shapes -------------------------------------------------------------------------------------------

struct ShapeOwner {
    std::vector<rugo_shape*> list;
    ~ShapeOwner() {
        for (rugo_shape* s : list)
            rugo_shape_destroy(s);
    }
    rugo_shape* make(const std::vector<rugo_vec2>& pts, const std::vector<double>& band, double mu,
                     double eps) {
        rugo_shape_def d = rugo_default_shape_def();
        d.points = pts.data();
        d.count = static_cast<int>(pts.size());
        d.tolerances = band.data();
        d.friction.alpha = 0.0; // constant μ = base: an ordinary material
        d.friction.base = mu;
        d.restitution.epsilon = eps;
        d.restitution.epsilon_max = eps;
        rugo_shape* s = nullptr;
        const rugo_status st = rugo_shape_create(&d, &s, nullptr);
        if (st != RUGO_OK) {
            std::fprintf(stderr, "b2_goals: shape refused: %s\n", rugo_status_string(st));
            std::exit(2);
        }
        list.push_back(s);
        return s;
    }
};

// A rectangle w x h: n control points evenly along its perimeter (corners included), so its sides are
// exactly straight and its corners rounded; a constant band.
rugo_shape* roughBox(ShapeOwner* o, double w, double h, int n, double band, double mu, double eps = 0.0) {
    std::vector<rugo_vec2> p;
    const double per = 2.0 * (w + h);
    for (int k = 0; k < n; ++k) {
        const double u = per * k / n;
        if (u < w)
            p.push_back(rugo_v2(-w / 2 + u, -h / 2));
        else if (u < w + h)
            p.push_back(rugo_v2(w / 2, -h / 2 + (u - w)));
        else if (u < 2 * w + h)
            p.push_back(rugo_v2(w / 2 - (u - w - h), h / 2));
        else
            p.push_back(rugo_v2(-w / 2, h / 2 - (u - 2 * w - h)));
    }
    return o->make(p, std::vector<double>(static_cast<size_t>(n), band), mu, eps);
}

// A disc whose curve passes through radius R at the joints.
rugo_shape* roughDisc(ShapeOwner* o, double R, int n, double band, double mu, double eps = 0.0) {
    const double joint = (4.0 + 2.0 * std::cos(2.0 * kPi / n)) / 6.0;
    std::vector<rugo_vec2> p;
    for (int k = 0; k < n; ++k)
        p.push_back(rugo_v2(R / joint * std::cos(2 * kPi * k / n), R / joint * std::sin(2 * kPi * k / n)));
    return o->make(p, std::vector<double>(static_cast<size_t>(n), band), mu, eps);
}

// The pile's outlines, r(θ) about the origin (star-shaped, so the polygon compounds are fans):
// 0 a convex rock, 1 a concave pebble (a peanut: concave at both waists), 2 a gear of 10 teeth.
rugo_shape* pileShape(ShapeOwner* o, int kind, uint64_t seed) {
    const int n = kind == 2 ? 128 : 64;
    rugo_rng rng;
    rugo_rng_seed(&rng, seed);
    const double R = 0.25;
    const double a2 = rugo_rng_range(&rng, 0.03, 0.08), a3 = rugo_rng_range(&rng, 0.0, 0.03);
    const double p2 = rugo_rng_range(&rng, 0.0, 2 * kPi), p3 = rugo_rng_range(&rng, 0.0, 2 * kPi);
    std::vector<rugo_vec2> p;
    std::vector<double> band;
    for (int k = 0; k < n; ++k) {
        const double t = 2 * kPi * k / n;
        double r = 1.0;
        if (kind == 0)
            r += a2 * std::cos(2 * t + p2) + a3 * std::cos(3 * t + p3);
        else if (kind == 1)
            r += 0.3 * std::cos(2 * t) + 0.08 * std::cos(t + p2);
        else
            r += 0.12 * std::tanh(3.0 * std::sin(10.0 * t + p2));
        p.push_back(rugo_v2(R * r * std::cos(t), R * r * std::sin(t)));
        band.push_back(rugo_rng_range(&rng, 0.001, 0.003));
    }
    return o->make(p, band, 0.5, 0.0);
}

b2Body* makeBody(b2World* w, b2BodyType type, b2Vec2 at, float angle = 0.0f) {
    b2BodyDef bd;
    bd.type = type;
    bd.position = at;
    bd.angle = angle;
    return w->CreateBody(&bd);
}

void addBox(b2Body* b, float hx, float hy, b2Vec2 c, float density, float mu, float eps = 0.0f) {
    b2PolygonShape s;
    s.SetAsBox(hx, hy, c, 0.0f);
    b2FixtureDef fd;
    fd.shape = &s;
    fd.density = density;
    fd.friction = mu;
    fd.restitution = eps;
    b->CreateFixture(&fd);
}

void attach(rugo::Bridge* br, b2Body* b, const rugo_shape* s, double density) {
    rugo::RoughBodyDef d;
    d.shape = s;
    d.density = density;
    const rugo_status st = br->Attach(b, d);
    if (st != RUGO_OK) {
        std::fprintf(stderr, "b2_goals: Attach: %s\n", rugo_status_string(st));
        std::exit(2);
    }
}

// The density of a native fixture of `area` with the rough shape's mass at `density`.
float sameMass(const rugo_shape* s, double density, double area) {
    return static_cast<float>(rugo_shape_mass(s).area * density / area);
}

// Deepest touching contact (most negative manifold separation) among the world's enabled contacts.
double deepestContact(b2World* w) {
    double d = 0.0;
    for (b2Contact* c = w->GetContactList(); c != nullptr; c = c->GetNext()) {
        if (!c->IsTouching() || !c->IsEnabled()) continue;
        b2WorldManifold wm;
        c->GetWorldManifold(&wm);
        for (int i = 0; i < c->GetManifold()->pointCount; ++i)
            d = std::min(d, static_cast<double>(wm.separations[i]));
    }
    return d;
}

void stepBoth(b2World* w, rugo::Bridge* br) {
    if (br != nullptr)
        br->Step(kDt, kVel, kPos);
    else
        w->Step(kDt, kVel, kPos);
}

// ---- stack ----------------------------------------------------------------------------------------

// Boxes of side `side` stacked with `gap` between them on a ground box, `steps` steps: the largest
// distance any box's centre moved sideways from where it was created.
double stackDrift(bool rough, int count, double side, double gap, double band, int steps) {
    ShapeOwner o;
    b2World w(b2Vec2(0.0f, -10.0f));
    std::unique_ptr<rugo::Bridge> br(rough ? new rugo::Bridge(&w) : nullptr);
    addBox(makeBody(&w, b2_staticBody, b2Vec2(0.0f, -1.0f)), 20.0f, 1.0f, b2Vec2(0.0f, 0.0f), 0.0f, 0.3f);
    rugo_shape* s = rough ? roughBox(&o, side, side, 64, band, 0.3) : nullptr;
    std::vector<b2Body*> bodies;
    for (int i = 0; i < count; ++i) {
        const float y = static_cast<float>(side / 2 + i * (side + gap));
        b2Body* b = makeBody(&w, b2_dynamicBody, b2Vec2(0.0f, y));
        if (rough)
            attach(br.get(), b, s, 1.0);
        else
            addBox(b, static_cast<float>(side / 2), static_cast<float>(side / 2), b2Vec2(0.0f, 0.0f), 1.0f,
                   0.3f);
        bodies.push_back(b);
    }
    double drift = 0.0;
    for (int k = 0; k < steps; ++k) {
        stepBoth(&w, br.get());
        for (const b2Body* b : bodies)
            drift = std::max(drift, std::fabs(static_cast<double>(b->GetPosition().x)));
    }
    return drift;
}

void runStack(const Options&) {
    const double n15 = stackDrift(false, 15, 1.0, 0.1, 0.0, 600),
                 r15 = stackDrift(true, 15, 1.0, 0.1, 0.002, 600);
    std::printf(
        "stack: 15 boxes (1 m, 10 cm apart), 10 s: largest sideways drift native %.4f m, rough %.4f m\n", n15,
        r15);
    sample_expect_le("stack: 15 rough boxes, drift over 10 s (m; goal 0.02)", r15, 0.02);
    const double n10 = stackDrift(false, 10, 1.0, 0.0, 0.0, 600),
                 r10 = stackDrift(true, 10, 1.0, 0.0, 0.002, 600);
    std::printf("stack: ten 1 m boxes created touching, 10 s: drift native %.4f m, rough %.4f m\n", n10, r10);
    sample_expect_le("stack: ten rough boxes created touching, drift (m; goal 0.005)", r10, 0.005);
}

// ---- overlap ----------------------------------------------------------------------------------------

// Two bodies (discs r 0.5 or 1 m boxes) created with centres 0.7 m apart, no gravity: their distance
// after 1 s.
double overlapDistance(bool rough, bool disc) {
    ShapeOwner o;
    b2World w(b2Vec2(0.0f, 0.0f));
    std::unique_ptr<rugo::Bridge> br(rough ? new rugo::Bridge(&w) : nullptr);
    rugo_shape* s = rough
                        ? (disc ? roughDisc(&o, 0.5, 32, 0.002, 0.4) : roughBox(&o, 1.0, 1.0, 64, 0.002, 0.4))
                        : nullptr;
    b2Body* b[2];
    for (int i = 0; i < 2; ++i) {
        b[i] = makeBody(&w, b2_dynamicBody, b2Vec2(0.7f * static_cast<float>(i), 0.0f));
        if (rough) {
            attach(br.get(), b[i], s, 1.0);
        } else if (disc) {
            b2CircleShape c;
            c.m_radius = 0.5f;
            b[i]->CreateFixture(&c, 1.0f);
        } else {
            addBox(b[i], 0.5f, 0.5f, b2Vec2(0.0f, 0.0f), 1.0f, 0.4f);
        }
    }
    for (int k = 0; k < 60; ++k)
        stepBoth(&w, br.get());
    return static_cast<double>((b[1]->GetPosition() - b[0]->GetPosition()).Length());
}

void runOverlap(const Options&) {
    for (int disc = 1; disc >= 0; --disc) {
        const double n = overlapDistance(false, disc != 0), r = overlapDistance(true, disc != 0);
        // Where each pair touches: the rough curves' 1 m plus both bands (2 mm each); native discs at
        // 1 m, native boxes at 1 m plus both polygons' skins (b2_polygonRadius).
        const double touchN = disc ? 1.0 : 1.0 + 2.0 * static_cast<double>(b2_polygonRadius), touchR = 1.004;
        std::printf(
            "overlap: two %s created 0.7 m apart, after 1 s: distance native %.4f m (touching at %.4f), "
            "rough %.4f m (touching at %.4f)\n",
            disc ? "discs (r 0.5 m)" : "1 m boxes", n, touchN, r, touchR);
        // Pushed apart as the native pair is: to where they touch, less Box2D's resting overlap (a linear
        // slop); two slops allowed.
        sample_expect_le(
            disc ? "overlap: rough discs pushed apart (touching distance - distance, m; <= 2 slop)"
                 : "overlap: rough boxes pushed apart (touching distance - distance, m; <= 2 slop)",
            touchR - r, 2 * kSlop);
    }
}

// ---- tumbler ------------------------------------------------------------------------------------------

struct TumblerResult {
    double msPerStep = 0.0, deepest = 0.0, firstStepDeepest = 0.0;
};

// `count` boxes of 0.25 m spawned 2 cm apart in a 10 m kinematic box container turning at 0.05 pi rad/s,
// `steps` steps: the time per step, the deepest contact over the run and after the first step.
TumblerResult tumbler(bool rough, int count, int steps) {
    ShapeOwner o;
    b2World w(b2Vec2(0.0f, -10.0f));
    std::unique_ptr<rugo::Bridge> br(rough ? new rugo::Bridge(&w) : nullptr);
    b2Body* box = makeBody(&w, b2_kinematicBody, b2Vec2(0.0f, 0.0f));
    addBox(box, 0.25f, 5.0f, b2Vec2(5.0f, 0.0f), 0.0f, 0.6f);
    addBox(box, 0.25f, 5.0f, b2Vec2(-5.0f, 0.0f), 0.0f, 0.6f);
    addBox(box, 5.0f, 0.25f, b2Vec2(0.0f, 5.0f), 0.0f, 0.6f);
    addBox(box, 5.0f, 0.25f, b2Vec2(0.0f, -5.0f), 0.0f, 0.6f);
    box->SetAngularVelocity(static_cast<float>(0.05 * kPi));
    rugo_shape* s = rough ? roughBox(&o, 0.25, 0.25, 16, 0.002, 0.6) : nullptr;
    const float dens = rough ? 1.0f : sameMass(roughBox(&o, 0.25, 0.25, 16, 0.002, 0.6), 1.0, 0.0625);
    const int cols = 30;
    for (int i = 0; i < count; ++i) {
        const float x = -4.3f + 0.27f * static_cast<float>(i % cols),
                    y = -4.5f + 0.27f * static_cast<float>(i / cols);
        b2Body* b = makeBody(&w, b2_dynamicBody, b2Vec2(x, y));
        if (rough)
            attach(br.get(), b, s, 1.0);
        else
            addBox(b, 0.125f, 0.125f, b2Vec2(0.0f, 0.0f), dens, 0.6f);
    }
    TumblerResult r;
    double t = 0.0;
    for (int k = 0; k < steps; ++k) {
        const double t0 = nowMs();
        stepBoth(&w, br.get());
        if (k >= 10) t += nowMs() - t0;
        const double d = deepestContact(&w);
        r.deepest = std::min(r.deepest, d);
        if (k == 0) r.firstStepDeepest = d;
    }
    r.msPerStep = t / std::max(1, steps - 10);
    return r;
}

void runTumbler(const Options& opt) {
    const int n = opt.quick ? 150 : opt.tumblerN, steps = opt.quick ? 120 : 300;
    const TumblerResult a = tumbler(false, n, steps), b = tumbler(true, n, steps);
    std::printf(
        "tumbler: %d boxes (0.25 m) 2 cm apart in a turning container, %d steps: native %.3f ms/step, "
        "rough %.3f ms/step (%.2fx); deepest contact native %.4f m, rough %.4f m; after the first step "
        "native %.4f, rough %.4f m\n",
        n, steps, a.msPerStep, b.msPerStep, b.msPerStep / a.msPerStep, a.deepest, b.deepest,
        a.firstStepDeepest, b.firstStepDeepest);
    sample_expect_le(
        "tumbler: bodies spawned apart are not pulled together (deepest contact after step 1, m)",
        -b.firstStepDeepest, kSlop);
    sample_expect_le("tumbler: deepest rough contact within the native one's plus 2 slop (m)",
                     -b.deepest - (-a.deepest), 2 * kSlop);
}

// ---- landing --------------------------------------------------------------------------------------

// A 1 m box dropped flat from 10 cm onto a ground box, 2 s: the largest |omega| after its first touch.
double landingSpin(bool rough) {
    ShapeOwner o;
    b2World w(b2Vec2(0.0f, -10.0f));
    std::unique_ptr<rugo::Bridge> br(rough ? new rugo::Bridge(&w) : nullptr);
    addBox(makeBody(&w, b2_staticBody, b2Vec2(0.0f, -1.0f)), 20.0f, 1.0f, b2Vec2(0.0f, 0.0f), 0.0f, 0.6f);
    b2Body* b = makeBody(&w, b2_dynamicBody, b2Vec2(0.0f, 0.6f));
    if (rough)
        attach(br.get(), b, roughBox(&o, 1.0, 1.0, 64, 0.002, 0.6), 1.0);
    else
        addBox(b, 0.5f, 0.5f, b2Vec2(0.0f, 0.0f), 1.0f, 0.6f);
    double spin = 0.0;
    for (int k = 0; k < 120; ++k) {
        stepBoth(&w, br.get());
        spin = std::max(spin, std::fabs(static_cast<double>(b->GetAngularVelocity())));
    }
    return spin;
}

// Box2D's conveyor belt: the user's PreSolve gives the platform's contacts a tangent speed.
struct Belt : b2ContactListener {
    const b2Fixture* platform = nullptr;
    void PreSolve(b2Contact* c, const b2Manifold*) override {
        if (c->GetFixtureA() == platform) c->SetTangentSpeed(5.0f);
        if (c->GetFixtureB() == platform) c->SetTangentSpeed(-5.0f);
    }
};

// A 1 m box dropped flat onto a 20 m belt moving at 5 m/s, until it leaves the belt: its largest |angle|.
double beltTilt(bool rough) {
    ShapeOwner o;
    b2World w(b2Vec2(0.0f, -10.0f));
    Belt belt;
    w.SetContactListener(&belt);
    std::unique_ptr<rugo::Bridge> br(rough ? new rugo::Bridge(&w) : nullptr);
    b2Body* g = makeBody(&w, b2_staticBody, b2Vec2(-5.0f, 5.0f));
    addBox(g, 10.0f, 0.5f, b2Vec2(0.0f, 0.0f), 0.0f, 0.8f);
    belt.platform = g->GetFixtureList();
    b2Body* b = makeBody(&w, b2_dynamicBody, b2Vec2(-12.0f, 6.6f));
    if (rough)
        attach(br.get(), b, roughBox(&o, 1.0, 1.0, 64, 0.002, 0.8), 20.0);
    else
        addBox(b, 0.5f, 0.5f, b2Vec2(0.0f, 0.0f), 20.0f, 0.8f);
    double tilt = 0.0;
    for (int k = 0; k < 300 && b->GetPosition().x < 4.0f; ++k) {
        stepBoth(&w, br.get());
        tilt = std::max(tilt, std::fabs(static_cast<double>(b->GetAngle())));
    }
    return tilt;
}

void runLanding(const Options&) {
    const double n = landingSpin(false), r = landingSpin(true);
    std::printf(
        "landing: 1 m box dropped flat from 10 cm: largest |omega| native %.4f rad/s, rough %.4f rad/s\n", n,
        r);
    sample_expect_le("landing: rough box lands flat (largest |omega|, rad/s; goal 0.01)", r, 0.01);
    const double bn = beltTilt(false), bt = beltTilt(true);
    std::printf(
        "landing: 1 m box dropped onto a 5 m/s belt: largest |angle| native %.4f rad, rough %.4f rad\n", bn,
        bt);
    sample_expect_le("landing: no tip-over on the belt (largest |angle|, rad)", bt, 0.05);
}

// ---- tunnelling -----------------------------------------------------------------------------------------

// One run: a body (0 a 0.5 m bullet box at 400 m/s, 1 a 4 x 0.2 m rod at 100 m/s spinning at up to 50
// rad/s) from x = -3 toward an obstacle at x = 0 (0 a 1 cm static box 20 m tall, 1 a two-sided edge,
// 2 a static 0.1 x 2 m rod), no gravity. Through: its centre crosses x = 0 within the obstacle's height
// (for the short rod, |y| < 0.9 m at the crossing).
bool throughOnce(bool rough, int body, int obstacle, uint64_t seed, ShapeOwner* o,
                 const rugo_shape* const* shapes) {
    rugo_rng rng;
    rugo_rng_seed(&rng, seed);
    b2World w(b2Vec2(0.0f, 0.0f));
    std::unique_ptr<rugo::Bridge> br(rough ? new rugo::Bridge(&w) : nullptr);
    (void)o;
    b2Body* g = makeBody(&w, b2_staticBody, b2Vec2(0.0f, 0.0f));
    if (obstacle == 0) {
        addBox(g, 0.005f, 10.0f, b2Vec2(0.0f, 0.0f), 0.0f, 0.4f);
    } else if (obstacle == 1) {
        b2EdgeShape e;
        e.SetTwoSided(b2Vec2(0.0f, -10.0f), b2Vec2(0.0f, 10.0f));
        g->CreateFixture(&e, 0.0f);
    } else {
        addBox(g, 0.05f, 1.0f, b2Vec2(0.0f, 0.0f), 0.0f, 0.4f);
    }
    const float y0 = obstacle == 2 ? static_cast<float>(rugo_rng_range(&rng, -0.6, 0.6)) : 0.0f;
    b2Body* b =
        makeBody(&w, b2_dynamicBody, b2Vec2(-3.0f, y0), static_cast<float>(rugo_rng_range(&rng, 0.0, kPi)));
    b->SetBullet(true);
    if (rough) {
        attach(br.get(), b, shapes[body], 1.0);
    } else if (body == 0) {
        addBox(b, 0.25f, 0.25f, b2Vec2(0.0f, 0.0f), 1.0f, 0.4f);
    } else {
        addBox(b, 2.0f, 0.1f, b2Vec2(0.0f, 0.0f), 1.0f, 0.4f);
    }
    const double speed = body == 0 ? 400.0 : 100.0, dir = rugo_rng_range(&rng, -0.05, 0.05);
    b->SetLinearVelocity(
        b2Vec2(static_cast<float>(speed * std::cos(dir)), static_cast<float>(speed * std::sin(dir))));
    b->SetAngularVelocity(
        static_cast<float>(body == 0 ? rugo_rng_range(&rng, -5.0, 5.0) : rugo_rng_range(&rng, -50.0, 50.0)));
    b2Vec2 prev = b->GetPosition();
    for (int k = 0; k < 30; ++k) {
        stepBoth(&w, br.get());
        const b2Vec2 p = b->GetPosition();
        if (prev.x < 0.0f && p.x >= 0.0f) {
            const float y = prev.y + (p.y - prev.y) * (0.0f - prev.x) / (p.x - prev.x);
            if (std::fabs(y) < (obstacle == 2 ? 0.9f : 9.5f)) return true;
        }
        prev = p;
    }
    return false;
}

// An ordinary 0.5 m box at 20 m/s onto a static slab (rough, or a native box), the slab's top at y = 0:
// its lowest point's deepest dip below the slab's contact surface (the rough slab's is its band above
// its curve).
double slabDip(bool rough) {
    ShapeOwner o;
    b2World w(b2Vec2(0.0f, -10.0f));
    std::unique_ptr<rugo::Bridge> br(rough ? new rugo::Bridge(&w) : nullptr);
    const double band = 0.002;
    b2Body* slab = makeBody(&w, b2_staticBody, b2Vec2(0.0f, -0.25f));
    if (rough)
        attach(br.get(), slab, roughBox(&o, 10.0, 0.5, 128, band, 0.6), 0.0);
    else
        addBox(slab, 5.0f, 0.25f, b2Vec2(0.0f, 0.0f), 0.0f, 0.6f);
    b2Body* b = makeBody(&w, b2_dynamicBody, b2Vec2(0.0f, 1.0f));
    addBox(b, 0.25f, 0.25f, b2Vec2(0.0f, 0.0f), 1.0f, 0.6f);
    b->SetLinearVelocity(b2Vec2(0.0f, -20.0f));
    const double surface = rough ? band : 0.0;
    double dip = -1e9;
    for (int k = 0; k < 60; ++k) {
        stepBoth(&w, br.get());
        const b2PolygonShape* ps = static_cast<const b2PolygonShape*>(b->GetFixtureList()->GetShape());
        for (int i = 0; i < ps->m_count; ++i)
            dip = std::max(dip, surface - static_cast<double>(b2Mul(b->GetTransform(), ps->m_vertices[i]).y));
    }
    return dip;
}

void runTunnel(const Options& opt) {
    const int runs = opt.quick ? 20 : opt.runs;
    ShapeOwner o;
    const rugo_shape* shapes[2] = {roughBox(&o, 0.5, 0.5, 16, 0.002, 0.4),
                                   roughBox(&o, 4.0, 0.2, 64, 0.002, 0.4)};
    static const char* const bodyName[2] = {"bullet box (400 m/s)", "spinning rod (100 m/s, |omega| <= 50)"};
    static const char* const obstacleName[3] = {"1 cm static box", "two-sided edge", "static rod 0.1 x 2 m"};
    int roughThrough = 0;
    for (int body = 0; body < 2; ++body)
        for (int obstacle = 0; obstacle < 3; ++obstacle) {
            int nt = 0, rt = 0;
            for (int i = 0; i < runs; ++i) {
                const uint64_t seed =
                    1000u * static_cast<uint64_t>(body * 3 + obstacle) + static_cast<uint64_t>(i);
                nt += throughOnce(false, body, obstacle, seed, &o, shapes);
                rt += throughOnce(true, body, obstacle, seed, &o, shapes);
            }
            roughThrough += rt;
            std::printf("tunnel: %s onto a %s: through in %d of %d runs native, %d of %d rough\n",
                        bodyName[body], obstacleName[obstacle], nt, runs, rt, runs);
        }
    sample_expect_le("tunnel: rough runs through a thin box, an edge or a rod (goal 0)", roughThrough, 0.0);
    const double dn = slabDip(false), dr = slabDip(true);
    std::printf(
        "tunnel: ordinary box at 20 m/s onto a static slab: deepest dip below the surface native %.4f m, "
        "rough %.4f m (< 0: stopped above it)\n",
        dn, dr);
    sample_expect_le("tunnel: dip into the rough slab minus the native one's (m; goal <= 1 slop)", dr - dn,
                     kSlop);
}

// ---- pile ------------------------------------------------------------------------------------------------

enum PileVariant { kRough = 0, kPolygon = 1, kCircle = 2 };
const char* const kPileName[3] = {"rough", "polygon", "circle"};

struct PileResult {
    double msPerStep = 0.0, deepest = 0.0;
    int escapes = 0;
    double firstEscape = -1.0;
};

// n bodies of the three kinds in a grid above a container (chain: a one-sided chain whose front faces
// in; otherwise three static boxes), `seconds` of 60 Hz steps: escapes (centre below the floor or
// beyond a wall), the deepest contact at the end and the time per step after the first second.
PileResult pile(PileVariant v, bool chain, int n, double seconds) {
    ShapeOwner o;
    rugo_shape* kinds[6];
    for (int k = 0; k < 6; ++k)
        kinds[k] = pileShape(&o, k % 3, 900u + static_cast<uint64_t>(k));
    b2World w(b2Vec2(0.0f, -10.0f));
    std::unique_ptr<rugo::Bridge> br(v == kRough ? new rugo::Bridge(&w) : nullptr);
    const int cols = 14;
    const float hw = 0.36f * cols + 0.5f, wallH = 0.72f * static_cast<float>((n + cols - 1) / cols) + 2.0f;
    b2Body* c = makeBody(&w, b2_staticBody, b2Vec2(0.0f, 0.0f));
    if (chain) {
        const b2Vec2 vs[4] = {b2Vec2(hw, wallH), b2Vec2(hw, 0.0f), b2Vec2(-hw, 0.0f), b2Vec2(-hw, wallH)};
        b2ChainShape ch;
        ch.CreateChain(vs, 4, b2Vec2(hw, wallH + 1.0f), b2Vec2(-hw, wallH + 1.0f));
        b2FixtureDef fd;
        fd.shape = &ch;
        fd.friction = 0.5f;
        c->CreateFixture(&fd);
    } else {
        addBox(c, hw + 0.5f, 0.5f, b2Vec2(0.0f, -0.5f), 0.0f, 0.5f);
        addBox(c, 0.5f, wallH / 2, b2Vec2(hw + 0.5f, wallH / 2), 0.0f, 0.5f);
        addBox(c, 0.5f, wallH / 2, b2Vec2(-hw - 0.5f, wallH / 2), 0.0f, 0.5f);
    }
    std::vector<std::vector<pile::Piece>> pieces(6);
    std::vector<double> radius(6, 0.0);
    for (int k = 0; k < 6; ++k) {
        rugo_contour cc;
        rugo_shape_level(kinds[k], rugo_shape_finest_level(kinds[k]), &cc);
        for (int i = 0; i < cc.count; ++i)
            for (int t = 0; t < 8; ++t) {
                const rugo_vec2 q = rugo_contour_point(cc, i, t / 8.0);
                radius[static_cast<size_t>(k)] =
                    std::max(radius[static_cast<size_t>(k)], std::hypot(q.x, q.y));
            }
        int nv = 0;
        double dev = 0.0;
        if (v == kPolygon && !pile::FitPolygon(kinds[k], rugo_v2(0.0, 0.0), 0.005,
                                               &pieces[static_cast<size_t>(k)], &nv, &dev)) {
            std::fprintf(stderr, "b2_goals: pile shape %d is not star-shaped\n", k);
            std::exit(2);
        }
    }
    std::vector<b2Body*> bodies;
    rugo_rng rng;
    rugo_rng_seed(&rng, 77);
    for (int i = 0; i < n; ++i) {
        const int k = (i * 7 + i / cols) % 6;
        const float x = -hw + 0.7f + 0.72f * static_cast<float>(i % cols) +
                        static_cast<float>(rugo_rng_range(&rng, -0.05, 0.05));
        const float y = 0.6f + 0.72f * static_cast<float>(i / cols);
        b2Body* b = makeBody(&w, b2_dynamicBody, b2Vec2(x, y),
                             static_cast<float>(rugo_rng_range(&rng, 0.0, 2 * kPi)));
        const rugo_shape* s = kinds[k];
        const double mass = rugo_shape_mass(s).area * 2.0;
        if (v == kRough) {
            attach(br.get(), b, s, 2.0);
        } else if (v == kPolygon) {
            double area = 0.0;
            for (const pile::Piece& p : pieces[static_cast<size_t>(k)])
                for (size_t j = 1; j + 1 < p.v.size(); ++j)
                    area += 0.5 * static_cast<double>(b2Cross(p.v[j] - p.v[0], p.v[j + 1] - p.v[0]));
            for (const pile::Piece& p : pieces[static_cast<size_t>(k)]) {
                b2PolygonShape ps;
                ps.Set(p.v.data(), static_cast<int32>(p.v.size()));
                b2FixtureDef fd;
                fd.shape = &ps;
                fd.density = static_cast<float>(mass / area);
                fd.friction = 0.5f;
                b->CreateFixture(&fd);
            }
        } else {
            b2CircleShape cs;
            cs.m_radius = static_cast<float>(radius[static_cast<size_t>(k)]);
            b2FixtureDef fd;
            fd.shape = &cs;
            fd.density = static_cast<float>(
                mass / (kPi * radius[static_cast<size_t>(k)] * radius[static_cast<size_t>(k)]));
            fd.friction = 0.5f;
            b->CreateFixture(&fd);
        }
        bodies.push_back(b);
    }
    PileResult r;
    const int steps = static_cast<int>(std::lround(seconds * 60.0));
    double t = 0.0;
    std::vector<char> escaped(bodies.size(), 0);
    for (int k = 0; k < steps; ++k) {
        const double t0 = nowMs();
        stepBoth(&w, br.get());
        if (k >= 60) t += nowMs() - t0;
        for (size_t i = 0; i < bodies.size(); ++i) {
            const b2Vec2 p = bodies[i]->GetWorldCenter();
            if (!escaped[i] && (p.y < 0.0f || std::fabs(p.x) > hw)) {
                escaped[i] = 1;
                ++r.escapes;
                if (r.firstEscape < 0.0) r.firstEscape = (k + 1) / 60.0;
            }
        }
    }
    r.msPerStep = t / std::max(1, steps - 60);
    r.deepest = deepestContact(&w);
    return r;
}

void runPile(const Options& opt) {
    const int n = opt.quick ? 60 : opt.pileN;
    const double seconds = opt.quick ? 4.0 : opt.pileSeconds;
    for (int chain = 1; chain >= 0; --chain) {
        PileResult r[3];
        for (int v = 0; v < 3; ++v)
            r[v] = pile(static_cast<PileVariant>(v), chain != 0, n, seconds);
        for (int v = 0; v < 3; ++v)
            std::printf(
                "pile: %d bodies in a %s container, %.0f s, %s: %.3f ms/step, %d escaped (first at %.2f s), "
                "deepest contact at the end %.4f m\n",
                n, chain ? "one-sided chain" : "box", seconds, kPileName[v], r[v].msPerStep, r[v].escapes,
                r[v].firstEscape, r[v].deepest);
        std::printf("pile: %s container: rough / polygon compounds %.2fx, rough / circles %.2fx\n",
                    chain ? "chain" : "box", r[0].msPerStep / r[1].msPerStep,
                    r[0].msPerStep / r[2].msPerStep);
        sample_expect_le(chain ? "pile (chain container): rough bodies escaped (goal 0)"
                               : "pile (box container): rough bodies escaped (goal 0)",
                         r[0].escapes, 0.0);
        sample_expect_le(
            chain ? "pile (chain): rough resting penetration beyond polygon compounds' (m; <= 1 slop)"
                  : "pile (box): rough resting penetration beyond polygon compounds' (m; <= 1 slop)",
            -r[0].deepest + r[1].deepest, kSlop);
    }
}

} // namespace

int main(int argc, char** argv) {
    Options opt;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (!std::strcmp(a, "--quick")) {
            opt.quick = true;
        } else if (!std::strcmp(a, "--only") && i + 1 < argc) {
            opt.only = argv[++i];
        } else if (!std::strcmp(a, "--runs") && i + 1 < argc) {
            opt.runs = std::atoi(argv[++i]);
        } else if (!std::strcmp(a, "--pile-n") && i + 1 < argc) {
            opt.pileN = std::atoi(argv[++i]);
        } else if (!std::strcmp(a, "--pile-seconds") && i + 1 < argc) {
            opt.pileSeconds = std::atof(argv[++i]);
        } else if (!std::strcmp(a, "--tumbler-n") && i + 1 < argc) {
            opt.tumblerN = std::atoi(argv[++i]);
        } else {
            std::fprintf(
                stderr,
                "usage: b2_goals [--quick] [--only stack,overlap,tumbler,landing,tunnel,pile] [--runs R] "
                "[--pile-n N] [--pile-seconds T] [--tumbler-n N]\n");
            return 2;
        }
    }
    if (opt.want("stack")) runStack(opt);
    if (opt.want("overlap")) runOverlap(opt);
    if (opt.want("landing")) runLanding(opt);
    if (opt.want("tunnel")) runTunnel(opt);
    if (opt.want("tumbler")) runTumbler(opt);
    if (opt.want("pile")) runPile(opt);
    return sample_finish();
}
