// Rough surfaces in a Box2D world (docs/box2d.md, "Friction and restitution"; docs/roughness.md,
// "Rolling resistance"): friction and restitution mixed with ordinary fixtures by the world's rule,
// per-point surface data (Bridge::GetPointInfo), rolling resistance per body.
#include "rugo/box2d.hpp"

extern "C" {
#include "test_util.h"
}

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

const double kPi = 3.14159265358979323846;

// A closed outline of n control points evenly along a w x h rectangle's perimeter (straight sides,
// rounded corners).
std::vector<rugo_vec2> rectPoints(int n, double w, double h) {
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
    return p;
}

// Control points on a circle whose curve has radius R at the joints.
std::vector<rugo_vec2> discPoints(int n, double R) {
    const double joint = (4.0 + 2.0 * std::cos(2.0 * kPi / n)) / 6.0;
    std::vector<rugo_vec2> p;
    for (int k = 0; k < n; ++k)
        p.push_back(
            rugo_v2(R / joint * std::cos(2.0 * kPi * k / n), R / joint * std::sin(2.0 * kPi * k / n)));
    return p;
}

// A shape with the given bands (nullptr: none) and friction map; restitution eps.
rugo_shape* makeShape(const std::vector<rugo_vec2>& pts, const std::vector<double>* bands,
                      rugo_friction_map friction, double eps) {
    rugo_shape_def d = rugo_default_shape_def();
    d.points = pts.data();
    d.count = static_cast<int>(pts.size());
    d.tolerances = bands ? bands->data() : nullptr;
    d.friction = friction;
    d.restitution.epsilon = eps;
    d.restitution.epsilon_max = eps;
    rugo_shape* s = nullptr;
    ck_assert_int_eq(rugo_shape_create(&d, &s, nullptr), RUGO_OK);
    return s;
}

rugo_friction_map constantFriction(double mu) {
    rugo_friction_map m = rugo_default_friction_map();
    m.alpha = 0.0;
    m.base = mu;
    return m;
}

// A static ramp: a box of half-length 20 m tilted by `degrees` through the origin, top face through it.
b2Body* ramp(b2World& w, double degrees, float mu, float eps = 0.0f) {
    b2BodyDef bd;
    bd.angle = static_cast<float>(degrees * kPi / 180.0);
    b2Body* g = w.CreateBody(&bd);
    b2PolygonShape box;
    box.SetAsBox(20.0f, 0.5f, b2Vec2(0.0f, -0.5f), 0.0f);
    b2FixtureDef fd;
    fd.shape = &box;
    fd.friction = mu;
    fd.restitution = eps;
    g->CreateFixture(&fd);
    return g;
}

// A point at distance `along` along the ramp and `above` over its surface.
b2Vec2 onRamp(double degrees, double along, double above) {
    const double a = degrees * kPi / 180.0;
    return b2Vec2(static_cast<float>(along * std::cos(a) - above * std::sin(a)),
                  static_cast<float>(along * std::sin(a) + above * std::cos(a)));
}

b2Body* dynamicBody(b2World& w, b2Vec2 at, double angle) {
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.position = at;
    bd.angle = static_cast<float>(angle);
    return w.CreateBody(&bd);
}

// The documented rule of a point (docs/box2d.md), from the shapes and fixtures alone: the rough side's
// μ(λ(t)) from its shape's band at (segment, t) at the body's level and its friction map.
struct RuleCheck : public b2ContactListener {
    rugo::Bridge* bridge = nullptr;
    rugo_mix_rule fixtureFriction = RUGO_MIX_GEOMETRIC, fixtureRestitution = RUGO_MIX_MAX;
    rugo_mix_rule pointMix = RUGO_MIX_MEAN;
    int checked[3] = {0, 0, 0}; // PreSolves with 1 and 2 points
    int postSolves = 0;
    double worstFriction = 0.0, worstLambda = 0.0, worstRestitution = 0.0;

