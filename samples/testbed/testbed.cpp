// The testbed's verbs (testbed.hpp): loading a scene, stepping it with timing, the mouse joint,
// spawning rocks, re-attaching rough bodies at another level of detail, the last step's contacts.
#include "testbed.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace testbed {

namespace {

using Clock = std::chrono::steady_clock;

double Ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

// Running means of the timing figures: each new step weighs this much.
constexpr double kTimingWeight = 0.05;

} // namespace

Scene::~Scene() {
    w.reset(); // the bridge and the world go before the shapes they use
    for (rugo_shape* s : ownedShapes)
        rugo_shape_destroy(s);
}

// ---- camera ---------------------------------------------------------------------------------------
b2Vec2 Camera::ToScreen(b2Vec2 p) const {
    return b2Vec2(0.5f * width + (p.x - center.x) * pixelsPerMetre,
                  0.5f * height - (p.y - center.y) * pixelsPerMetre);
}

b2Vec2 Camera::ToWorld(b2Vec2 s) const {
    return b2Vec2(center.x + (s.x - 0.5f * width) / pixelsPerMetre,
                  center.y - (s.y - 0.5f * height) / pixelsPerMetre);
}

void Camera::Fit(b2Vec2 lo, b2Vec2 hi) {
    center = 0.5f * (lo + hi);
    const float w = std::max(hi.x - lo.x, 0.1f), h = std::max(hi.y - lo.y, 0.1f);
    pixelsPerMetre = 0.92f * std::min(width / w, height / h);
}

// ---- the contact listener: timing, the conveyor, the mouse joint's end ----------------------------
//
// Box2D calls PreSolve from inside b2World::Step, first in its collide phase (every touching contact
// after its narrow phase) and again in its TOI phase. The bridge is the world's listener and chains to
// this one at the end of its own PreSolve, so the time from this listener's previous callback to a
// rough contact's PreSolve is the bridge's work on that contact (plus Box2D's box-vs-box test of the
// proxy pair, a fraction of a microsecond). Summed over the collide phase (the step's time minus
// Box2D's solve and TOI phases), that is the bridge's share; the TOI phase's rough contacts are not
// counted (Box2D's TOI search runs between its callbacks).
class Testbed::Listener : public b2ContactListener, public b2DestructionListener {
  public:
    explicit Listener(Testbed* tb) : m_tb(tb) {}

    void BeginStep() {
        m_start = m_last = Clock::now();
        m_calls.clear();
    }
    // The bridge's share of the step's collide phase, given its end (ms after BeginStep).
    double BridgeMs(double collideEnd) const {
        double sum = 0.0;
        for (const Call& c : m_calls)
            if (c.at <= collideEnd) sum += c.gap;
        return sum;
    }

    void BeginContact(b2Contact*) override { m_last = Clock::now(); }
    void EndContact(b2Contact*) override { m_last = Clock::now(); }
    void PreSolve(b2Contact* c, const b2Manifold*) override {
        const Clock::time_point now = Clock::now();
        const rugo::Bridge* br = m_tb->m_scene->w->bridge.get();
        if (br && (br->IsProxy(c->GetFixtureA()) || br->IsProxy(c->GetFixtureB())))
            m_calls.push_back({Ms(now - m_start), Ms(now - m_last)});
        const Scene& s = *m_tb->m_scene;
        if (s.belt != nullptr) {
            // Box2D's conveyor: the belt's surface moves at beltSpeed along its tangent.
            if (c->GetFixtureA()->GetBody() == s.belt) c->SetTangentSpeed(s.beltSpeed);
            if (c->GetFixtureB()->GetBody() == s.belt) c->SetTangentSpeed(-s.beltSpeed);
        }
        m_last = Clock::now();
    }
    void PostSolve(b2Contact*, const b2ContactImpulse*) override { m_last = Clock::now(); }

    void SayGoodbye(b2Joint* joint) override {
        if (joint == m_tb->m_mouse) m_tb->m_mouse = nullptr;
    }
    void SayGoodbye(b2Fixture*) override {}

  private:
    struct Call {
        double at, gap; // ms since the step began, ms since the previous callback
    };
    Testbed* m_tb;
    Clock::time_point m_start, m_last;
    std::vector<Call> m_calls;
};

