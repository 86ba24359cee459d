// The Box2D 2.4 bridge (include/rugo/box2d.hpp, docs/box2d.md): acceptance tests.
#include "rugo/box2d.hpp"

extern "C" {
#include "test_util.h"
}

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {

const double kPi = 3.14159265358979323846;

// Shapes ------------------------------------------------------------------------------------------

rugo_shape* makeShape(const std::vector<rugo_vec2>& pts, const std::vector<double>* tol, double mu,
                      double eps) {
    rugo_shape_def d = rugo_default_shape_def();
    d.points = pts.data();
    d.count = static_cast<int>(pts.size());
    d.tolerances = tol ? tol->data() : nullptr;
    d.friction.alpha = 0.0; // constant μ = base (an ordinary material)
    d.friction.base = mu;
    d.restitution.epsilon = eps;
    d.restitution.epsilon_max = eps;
    rugo_shape* s = nullptr;
    ck_assert_int_eq(rugo_shape_create(&d, &s, nullptr), RUGO_OK);
    return s;
}

// Control points on a circle, scaled so that the curve's radius (at the joints) is R.
rugo_shape* makeDisc(int n, double R, double mu, double eps) {
    const double joint = (4.0 + 2.0 * std::cos(2.0 * kPi / n)) / 6.0;
    std::vector<rugo_vec2> p(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k)
        p[static_cast<size_t>(k)] =
            rugo_v2(R / joint * std::cos(2.0 * kPi * k / n), R / joint * std::sin(2.0 * kPi * k / n));
    return makeShape(p, nullptr, mu, eps);
}

// A rounded rectangle: n control points evenly along the rectangle's perimeter (corners included), so
// the sides are exactly straight and the corners rounded. Optional seeded jitter along the normal and
// a constant tolerance band make it rough.
std::vector<rugo_vec2> rectPoints(int n, double w, double h, test_rng* rng, double jitter) {
    std::vector<rugo_vec2> p;
    const double per = 2.0 * (w + h);
    for (int k = 0; k < n; ++k) {
        double u = per * k / n;
        rugo_vec2 q, nn;
        if (u < w) {
            q = rugo_v2(-w / 2 + u, -h / 2);
            nn = rugo_v2(0, -1);
        } else if (u < w + h) {
            q = rugo_v2(w / 2, -h / 2 + (u - w));
            nn = rugo_v2(1, 0);
        } else if (u < 2 * w + h) {
            q = rugo_v2(w / 2 - (u - w - h), h / 2);
            nn = rugo_v2(0, 1);
        } else {
            q = rugo_v2(-w / 2, h / 2 - (u - 2 * w - h));
            nn = rugo_v2(-1, 0);
        }
        if (rng) {
            const double j = test_rng_uniform(rng, -jitter, jitter);
            q = rugo_v2_add(q, rugo_v2_scale(j, nn));
        }
        p.push_back(q);
    }
    return p;
}

b2Body* groundBox(b2World& w, float hx, float hy, b2Vec2 at, float mu, float eps = 0.0f) {
    b2BodyDef bd;
    bd.position = at;
    b2Body* g = w.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(hx, hy);
    b2FixtureDef fd;
    fd.shape = &box;
    fd.friction = mu;
    fd.restitution = eps;
    g->CreateFixture(&fd);
    return g;
}

b2Body* dynamicBody(b2World& w, b2Vec2 at, float angle = 0.0f) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position = at;
    bd.angle = angle;
    return w.CreateBody(&bd);
}

rugo::RoughBodyDef roughDef(const rugo_shape* s, double density = 1.0, int level = RUGO_LOD_AUTO) {
    rugo::RoughBodyDef d;
    d.shape = s;
    d.density = density;
    d.lod = level;
    return d;
}

b2Vec2 gravityDownSlope(double degrees) {
    const double t = degrees * kPi / 180.0;
    return b2Vec2(static_cast<float>(9.8 * std::sin(t)), static_cast<float>(-9.8 * std::cos(t)));
}

// Five 1 x 0.5 m rough boxes (32 jittered control points, a constant band, mu 0.6) stacked on the
// ground from y = 0.26 m, attached at the finest level; their shapes go to *shapes.
std::vector<b2Body*> stackFiveRoughBoxes(b2World& w, rugo::Bridge& bridge, test_rng* rng, double band,
                                         std::vector<rugo_shape*>* shapes) {
    std::vector<b2Body*> bodies;
    for (int i = 0; i < 5; ++i) {
        std::vector<double> tol(32, band);
        shapes->push_back(makeShape(rectPoints(32, 1.0, 0.5, rng, 0.003), &tol, 0.6, 0.0));
        b2Body* b = dynamicBody(w, b2Vec2(0.0f, 0.26f + 0.52f * static_cast<float>(i)));
        ck_assert_int_eq(bridge.Attach(b, roughDef(shapes->back(), 1.0, 0)), RUGO_OK);
        bodies.push_back(b);
    }
    return bodies;
}

} // namespace