    // μ and λ of a rough side from the shape, independently of the bridge's computation.
    double roughMu(const b2Body* body, const rugo::SurfacePoint& s, double* lambda) const {
        const rugo_shape* shape = bridge->GetShape(body);
        rugo_tolerance_level tl;
        ck_assert(s.level >= bridge->GetLevel(body) && s.level <= rugo_shape_finest_level(shape));
        ck_assert_int_eq(rugo_shape_tolerance_level(shape, s.level, &tl), RUGO_OK);
        ck_assert(s.segment >= 0 && s.segment < tl.count);
        ck_assert(s.t >= 0.0 && s.t <= 1.0);
        *lambda = rugo_tolerance_at(tl.total, tl.count, s.segment, s.t, 0.0);
        const rugo_friction_map m = rugo_shape_friction_map(shape);
        return rugo_friction(&m, *lambda);
    }

    void PreSolve(b2Contact* c, const b2Manifold*) override {
        const int n = c->GetManifold()->pointCount;
        if (n == 0) return;
        double mus[2] = {0.0, 0.0};
        for (int i = 0; i < n; ++i) {
            rugo::PointInfo info;
            ck_assert_int_eq(bridge->GetPointInfo(c, i, &info), RUGO_OK);
            const b2Fixture* f[2] = {c->GetFixtureA(), c->GetFixtureB()};
            const rugo::SurfacePoint* side[2] = {&info.a, &info.b};
            double mu[2], eps[2];
            int rough = 0;
            for (int k = 0; k < 2; ++k) {
                const b2Body* body = f[k]->GetBody();
                ck_assert(side[k]->rough == bridge->IsRough(body));
                if (side[k]->rough) {
                    ++rough;
                    double lam = 0.0;
                    mu[k] = roughMu(body, *side[k], &lam);
                    eps[k] = rugo_shape_restitution(bridge->GetShape(body)).epsilon;
                    worstLambda = std::fmax(worstLambda, std::fabs(lam - side[k]->lambda));
                } else {
                    ck_assert_int_eq(side[k]->segment, -1);
                    ck_assert_int_eq(side[k]->level, -1);
                    mu[k] = static_cast<double>(f[k]->GetFriction());
                    eps[k] = static_cast<double>(f[k]->GetRestitution());
                }
            }
            const double expectMu = rugo_mix(rough == 2 ? RUGO_MIX_MAX : fixtureFriction, mu[0], mu[1]);
            const double expectEps = rugo_mix(rough == 2 ? RUGO_MIX_MIN : fixtureRestitution, eps[0], eps[1]);
            worstFriction = std::fmax(worstFriction, std::fabs(info.friction - expectMu));
            worstRestitution = std::fmax(worstRestitution, std::fabs(info.restitution - expectEps));
            mus[i] = expectMu;
        }
        // The contact's friction, as Box2D's solver will use it (before any user change).
        const double expect = n == 2 ? rugo_mix(pointMix, mus[0], mus[1]) : mus[0];
        worstFriction = std::fmax(worstFriction, std::fabs(static_cast<double>(c->GetFriction()) - expect));
        ++checked[n];
    }
    void PostSolve(b2Contact* c, const b2ContactImpulse*) override {
        rugo::PointInfo info;
        for (int i = 0; i < c->GetManifold()->pointCount; ++i) {
            ck_assert_int_eq(bridge->GetPointInfo(c, i, &info), RUGO_OK);
            ++postSolves;
        }
    }
};

} // namespace