// ---- loading --------------------------------------------------------------------------------------
Testbed::Testbed() : m_listener(std::make_unique<Listener>(this)) {
    auto rocks = std::make_shared<pile::ShapeSet>();
    if (pile::BuildShapes(64, rocks.get())) m_rocks = rocks;
}

Testbed::~Testbed() {
    m_mouse = nullptr;
    m_scene.reset();
}

bool Testbed::Load(int sceneIndex, int variant) {
    const std::vector<SceneInfo>& list = SceneList();
    if (sceneIndex < 0 || sceneIndex >= static_cast<int>(list.size())) return false;
    variant = std::max(0, std::min(variant, list[static_cast<size_t>(sceneIndex)].variants - 1));
    auto s = std::make_unique<Scene>();
    s->name = list[static_cast<size_t>(sceneIndex)].name;
    s->variant = variant;
    // Built beside the running scene, which stays if the new one cannot be built.
    if (!list[static_cast<size_t>(sceneIndex)].build(variant, s.get())) return false;
    m_mouse = nullptr;
    m_anchor = nullptr;
    m_rough.clear();
    m_contacts.clear();
    m_scene = std::move(s);
    settings.detail = Detail::kScene;
    status.clear();
    m_sceneIndex = sceneIndex;
    m_variant = variant;
    m_steps = 0;
    m_spawnCount = 0;
    m_timing = Timing();
    b2World* world = m_scene->w->world.get();
    world->SetContactListener(m_listener.get()); // the bridge re-chains in front of it at the next step
    if (m_scene->w->bridge)
        m_scene->w->bridge->SetDestructionListener(m_listener.get());
    else
        world->SetDestructionListener(m_listener.get());
    settings.gravity = world->GetGravity().y;
    for (b2Body* b = world->GetBodyList(); b; b = b->GetNext()) {
        const rugo::Bridge* br = m_scene->w->bridge.get();
        if (!br || !br->IsRough(b)) continue;
        const rugo_shape* shape = br->GetShape(b);
        double density = 1.0; // static bodies: any positive value (their mass is not used)
        if (b->GetType() == b2_dynamicBody) {
            b2MassData md;
            br->GetExactMass(b, &md);
            density = md.mass / rugo_shape_mass(shape).area;
        }
        Record(b, shape, density, br->GetLevel(b) - rugo_shape_finest_level(shape));
    }
    b2BodyDef ad;
    m_anchor = world->CreateBody(&ad);
    camera.Fit(m_scene->viewLo, m_scene->viewHi);
    return true;
}

int FindScene(const std::string& name) {
    const std::vector<SceneInfo>& list = SceneList();
    for (size_t i = 0; i < list.size(); ++i)
        if (name == list[i].name) return static_cast<int>(i);
    return -1;
}

void Testbed::Record(b2Body* body, const rugo_shape* shape, double density, int lod) {
    m_rough[body] = RoughRecord{shape, density, lod};
}

// ---- stepping -------------------------------------------------------------------------------------
void Testbed::Frame() {
    if (settings.pause && !m_stepOnce) return;
    m_stepOnce = false;
    Scene& s = *m_scene;
    if (s.preStep) s.preStep(s, *this);
    b2World* world = s.w->world.get();
    m_listener->BeginStep();
    const Clock::time_point t0 = Clock::now();
    if (s.w->bridge)
        s.w->bridge->Step(s.dt, settings.velocityIterations, settings.positionIterations);
    else
        world->Step(s.dt, settings.velocityIterations, settings.positionIterations);
    const double ms = Ms(Clock::now() - t0);
    const b2Profile& prof = world->GetProfile();
    const double bridge = m_listener->BridgeMs(ms - prof.solve - prof.solveTOI);
    auto mix = [](double& avg, double v, bool first) { avg = first ? v : avg + kTimingWeight * (v - avg); };
    const bool first = m_steps == 0;
    mix(m_timing.stepMs, ms, first);
    mix(m_timing.bridgeMs, bridge, first);
    mix(m_timing.box2dMs, ms - bridge, first);
    mix(m_timing.collideMs, prof.collide, first);
    mix(m_timing.solveMs, prof.solve, first);
    mix(m_timing.toiMs, prof.solveTOI, first);
    s.w->time += s.dt;
    ++s.w->steps;
    ++m_steps;
    GatherContacts();
}