// ---- rolling disc against a native circle ----------------------------------------------------------
START_TEST(test_disc_rolls_like_circle) {
    const double R = 0.5, mu = 0.6;
    rugo_shape* disc = makeDisc(64, R, mu, 0.0);
    double travelled[2];
    for (int kind = 0; kind < 2; ++kind) {
        b2World w(gravityDownSlope(30.0)); // a 30° incline: gravity rotated, ground flat
        groundBox(w, 200.0f, 1.0f, b2Vec2(0.0f, -1.0f), static_cast<float>(mu));
        rugo::Bridge bridge(&w);
        b2Body* b = dynamicBody(w, b2Vec2(0.0f, static_cast<float>(R + 0.01)));
        const rugo_mass_properties mp = rugo_shape_mass(disc);
        if (kind == 0) {
            ck_assert_int_eq(bridge.Attach(b, roughDef(disc, 1.0, 0)), RUGO_OK);
        } else {
            b2CircleShape c;
            c.m_radius = static_cast<float>(R);
            b2FixtureDef fd;
            fd.shape = &c;
            fd.density = static_cast<float>(mp.area / (kPi * R * R)); // same mass
            fd.friction = static_cast<float>(mu);
            b->CreateFixture(&fd);
        }
        const float x0 = b->GetPosition().x;
        for (int i = 0; i < 120; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        travelled[kind] = static_cast<double>(b->GetPosition().x - x0);
    }
    const double expect = (2.0 / 3.0) * 9.8 * 0.5 * 2.0; // (2/3) g sin30 t^2 / 2
    std::printf("disc: rough %.4f m, circle %.4f m, rolling theory %.4f m, rel diff %.3g\n", travelled[0],
                travelled[1], expect, std::fabs(travelled[0] - travelled[1]) / travelled[1]);
    // 2%: the acceptance bound (the curve's radius varies by ~1e-5 between joints and mid-segments).
    ck_assert(std::fabs(travelled[0] - travelled[1]) <= 0.02 * travelled[1]);
    rugo_shape_destroy(disc);
}
END_TEST

// ---- sliding block stops at v^2 / (2 g (mu cos - sin)) ---------------------------------------------
START_TEST(test_block_stops) {
    const double mu = 0.5, theta = 10.0, v = 5.0;
    rugo_shape* block = makeShape(rectPoints(32, 1.0, 0.5, nullptr, 0.0), nullptr, mu, 0.0);
    b2World w(gravityDownSlope(theta));
    groundBox(w, 200.0f, 1.0f, b2Vec2(0.0f, -1.0f), static_cast<float>(mu));
    rugo::Bridge bridge(&w);
    b2Body* b = dynamicBody(w, b2Vec2(0.0f, 0.26f));
    ck_assert_int_eq(bridge.Attach(b, roughDef(block, 1.0, 0)), RUGO_OK);
    // Settle first, then launch.
    for (int i = 0; i < 30; ++i)
        bridge.Step(1.0f / 60.0f, 8, 3);
    // Settling on the slope slides it a little; measure from the launch.
    b->SetLinearVelocity(b2Vec2(static_cast<float>(v), 0.0f));
    b->SetAngularVelocity(0.0f);
    const float x0 = b->GetPosition().x;
    int steps = 0;
    for (; steps < 600; ++steps) {
        bridge.Step(1.0f / 60.0f, 8, 3);
        if (getenv("DBG_BLOCK") && steps % 5 == 0)
            std::printf("t %.3f x %.4f vx %.4f vy %.4f w %.4f y %.4f ang %.4f dis %ld pts %ld\n",
                        steps / 60.0, b->GetPosition().x - x0, b->GetLinearVelocity().x,
                        b->GetLinearVelocity().y, b->GetAngularVelocity(), b->GetPosition().y, b->GetAngle(),
                        bridge.GetStats().emptyEvaluations, bridge.GetStats().pointsSubmitted);
        if (b->GetLinearVelocity().Length() < 1e-3f) break;
    }
    const double t = theta * kPi / 180.0;
    const double expect = v * v / (2.0 * 9.8 * (mu * std::cos(t) - std::sin(t)));
    const double got = static_cast<double>(b->GetPosition().x - x0);
    std::printf("block: stopped after %.4f m (theory %.4f m), rel diff %.3g, %d steps\n", got, expect,
                std::fabs(got - expect) / expect, steps);
    // 3%: the acceptance bound (Box2D's explicit Euler over ~40 steps and the first step's sliding).
    ck_assert(std::fabs(got - expect) <= 0.03 * expect);
    rugo_shape_destroy(block);
}
END_TEST

// ---- a stack of five rough bodies rests -----------------------------------------------------------
START_TEST(test_stack_rests) {
    test_rng rng = test_rng_seed(5);
    const double band = 0.004;
    std::vector<rugo_shape*> shapes;
    b2World w(b2Vec2(0.0f, -9.8f));
    groundBox(w, 20.0f, 1.0f, b2Vec2(0.0f, -1.0f), 0.6f);
    rugo::Bridge bridge(&w);
    std::vector<b2Body*> bodies = stackFiveRoughBoxes(w, bridge, &rng, band, &shapes);
    std::vector<b2Vec2> settled;
    double maxPen = 0.0, maxPenBand = 0.0;
    rugo_collide_context* ctx = nullptr;
    ck_assert_int_eq(rugo_collide_context_create(nullptr, &ctx), RUGO_OK);
    for (int step = 0; step < 600; ++step) {
        bridge.Step(1.0f / 60.0f, 8, 3);
        if (step == 59)
            for (b2Body* b : bodies)
                settled.push_back(b->GetPosition());
        if (step % 10 != 9) continue;
        for (size_t i = 0; i + 1 < bodies.size(); ++i) {
            rugo_contact c[64];
            int n = 0;
            rugo_contact_state st;
            const b2Transform& xa = bodies[i]->GetTransform();
            const b2Transform& xb = bodies[i + 1]->GetTransform();
            rugo_transform ta = rugo_make_transform(xa.p.x, xa.p.y, xa.q.GetAngle());
            rugo_transform tb = rugo_make_transform(xb.p.x, xb.p.y, xb.q.GetAngle());
            ck_assert_int_eq(
                test_collide_shapes(ctx, shapes[i], ta, shapes[i + 1], tb, nullptr, c, 64, &n, &st, nullptr),
                RUGO_OK);
            for (int k = 0; k < n; ++k) {
                maxPen = std::max(maxPen, -c[k].separation - (c[k].tolerance_a + c[k].tolerance_b));
                maxPenBand = std::max(maxPenBand, -c[k].separation);
            }
        }
    }
    double maxMove = 0.0;
    for (size_t i = 0; i < bodies.size(); ++i)
        maxMove = std::max(maxMove, static_cast<double>((bodies[i]->GetPosition() - settled[i]).Length()));
    std::printf(
        "stack: max movement 1..10 s %.3g m; max band-adjusted penetration %.3g m, max curve penetration "
        "%.3g m (band %.3g, slop %.3g)\n",
        maxMove, maxPen, maxPenBand, 2 * band, static_cast<double>(b2_linearSlop));
    ck_assert(maxMove <= 0.01); // 1 cm: the acceptance bound
    // Curve penetration at most the two bands plus 2 linear slop (Box2D's position solver target).
    ck_assert(maxPenBand <= 2 * band + 2.0 * static_cast<double>(b2_linearSlop));
    rugo_collide_context_destroy(ctx);
    for (rugo_shape* s : shapes)
        rugo_shape_destroy(s);
}
END_TEST

// ---- rough bodies at rest fall asleep ------------------------------------------------------------
// Five banded rough boxes stacked on the ground and a banded rough disc rolling on it (rolling
// resistance from the bands stops it): once at rest they fall asleep as Box2D bodies do (0.5 s below
// its sleep tolerances). The bridge's rolling resistance acts on every step's contacts; it must not wake
// the bodies or restart their sleep timers.
START_TEST(test_rough_bodies_fall_asleep) {
    test_rng rng = test_rng_seed(11);
    const double band = 0.004;
    std::vector<rugo_shape*> shapes;
    b2World w(b2Vec2(0.0f, -9.8f));
    groundBox(w, 20.0f, 1.0f, b2Vec2(0.0f, -1.0f), 0.6f);
    rugo::Bridge bridge(&w);
    std::vector<b2Body*> bodies = stackFiveRoughBoxes(w, bridge, &rng, band, &shapes);
    {
        std::vector<double> tol(64, band);
        std::vector<rugo_vec2> p(64);
        for (int k = 0; k < 64; ++k)
            p[static_cast<size_t>(k)] =
                rugo_v2(0.5 * std::cos(2.0 * kPi * k / 64), 0.5 * std::sin(2.0 * kPi * k / 64));
        shapes.push_back(makeShape(p, &tol, 0.6, 0.0));
        b2Body* disc = dynamicBody(w, b2Vec2(5.0f, 0.52f));
        ck_assert_int_eq(bridge.Attach(disc, roughDef(shapes.back(), 1.0, 0)), RUGO_OK);
        disc->SetLinearVelocity(b2Vec2(0.2f, 0.0f));
        disc->SetAngularVelocity(-0.4f);
        bodies.push_back(disc);
    }
    int asleepAt = -1;
    for (int step = 0; step < 600 && asleepAt < 0; ++step) {
        bridge.Step(1.0f / 60.0f, 8, 3);
        bool any = false;
        for (const b2Body* b : bodies)
            any = any || b->IsAwake();
        if (!any) asleepAt = step + 1;
    }
    std::printf("rest: the stack and the rolling disc all asleep after %d steps\n", asleepAt);
    // Measured: 248 steps; never within the 600 while rolling resistance woke the bodies.
    ck_assert_msg(asleepAt > 0 && asleepAt <= 300, "bodies still awake after 600 steps or slept at %d",
                  asleepAt);
    for (rugo_shape* s : shapes)
        rugo_shape_destroy(s);
}
END_TEST

// ---- fast rough bodies do not tunnel -------------------------------------------------------------
// Random rough stars and a flat ellipse (0.8 x 0.24 m), at four angles and spinning at 0 or +-9 rad/s,
// thrown at 100 m/s against a 1 cm static box or an edge. The wall is 100 m tall so that a body deflected
// sideways cannot go around its end (that is not tunnelling). The curve may enter the wall's skin and
// the body's band (8 mm) but never pass it.
START_TEST(test_fast_body_no_tunnel) {
    int runs = 0, speculative = 0;
    double minGap = 1e9, maxShort = 0.0;
    for (int seed = 1; seed <= 4; ++seed)
        for (int wall = 0; wall < 2; ++wall)
            for (int a = 0; a < 4; ++a)
                for (int spinIndex = 0; spinIndex < 3; ++spinIndex) {
                    test_rng rng = test_rng_seed(static_cast<uint64_t>(seed));
                    std::vector<rugo_vec2> pts(32);
                    if (seed <= 3)
                        test_random_star(&rng, 32, rugo_v2(0, 0), 0.3, 0.3, pts.data());
                    else
                        for (int k = 0; k < 32; ++k)
                            pts[static_cast<size_t>(k)] =
                                rugo_v2(0.4 * std::cos(2 * kPi * k / 32), 0.12 * std::sin(2 * kPi * k / 32));
                    std::vector<double> tol(32);
                    for (double& t : tol)
                        t = test_rng_uniform(&rng, 0.0, 0.004);
                    rugo_shape* s = makeShape(pts, &tol, 0.4, 0.0);
                    b2World w(b2Vec2(0.0f, 0.0f));
                    rugo::Bridge bridge(&w);
                    b2BodyDef bd;
                    bd.position = b2Vec2(5.0f, 0.0f);
                    b2Body* g = w.CreateBody(&bd);
                    if (wall == 0) {
                        b2PolygonShape box; // 1 cm thick
                        box.SetAsBox(0.005f, 50.0f);
                        g->CreateFixture(&box, 0.0f);
                    } else {
                        b2EdgeShape e;
                        e.SetTwoSided(b2Vec2(0.0f, -50.0f), b2Vec2(0.0f, 50.0f));
                        g->CreateFixture(&e, 0.0f);
                    }
                    const float angle = 0.7f * static_cast<float>(a);
                    b2Body* b = dynamicBody(w, b2Vec2(0.0f, 0.1f * static_cast<float>(a)), angle);
                    ck_assert_int_eq(bridge.Attach(b, roughDef(s)), RUGO_OK);
                    b->SetLinearVelocity(b2Vec2(100.0f, 0.0f));
                    b->SetAngularVelocity(spinIndex == 0 ? 0.0f : (spinIndex == 1 ? 9.0f : -9.0f));
                    rugo_contour curve;
                    rugo_shape_level(s, bridge.GetLevel(b), &curve);
                    double gapAtStop = 1e9;
                    for (int i = 0; i < 40; ++i) {
                        bridge.Step(1.0f / 60.0f, 8, 3);
                        // Rightmost point of the true curve (dense samples) against the wall's left face.
                        double xmax = -1e9;
                        const b2Transform& x = b->GetTransform();
                        for (int k = 0; k < curve.count * 16; ++k) {
                            rugo_vec2 p = rugo_contour_point_at(curve, k / 16.0);
                            xmax = std::max(
                                xmax,
                                static_cast<double>(
                                    b2Mul(x, b2Vec2(static_cast<float>(p.x), static_cast<float>(p.y))).x));
                        }
                        const double face = wall == 0 ? 4.995 : 5.0;
                        ck_assert_msg(b->GetPosition().x < 5.0f,
                                      "tunnelled: seed %d wall %d angle %d spin %d", seed, wall, a,
                                      spinIndex);
                        if (getenv("DBG_CCD") && xmax > face)
                            std::printf(
                                "seed %d wall %d angle %d spin %d step %d: past the face by %.3g, v %.3g\n",
                                seed, wall, a, spinIndex, i, xmax - face, b->GetLinearVelocity().x);
                        ck_assert_msg(xmax <= face + 0.01 + 0.008, "through the wall by %.3g", xmax - face);
                        minGap = std::min(minGap, face - xmax);
                        if (i == 0) gapAtStop = face - xmax;
                    }
                    maxShort = std::max(maxShort, gapAtStop);
                    speculative += bridge.GetStats().speculativePoints > 0;
                    ++runs;
                    rugo_shape_destroy(s);
                }
    std::printf(
        "ccd: %d runs at 100 m/s, none through; %d used speculative points; deepest reach past the face "
        "%.3g m; largest gap left after the impact step %.3g m\n",
        runs, speculative, -minGap, maxShort);
}
END_TEST

// ---- listeners and filters chain ------------------------------------------------------------------
namespace {
struct CountingListener : public b2ContactListener {
    const rugo::Bridge* bridge = nullptr;
    int begin = 0, end = 0, pre = 0, post = 0, preRough = 0, preRoughDisabled = 0, preOrdinary = 0,
        badManifold = 0;
    void BeginContact(b2Contact*) override { ++begin; }
    void EndContact(b2Contact*) override { ++end; }
    void PreSolve(b2Contact* c, const b2Manifold*) override {
        ++pre;
        const bool rough = bridge && (bridge->IsProxy(c->GetFixtureA()) || bridge->IsProxy(c->GetFixtureB()));
        if (!rough) {
            ++preOrdinary;
            return;
        }
        ++preRough;
        const b2Manifold* m = c->GetManifold();
        if (!c->IsEnabled()) {
            ++preRoughDisabled;
            if (m->pointCount != 0) ++badManifold;
        } else if (m->pointCount < 1 || (m->type != b2Manifold::e_faceA && m->type != b2Manifold::e_faceB)) {
            ++badManifold;
        }
    }
    void PostSolve(b2Contact*, const b2ContactImpulse*) override { ++post; }
};
struct CountingFilter : public b2ContactFilter {
    int calls = 0;
    bool ShouldCollide(b2Fixture* a, b2Fixture* b) override {
        ++calls;
        return b2ContactFilter::ShouldCollide(a, b);
    }
};
} // namespace

START_TEST(test_listeners_chain) {
    rugo_shape* disc = makeDisc(32, 0.3, 0.5, 0.0);
    b2World w(b2Vec2(0.0f, -9.8f));
    CountingListener user;
    CountingListener later; // set after the bridge below; declared first because it must outlive the bridge
    CountingFilter filter;
    w.SetContactListener(&user);
    w.SetContactFilter(&filter);
    groundBox(w, 10.0f, 1.0f, b2Vec2(0.0f, -1.0f), 0.5f);
    rugo::Bridge bridge(&w);
    user.bridge = &bridge;
    b2Body* rough = dynamicBody(w, b2Vec2(0.0f, 0.35f));
    ck_assert_int_eq(bridge.Attach(rough, roughDef(disc)), RUGO_OK);
    b2Body* box = dynamicBody(w, b2Vec2(3.0f, 0.3f));
    b2PolygonShape p;
    p.SetAsBox(0.25f, 0.25f);
    box->CreateFixture(&p, 1.0f);
    for (int i = 0; i < 60; ++i)
        bridge.Step(1.0f / 60.0f, 8, 3);
    std::printf("listeners: begin %d pre %d (rough %d, of them disabled %d; ordinary %d) post %d filter %d\n",
                user.begin, user.pre, user.preRough, user.preRoughDisabled, user.preOrdinary, user.post,
                filter.calls);
    ck_assert_int_gt(user.begin, 0);
    ck_assert_int_gt(user.preRough, 0);
    ck_assert_int_gt(user.preOrdinary, 0);
    ck_assert_int_gt(user.post, 0);
    ck_assert_int_gt(filter.calls, 0);
    ck_assert_int_eq(user.badManifold, 0); // the user sees the bridge's manifold, never Box2D's box one
    // A listener set on the world after the bridge is chained at the next Step.
    later.bridge = &bridge;
    w.SetContactListener(&later);
    const long before = bridge.GetStats().listenersRechained;
    rough->SetLinearVelocity(b2Vec2(0.5f, 0.0f)); // keep it awake
    for (int i = 0; i < 10; ++i)
        bridge.Step(1.0f / 60.0f, 8, 3);
    ck_assert_int_eq(bridge.GetStats().listenersRechained, before + 1);
    ck_assert_int_gt(later.preRough, 0);
    ck_assert_int_eq(later.badManifold, 0);
    // Destroying the bridge restores the user's listener.
    rugo_shape_destroy(disc);
}
END_TEST

// ---- mass --------------------------------------------------------------------------------------
static void checkMass(const b2Body* b, double m, rugo_vec2 c, double iOrigin, bool fixedRotation) {
    // 1e-6 relative: Box2D stores float (6e-8) and SetMassData subtracts m|c|^2 and adds it back.
    ck_assert_msg(std::fabs(static_cast<double>(b->GetMass()) - m) <= 1e-6 * m, "mass %.9g vs %.9g",
                  static_cast<double>(b->GetMass()), m);
    const double scale = std::sqrt(iOrigin / m);
    ck_assert(std::fabs(static_cast<double>(b->GetLocalCenter().x) - c.x) <= 1e-6 * scale);
    ck_assert(std::fabs(static_cast<double>(b->GetLocalCenter().y) - c.y) <= 1e-6 * scale);
    if (!fixedRotation)
        ck_assert_msg(std::fabs(static_cast<double>(b->GetInertia()) - iOrigin) <= 1e-6 * iOrigin,
                      "I %.9g vs %.9g", static_cast<double>(b->GetInertia()), iOrigin);
}

START_TEST(test_mass_repaired) {
    test_rng rng = test_rng_seed(11);
    std::vector<rugo_vec2> pts(32);
    test_random_star(&rng, 32, rugo_v2(0.2, -0.1), 0.5, 0.3, pts.data());
    rugo_shape* s = makeShape(pts, nullptr, 0.5, 0.0);
    b2World w(b2Vec2(0.0f, -9.8f));
    rugo::Bridge bridge(&w);
    b2Body* b = dynamicBody(w, b2Vec2(1.0f, 2.0f));
    const double rho = 2.5;
    ck_assert_int_eq(bridge.Attach(b, roughDef(s, rho)), RUGO_OK);
    const rugo_mass_properties mp = rugo_shape_mass(s);
    const double m0 = mp.area * rho;
    const double i0 = rho * mp.inertia + m0 * (mp.centroid.x * mp.centroid.x + mp.centroid.y * mp.centroid.y);
    checkMass(b, m0, mp.centroid, i0, false);
    b->SetType(b2_staticBody);
    bridge.Step(1.0f / 60.0f, 8, 3);
    b->SetType(b2_dynamicBody);
    bridge.Step(1.0f / 60.0f, 8, 3);
    checkMass(b, m0, mp.centroid, i0, false);
    // An ordinary fixture with density: exact sum (circle: m = ρ π r², I_origin = m (r²/2 + |p|²)).
    b2CircleShape c;
    c.m_radius = 0.2f;
    c.m_p = b2Vec2(0.5f, 0.0f);
    b2Fixture* f = b->CreateFixture(&c, 3.0f);
    ck_assert_int_eq(bridge.SyncMass(b), RUGO_OK);
    const double r = static_cast<double>(c.m_radius), mc = 3.0 * kPi * r * r;
    const double ic = mc * (r * r / 2 + 0.25);
    const rugo_vec2 cc = rugo_v2((m0 * mp.centroid.x + mc * 0.5) / (m0 + mc), m0 * mp.centroid.y / (m0 + mc));
    checkMass(b, m0 + mc, cc, i0 + ic, false);
    b->DestroyFixture(f);
    bridge.Step(1.0f / 60.0f, 8, 3);
    checkMass(b, m0, mp.centroid, i0, false);
    b->SetFixedRotation(true);
    bridge.Step(1.0f / 60.0f, 8, 3);
    checkMass(b, m0, mp.centroid, i0, true);
    ck_assert(b->GetAngularVelocity() == 0.0f);
    b->SetFixedRotation(false);
    bridge.Step(1.0f / 60.0f, 8, 3);
    checkMass(b, m0, mp.centroid, i0, false);
    b2MassData md;
    ck_assert_int_eq(bridge.GetExactMass(b, &md), RUGO_OK);
    ck_assert(std::fabs(static_cast<double>(md.mass) - m0) <= 1e-6 * m0);
    std::printf("mass: reapplied %ld times\n", bridge.GetStats().massReapplied);
    ck_assert_int_ge(bridge.GetStats().massReapplied, 4);
    rugo_shape_destroy(s);
}
END_TEST

// ---- lifetime ------------------------------------------------------------------------------------
namespace {
struct LockedAttach : public b2ContactListener {
    rugo::Bridge* bridge = nullptr;
    b2Body* other = nullptr;
    const rugo_shape* shape = nullptr;
    int attachStatus = -1, detachStatus = -1;
    void PreSolve(b2Contact* c, const b2Manifold*) override {
        if (attachStatus >= 0) return;
        attachStatus = bridge->Attach(other, roughDef(shape));
        detachStatus = bridge->Detach(bridge->IsProxy(c->GetFixtureA()) ? c->GetFixtureA()->GetBody()
                                                                        : c->GetFixtureB()->GetBody());
    }
};
struct Goodbyes : public b2DestructionListener {
    int fixtures = 0;
    void SayGoodbye(b2Joint*) override {}
    void SayGoodbye(b2Fixture*) override { ++fixtures; }
};
} // namespace

START_TEST(test_lifetime) {
    rugo_shape* disc = makeDisc(32, 0.3, 0.5, 0.0);
    { // Detach, DestroyBody, attach twice, bad arguments.
        b2World w(b2Vec2(0.0f, -9.8f));
        Goodbyes bye;
        rugo::BridgeDef bdef;
        bdef.destructionListener = &bye;
        rugo::Bridge bridge(&w, bdef);
        b2Body* a = dynamicBody(w, b2Vec2(0, 0));
        b2Body* b = dynamicBody(w, b2Vec2(0, 1));
        ck_assert_int_eq(bridge.Attach(a, roughDef(disc)), RUGO_OK);
        ck_assert_int_eq(bridge.Attach(a, roughDef(disc)), RUGO_ERR_ALREADY_ATTACHED);
        ck_assert_str_eq(bridge.LastError(), "body: already has a rough shape; Detach it first");
        ck_assert_int_eq(bridge.Attach(nullptr, roughDef(disc)), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_str_eq(bridge.LastError(), "body: is null");
        ck_assert_int_eq(bridge.Attach(b, roughDef(nullptr)), RUGO_ERR_NULL_ARGUMENT);
        ck_assert_msg(std::strstr(bridge.LastError(), "RoughBodyDef::shape: is null; build one") != nullptr,
                      "%s", bridge.LastError());
        ck_assert_int_eq(bridge.Attach(b, roughDef(disc, 0.0)), RUGO_ERR_BAD_ARGUMENT);
        // the message names the field, the value and a way out
        ck_assert_msg(std::strstr(bridge.LastError(), "RoughBodyDef::density: is 0;") != nullptr &&
                          std::strstr(bridge.LastError(), "kg/m^2") != nullptr,
                      "%s", bridge.LastError());
        rugo::RoughBodyDef bad = roughDef(disc);
        bad.maxProxies = 99;
        ck_assert_int_eq(bridge.Attach(b, bad), RUGO_ERR_BAD_ARGUMENT);
        ck_assert_msg(std::strstr(bridge.LastError(), "RoughBodyDef::maxProxies: is 99;") != nullptr, "%s",
                      bridge.LastError());
        // a 100 km rough body is refused, naming its size
        rugo_shape* huge = makeDisc(32, 5e4, 0.5, 0.0);
        ck_assert_int_eq(bridge.Attach(b, roughDef(huge)), RUGO_ERR_BAD_SIZE);
        ck_assert_msg(std::strstr(bridge.LastError(), "RoughBodyDef::shape: is 1") != nullptr &&
                          std::strstr(bridge.LastError(), "kMaxBodySize") != nullptr,
                      "%s", bridge.LastError());
        rugo_shape_destroy(huge);
        ck_assert_int_eq(bridge.Attach(b, roughDef(disc)), RUGO_OK);
        ck_assert_str_eq(bridge.LastError(), "");
        ck_assert_int_eq(bridge.Detach(b), RUGO_OK);
        ck_assert(!bridge.IsRough(b));
        ck_assert(b->GetFixtureList() == nullptr);
        ck_assert_int_eq(bridge.Detach(b), RUGO_ERR_NOT_ATTACHED);
        for (int i = 0; i < 5; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        w.DestroyBody(a);
        ck_assert(!bridge.IsRough(a));
        ck_assert_int_gt(bye.fixtures, 0); // the user's destruction listener is chained
        for (int i = 0; i < 5; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
    }
    { // Bridge destroyed before the world: proxies removed, callbacks restored.
        b2World w(b2Vec2(0.0f, -9.8f));
        CountingListener user;
        w.SetContactListener(&user);
        b2Body* a = dynamicBody(w, b2Vec2(0, 0));
        {
            rugo::Bridge bridge(&w);
            ck_assert_int_eq(bridge.Attach(a, roughDef(disc)), RUGO_OK);
            bridge.Step(1.0f / 60.0f, 8, 3);
        }
        ck_assert(a->GetFixtureList() == nullptr);
        ck_assert(w.GetContactManager().m_contactListener == &user);
        w.Step(1.0f / 60.0f, 8, 3);
    }
    { // World destroyed first, then ReleaseWorld.
        b2World* w = new b2World(b2Vec2(0.0f, -9.8f));
        rugo::Bridge bridge(w);
        groundBox(*w, 5.0f, 1.0f, b2Vec2(0.0f, -1.0f), 0.5f);
        b2Body* a = dynamicBody(*w, b2Vec2(0, 0.3f));
        ck_assert_int_eq(bridge.Attach(a, roughDef(disc)), RUGO_OK);
        bridge.Step(1.0f / 60.0f, 8, 3);
        delete w;
        bridge.ReleaseWorld();
        ck_assert(bridge.GetWorld() == nullptr);
    }
    { // Attach/Detach inside a callback.
        b2World w(b2Vec2(0.0f, -9.8f));
        LockedAttach
            l; // chained listeners must outlive the bridge (its destructor still forwards EndContact)
        rugo::Bridge bridge(&w);
        groundBox(w, 5.0f, 1.0f, b2Vec2(0.0f, -1.0f), 0.5f);
        b2Body* a = dynamicBody(w, b2Vec2(0, 0.3f));
        b2Body* other = dynamicBody(w, b2Vec2(3, 3));
        ck_assert_int_eq(bridge.Attach(a, roughDef(disc)), RUGO_OK);
        l.bridge = &bridge;
        l.other = other;
        l.shape = disc;
        w.SetContactListener(&l);
        for (int i = 0; i < 30; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        ck_assert_int_eq(l.attachStatus, RUGO_ERR_WORLD_LOCKED);
        ck_assert_int_eq(l.detachStatus, RUGO_ERR_WORLD_LOCKED);
    }
    rugo_shape_destroy(disc);
}
END_TEST

// ---- hardening (an API review, 2026-11-22): each case aborted, crashed or gave NaN before -------
namespace {
// Forwards every callback to the listener it replaced (the bridge), as listener chains often do.
struct Forwarding : public b2ContactListener {
    b2ContactListener* next = nullptr;
    int depth = 0, maxDepth = 0, pre = 0, begin = 0;
    void BeginContact(b2Contact* c) override {
        ++begin;
        if (next) next->BeginContact(c);
    }
    void EndContact(b2Contact* c) override {
        if (next) next->EndContact(c);
    }
    void PreSolve(b2Contact* c, const b2Manifold* m) override {
        ++pre;
        maxDepth = std::max(maxDepth, ++depth);
        if (next && depth < 100) next->PreSolve(c, m); // (the cap only keeps a failing test finite)
        --depth;
    }
    void PostSolve(b2Contact* c, const b2ContactImpulse* i) override {
        if (next) next->PostSolve(c, i);
    }
};
// Detaches a body from EndContact, which Box2D also raises outside Step (DestroyBody, SetEnabled).
struct DetachOnEnd : public b2ContactListener {
    rugo::Bridge* bridge = nullptr;
    b2Body* victim = nullptr;
    int status = -1;
    void EndContact(b2Contact*) override {
        if (victim == nullptr) return;
        b2Body* v = victim;
        victim = nullptr;
        status = bridge->Detach(v);
    }
};
} // namespace

START_TEST(test_bridge_hardening) {
    rugo_shape* disc = makeDisc(32, 0.3, 0.5, 0.0);
    rugo_shape* block = makeShape(rectPoints(32, 0.6, 0.3, nullptr, 0.0), nullptr, 0.4, 0.0);
    { // Densities whose mass or inertia leaves Box2D's floats (1e40 aborted in SetMassData, 1e39 gave
        // NaN poses, 1e-50 a mass of 0): BAD_ARGUMENT. RayCast of zero length or NaN (Box2D asserts).
        b2World w(b2Vec2(0.0f, -9.8f));
        rugo::Bridge bridge(&w);
        b2Body* a = dynamicBody(w, b2Vec2(0, 1));
        for (double d : {1e40, 1e39, 1e-50})
            ck_assert_int_eq(bridge.Attach(a, roughDef(disc, d)), RUGO_ERR_BAD_ARGUMENT);
        ck_assert_int_eq(bridge.Attach(a, roughDef(disc, 1e3)), RUGO_OK);
        rugo::RayHit hit;
        ck_assert(!bridge.RayCast(b2Vec2(0, 1), b2Vec2(0, 1), &hit));
        ck_assert(!bridge.RayCast(b2Vec2(NAN, 1), b2Vec2(0, 1), &hit));
        ck_assert(bridge.RayCast(b2Vec2(-2, 1), b2Vec2(2, 1), &hit)); // and a real ray still hits
        ck_assert(hit.body == a);
    }
    { // An unknown pointFrictionMix falls back to the default (it gave NaN friction).
        b2World w(b2Vec2(0.0f, -9.8f));
        rugo::BridgeDef def;
        const int seven = 7;
        std::memcpy(&def.pointFrictionMix, &seven, sizeof seven);
        rugo::Bridge bridge(&w, def);
        groundBox(w, 5.0f, 0.5f, b2Vec2(0.0f, -0.5f), 0.5f);
        b2Body* a = dynamicBody(w, b2Vec2(0, 0.16f));
        ck_assert_int_eq(bridge.Attach(a, roughDef(block)), RUGO_OK);
        int twoPoint = 0;
        for (int i = 0; i < 30; ++i) {
            bridge.Step(1.0f / 60.0f, 8, 3);
            for (b2Contact* c = w.GetContactList(); c; c = c->GetNext()) {
                ck_assert(std::isfinite(c->GetFriction()));
                twoPoint += c->IsTouching() && c->GetManifold()->pointCount == 2;
            }
        }
        ck_assert_int_gt(twoPoint, 0);
        ck_assert(std::isfinite(a->GetPosition().y) && a->GetPosition().y > 0.1f);
    }
    { // Detach from an EndContact that DestroyBody raises outside Step: WORLD_LOCKED (it returned OK,
        // then Box2D crashed in b2Contact::Destroy).
        b2World w(b2Vec2(0.0f, -9.8f));
        DetachOnEnd l;
        w.SetContactListener(&l);
        rugo::Bridge bridge(&w);
        groundBox(w, 5.0f, 0.5f, b2Vec2(0.0f, -0.5f), 0.5f);
        b2Body* a = dynamicBody(w, b2Vec2(-0.5f, 0.35f));
        b2Body* b = dynamicBody(w, b2Vec2(0.5f, 0.35f));
        ck_assert_int_eq(bridge.Attach(a, roughDef(disc)), RUGO_OK);
        ck_assert_int_eq(bridge.Attach(b, roughDef(disc)), RUGO_OK);
        for (int i = 0; i < 30; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        l.bridge = &bridge;
        l.victim = a;
        w.DestroyBody(a); // ends a's contact with the ground outside Step
        ck_assert_int_eq(l.status, RUGO_ERR_WORLD_LOCKED);
        ck_assert(!bridge.IsRough(a));
        ck_assert(bridge.IsRough(b));
        for (int i = 0; i < 10; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        ck_assert_int_eq(bridge.Detach(b), RUGO_OK); // and outside any callback Detach works
    }
    { // A listener that forwards to the one it replaced (the bridge): no recursion (it overflowed the
        // stack), and both see the callbacks.
        b2World w(b2Vec2(0.0f, -9.8f));
        groundBox(w, 5.0f, 0.5f, b2Vec2(0.0f, -0.5f), 0.5f);
        Forwarding f; // outlives the bridge, which chains to it from the first Step on
        rugo::Bridge bridge(&w);
        b2Body* a = dynamicBody(w, b2Vec2(0, 0.35f));
        ck_assert_int_eq(bridge.Attach(a, roughDef(disc)), RUGO_OK);
        f.next = w.GetContactManager().m_contactListener;
        w.SetContactListener(&f);
        for (int i = 0; i < 30; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        ck_assert_int_eq(f.maxDepth, 1);
        ck_assert_int_gt(f.pre, 0);
        ck_assert_int_gt(bridge.GetStats().preSolves, 0);
        ck_assert(a->GetPosition().y > 0.25f && a->GetPosition().y < 0.35f); // resting on the ground
    }
    { // A second bridge on the same world is inert; the first keeps working.
        b2World w(b2Vec2(0.0f, -9.8f));
        rugo::Bridge first(&w);
        b2Body* a = dynamicBody(w, b2Vec2(0, 1));
        {
            rugo::Bridge second(&w);
            ck_assert(second.GetWorld() == nullptr);
            ck_assert_int_eq(second.Attach(a, roughDef(disc)), RUGO_ERR_BAD_ARGUMENT);
        }
        ck_assert_int_eq(first.Attach(a, roughDef(disc)), RUGO_OK);
        w.DestroyBody(a);
        ck_assert(!first.IsRough(a));
        first.Step(1.0f / 60.0f, 8, 3);
    }
    rugo_shape_destroy(block);
    rugo_shape_destroy(disc);
}
END_TEST

// ---- memory and sharing ------------------------------------------------------------------------
START_TEST(test_memory_and_sharing) {
    rugo_shape* disc = makeDisc(64, 0.3, 0.5, 0.0);
    b2World w(b2Vec2(0.0f, -9.8f));
    rugo::Bridge bridge(&w);
    b2Body* a = dynamicBody(w, b2Vec2(0, 0));
    b2Body* b = dynamicBody(w, b2Vec2(2, 0));
    ck_assert_int_eq(bridge.Attach(a, roughDef(disc)), RUGO_OK);
    ck_assert_int_eq(bridge.Attach(b, roughDef(disc)), RUGO_OK);
    ck_assert_ptr_eq(bridge.GetShape(a), bridge.GetShape(b));
    rugo::BodyMemory ma = bridge.GetBodyMemory(a), mb = bridge.GetBodyMemory(b);
    std::printf(
        "memory: per rough body %zu bytes bridge + %zu bytes Box2D (%d proxies); shared shape %zu bytes\n",
        ma.bridgeBytes, ma.box2dBytes, ma.proxyCount, ma.sharedShapeBytes);
    ck_assert_int_gt(static_cast<long>(ma.bridgeBytes), 0);
    ck_assert_int_gt(static_cast<long>(ma.box2dBytes), 0);
    ck_assert_int_eq(ma.proxyCount, bridge.GetProxyCount(a));
    ck_assert_int_eq(ma.proxyCount, 1); // a disc is convex: one proxy
    ck_assert_int_eq(static_cast<long>(ma.sharedShapeBytes), static_cast<long>(mb.sharedShapeBytes));
    ck_assert_int_eq(bridge.GetBodyMemory(nullptr).proxyCount, 0);
    rugo_shape_destroy(disc);
}
END_TEST

// ---- manifold encoding, ids and warm starting ----------------------------------------------------
namespace {
struct ManifoldChecker : public b2ContactListener {
    rugo::Bridge* bridge = nullptr;
    rugo_collide_context* ctx = nullptr;
    int checked = 0, warm = 0, speculativeSeen = 0, completed = 0;
    double maxSepErr = 0.0, maxNormalErr = 0.0, maxCompletedAngle = 0.0;
    std::vector<uint32> lastKeys;
    int persisted = 0;
    void PreSolve(b2Contact* c, const b2Manifold*) override {
        b2Fixture* fa = c->GetFixtureA();
        b2Fixture* fb = c->GetFixtureB();
        const bool pa = bridge->IsProxy(fa), pb = bridge->IsProxy(fb);
        if (!(pa || pb) || !c->IsEnabled()) return;

        b2WorldManifold wm;
        c->GetWorldManifold(&wm);
        const b2Manifold* m = c->GetManifold();
        // librugo's answer at the same poses, in Box2D's A -> B orientation.
        rugo_contact k[64];
        int n = 0;
        rugo_contact_state st;
        rugo_contact_query q = test_exact_query();
        q.margin = 1.0; // a superset of the bridge's (speculative) query; the same minima, the same values
        const b2Body* bA = fa->GetBody();
        const b2Body* bB = fb->GetBody();
        auto tr = [](const b2Transform& x) {
            rugo_transform t;
            t.p = rugo_v2(x.p.x, x.p.y);
            double l = std::hypot(static_cast<double>(x.q.c), static_cast<double>(x.q.s));
            t.q.c = x.q.c / l;
            t.q.s = x.q.s / l;
            return t;
        };
        bool flip = false;
        if (pa && pb) {
            q.lod = 0;
            ck_assert_int_eq(test_collide_shapes(ctx, bridge->GetShape(bA), tr(bA->GetTransform()),
                                                 bridge->GetShape(bB), tr(bB->GetTransform()), &q, k, 64, &n,
                                                 &st, nullptr),
                             RUGO_OK);
        } else {
            const b2Body* rb = pa ? bA : bB;
            const b2Fixture* of = pa ? fb : fa;
            const b2CircleShape* cs = static_cast<const b2CircleShape*>(of->GetShape());
            b2Vec2 cw = b2Mul(of->GetBody()->GetTransform(), cs->m_p);
            q.lod = 0;
            ck_assert_int_eq(test_collide_circle(ctx, bridge->GetShape(rb), tr(rb->GetTransform()),
                                                 rugo_v2(cw.x, cw.y), cs->m_radius, &q, k, 64, &n, &st,
                                                 nullptr),
                             RUGO_OK);
            flip = !pa;
        }
        // Point 0 is the deepest point owned by this proxy pair: find it among librugo's contacts.
        double best = 1e9;
        int bi = -1;
        for (int i = 0; i < n; ++i) {
            const double s = k[i].separation - k[i].tolerance_a - k[i].tolerance_b;
            rugo_vec2 nn = flip ? rugo_v2_scale(-1.0, k[i].normal) : k[i].normal;
            const double e =
                std::fabs(s - static_cast<double>(wm.separations[0])) +
                std::hypot(nn.x - static_cast<double>(wm.normal.x), nn.y - static_cast<double>(wm.normal.y));
            if (e < best) {
                best = e;
                bi = i;
            }
        }
        ck_assert_int_ge(bi, 0);
        // The same point along the surface (tangential offset; along n the bands shift it).
        const rugo_vec2 pk = flip ? k[bi].point_a : k[bi].point_b;
        const double tang =
            std::fabs((static_cast<double>(wm.points[0].x) - pk.x) * static_cast<double>(wm.normal.y) -
                      (static_cast<double>(wm.points[0].y) - pk.y) * static_cast<double>(wm.normal.x));
        if (best > 1e-3 || tang > 1e-3) {
            // Led by a point the patch builder added (a flat face's end, the band-adjusted deepest
            // point beside a contact) or by the mean normal of merged regions (docs/box2d.md, "Which
            // points"), not by one librugo contact: its normal lies within the merge angle (30 degrees)
            // of one of librugo's contacts.
            ++completed;
            double angle = 180.0;
            for (int i = 0; i < n; ++i) {
                const rugo_vec2 nn = flip ? rugo_v2_scale(-1.0, k[i].normal) : k[i].normal;
                const double dot =
                    nn.x * static_cast<double>(wm.normal.x) + nn.y * static_cast<double>(wm.normal.y);
                angle = std::min(angle, std::acos(std::max(-1.0, std::min(1.0, dot))) * 180.0 / kPi);
            }
            maxCompletedAngle = std::max(maxCompletedAngle, angle);
            return;
        }
        const double s0 = k[bi].separation - k[bi].tolerance_a - k[bi].tolerance_b;
        rugo_vec2 n0 = flip ? rugo_v2_scale(-1.0, k[bi].normal) : k[bi].normal;
        maxSepErr = std::max(maxSepErr, std::fabs(s0 - static_cast<double>(wm.separations[0])));
        maxNormalErr = std::max(maxNormalErr, std::hypot(n0.x - static_cast<double>(wm.normal.x),
                                                         n0.y - static_cast<double>(wm.normal.y)));
        speculativeSeen += s0 > 0.0;
        ++checked;
        for (int i = 0; i < m->pointCount; ++i) {
            if (m->points[i].normalImpulse > 0.0f) ++warm;
            for (uint32 key : lastKeys)
                if (key == m->points[i].id.key) {
                    ++persisted;
                    break;
                }
        }
        lastKeys.clear();
        for (int i = 0; i < m->pointCount; ++i)
            lastKeys.push_back(m->points[i].id.key);
    }
};
} // namespace

START_TEST(test_manifold_encoding) {
    test_rng rng = test_rng_seed(3);
    std::vector<rugo_vec2> pts(32);
    test_random_star(&rng, 32, rugo_v2(0, 0), 0.4, 0.2, pts.data());
    std::vector<double> tol(32);
    for (double& t : tol)
        t = test_rng_uniform(&rng, 0.0, 0.003);
    rugo_shape* s = makeShape(pts, &tol, 0.5, 0.0);
    rugo_collide_context* ctx = nullptr;
    ck_assert_int_eq(rugo_collide_context_create(nullptr, &ctx), RUGO_OK);
    // Every pair searched every step (reuseDistance 0) against the exact query to float precision; with
    // the default kept answers (reused while the pair moves by at most r = 1.25 mm) to within 2r.
    for (int run = 0; run < 4; ++run) {
        const int pair = run % 2;
        const bool exact = run < 2;
        b2World w(b2Vec2(0.0f, -9.8f));
        ManifoldChecker chk; // outlives the bridge, which chains to it
        rugo::BridgeDef bdef;
        if (exact) bdef.reuseDistance = 0.0;
        rugo::Bridge bridge(&w, bdef);
        chk.bridge = &bridge;
        chk.ctx = ctx;
        w.SetContactListener(&chk);
        b2BodyDef sd;
        b2Body* below = w.CreateBody(&sd);
        if (pair == 0) {
            b2CircleShape c; // rough body resting on a static circle
            c.m_radius = 1.0f;
            c.m_p = b2Vec2(0.0f, -1.0f);
            below->CreateFixture(&c, 0.0f);
        } else {
            ck_assert_int_eq(bridge.Attach(below, roughDef(s, 1.0, 0)), RUGO_OK); // static rough body
        }
        b2Body* top = dynamicBody(w, b2Vec2(0.0f, pair == 0 ? 0.45f : 0.85f), 0.3f);
        ck_assert_int_eq(bridge.Attach(top, roughDef(s, 1.0, 0)), RUGO_OK);
        for (int i = 0; i < 90; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        std::printf(
            "manifold %s, %s: %d checked against librugo (and %d led by a completed point), max |ds| %.3g m, "
            "max |dn| %.3g; %d points warm-started, %d ids persisted; completed points' normals within %.3g "
            "deg of a contact's; %ld of %ld queries answered from the kept answer\n",
            pair == 0 ? "rough-circle" : "rough-rough", exact ? "searched every step" : "kept answers",
            chk.checked, chk.completed, chk.maxSepErr, chk.maxNormalErr, chk.warm, chk.persisted,
            chk.maxCompletedAngle, bridge.GetStats().queriesReused, bridge.GetStats().queries);
        if (exact) {
            ck_assert(chk.completed <= chk.checked);
            ck_assert_int_gt(chk.checked, 10);
            // Float precision of Box2D's manifold (positions ~1 m: 1e-7 relative, a few roundings).
            ck_assert(chk.maxSepErr <= 2e-5);
            ck_assert(chk.maxNormalErr <= 2e-5);
            ck_assert_int_eq(bridge.GetStats().queriesReused, 0);
        } else {
            ck_assert_int_gt(chk.checked + chk.completed, 10);
            ck_assert(chk.maxSepErr <= 2.0 * bdef.reuseDistance);
            ck_assert(chk.maxNormalErr <= 0.05);
            ck_assert_int_gt(bridge.GetStats().queriesReused, 0);
        }
        ck_assert(chk.maxCompletedAngle <= 30.0); // within the merge angle of a region
        ck_assert_int_gt(chk.warm, 10);
        ck_assert_int_gt(chk.persisted, 10);
    }
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(s);
}
END_TEST

// ---- queries --------------------------------------------------------------------------------
START_TEST(test_queries) {
    rugo_shape* disc = makeDisc(32, 0.5, 0.5, 0.0);
    b2World w(b2Vec2(0.0f, 0.0f));
    rugo::Bridge bridge(&w);
    b2Body* a = dynamicBody(w, b2Vec2(2.0f, 0.0f));
    ck_assert_int_eq(bridge.Attach(a, roughDef(disc, 1.0, 0)), RUGO_OK);
    b2Body* o = dynamicBody(w, b2Vec2(5.0f, 0.0f));
    b2PolygonShape p;
    p.SetAsBox(0.25f, 0.25f);
    o->CreateFixture(&p, 1.0f);
    rugo::RayHit hit;
    ck_assert(bridge.RayCast(b2Vec2(0.0f, 0.0f), b2Vec2(10.0f, 0.0f), &hit));
    ck_assert_ptr_eq(hit.body, a);
    ck_assert(std::fabs(hit.point.x - 1.5f) <
              1e-4f); // the curve's radius is 0.5 at the joints (~1e-4 between)
    ck_assert(hit.normal.x < -0.999f);
    ck_assert(bridge.RayCast(b2Vec2(2.0f, 0.0f), b2Vec2(10.0f, 0.0f), &hit)); // from inside the proxies
    ck_assert_ptr_eq(hit.body, a);
    ck_assert(bridge.RayCast(b2Vec2(3.0f, 0.0f), b2Vec2(10.0f, 0.0f), &hit));
    ck_assert_ptr_eq(hit.body, o);
    ck_assert_int_eq(hit.segment, -1);
    ck_assert(!bridge.RayCast(b2Vec2(0.0f, 3.0f), b2Vec2(10.0f, 3.0f), &hit));
    ck_assert(bridge.TestPoint(a, b2Vec2(2.4f, 0.0f)));
    ck_assert(!bridge.TestPoint(a, b2Vec2(2.4f, 0.4f))); // inside the proxy boxes, outside the curve
    int found = 0;
    b2AABB box;
    box.lowerBound = b2Vec2(2.37f, 0.37f); // a corner region of the boxes the curve does not reach
    box.upperBound = b2Vec2(2.45f, 0.45f);
    bridge.QueryAABB(box, [&](b2Body*) {
        ++found;
        return true;
    });
    ck_assert_int_eq(found, 0);
    box.lowerBound = b2Vec2(1.0f, -1.0f);
    box.upperBound = b2Vec2(6.0f, 1.0f);
    found = 0;
    bridge.QueryAABB(box, [&](b2Body*) {
        ++found;
        return true;
    });
    ck_assert_int_eq(found, 2);
    rugo_shape_destroy(disc);
}
END_TEST

// ---- one region, one normal (regression: rough body vs circle overlap) ----------------------------
// A rough star and a dynamic circle start 0.1 m into each other and are pushed together. librugo
// reports one intersecting region; every manifold the bridge submits for the body pair (through any
// of the proxy pairs that overlap the circle) must carry that region's normal, so the overlap shrinks.
// Before the fix, proxy pairs without a librugo contact made manifolds from their joints' own
// closest-point directions (up to ~90 degrees off), which pushed the circle further in.
namespace {
struct RegionNormalChecker : public b2ContactListener {
    rugo::Bridge* bridge = nullptr;
    rugo_collide_context* ctx = nullptr;
    const b2Body* rough = nullptr;
    const b2Body* circle = nullptr;
    double radius = 0.0;
    double maxAngle = 0.0; // degrees, between a submitted normal and librugo's deepest region normal
    int manifolds = 0;
    void PreSolve(b2Contact* c, const b2Manifold*) override {
        const b2Body* bA = c->GetFixtureA()->GetBody();
        const b2Body* bB = c->GetFixtureB()->GetBody();
        if (!((bA == rough && bB == circle) || (bA == circle && bB == rough))) return;
        if (!c->IsEnabled() || c->GetManifold()->pointCount == 0) return;
        rugo_contact k[16];
        int n = 0;
        rugo_contact_state st;
        const b2Transform& xr = rough->GetTransform();
        rugo_transform t;
        t.p = rugo_v2(xr.p.x, xr.p.y);
        const double l = std::hypot(static_cast<double>(xr.q.c), static_cast<double>(xr.q.s));
        t.q.c = xr.q.c / l;
        t.q.s = xr.q.s / l;
        const b2Vec2 cc = circle->GetWorldCenter();
        ck_assert_int_eq(test_collide_circle(ctx, bridge->GetShape(rough), t, rugo_v2(cc.x, cc.y), radius,
                                             nullptr, k, 16, &n, &st, nullptr),
                         RUGO_OK);
        if (n == 0) return; // a speculative point (checked by the other tests)
        int d = 0;
        for (int i = 1; i < n; ++i)
            if (k[i].separation < k[d].separation) d = i;
        b2WorldManifold wm;
        c->GetWorldManifold(&wm);
        const double sgn = bA == rough ? 1.0 : -1.0; // librugo: rough -> circle
        const double dot = sgn * (k[d].normal.x * static_cast<double>(wm.normal.x) +
                                  k[d].normal.y * static_cast<double>(wm.normal.y));
        maxAngle = std::max(maxAngle, std::acos(std::max(-1.0, std::min(1.0, dot))) * 180.0 / kPi);
        ++manifolds;
    }
};
} // namespace

START_TEST(test_circle_overlap_one_normal) {
    test_rng rng = test_rng_seed(7);
    std::vector<rugo_vec2> pts(32);
    test_random_star(&rng, 32, rugo_v2(0, 0), 0.4, 0.2, pts.data());
    std::vector<double> tol(32);
    for (double& t : tol)
        t = test_rng_uniform(&rng, 0.0, 0.003);
    rugo_shape* s = makeShape(pts, &tol, 0.5, 0.0);
    rugo_collide_context* ctx = nullptr;
    ck_assert_int_eq(rugo_collide_context_create(nullptr, &ctx), RUGO_OK);
    const double R = 0.25;
    auto depth = [&](const b2Body* rb, b2Vec2 cc) {
        const b2Transform& x = rb->GetTransform();
        rugo_transform t = rugo_make_transform(x.p.x, x.p.y, rb->GetAngle());
        rugo_contact k[16];
        int n = 0;
        rugo_contact_state st;
        ck_assert_int_eq(
            test_collide_circle(ctx, s, t, rugo_v2(cc.x, cc.y), R, nullptr, k, 16, &n, &st, nullptr),
            RUGO_OK);
        double d = 0.0;
        for (int i = 0; i < n; ++i)
            d = std::max(d, -(k[i].separation - k[i].tolerance_a - k[i].tolerance_b));
        return d;
    };
    int cases = 0;
    double worstAngle = 0.0, worstGrowth = 0.0, worstEnd = 0.0;
    for (int dir = 0; dir < 8; ++dir) {
        const double a = 2.0 * kPi * dir / 8.0 + 0.3;
        const b2Vec2 u(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)));
        b2World w(b2Vec2(0.0f, 0.0f));
        RegionNormalChecker chk;
        rugo::Bridge bridge(&w);
        chk.bridge = &bridge;
        chk.ctx = ctx;
        chk.radius = R;
        w.SetContactListener(&chk);
        b2Body* rough = dynamicBody(w, b2Vec2(0.0f, 0.0f));
        ck_assert_int_eq(bridge.Attach(rough, roughDef(s, 1.0, 0)), RUGO_OK);
        // The circle along u, 0.1 m into the rough body (bisection on librugo's depth).
        double lo = 0.0, hi = 1.2;
        for (int it = 0; it < 40; ++it) {
            const double mid = 0.5 * (lo + hi);
            (depth(rough, static_cast<float>(mid) * u) > 0.1 ? lo : hi) = mid;
        }
        b2Body* circle = dynamicBody(w, static_cast<float>(hi) * u);
        b2CircleShape cs;
        cs.m_radius = static_cast<float>(R);
        circle->CreateFixture(&cs, 1.0f);
        chk.rough = rough;
        chk.circle = circle;
        double prev = depth(rough, circle->GetWorldCenter());
        const double start = prev;
        for (int i = 0; i < 120; ++i) {
            // Pressed together: equal and opposite forces along the line of centres.
            b2Vec2 d = circle->GetWorldCenter() - rough->GetWorldCenter();
            d.Normalize();
            circle->ApplyForceToCenter(-2.0f * d, true);
            rough->ApplyForceToCenter(2.0f * d, true);
            bridge.Step(1.0f / 60.0f, 8, 3);
            const double now = depth(rough, circle->GetWorldCenter());
            worstGrowth = std::max(worstGrowth, now - prev);
            prev = now;
        }
        worstEnd = std::max(worstEnd, prev);
        worstAngle = std::max(worstAngle, chk.maxAngle);
        ck_assert_int_gt(chk.manifolds, 10);
        ck_assert(start > 0.09);
        ++cases;
    }
    std::printf("circle overlap: %d directions from 0.1 m deep; largest growth in a step %.4f m, largest "
                "depth after 2 s "
                "%.4f m; submitted normals within %.2f deg of librugo's region normal\n",
                cases, worstGrowth, worstEnd, worstAngle);
    ck_assert(worstAngle <= 10.0);              // one region, one normal (joints take the region's)
    ck_assert(worstGrowth <= b2_linearSlop);    // the overlap never grows
    ck_assert(worstEnd <= 2.0 * b2_linearSlop); // and resolves to Box2D's resting penetration
    rugo_collide_context_destroy(ctx);
    rugo_shape_destroy(s);
}
END_TEST

// ---- sensors, kinematic bodies, chains, debug draw ------------------------------------------------
namespace {
struct SensorCounter : public b2ContactListener {
    int begin = 0, end = 0, preSensor = 0;
    static bool sensor(const b2Contact* c) {
        return c->GetFixtureA()->IsSensor() || c->GetFixtureB()->IsSensor();
    }
    void BeginContact(b2Contact* c) override { begin += sensor(c); }
    void EndContact(b2Contact* c) override { end += sensor(c); }
    void PreSolve(b2Contact* c, const b2Manifold*) override { preSensor += sensor(c); }
};
} // namespace

// A static rough sensor: a box falls through it (no response), Box2D reports begin and end, and the
// bridge never writes a manifold for it (Box2D calls no PreSolve for sensors).
START_TEST(test_sensor) {
    rugo_shape* disc = makeDisc(32, 0.5, 0.5, 0.0);
    b2World w(b2Vec2(0.0f, -9.8f));
    SensorCounter counter; // outlives the bridge
    w.SetContactListener(&counter);
    groundBox(w, 5.0f, 1.0f, b2Vec2(0.0f, -1.0f), 0.5f);
    rugo::Bridge bridge(&w);
    b2BodyDef sd;
    sd.position.Set(0.0f, 1.5f);
    b2Body* sensorBody = w.CreateBody(&sd);
    rugo::RoughBodyDef rd = roughDef(disc, 1.0, 0);
    rd.isSensor = true;
    ck_assert_int_eq(bridge.Attach(sensorBody, rd), RUGO_OK);
    for (b2Fixture* f = sensorBody->GetFixtureList(); f; f = f->GetNext())
        ck_assert(f->IsSensor());
    b2Body* box = dynamicBody(w, b2Vec2(0.0f, 3.0f));
    b2PolygonShape p;
    p.SetAsBox(0.2f, 0.2f);
    box->CreateFixture(&p, 1.0f);
    const long pre0 = bridge.GetStats().preSolves;
    for (int i = 0; i < 120; ++i)
        bridge.Step(1.0f / 60.0f, 8, 3);
    std::printf("sensor: begin %d end %d, presolves on sensors %d, box at y %.3f\n", counter.begin,
                counter.end, counter.preSensor, static_cast<double>(box->GetPosition().y));
    ck_assert_int_ge(counter.begin, 1);
    ck_assert_int_eq(counter.begin, counter.end); // entered and left
    ck_assert_int_eq(counter.preSensor, 0);
    ck_assert_int_eq(bridge.GetStats().preSolves, pre0);
    ck_assert(std::fabs(box->GetPosition().y - 0.2f) < 0.02f); // fell through onto the ground
    rugo_shape_destroy(disc);
}
END_TEST

// A rough disc rides a rough kinematic platform moving up at 0.5 m/s: it neither sinks into it nor is
// thrown off, and rises with it.
START_TEST(test_kinematic_platform) {
    std::vector<double> tol(32, 0.003);
    rugo_shape* plate = makeShape(rectPoints(32, 2.0, 0.3, nullptr, 0.0), &tol, 0.6, 0.0);
    rugo_shape* disc = makeDisc(32, 0.3, 0.6, 0.0);
    b2World w(b2Vec2(0.0f, -9.8f));
    rugo::Bridge bridge(&w);
    b2BodyDef kd;
    kd.type = b2_kinematicBody;
    kd.position.Set(0.0f, 0.0f);
    b2Body* platform = w.CreateBody(&kd);
    ck_assert_int_eq(bridge.Attach(platform, roughDef(plate, 1.0, 0)), RUGO_OK);
    b2Body* rider = dynamicBody(w, b2Vec2(0.0f, 0.15f + 0.3f + 0.01f));
    ck_assert_int_eq(bridge.Attach(rider, roughDef(disc, 1.0, 0)), RUGO_OK);
    for (int i = 0; i < 60; ++i) // settle
        bridge.Step(1.0f / 60.0f, 8, 3);
    const float gap0 = rider->GetPosition().y - platform->GetPosition().y;
    platform->SetLinearVelocity(b2Vec2(0.0f, 0.5f));
    float worstDev = 0.0f;
    for (int i = 0; i < 120; ++i) {
        bridge.Step(1.0f / 60.0f, 8, 3);
        worstDev = std::max(worstDev, std::fabs(rider->GetPosition().y - platform->GetPosition().y - gap0));
    }
    std::printf(
        "kinematic platform: rose %.3f m, rider gap %.4f m, largest change of the gap %.4f m, rider x %.4f\n",
        static_cast<double>(platform->GetPosition().y), static_cast<double>(gap0),
        static_cast<double>(worstDev), static_cast<double>(rider->GetPosition().x));
    ck_assert(std::fabs(platform->GetPosition().y - 1.0f) < 0.01f);
    ck_assert(std::fabs(gap0 - 0.45f) < 0.01f); // resting on the plate: half heights, within the bands
    ck_assert(worstDev < 0.01f);                // rides along: 1 cm (Box2D's slop is 5 mm)
    ck_assert(std::fabs(rider->GetPosition().x) < 0.01f);
    rugo_shape_destroy(plate);
    rugo_shape_destroy(disc);
}
END_TEST

// A frictionless smooth block slides at 3 m/s over a flat chain of 40 collinear 0.25 m edges: the
// bridge must treat chain children as Box2D 2.4.1 does (one-sided, normals kept in the edge's Gauss map
// with the ghost vertices: b2_collide_edge.cpp), so the block does not catch on the inner vertices (no
// vertical kick, no loss of speed), the same as on one long edge. Box2D 2.4.1's chains are one-sided
// with the front on the right of v1 -> v2, so a floor runs from right to left.
static void slideOnFloor(bool chain, double* speedLoss, double* maxVy, double* maxOmega) {
    rugo_shape* block = makeShape(rectPoints(32, 0.6, 0.3, nullptr, 0.0), nullptr, 0.0, 0.0);
    b2World w(b2Vec2(0.0f, -9.8f));
    rugo::Bridge bridge(&w);
    b2BodyDef gd;
    b2Body* ground = w.CreateBody(&gd);
    b2FixtureDef fd;
    fd.friction = 0.0f; // the bridge takes max(surface μ, fixture friction)
    b2ChainShape c;
    b2EdgeShape e;
    if (chain) {
        std::vector<b2Vec2> v;
        for (int i = 0; i <= 40; ++i)
            v.push_back(b2Vec2(8.0f - 0.25f * static_cast<float>(i), 0.0f));
        c.CreateChain(v.data(), static_cast<int32>(v.size()), b2Vec2(8.25f, 0.0f), b2Vec2(-2.25f, 0.0f));
        fd.shape = &c;
    } else {
        e.SetTwoSided(b2Vec2(-2.0f, 0.0f), b2Vec2(8.0f, 0.0f));
        fd.shape = &e;
    }
    ground->CreateFixture(&fd);
    b2Body* b = dynamicBody(w, b2Vec2(-1.5f, 0.15f + 0.01f));
    ck_assert_int_eq(bridge.Attach(b, roughDef(block, 1.0, 0)), RUGO_OK);
    for (int i = 0; i < 30; ++i) // settle
        bridge.Step(1.0f / 60.0f, 8, 3);
    b->SetLinearVelocity(b2Vec2(3.0f, 0.0f));
    *maxVy = *maxOmega = 0.0;
    for (int i = 0; i < 120; ++i) {
        bridge.Step(1.0f / 60.0f, 8, 3);
        *maxVy = std::max(*maxVy, std::fabs(static_cast<double>(b->GetLinearVelocity().y)));
        *maxOmega = std::max(*maxOmega, std::fabs(static_cast<double>(b->GetAngularVelocity())));
    }
    *speedLoss = 1.0 - static_cast<double>(b->GetLinearVelocity().x) / 3.0;
    rugo_shape_destroy(block);
}

// One-sided like Box2D: a native box and a rough disc thrown up from below the floor chain pass through
// it; dropped from above, both land on it.
static void throughChain(bool fromBelow, float* boxY, float* roughY) {
    rugo_shape* disc = makeDisc(32, 0.2, 0.5, 0.0);
    b2World w(b2Vec2(0.0f, -9.8f));
    rugo::Bridge bridge(&w);
    b2BodyDef gd;
    b2Body* ground = w.CreateBody(&gd);
    b2Vec2 v[3] = {b2Vec2(3.0f, 0.0f), b2Vec2(0.0f, 0.0f), b2Vec2(-3.0f, 0.0f)};
    b2ChainShape c;
    c.CreateChain(v, 3, b2Vec2(4.0f, 0.0f), b2Vec2(-4.0f, 0.0f));
    ground->CreateFixture(&c, 0.0f);
    const float y0 = fromBelow ? -0.5f : 0.5f, vy = fromBelow ? 8.0f : 0.0f;
    b2Body* box = dynamicBody(w, b2Vec2(-1.0f, y0));
    b2PolygonShape p;
    p.SetAsBox(0.2f, 0.2f);
    box->CreateFixture(&p, 1.0f);
    box->SetLinearVelocity(b2Vec2(0.0f, vy));
    b2Body* rough = dynamicBody(w, b2Vec2(1.0f, y0));
    ck_assert_int_eq(bridge.Attach(rough, roughDef(disc, 1.0, 0)), RUGO_OK);
    rough->SetLinearVelocity(b2Vec2(0.0f, vy));
    float topBox = -1e9f, topRough = -1e9f;
    for (int i = 0; i < 30; ++i) {
        bridge.Step(1.0f / 60.0f, 8, 3);
        topBox = std::max(topBox, box->GetPosition().y);
        topRough = std::max(topRough, rough->GetPosition().y);
    }
    *boxY = fromBelow ? topBox : box->GetPosition().y;
    *roughY = fromBelow ? topRough : rough->GetPosition().y;
    rugo_shape_destroy(disc);
}

START_TEST(test_chain_one_sided_no_ghost_bumps) {
    double lossEdge, vyEdge, omEdge, lossChain, vyChain, omChain;
    slideOnFloor(false, &lossEdge, &vyEdge, &omEdge);
    slideOnFloor(true, &lossChain, &vyChain, &omChain);
    std::printf("sliding over one edge: speed loss %.2e, largest |vy| %.2e m/s, |w| %.2e rad/s; over a "
                "40-edge chain: "
                "%.2e, %.2e m/s, %.2e rad/s\n",
                lossEdge, vyEdge, omEdge, lossChain, vyChain, omChain);
    std::fflush(stdout);
    ck_assert(std::fabs(lossChain) < 0.005 && std::fabs(lossEdge) < 0.005);
    ck_assert(vyChain < 0.02 && omChain < 0.05);
    float boxUp, roughUp, boxDown, roughDown;
    throughChain(true, &boxUp, &roughUp);
    throughChain(false, &boxDown, &roughDown);
    std::printf(
        "one-sided chain: thrown up from below, highest box %.3f m, rough disc %.3f m; dropped from above, "
        "box rests at %.3f m, rough disc at %.3f m\n",
        static_cast<double>(boxUp), static_cast<double>(roughUp), static_cast<double>(boxDown),
        static_cast<double>(roughDown));
    ck_assert(boxUp > 1.0f && roughUp > 1.0f);    // both passed through the back of the chain
    ck_assert(std::fabs(boxDown - 0.2f) < 0.02f); // both landed on its front
    ck_assert(std::fabs(roughDown - 0.2f) < 0.02f);
}
END_TEST

namespace {
// Records what the bridge draws.
struct RecordingDraw : public b2Draw {
    std::vector<b2Vec2> segmentEnds;
    int segments = 0, polygons = 0, points = 0, other = 0;
    std::vector<std::vector<b2Vec2>> polys;
    void DrawPolygon(const b2Vec2* v, int32 n, const b2Color&) override {
        ++polygons;
        polys.emplace_back(v, v + n);
    }
    void DrawSolidPolygon(const b2Vec2*, int32, const b2Color&) override { ++other; }
    void DrawCircle(const b2Vec2&, float, const b2Color&) override { ++other; }
    void DrawSolidCircle(const b2Vec2&, float, const b2Vec2&, const b2Color&) override { ++other; }
    void DrawSegment(const b2Vec2& a, const b2Vec2& b, const b2Color&) override {
        ++segments;
        segmentEnds.push_back(a);
        segmentEnds.push_back(b);
    }
    void DrawTransform(const b2Transform&) override { ++other; }
    void DrawPoint(const b2Vec2&, float, const b2Color&) override { ++points; }
};
} // namespace

// Debug draw: the curve as 8 segments per curve segment on the true curve, the band's two offsets at
// +-λ, one polygon per proxy enclosing the curve, and the last step's contacts.
START_TEST(test_draw) {
    const double R = 0.4, lam = 0.01;
    const int n = 32;
    const double joint = (4.0 + 2.0 * std::cos(2.0 * kPi / n)) / 6.0;
    std::vector<rugo_vec2> pts;
    for (int k = 0; k < n; ++k)
        pts.push_back(rugo_v2(R / joint * std::cos(2 * kPi * k / n), R / joint * std::sin(2 * kPi * k / n)));
    std::vector<double> tol(n, lam);
    rugo_shape* disc = makeShape(pts, &tol, 0.5, 0.0);
    b2World w(b2Vec2(0.0f, -9.8f));
    groundBox(w, 5.0f, 1.0f, b2Vec2(0.0f, -1.0f), 0.5f);
    rugo::Bridge bridge(&w);
    const b2Vec2 at(1.0f, R + lam + 0.2f);
    b2Body* b = dynamicBody(w, at);
    ck_assert_int_eq(bridge.Attach(b, roughDef(disc, 1.0, 0)), RUGO_OK);
    const int proxies = bridge.GetBodyMemory(b).proxyCount;
    RecordingDraw d;
    bridge.Draw(&d, rugo::kDrawCurve);
    ck_assert_int_eq(d.segments, 8 * n);
    double worst = 0.0;
    for (const b2Vec2& p : d.segmentEnds)
        worst = std::max(worst, std::fabs(static_cast<double>((p - at).Length()) - R));
    ck_assert_msg(worst < 2e-3, "curve drawn %g from the circle",
                  worst); // the spline's radius varies ~1e-3 between joints
    RecordingDraw band;
    bridge.Draw(&band, rugo::kDrawBand);
    ck_assert_int_eq(band.segments, 2 * 8 * n);
    int outer = 0, inner = 0;
    for (const b2Vec2& p : band.segmentEnds) {
        const double r = static_cast<double>((p - at).Length());
        outer += std::fabs(r - (R + lam)) < 2e-3;
        inner += std::fabs(r - (R - lam)) < 2e-3;
    }
    ck_assert_int_eq(outer + inner, static_cast<int>(band.segmentEnds.size()));
    ck_assert_int_eq(outer, inner);
    RecordingDraw boxes;
    bridge.Draw(&boxes, rugo::kDrawProxies);
    ck_assert_int_eq(boxes.polygons, proxies);
    ck_assert_int_eq(boxes.segments, 0);
    // Every point of the curve lies in some proxy box (convex polygons, counter-clockwise).
    for (const b2Vec2& p : d.segmentEnds) {
        bool inside = false;
        for (const auto& poly : boxes.polys) {
            bool in = true;
            for (size_t i = 0; i < poly.size(); ++i) {
                const b2Vec2 e = poly[(i + 1) % poly.size()] - poly[i];
                if (b2Cross(e, p - poly[i]) < -1e-4f) in = false;
            }
            inside = inside || in;
        }
        ck_assert(inside);
    }
    RecordingDraw none;
    bridge.Draw(&none, rugo::kDrawContacts);
    ck_assert_int_eq(none.points, 0); // no step yet
    for (int i = 0; i < 20;
         ++i) // lands after ~0.2 s (and would sleep, with no contacts to draw, after 0.5 s more)
        bridge.Step(1.0f / 60.0f, 8, 3);
    RecordingDraw contacts;
    bridge.Draw(&contacts, rugo::kDrawContacts);
    std::printf(
        "draw: %d curve segments, %d band segments, %d proxy boxes, %d contact points after landing\n",
        d.segments, band.segments, boxes.polygons, contacts.points);
    ck_assert_int_ge(contacts.points, 1);
    ck_assert_int_eq(contacts.segments, contacts.points); // one normal per point
    bridge.Draw(nullptr, rugo::kDrawCurve);               // no-op, no crash
    rugo_shape_destroy(disc);
}
END_TEST

// ---- misuse from inside the bridge's own callbacks (run under the sanitizers by scripts/test.sh) -----
namespace {
// Destroys or detaches bodies from inside Draw (any b2Draw call).
struct DestroyingDraw : public b2Draw {
    b2World* world = nullptr;
    rugo::Bridge* bridge = nullptr;
    b2Body* destroy = nullptr;
    b2Body* detach = nullptr;
    rugo_status detachStatus = RUGO_OK;
    int calls = 0;
    void act() {
        if (++calls != 3) return; // in the middle of drawing the first body
        if (destroy) world->DestroyBody(destroy);
        if (detach) detachStatus = bridge->Detach(detach);
        destroy = detach = nullptr;
    }
    void DrawPolygon(const b2Vec2*, int32, const b2Color&) override { act(); }
    void DrawSolidPolygon(const b2Vec2*, int32, const b2Color&) override { act(); }
    void DrawCircle(const b2Vec2&, float, const b2Color&) override { act(); }
    void DrawSolidCircle(const b2Vec2&, float, const b2Vec2&, const b2Color&) override { act(); }
    void DrawSegment(const b2Vec2&, const b2Vec2&, const b2Color&) override { act(); }
    void DrawTransform(const b2Transform&) override { act(); }
    void DrawPoint(const b2Vec2&, float, const b2Color&) override { act(); }
};
// Tries to detach another rough body when a contact ends: Box2D calls EndContact outside Step too,
// from DestroyFixture while it walks the body's contacts (the bridge's Detach and destructor remove
// proxies that way), where removing more fixtures would destroy contacts under that walk.
struct EndContactMisuse : public b2ContactListener {
    rugo::Bridge* bridge = nullptr;
    b2Body* detach = nullptr;
    rugo_status status = RUGO_OK;
    int ends = 0, tries = 0;
    void EndContact(b2Contact*) override {
        ++ends;
        if (detach && bridge) {
            ++tries;
            status = bridge->Detach(detach);
            detach = nullptr;
        }
    }
};
} // namespace

START_TEST(test_misuse_in_callbacks) {
    rugo_shape* disc = makeDisc(32, 0.3, 0.5, 0.0);
    { // QueryAABB: the callback destroys the body it is given, a rough body not yet reported, and
        // detaches a third; destroyed bodies are not reported afterwards.
        b2World w(b2Vec2(0.0f, -9.8f));
        rugo::Bridge bridge(&w);
        std::vector<b2Body*> bodies;
        for (int i = 0; i < 6; ++i) {
            b2Body* b = dynamicBody(w, b2Vec2(0.7f * static_cast<float>(i), 0.0f));
            if (i % 2 == 0) {
                ck_assert_int_eq(bridge.Attach(b, roughDef(disc)), RUGO_OK);
            } else {
                b2PolygonShape p;
                p.SetAsBox(0.2f, 0.2f);
                b->CreateFixture(&p, 1.0f);
            }
            bodies.push_back(b);
        }
        b2AABB all;
        all.lowerBound.Set(-1.0f, -1.0f);
        all.upperBound.Set(5.0f, 1.0f);
        std::vector<b2Body*> seen;
        bool first = true;
        bridge.QueryAABB(all, [&](b2Body* b) {
            seen.push_back(b);
            if (first) {
                first = false;
                b2Body* victims[2] = {b, nullptr};
                for (b2Body* o : bodies) // a rough body other than b, destroyed before it is reported
                    if (o != b && bridge.IsRough(o) && victims[1] == nullptr) victims[1] = o;
                for (b2Body* o : bodies) // and another rough body detached
                    if (o != b && o != victims[1] && bridge.IsRough(o)) {
                        ck_assert_int_eq(bridge.Detach(o), RUGO_OK);
                        break;
                    }
                for (b2Body* v : victims) {
                    bodies.erase(std::find(bodies.begin(), bodies.end(), v));
                    w.DestroyBody(v);
                }
            }
            return true;
        });
        // 6 bodies, 2 destroyed in the first callback: the first and at most the 4 survivors after it
        ck_assert_int_ge(static_cast<int>(seen.size()), 2);
        ck_assert_int_le(static_cast<int>(seen.size()), 5);
        for (size_t i = 1; i < seen.size(); ++i)
            ck_assert(std::find(bodies.begin(), bodies.end(), seen[i]) !=
                      bodies.end()); // never a destroyed one
        ck_assert_int_eq(w.GetBodyCount(), 4);
    }
    { // Draw: a b2Draw call destroys a rough body and detaches another while the bridge draws.
        b2World w(b2Vec2(0.0f, -9.8f));
        rugo::Bridge bridge(&w);
        b2Body* a = dynamicBody(w, b2Vec2(0.0f, 0.0f));
        b2Body* b = dynamicBody(w, b2Vec2(1.0f, 0.0f));
        b2Body* c = dynamicBody(w, b2Vec2(2.0f, 0.0f));
        for (b2Body* x : {a, b, c})
            ck_assert_int_eq(bridge.Attach(x, roughDef(disc)), RUGO_OK);
        DestroyingDraw d;
        d.world = &w;
        d.bridge = &bridge;
        d.destroy = b;
        d.detach = c;
        bridge.Draw(&d, rugo::kDrawCurve | rugo::kDrawBand | rugo::kDrawProxies);
        ck_assert_int_eq(d.detachStatus, RUGO_OK);
        ck_assert(!bridge.IsRough(c));
        RecordingDraw after;
        bridge.Draw(&after, rugo::kDrawCurve);
        ck_assert_int_eq(after.segments,
                         8 * (1 << bridge.GetLevel(a))); // only a is left: 8 per segment of its level
    }
    { // EndContact during Detach tries to detach another body: a clear status, nothing corrupted.
        b2World w(b2Vec2(0.0f, -9.8f));
        EndContactMisuse l; // outlives the bridge
        w.SetContactListener(&l);
        groundBox(w, 5.0f, 1.0f, b2Vec2(0.0f, -1.0f), 0.5f);
        std::vector<b2Body*> rough;
        {
            rugo::Bridge bridge(&w);
            l.bridge = &bridge;
            for (int i = 0; i < 4; ++i) {
                b2Body* b = dynamicBody(w, b2Vec2(-1.5f + 0.61f * static_cast<float>(i), 0.31f));
                ck_assert_int_eq(bridge.Attach(b, roughDef(disc)), RUGO_OK);
                rough.push_back(b);
            }
            for (int i = 0; i < 30; ++i)
                bridge.Step(1.0f / 60.0f, 8, 3);
            l.detach = rough[1];
            ck_assert_int_eq(bridge.Detach(rough[0]), RUGO_OK); // resting on the ground: EndContact runs
            ck_assert_int_eq(l.tries, 1);
            ck_assert_int_eq(l.status, RUGO_ERR_WORLD_LOCKED);
            ck_assert(bridge.IsRough(rough[1]) && !bridge.IsRough(rough[0]));
            ck_assert_int_eq(bridge.Detach(rough[1]), RUGO_OK); // and works once outside
            for (int i = 0; i < 10; ++i)
                bridge.Step(1.0f / 60.0f, 8, 3);
            l.bridge = nullptr;
        } // the destructor detaches rough[2] and rough[3] (EndContacts forwarded)
        ck_assert_int_gt(l.ends, 0);
        ck_assert(rough[2]->GetFixtureList() == nullptr && rough[3]->GetFixtureList() == nullptr);
        w.Step(1.0f / 60.0f, 8, 3);
    }
    rugo_shape_destroy(disc);
}
END_TEST

int main(void) {
    Suite* s = suite_create("box2d");
    TCase* tc = tcase_create("bridge");
    tcase_set_timeout(tc, 1200);
    tcase_add_test(tc, test_manifold_encoding);
    tcase_add_test(tc, test_circle_overlap_one_normal);
    tcase_add_test(tc, test_listeners_chain);
    tcase_add_test(tc, test_mass_repaired);
    tcase_add_test(tc, test_lifetime);
    tcase_add_test(tc, test_memory_and_sharing);
    tcase_add_test(tc, test_queries);
    tcase_add_test(tc, test_disc_rolls_like_circle);
    tcase_add_test(tc, test_block_stops);
    tcase_add_test(tc, test_stack_rests);
    tcase_add_test(tc, test_rough_bodies_fall_asleep);
    tcase_add_test(tc, test_fast_body_no_tunnel);
    tcase_add_test(tc, test_sensor);
    tcase_add_test(tc, test_kinematic_platform);
    tcase_add_test(tc, test_chain_one_sided_no_ghost_bumps);
    tcase_add_test(tc, test_draw);
    tcase_add_test(tc, test_misuse_in_callbacks);
    tcase_add_test(tc, test_bridge_hardening);
    suite_add_tcase(s, tc);
    return test_run_suite(s);
}