// ---- friction read in PreSolve equals the documented rule at every point --------------------------
START_TEST(test_presolve_friction_is_the_rule) {
    // A rough box (2-point manifolds on a flat ramp) and a rough disc (1 point) with bands varying along
    // the outline and the default friction map (μ 0.3 to 0.9 over 0.5 to 6 mm), on ordinary ramps of
    // μ 0.2 and 0.8 at 5, 15 and 25 degrees, dropped at four angles each: 24 poses per ramp and body
    // kind, every step of their fall, slide and rest checked.
    test_rng rng = test_rng_seed(22);
    std::vector<double> boxBands(32), discBands(32);
    for (double& b : boxBands)
        b = test_rng_uniform(&rng, 0.0003, 0.006);
    for (double& b : discBands)
        b = test_rng_uniform(&rng, 0.0003, 0.006);
    rugo_shape* box = makeShape(rectPoints(32, 0.6, 0.3), &boxBands, rugo_default_friction_map(), 0.3);
    rugo_shape* disc = makeShape(discPoints(32, 0.2), &discBands, rugo_default_friction_map(), 0.3);
    const double slopes[3] = {5.0, 15.0, 25.0};
    const float rampMu[2] = {0.2f, 0.8f};
    for (int rule = 0; rule < 2; ++rule) {
        RuleCheck check;
        int poses = 0;
        for (float mu : rampMu)
            for (double slope : slopes) {
                b2World w(b2Vec2(0.0f, -9.8f));
                w.SetContactListener(&check);
                ramp(w, slope, mu, 0.1f);
                rugo::BridgeDef bd;
                if (rule == 1) { // the thesis' rules, selected
                    bd.fixtureFrictionMix = RUGO_MIX_MAX;
                    bd.fixtureRestitutionMix = RUGO_MIX_MIN;
                }
                check.fixtureFriction = bd.fixtureFrictionMix;
                check.fixtureRestitution = bd.fixtureRestitutionMix;
                rugo::Bridge bridge(&w, bd);
                check.bridge = &bridge;
                for (int k = 0; k < 4; ++k) {
                    const double angle = slope * kPi / 180.0 + 0.3 * k;
                    b2Body* a = dynamicBody(w, onRamp(slope, -6.0 + 1.5 * k, 0.5), angle);
                    rugo::RoughBodyDef rd;
                    rd.shape = box;
                    ck_assert_int_eq(bridge.Attach(a, rd), RUGO_OK);
                    b2Body* b = dynamicBody(w, onRamp(slope, 1.0 + 1.5 * k, 0.4), angle);
                    rd.shape = disc;
                    ck_assert_int_eq(bridge.Attach(b, rd), RUGO_OK);
                    poses += 2;
                }
                // A rough body on a rough body too (the thesis' rule at every point).
                b2Body* top = dynamicBody(w, onRamp(slope, -6.0, 1.2), slope * kPi / 180.0);
                rugo::RoughBodyDef rd;
                rd.shape = disc;
                ck_assert_int_eq(bridge.Attach(top, rd), RUGO_OK);
                for (int i = 0; i < 90; ++i)
                    bridge.Step(1.0f / 60.0f, 8, 3);
            }
        std::printf(
            "mixing rule %s: %d bodies dropped, PreSolves checked: %d one-point, %d two-point; "
            "PostSolve points %d; worst |mu - rule| %.3g, |eps - rule| %.3g, |lambda - shape| %.3g m\n",
            rule == 0 ? "world (sqrt, max)" : "thesis (max, min)", poses, check.checked[1], check.checked[2],
            check.postSolves, check.worstFriction, check.worstRestitution, check.worstLambda);
        ck_assert_int_ge(poses, 24);
        ck_assert_int_ge(check.checked[1], 24);
        ck_assert_int_ge(check.checked[2], 24);
        ck_assert_int_gt(check.postSolves, 0);
        // Box2D keeps friction in a float: 1e-6 covers its rounding of μ <= 1.
        ck_assert(check.worstFriction <= 1e-6);
        ck_assert(check.worstRestitution <= 1e-12);
        // t is reported in float: λ from it agrees to the band's slope times 1e-7.
        ck_assert(check.worstLambda <= 1e-8);
    }
    rugo_shape_destroy(box);
    rugo_shape_destroy(disc);
}
END_TEST