void Testbed::ApplyGravity() { m_scene->w->world->SetGravity(b2Vec2(0.0f, settings.gravity)); }

void Testbed::GatherContacts() {
    m_contacts.clear();
    const rugo::Bridge* br = m_scene->w->bridge.get();
    for (b2Contact* c = m_scene->w->world->GetContactList(); c; c = c->GetNext()) {
        if (!c->IsTouching() || !c->IsEnabled() || c->GetManifold()->pointCount == 0) continue;
        ContactView v;
        v.contact = c;
        v.a = c->GetFixtureA()->GetBody();
        v.b = c->GetFixtureB()->GetBody();
        v.rough = br && (br->IsProxy(c->GetFixtureA()) || br->IsProxy(c->GetFixtureB()));
        b2WorldManifold wm;
        c->GetWorldManifold(&wm);
        v.points = c->GetManifold()->pointCount;
        for (int k = 0; k < v.points; ++k) {
            v.p[k] = wm.points[k];
            v.separation[k] = wm.separations[k];
            v.normalImpulse[k] = c->GetManifold()->points[k].normalImpulse;
        }
        v.normal = wm.normal;
        v.friction = c->GetFriction();
        v.restitution = c->GetRestitution();
        v.hasInfo = v.rough;
        for (int k = 0; k < v.points && v.hasInfo; ++k)
            v.hasInfo = br->GetPointInfo(c, k, &v.info[k]) == RUGO_OK;
        m_contacts.push_back(v);
    }
}

// ---- the mouse joint ------------------------------------------------------------------------------
b2Body* Testbed::Pick(b2Vec2 p) const {
    const rugo::Bridge* br = m_scene->w->bridge.get();
    b2Body* found = nullptr;
    auto test = [&](b2Body* b) {
        if (b->GetType() != b2_dynamicBody) return true;
        if (br && br->IsRough(b)) {
            if (br->TestPoint(b, p)) found = b;
        } else {
            for (b2Fixture* f = b->GetFixtureList(); f; f = f->GetNext())
                if (!(br && br->IsProxy(f)) && f->TestPoint(p)) found = b;
        }
        return found == nullptr;
    };
    b2AABB box;
    box.lowerBound = p - b2Vec2(0.001f, 0.001f);
    box.upperBound = p + b2Vec2(0.001f, 0.001f);
    if (br) {
        br->QueryAABB(box, test);
    } else {
        struct Query : b2QueryCallback {
            std::function<bool(b2Body*)> f;
            bool ReportFixture(b2Fixture* fx) override { return f(fx->GetBody()); }
        } q;
        q.f = test;
        m_scene->w->world->QueryAABB(&q, box);
    }
    return found;
}

bool Testbed::MouseDown(b2Vec2 p) {
    if (m_mouse) MouseUp();
    b2Body* body = Pick(p);
    if (body == nullptr) return false;
    b2MouseJointDef jd;
    jd.bodyA = m_anchor;
    jd.bodyB = body;
    jd.target = p;
    jd.maxForce = 1000.0f * body->GetMass();
    b2LinearStiffness(jd.stiffness, jd.damping, 5.0f, 0.7f, jd.bodyA, jd.bodyB);
    m_mouse = static_cast<b2MouseJoint*>(m_scene->w->world->CreateJoint(&jd));
    body->SetAwake(true);
    return true;
}

void Testbed::MouseMove(b2Vec2 p) {
    if (m_mouse) m_mouse->SetTarget(p);
}

void Testbed::MouseUp() {
    if (m_mouse) m_scene->w->world->DestroyJoint(m_mouse);
    m_mouse = nullptr;
}

b2Body* Testbed::Dragged() const { return m_mouse ? m_mouse->GetBodyB() : nullptr; }

