// The testbed's scenes: the scene table's rows (the main demo, the thesis' chapter-7 scenes) as they
// are, and the testbed's own — the benchmark's pile as rough bodies beside the same outlines as Box2D
// polygon compounds, a ramp whose friction grows along it, levels of detail switched live, a wheel in
// a groove and a conveyor.
#include "testbed.hpp"

extern "C" {
#include "scenes.h"
}

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace testbed {

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- helpers --------------------------------------------------------------------------------------

// A scene-table row into *s: its world, framing and description.
bool FromTable(const char* name, int variant, Scene* s) {
    s->w = std::make_unique<scene_table::World>();
    if (!scene_table::Create(name, variant, s->w.get())) return false;
    const scene& sc = *s->w->sc;
    s->dt = static_cast<float>(sc.time_step);
    s->viewLo.Set(static_cast<float>(sc.view_lo.x), static_cast<float>(sc.view_lo.y));
    s->viewHi.Set(static_cast<float>(sc.view_hi.x), static_cast<float>(sc.view_hi.y));
    char note[256];
    std::snprintf(note, sizeof note, "%s %s (%s): %s", sc.figure, sc.name, sc.label, sc.measures);
    s->note = note;
    return true;
}

// An empty world with gravity and a bridge at the benchmark's error budget.
void NewWorld(Scene* s) {
    s->w = std::make_unique<scene_table::World>();
    s->w->world = std::make_unique<b2World>(b2Vec2(0.0f, -9.8f));
    rugo::BridgeDef bd;
    bd.errorBudget = pile::kBudget;
    s->w->bridge = std::make_unique<rugo::Bridge>(s->w->world.get(), bd);
}

// n control points along a closed polyline (counter-clockwise), equally spaced by arc length.
std::vector<rugo_vec2> SampleOutline(const std::vector<rugo_vec2>& poly, int n) {
    std::vector<double> acc(1, 0.0);
    for (size_t i = 0; i < poly.size(); ++i) {
        const rugo_vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
        acc.push_back(acc.back() + std::hypot(b.x - a.x, b.y - a.y));
    }
    std::vector<rugo_vec2> out;
    size_t e = 0;
    for (int k = 0; k < n; ++k) {
        const double s = acc.back() * k / n;
        while (acc[e + 1] < s)
            ++e;
        const rugo_vec2 a = poly[e], b = poly[(e + 1) % poly.size()];
        const double u = (s - acc[e]) / std::max(acc[e + 1] - acc[e], 1e-12);
        out.push_back(rugo_v2(a.x + u * (b.x - a.x), a.y + u * (b.y - a.y)));
    }
    return out;
}

// A rough shape of the scenes' friction map, owned by the scene; nullptr (with a message) on error.
rugo_shape* MakeShape(const std::vector<rugo_vec2>& pts, const std::vector<double>& lambda, Scene* s) {
    rugo_shape_def d = rugo_default_shape_def();
    d.points = pts.data();
    d.count = static_cast<int>(pts.size());
    d.tolerances = lambda.data();
    d.friction = scene_friction_map();
    rugo_shape* shape = nullptr;
    const rugo_status st = rugo_shape_create(&d, &shape, nullptr);
    if (st != RUGO_OK) {
        std::fprintf(stderr, "testbed: %s: shape: %s\n", s->name.c_str(), rugo_status_string(st));
        return nullptr;
    }
    s->ownedShapes.push_back(shape);
    return shape;
}

// λ of a tolerance-library preset in metres (scenes.h's scale), n segments.
std::vector<double> Preset(rugo_tolerance_preset p, std::uint64_t seed, int n) {
    std::vector<double> lam(static_cast<size_t>(n), 0.0);
    rugo_tolerances_preset(p, seed, n, lam.data());
    for (double& l : lam)
        l *= SCENE_ROUGHNESS_SCALE;
    return lam;
}

b2Body* AddBody(Scene* s, b2BodyType type, b2Vec2 p, float angle = 0.0f) {
    b2BodyDef bd;
    bd.type = type;
    bd.position = p;
    bd.angle = angle;
    return s->w->world->CreateBody(&bd);
}

bool AttachRough(Scene* s, b2Body* b, const rugo_shape* shape, double density) {
    rugo::RoughBodyDef rd;
    rd.shape = shape;
    rd.density = density;
    const rugo_status st = s->w->bridge->Attach(b, rd);
    if (st != RUGO_OK)
        std::fprintf(stderr, "testbed: %s: Attach: %s\n", s->name.c_str(), rugo_status_string(st));
    s->w->bodies.push_back(b);
    return st == RUGO_OK;
}

void AddBox(b2Body* b, float hx, float hy, b2Vec2 centre, float friction = 0.6f) {
    b2PolygonShape box;
    box.SetAsBox(hx, hy, centre, 0.0f);
    b2FixtureDef fd;
    fd.shape = &box;
    fd.friction = friction;
    fd.density = 1.0f;
    b->CreateFixture(&fd);
}

// ---- the pile, rough beside polygons --------------------------------------------------------------

// The benchmark's pile (pile_scene.hpp: its shapes, layout and poses) twice in one world: on the left
// through the bridge at the automatic level, on the right as Box2D polygon compounds fitted within the
// same error (5 mm).
bool BuildPileSideBySide(int variant, Scene* s) {
    const int n = variant == 0 ? 16 : 36;
    auto set = std::make_shared<pile::ShapeSet>();
    if (!pile::BuildShapes(64, set.get())) return false;
    s->pileShapes = set;
    NewWorld(s);
    const pile::Layout L = pile::MakeLayout(n, *set);
    const float gap = 0.8f, off = static_cast<float>(L.halfWidth) + 0.5f + gap;
    b2Body* ground = AddBody(s, b2_staticBody, b2Vec2(0.0f, 0.0f));
    for (int side = -1; side <= 1; side += 2) {
        const float cx = static_cast<float>(side) * off, hw = static_cast<float>(L.halfWidth),
                    hh = static_cast<float>(0.5 * L.wallHeight);
        AddBox(ground, hw + 0.5f, 0.5f, b2Vec2(cx, -0.5f));
        AddBox(ground, 0.5f, hh, b2Vec2(cx - hw - 0.5f, hh));
        AddBox(ground, 0.5f, hh, b2Vec2(cx + hw + 0.5f, hh));
    }
    for (int side = -1; side <= 1; side += 2) {
        rugo_rng rng;
        rugo_rng_seed(&rng, 4242); // the same poses on both sides
        for (int i = 0; i < n; ++i) {
            const int row = i / L.cols, col = i % L.cols, k = pile::ShapeOf(i, L);
            const double x = side * static_cast<double>(off) - 0.5 * (L.cols - 1) * L.spacing +
                             col * L.spacing + rugo_rng_range(&rng, -0.05, 0.05);
            const double y = 0.5 * L.spacing + 0.05 + row * L.spacing;
            const double ang = rugo_rng_range(&rng, 0.0, 2.0 * kPi);
            const rugo_vec2 c = set->centroid[static_cast<size_t>(k)];
            const double ca = std::cos(ang), sa = std::sin(ang);
            b2Body* b = AddBody(s, b2_dynamicBody,
                                b2Vec2(static_cast<float>(x - (ca * c.x - sa * c.y)),
                                       static_cast<float>(y - (sa * c.x + ca * c.y))),
                                static_cast<float>(ang));
            if (side < 0) {
                if (!AttachRough(s, b, set->shapes[static_cast<size_t>(k)], pile::kDensity)) return false;
                continue;
            }
            for (const pile::Piece& pc : set->pieces[static_cast<size_t>(k)]) {
                b2PolygonShape ps;
                ps.Set(pc.v.data(), static_cast<int32>(pc.v.size()));
                b2FixtureDef fd;
                fd.shape = &ps;
                fd.density = static_cast<float>(pile::kDensity);
                fd.friction = 0.5f;
                b->CreateFixture(&fd);
            }
            s->w->bodies.push_back(b);
        }
    }
    const float top = static_cast<float>(L.wallHeight);
    s->viewLo.Set(-2.0f * off - 0.5f, -1.0f);
    s->viewHi.Set(2.0f * off + 0.5f, top);
    s->note = "The benchmark's pile: left, rough bodies through the bridge (automatic level, 5 mm budget); "
              "right, the same outlines as Box2D polygon compounds within 5 mm (friction 0.5).";
    return true;
}

// ---- a ramp whose friction grows along it ---------------------------------------------------------

// An 8 m slab tilted 20 degrees whose top surface's λ grows linearly from the library's smoothest
// (μ = 0.1) at the high end to its roughest (μ = 0.9) at the low end: sleds speed up on the smooth
// part and stop where μ passes tan 20° = 0.36, a third of the way down.
bool BuildRamp(int, Scene* s) {
    NewWorld(s);
    const double hl = 4.0, ht = 0.2;
    const int n = 256;
    const std::vector<rugo_vec2> pts =
        SampleOutline({rugo_v2(-hl, -ht), rugo_v2(hl, -ht), rugo_v2(hl, ht), rugo_v2(-hl, ht)}, n);
    const double lamLo = 0.04 * SCENE_ROUGHNESS_SCALE, lamHi = 0.65 * SCENE_ROUGHNESS_SCALE;
    std::vector<double> lam(static_cast<size_t>(n), lamLo);
    for (int i = 0; i < n; ++i) {
        const rugo_vec2 a = pts[static_cast<size_t>(i)], b = pts[static_cast<size_t>((i + 1) % n)];
        if (a.y > 0.9 * ht && b.y > 0.9 * ht) { // the top surface
            const double u = (0.5 * (a.x + b.x) + hl) / (2.0 * hl);
            lam[static_cast<size_t>(i)] = lamLo + (lamHi - lamLo) * (1.0 - u); // rough at low x
        }
    }
    const rugo_shape* ramp = MakeShape(pts, lam, s);
    // The sled: a 0.6 m x 0.24 m block, smooth (λ of the library's smoothest surface).
    const std::vector<rugo_vec2> sp = SampleOutline(
        {rugo_v2(-0.3, -0.12), rugo_v2(0.3, -0.12), rugo_v2(0.3, 0.12), rugo_v2(-0.3, 0.12)}, 32);
    const rugo_shape* sled = MakeShape(sp, std::vector<double>(32, lamLo), s);
    if (!ramp || !sled) return false;
    const float angle = static_cast<float>(20.0 * kPi / 180.0);
    // High end on the right: rotate by +20 degrees; the top surface's x runs from the low end (-4)
    // to the high end (+4), rough at the low end.
    b2Body* rb = AddBody(s, b2_staticBody, b2Vec2(0.0f, 0.0f), angle);
    if (!AttachRough(s, rb, ramp, 1.0)) return false;
    const b2Vec2 down(-std::cos(angle), -std::sin(angle)), normal(-std::sin(angle), std::cos(angle));
    for (int i = 0; i < 2; ++i) {
        const float along = 3.5f - 1.0f * static_cast<float>(i); // distance from the centre, up the ramp
        const b2Vec2 p = -along * down + (static_cast<float>(ht) + 0.13f) * normal;
        b2Body* b = AddBody(s, b2_dynamicBody, p, angle);
        if (!AttachRough(s, b, sled, 2.0)) return false;
    }
    b2Body* ground = AddBody(s, b2_staticBody, b2Vec2(0.0f, 0.0f));
    AddBox(ground, 6.0f, 0.25f, b2Vec2(-1.0f, -2.0f));
    s->viewLo.Set(-5.5f, -2.5f);
    s->viewHi.Set(4.5f, 2.5f);
    s->note = "A 20-degree ramp whose surface goes from mu = 0.1 (top) to mu = 0.9 (bottom): the sleds "
              "stop where mu passes tan 20 = 0.36. Turn on bands (exaggerated) and contacts.";
    return true;
}

// ---- levels of detail switched live ---------------------------------------------------------------

// Fig. 7.13's scene at the finest level, switched every 2 s to the next level of 0, -1, -2, -3, -2,
// -1 (every rough body detached and attached again at it, its pose and velocity kept).
bool BuildLodLive(int, Scene* s) {
    if (!FromTable("fig7_13_levels", 2, s)) return false;
    s->note = "Fig. 7.13's bodies; the level of detail of every rough body switches every 2 s (0, -1, -2, "
              "-3, -2, -1). Choose 'scene' or 'error budget' under Level of detail to stop the cycle.";
    s->preStep = [](Scene& sc, Testbed& tb) {
        static const int kCycle[] = {0, -1, -2, -3, -2, -1};
        const long period = 120;
        if (sc.w->steps == 0) tb.settings.detail = Detail::kLevel;
        if (tb.settings.detail != Detail::kLevel) {
            tb.status = "level cycle stopped";
            return;
        }
        if (sc.w->steps % period == 0) {
            tb.settings.level = kCycle[(sc.w->steps / period) % 6];
            tb.ApplyDetail();
        }
        char buf[96];
        std::snprintf(buf, sizeof buf, "level cycle: level %d for %.1f s more", tb.settings.level,
                      static_cast<double>(period - sc.w->steps % period) * sc.dt);
        tb.status = buf;
    };
    return true;
}

// ---- a wheel in a groove --------------------------------------------------------------------------

// A rough wheel and an ordinary Box2D circle of the same size released on either side of a circular
// groove cut into a rough block: they roll down, cross and rock until they rest at the bottom.
bool BuildWheelGroove(int, Scene* s) {
    NewWorld(s);
    // The block: x in [-3, 3], y in [-1, 0], a groove of radius 1.5 m, 0.6 m deep, |x| <= 1.2.
    const double R = 1.5, cy = 0.9, a0 = std::atan2(0.0 - cy, 1.2);
    std::vector<rugo_vec2> poly = {rugo_v2(-3.0, -1.0), rugo_v2(3.0, -1.0), rugo_v2(3.0, 0.0),
                                   rugo_v2(1.2, 0.0)};
    // The groove: the circle's lower arc from (1.2, 0) at angle a0 to (-1.2, 0), through the bottom
    // (angle -90 degrees), clockwise seen from the centre, which is counter-clockwise along the block.
    const double start = a0, end = -kPi - a0; // e.g. -36.9 deg down to -143.1 deg
    for (int k = 1; k < 48; ++k) {
        const double a = start + (end - start) * k / 48.0;
        poly.push_back(rugo_v2(R * std::cos(a), cy + R * std::sin(a)));
    }
    poly.push_back(rugo_v2(-1.2, 0.0));
    poly.push_back(rugo_v2(-3.0, 0.0));
    const int n = 256;
    const rugo_shape* block = MakeShape(SampleOutline(poly, n), Preset(RUGO_PRESET_TIPO_2, 31, n), s);
    // The wheel: radius 0.3 m, 64 control points, tipo_3 roughness.
    std::vector<rugo_vec2> wheel;
    for (int k = 0; k < 64; ++k) {
        const double a = 2.0 * kPi * k / 64;
        wheel.push_back(rugo_v2(0.3 * std::cos(a), 0.3 * std::sin(a)));
    }
    const rugo_shape* ws = MakeShape(wheel, Preset(RUGO_PRESET_TIPO_3, 32, 64), s);
    if (!block || !ws) return false;
    b2Body* bb = AddBody(s, b2_staticBody, b2Vec2(0.0f, 0.0f));
    if (!AttachRough(s, bb, block, 1.0)) return false;
    b2Body* wb = AddBody(s, b2_dynamicBody, b2Vec2(-2.2f, 0.33f));
    if (!AttachRough(s, wb, ws, 1.0)) return false;
    wb->SetLinearVelocity(b2Vec2(1.5f, 0.0f));
    b2Body* cb = AddBody(s, b2_dynamicBody, b2Vec2(2.2f, 0.32f));
    b2CircleShape circle;
    circle.m_radius = 0.3f;
    b2FixtureDef fd;
    fd.shape = &circle;
    fd.density = 1.0f;
    fd.friction = 0.5f;
    cb->CreateFixture(&fd);
    cb->SetLinearVelocity(b2Vec2(-1.5f, 0.0f));
    s->w->bodies.push_back(cb);
    s->viewLo.Set(-3.3f, -1.3f);
    s->viewHi.Set(3.3f, 1.5f);
    s->note = "A rough wheel (left, tipo_3) and a Box2D circle (right) rolling in a groove cut into a "
              "rough block (tipo_2).";
    return true;
}

// ---- a conveyor -----------------------------------------------------------------------------------

// A rough belt whose surface moves at 1.5 m/s (Box2D's tangent speed, set in PreSolve on the contacts
// the bridge has written), fed with a rock every 0.75 s, dropping them into a bin.
bool BuildConveyor(int, Scene* s) {
    NewWorld(s);
    const int n = 256;
    const std::vector<rugo_vec2> pts = SampleOutline(
        {rugo_v2(-3.5, -0.125), rugo_v2(3.5, -0.125), rugo_v2(3.5, 0.125), rugo_v2(-3.5, 0.125)}, n);
    const rugo_shape* belt = MakeShape(pts, Preset(RUGO_PRESET_TIPO_1, 41, n), s);
    if (!belt) return false;
    b2Body* bb = AddBody(s, b2_staticBody, b2Vec2(-1.0f, 1.0f));
    if (!AttachRough(s, bb, belt, 1.0)) return false;
    s->belt = bb;
    s->beltSpeed = 1.5f;
    b2Body* bin = AddBody(s, b2_staticBody, b2Vec2(0.0f, 0.0f));
    AddBox(bin, 2.0f, 0.2f, b2Vec2(4.5f, -1.5f));
    AddBox(bin, 0.15f, 1.2f, b2Vec2(2.6f, -0.5f));
    AddBox(bin, 0.15f, 1.6f, b2Vec2(6.4f, -0.1f));
    s->viewLo.Set(-5.0f, -2.0f);
    s->viewHi.Set(7.0f, 3.0f);
    s->note = "A rough belt moving at 1.5 m/s (tangent speed) carries rocks into a bin; a rock every 0.75 s, "
              "24 in all.";
    s->preStep = [](Scene& sc, Testbed& tb) {
        const long every = 45, count = 24;
        if (sc.w->steps % every == 0 && sc.w->steps / every < count) tb.Spawn(b2Vec2(-3.8f, 1.7f));
    };
    return true;
}

bool Demo(int v, Scene* s) { return FromTable("demo", v, s); }
bool Ball(int v, Scene* s) { return FromTable("fig7_5_ball", v, s); }
bool Thrown(int v, Scene* s) { return FromTable("fig7_8_thrown", v, s); }
bool FourBodies(int v, Scene* s) { return FromTable("fig7_9_four_bodies", v, s); }
bool Grafica(int v, Scene* s) { return FromTable("fig7_10_grafica", v, s); }
bool Levels(int v, Scene* s) { return FromTable("fig7_13_levels", v, s); }

int Variants(const char* name) {
    const scene_table::Entry* e = scene_table::Find(name);
    return e ? e->variants : 1;
}

} // namespace

const std::vector<SceneInfo>& SceneList() {
    static const std::vector<SceneInfo> list = {
        {"demo", "Main demo (README)", Variants("demo"), Demo},
        {"fig7_5_ball", "Fig. 7.5 ball on a block", Variants("fig7_5_ball"), Ball},
        {"fig7_8_thrown", "Fig. 7.8 thrown body", Variants("fig7_8_thrown"), Thrown},
        {"fig7_9_four_bodies", "Fig. 7.9 four bodies", Variants("fig7_9_four_bodies"), FourBodies},
        {"fig7_10_grafica", "Fig. 7.10 letters", Variants("fig7_10_grafica"), Grafica},
        {"fig7_13_levels", "Fig. 7.13 levels of detail", Variants("fig7_13_levels"), Levels},
        {"pile_vs_polygons", "Pile: rough | polygons", 2, BuildPileSideBySide},
        {"friction_ramp", "Ramp, friction along it", 1, BuildRamp},
        {"lod_live", "Levels switched live", 1, BuildLodLive},
        {"wheel_groove", "Wheel in a groove", 1, BuildWheelGroove},
        {"conveyor", "Conveyor", 1, BuildConveyor},
    };
    return list;
}

} // namespace testbed