// ---- rough and ordinary boxes on one ramp follow one rule ------------------------------------------
// A box of μ 0.1 on a ramp of μ 0.9 at 20°: Box2D mixes √(0.1 · 0.9) = 0.3 < tan 20° = 0.364, so an
// ordinary box slides at g (sin 20° − 0.3 cos 20°); a rough box of constant μ 0.1 does the same by
// default, and stays put under the thesis' max (0.9).
START_TEST(test_ramp_rough_and_ordinary_side_by_side) {
    const double slope = 20.0, muBox = 0.1, muRamp = 0.9;
    rugo_shape* box = makeShape(rectPoints(32, 0.6, 0.3), nullptr, constantFriction(muBox), 0.0);
    double travelled[3];
    for (int kind = 0; kind < 3; ++kind) { // 0 ordinary, 1 rough (world rule), 2 rough (thesis rule)
        b2World w(b2Vec2(0.0f, -9.8f));
        ramp(w, slope, static_cast<float>(muRamp));
        rugo::BridgeDef bd;
        if (kind == 2) bd.fixtureFrictionMix = RUGO_MIX_MAX;
        rugo::Bridge bridge(&w, bd);
        b2Body* b = dynamicBody(w, onRamp(slope, 0.0, 0.151), slope * kPi / 180.0);
        if (kind == 0) {
            b2PolygonShape poly;
            poly.SetAsBox(0.3f, 0.15f);
            b2FixtureDef fd;
            fd.shape = &poly;
            fd.density = 1.0f;
            fd.friction = static_cast<float>(muBox);
            b->CreateFixture(&fd);
        } else {
            rugo::RoughBodyDef rd;
            rd.shape = box;
            ck_assert_int_eq(bridge.Attach(b, rd), RUGO_OK);
        }
        const b2Vec2 p0 = b->GetPosition();
        for (int i = 0; i < 60; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        const b2Vec2 d = b->GetPosition() - p0;
        travelled[kind] = -static_cast<double>(b2Dot(d, onRamp(slope, 1.0, 0.0)));
    }
    const double t = slope * kPi / 180.0;
    const double expect = 0.5 * 9.8 * (std::sin(t) - std::sqrt(muBox * muRamp) * std::cos(t));
    std::printf("ramp 20 deg, box mu 0.1 on ramp mu 0.9, 1 s: ordinary %.4f m, rough (world rule) %.4f m, "
                "rough (thesis max) %.4f m; theory %.4f m\n",
                travelled[0], travelled[1], travelled[2], expect);
    ck_assert(std::fabs(travelled[0] - expect) <= 0.03 * expect);
    ck_assert(std::fabs(travelled[1] - travelled[0]) <= 0.03 * travelled[0]);
    ck_assert(std::fabs(travelled[2]) <= 0.01);
    rugo_shape_destroy(box);
}
END_TEST

// ---- GetPointInfo's refusals ------------------------------------------------------------------------
START_TEST(test_point_info_refusals) {
    b2World w(b2Vec2(0.0f, -9.8f));
    ramp(w, 0.0, 0.5f);
    rugo::Bridge bridge(&w);
    rugo_shape* disc = makeShape(discPoints(16, 0.2), nullptr, constantFriction(0.5), 0.0);
    b2Body* rough = dynamicBody(w, b2Vec2(0.0f, 0.2f), 0.0);
    rugo::RoughBodyDef rd;
    rd.shape = disc;
    ck_assert_int_eq(bridge.Attach(rough, rd), RUGO_OK);
    b2Body* plain = dynamicBody(w, b2Vec2(3.0f, 0.2f), 0.0);
    b2CircleShape c;
    c.m_radius = 0.2f;
    b2FixtureDef fd;
    fd.shape = &c;
    fd.density = 1.0f;
    plain->CreateFixture(&fd);
    for (int i = 0; i < 30; ++i)
        bridge.Step(1.0f / 60.0f, 8, 3);
    const b2Contact* roughContact = nullptr;
    const b2Contact* plainContact = nullptr;
    for (const b2Contact* k = w.GetContactList(); k != nullptr; k = k->GetNext()) {
        const bool r =
            bridge.IsRough(k->GetFixtureA()->GetBody()) || bridge.IsRough(k->GetFixtureB()->GetBody());
        if (k->IsTouching()) (r ? roughContact : plainContact) = k;
    }
    ck_assert_ptr_nonnull(roughContact);
    ck_assert_ptr_nonnull(plainContact);
    rugo::PointInfo info;
    info.friction = -7.0;
    ck_assert_int_eq(bridge.GetPointInfo(nullptr, 0, &info), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(bridge.GetPointInfo(roughContact, 0, nullptr), RUGO_ERR_NULL_ARGUMENT);
    ck_assert_int_eq(bridge.GetPointInfo(plainContact, 0, &info), RUGO_ERR_NOT_ATTACHED);
    ck_assert_int_eq(bridge.GetPointInfo(roughContact, -1, &info), RUGO_ERR_BAD_ARGUMENT);
    ck_assert_int_eq(bridge.GetPointInfo(roughContact, roughContact->GetManifold()->pointCount, &info),
                     RUGO_ERR_BAD_ARGUMENT);
    ck_assert(info.friction == -7.0); // untouched on error
    ck_assert_int_eq(bridge.GetPointInfo(roughContact, 0, &info), RUGO_OK);
    ck_assert(std::fabs(info.friction - 0.5) <= 1e-12); // √(0.5 · 0.5)
    // Another bridge's contact.
    b2World w2(b2Vec2(0.0f, -9.8f));
    rugo::Bridge other(&w2);
    ck_assert_int_eq(other.GetPointInfo(roughContact, 0, &info), RUGO_ERR_NOT_ATTACHED);
    // Rolling resistance refusals name the field.
    b2Body* more = dynamicBody(w, b2Vec2(6.0f, 0.2f), 0.0);
    rd.rollingResistance = -1.0;
    ck_assert_int_eq(bridge.Attach(more, rd), RUGO_ERR_BAD_ARGUMENT);
    ck_assert(std::strstr(bridge.LastError(), "rollingResistance") != nullptr);
    rd.rollingResistance = NAN;
    ck_assert_int_eq(bridge.Attach(more, rd), RUGO_ERR_BAD_ARGUMENT);
    rd.rollingResistance = 0.0;
    ck_assert_int_eq(bridge.Attach(more, rd), RUGO_OK);
    rugo_shape_destroy(disc);
}
END_TEST

// ---- a rough ball bounces off an ordinary floor as a circle does ------------------------------------
// ε 0.5 against a floor of ε 0: Box2D's max gives 0.5 (apex ε² h = 0.25 m from 1 m); the thesis' min,
// selected, gives 0 (no bounce). The bridge turns a bouncing body round when its step would close the
// gap (docs/box2d.md, "Continuous collision"), at most that step's approach early, so its apex may lie
// higher by up to that approach, v dt (7.4 cm here); no lower than the circle's by more than 5 %.
START_TEST(test_restitution_world_rule) {
    rugo_shape* disc = makeShape(discPoints(64, 0.25), nullptr, constantFriction(0.5), 0.5);
    double apex[3];
    for (int kind = 0; kind < 3; ++kind) { // rough (world rule), circle, rough (thesis rule)
        b2World w(b2Vec2(0.0f, -9.8f));
        ramp(w, 0.0, 0.5f, 0.0f);
        rugo::BridgeDef bd;
        if (kind == 2) bd.fixtureRestitutionMix = RUGO_MIX_MIN;
        rugo::Bridge bridge(&w, bd);
        b2Body* b = dynamicBody(w, b2Vec2(0.0f, 1.25f), 0.0);
        if (kind != 1) {
            rugo::RoughBodyDef rd;
            rd.shape = disc;
            ck_assert_int_eq(bridge.Attach(b, rd), RUGO_OK);
        } else {
            b2CircleShape c;
            c.m_radius = 0.25f;
            b2FixtureDef fd;
            fd.shape = &c;
            fd.density = 1.0f;
            fd.restitution = 0.5f;
            fd.friction = 0.5f;
            b->CreateFixture(&fd);
        }
        bool bounced = false;
        apex[kind] = 0.0;
        for (int i = 0; i < 120; ++i) {
            bridge.Step(1.0f / 60.0f, 8, 3);
            if (b->GetLinearVelocity().y > 0.0f) bounced = true;
            if (bounced) apex[kind] = std::fmax(apex[kind], static_cast<double>(b->GetPosition().y) - 0.25);
        }
    }
    const double early = std::sqrt(2.0 * 9.8 * 1.0) / 60.0;
    std::printf(
        "drop from 1 m, eps 0.5 on a floor of eps 0: apex after the bounce rough %.4f m, circle %.4f m "
        "(theory 0.25 m), rough with the thesis' min %.4f m\n",
        apex[0], apex[1], apex[2]);
    ck_assert(apex[1] > 0.2);
    ck_assert(apex[0] >= 0.95 * apex[1] && apex[0] <= apex[1] + early);
    ck_assert(apex[2] <= 0.01);
    rugo_shape_destroy(disc);
}
END_TEST

// ---- rolling resistance: off matches a circle, on matches the model --------------------------------
// A disc of R = 0.5 m with a constant band λ = 5 mm rolls 2 s down a 30° incline of an ordinary floor.
// With k = 0 it matches a native circle of the same mass (the acceptance bound, 2 %). With k on, the
// torque k N λ (docs/roughness.md) lowers its acceleration by g cos θ (k λ / R') / (1 + I / m R'²),
// R' = R + λ the radius it rolls on (its band's edge): that drop, measured against the same disc with
// k = 0 in the same run, matches the formula within 5 %.
START_TEST(test_rolling_resistance_incline) {
    const double R = 0.5, lam = 0.005, mu = 0.6, theta = 30.0 * kPi / 180.0, T = 2.0;
    const std::vector<double> bands(64, lam);
    rugo_shape* disc = makeShape(discPoints(64, R), &bands, constantFriction(mu), 0.0);
    const rugo_mass_properties mp = rugo_shape_mass(disc);
    const double ks[4] = {-1.0, 0.0, rugo::kDefaultRollingResistance, 4.0}; // -1: native circle
    double accel[4];
    for (int v = 0; v < 4; ++v) {
        b2World w(
            b2Vec2(static_cast<float>(9.8 * std::sin(theta)), static_cast<float>(-9.8 * std::cos(theta))));
        ramp(w, 0.0, static_cast<float>(mu));
        rugo::Bridge bridge(&w);
        b2Body* b = dynamicBody(w, b2Vec2(0.0f, static_cast<float>(R + lam + 0.002)), 0.0);
        if (v == 0) {
            b2CircleShape c;
            c.m_radius = static_cast<float>(R + lam);
            b2FixtureDef fd;
            fd.shape = &c;
            fd.density = static_cast<float>(mp.area / (kPi * (R + lam) * (R + lam)));
            fd.friction = static_cast<float>(mu);
            b->CreateFixture(&fd);
        } else {
            rugo::RoughBodyDef rd;
            rd.shape = disc;
            rd.lod = 0;
            rd.rollingResistance = ks[v];
            ck_assert_int_eq(bridge.Attach(b, rd), RUGO_OK);
        }
        for (int i = 0; i < 15; ++i) // land first
            bridge.Step(1.0f / 60.0f, 8, 3);
        const double x0 = static_cast<double>(b->GetPosition().x),
                     v0 = static_cast<double>(b->GetLinearVelocity().x);
        const int steps = static_cast<int>(T * 60.0);
        for (int i = 0; i < steps; ++i)
            bridge.Step(1.0f / 60.0f, 8, 3);
        const double x = static_cast<double>(b->GetPosition().x) - x0;
        accel[v] = 2.0 * (x - v0 * T) / (T * T);
    }
    const double Rp = R + lam, iratio = mp.inertia / (mp.area * Rp * Rp);
    const double a0 = 9.8 * std::sin(theta) / (1.0 + iratio);
    std::printf(
        "rolling resistance, 30 deg, R %.2f m, band %.0f mm: acceleration circle %.4f, k=0 %.4f (%.2f %% "
        "off), theory (k = 0) %.4f m/s^2\n",
        R, lam * 1e3, accel[0], accel[1], 100.0 * std::fabs(accel[1] - accel[0]) / accel[0], a0);
    ck_assert(std::fabs(accel[1] - accel[0]) <= 0.02 * accel[0]);
    for (int v = 2; v < 4; ++v) {
        const double drop = accel[1] - accel[v];
        const double model = 9.8 * std::cos(theta) * (ks[v] * lam / Rp) / (1.0 + iratio);
        std::printf("  k = %.2f: acceleration %.4f, drop %.5f against the model's %.5f m/s^2 (%.2f %%)\n",
                    ks[v], accel[v], drop, model, 100.0 * (drop - model) / model);
        ck_assert(std::fabs(drop - model) <= 0.05 * model);
    }
    rugo_shape_destroy(disc);
}
END_TEST

int main(void) {
    Suite* s = suite_create("box2d_surface");
    TCase* tc = tcase_create("core");
    tcase_set_timeout(tc, 600);
    tcase_add_test(tc, test_presolve_friction_is_the_rule);
    tcase_add_test(tc, test_ramp_rough_and_ordinary_side_by_side);
    tcase_add_test(tc, test_point_info_refusals);
    tcase_add_test(tc, test_restitution_world_rule);
    tcase_add_test(tc, test_rolling_resistance_incline);
    suite_add_tcase(s, tc);
    SRunner* sr = srunner_create(s);
    srunner_run_all(sr, CK_NORMAL);
    const int failed = srunner_ntests_failed(sr);
    srunner_free(sr);
    return failed == 0 ? 0 : 1;
}