// ---- spawning and levels of detail ----------------------------------------------------------------
b2Body* Testbed::Spawn(b2Vec2 p) {
    rugo::Bridge* br = m_scene->w->bridge.get();
    if (!m_rocks || !br || m_scene->w->world->IsLocked()) return nullptr;
    const int k = static_cast<int>(m_spawnCount % pile::kShapes);
    const double angle = 2.399963 * static_cast<double>(m_spawnCount); // golden angle: varied poses
    ++m_spawnCount;
    const rugo_vec2 c = m_rocks->centroid[static_cast<size_t>(k)];
    const double ca = std::cos(angle), sa = std::sin(angle);
    b2BodyDef bd;
    bd.type = b2_dynamicBody;
    bd.angle = static_cast<float>(angle);
    // The body's origin is the shape's frame: put the centroid under the cursor.
    bd.position.Set(p.x - static_cast<float>(ca * c.x - sa * c.y),
                    p.y - static_cast<float>(sa * c.x + ca * c.y));
    b2Body* b = m_scene->w->world->CreateBody(&bd);
    const RoughRecord r{m_rocks->shapes[static_cast<size_t>(k)], pile::kDensity, RUGO_LOD_AUTO};
    Attach(b, r);
    if (!br->IsRough(b)) {
        m_scene->w->world->DestroyBody(b);
        return nullptr;
    }
    m_rough[b] = r;
    return b;
}

void Testbed::Attach(b2Body* body, const RoughRecord& r) {
    rugo::RoughBodyDef rd;
    rd.shape = r.shape;
    rd.density = r.density;
    switch (settings.detail) {
    case Detail::kScene:
        rd.lod = r.sceneLod;
        break;
    case Detail::kBudget:
        rd.lod = RUGO_LOD_AUTO;
        rd.errorBudget = settings.errorBudget;
        break;
    case Detail::kLevel:
        rd.lod =
            std::max(settings.level, rugo_shape_coarsest_level(r.shape) - rugo_shape_finest_level(r.shape));
        break;
    }
    const rugo_status st = m_scene->w->bridge->Attach(body, rd);
    if (st != RUGO_OK) std::fprintf(stderr, "testbed: Attach: %s\n", rugo_status_string(st));
}

void Testbed::ApplyDetail() {
    rugo::Bridge* br = m_scene->w->bridge.get();
    if (!br) return;
    for (const auto& kv : m_rough) {
        b2Body* b = const_cast<b2Body*>(kv.first);
        if (br->Detach(b) != RUGO_OK) continue;
        Attach(b, kv.second);
        b->SetAwake(true);
    }
    GatherContacts();
}

// ---- what the panel shows -------------------------------------------------------------------------
int Testbed::BodyCount() const { return m_scene->w->world->GetBodyCount() - (m_anchor ? 1 : 0); }

int Testbed::RoughBodyCount() const { return static_cast<int>(m_rough.size()); }

int Testbed::NearestContact(b2Vec2 p, float radius, int* k) const {
    int best = -1;
    float bestD = radius;
    for (size_t i = 0; i < m_contacts.size(); ++i)
        for (int j = 0; j < m_contacts[i].points; ++j) {
            const float d = b2Distance(p, m_contacts[i].p[j]);
            if (d <= bestD) {
                bestD = d;
                best = static_cast<int>(i);
                *k = j;
            }
        }
    return best;
}

SurfacePoint Testbed::Surface(const b2Body* body, b2Vec2 worldPoint) const {
    SurfacePoint sp;
    const rugo::Bridge* br = m_scene->w->bridge.get();
    if (!br || !br->IsRough(body)) return sp;
    const rugo_shape* shape = br->GetShape(body);
    sp.rough = true;
    sp.level = br->GetLevel(body);
    const b2Vec2 local = b2MulT(body->GetTransform(), worldPoint);
    rugo_curve_point cp;
    if (rugo_shape_closest_point(shape, sp.level, rugo_v2(local.x, local.y), &cp) != RUGO_OK) return sp;
    sp.segment = cp.segment;
    sp.t = cp.t;
    sp.distance = cp.distance;
    rugo_tolerance_level tl;
    if (rugo_shape_tolerance_level(shape, sp.level, &tl) == RUGO_OK)
        sp.lambda = rugo_tolerance_at(tl.total, tl.count, cp.segment, cp.t, 0.0);
    const rugo_friction_map map = rugo_shape_friction_map(shape);
    sp.mu = rugo_friction(&map, sp.lambda);
    return sp;
}

b2Color MuColour(float mu) {
    const float t = std::max(0.0f, std::min(1.0f, mu));
    if (t < 0.5f) return b2Color(0.2f, 0.4f + 1.2f * t, 1.0f - 1.6f * t);
    return b2Color(0.2f + 1.6f * (t - 0.5f), 1.0f - 1.2f * (t - 0.5f), 0.2f);
}

} // namespace testbed
