// The testbed's state and verbs without any window code: a running scene, the settings the panel
// edits, stepping with timing, the mouse joint, spawning, level-of-detail changes, the contacts of the
// last step and the world drawn through a b2Draw (the bridge's debug draw for rough bodies). main.cpp
// owns the window; testbed_ui.cpp the panel; headless_run.cpp scripts it for the test.
#ifndef RUGO_TESTBED_TESTBED_HPP
#define RUGO_TESTBED_TESTBED_HPP

#include "rugo/box2d.hpp"

#include "pile_scene.hpp"
#include "scene_table.hpp"

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace testbed {

class Testbed;

// Where the world is on the screen: a view centre and a scale, over a viewport of pixels (y down).
struct Camera {
    b2Vec2 center{0.0f, 0.0f};
    float pixelsPerMetre = 60.0f;
    float width = 960.0f, height = 720.0f; // the world's viewport (the panel is to its right)
    b2Vec2 ToScreen(b2Vec2 p) const;
    b2Vec2 ToWorld(b2Vec2 screen) const;
    // Frames the box lo..hi with a margin.
    void Fit(b2Vec2 lo, b2Vec2 hi);
};

// A running scene: a scene-table world (scene_table.hpp), the shapes a testbed scene built itself
// (freed after the world), its framing and its per-step hook.
struct Scene {
    std::string name;
    int variant = 0;
    std::string note; // one line: what the scene shows
    std::unique_ptr<scene_table::World> w;
    std::vector<rugo_shape*> ownedShapes;
    std::shared_ptr<const pile::ShapeSet> pileShapes;
    float dt = 1.0f / 60.0f;
    b2Vec2 viewLo{-5.0f, -1.0f}, viewHi{5.0f, 5.0f};
    // Called before every step (the conveyor's belt and feed, the level cycling).
    std::function<void(Scene&, Testbed&)> preStep;
    b2Body* belt = nullptr; // the conveyor's belt: contacts with it get beltSpeed as tangent speed
    float beltSpeed = 0.0f;
    Scene() = default;
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;
    ~Scene();
};

// One row of the testbed's scene list.
struct SceneInfo {
    const char* name;
    const char* title;
    int variants;
    bool (*build)(int variant, Scene* out); // false, with a message on stderr, if it cannot
};
const std::vector<SceneInfo>& SceneList();
int FindScene(const std::string& name); // -1 if none

// How rough bodies choose their level of detail.
enum class Detail { kScene = 0, kBudget = 1, kLevel = 2 };

struct Settings {
    bool pause = false;
    // Drawing.
    bool drawCurves = true;
    bool drawBands = false;
    float bandExaggeration = 1.0f; // 1: the bridge's own band drawing; more: drawn here, λ times this
    bool drawProxies = false;
    bool drawTree = false;
    int treeLevel = 3;               // absolute MOBBtree level, clamped to each shape's J_min..J
    bool drawContacts = true;        // points and normals coloured by μ (this testbed)
    bool drawBridgeContacts = false; // the bridge's own kDrawContacts (red)
    bool drawOrdinary = true;        // ordinary Box2D fixtures
    // Level of detail of every rough body (applied live by detaching and re-attaching).
    Detail detail = Detail::kScene;
    float errorBudget = 0.005f; // m
    int level = 0;              // relative: 0 finest, -1, -2, ...
    // World.
    float gravity = -9.8f;
    int velocityIterations = 8, positionIterations = 3;
};

// A touching, enabled contact after the last step (what the contact toggle draws and hovering shows).
struct ContactView {
    b2Contact* contact = nullptr;
    b2Body *a = nullptr, *b = nullptr;
    bool rough = false;
    int points = 0;
    b2Vec2 p[2];
    float separation[2] = {0.0f, 0.0f};
    float normalImpulse[2] = {0.0f, 0.0f};
    b2Vec2 normal{0.0f, 0.0f}; // from a to b
    float friction = 0.0f, restitution = 0.0f;
    // The surfaces at each point as the bridge computed them (Bridge::GetPointInfo; rough contacts).
    bool hasInfo = false;
    rugo::PointInfo info[2];
};

// What the public API tells about one rough body at a world point: the closest point of its curve at
// its contact level (segment, t), the band λ(t) there and the surface's μ(λ) and ε.
struct SurfacePoint {
    bool rough = false;
    int level = -1, segment = -1;
    double t = 0.0, lambda = 0.0, mu = 0.0, distance = 0.0;
};

// Timing of the last steps (ms, running means over kTimingWindow steps).
struct Timing {
    double stepMs = 0.0;                                // Bridge::Step, wall clock
    double bridgeMs = 0.0;                              // the bridge's share: see ContactTimer (testbed.cpp)
    double box2dMs = 0.0;                               // the rest
    double collideMs = 0.0, solveMs = 0.0, toiMs = 0.0; // Box2D's b2Profile (collide includes PreSolve)
};

class Testbed {
  public:
    Testbed();
    ~Testbed();
    Testbed(const Testbed&) = delete;
    Testbed& operator=(const Testbed&) = delete;

    bool Load(int sceneIndex, int variant); // false, with a message, if the scene cannot be built
    bool Restart() { return Load(m_sceneIndex, m_variant); }
    int SceneIndex() const { return m_sceneIndex; }
    int Variant() const { return m_variant; }
    Scene& Current() { return *m_scene; }
    const Scene& Current() const { return *m_scene; }

    // One frame: steps once unless paused (or the single step asked for while paused).
    void Frame();
    void SingleStep() { m_stepOnce = true; }
    long Steps() const { return m_steps; }

    // Mouse in world coordinates: drag a dynamic body with a b2MouseJoint.
    bool MouseDown(b2Vec2 p); // true if a body was picked
    void MouseMove(b2Vec2 p);
    void MouseUp();
    b2Body* Dragged() const;
    b2Body* Pick(b2Vec2 p) const; // the dynamic body under p (its true curve for a rough body)
    // A rough rock (one of the pile's shapes) at p, at the current level-of-detail setting.
    b2Body* Spawn(b2Vec2 p);

    // Re-attaches every rough body at the level the settings say (after the panel changed them).
    void ApplyDetail();
    // Gravity and iterations take effect at the next step; gravity needs this.
    void ApplyGravity();

    void Draw(b2Draw* draw) const; // the whole world

    Settings settings;
    Camera camera;
    const Timing& GetTiming() const { return m_timing; }
    const std::vector<ContactView>& Contacts() const { return m_contacts; }
    // The contact point nearest to p within radius (world units); -1 if none; *k = its point index.
    int NearestContact(b2Vec2 p, float radius, int* k) const;
    SurfacePoint Surface(const b2Body* body, b2Vec2 worldPoint) const;
    int BodyCount() const; // the scene's bodies (not the testbed's mouse-joint anchor)
    int RoughBodyCount() const;
    int LevelOf(const b2Body* b) const { return m_scene->w->bridge->GetLevel(b); }
    // A line the scene's hook shows in the panel (the level cycle of lod_live).
    std::string status;
    // The contact whose tooltip the last frame showed (index into Contacts()); -1 if none.
    int hovered = -1;

  private:
    struct RoughRecord {
        const rugo_shape* shape;
        double density;
        int sceneLod; // the level the scene gave it (RoughBodyDef::lod)
    };
    class Listener;
    void Record(b2Body* body, const rugo_shape* shape, double density, int lod);
    void Attach(b2Body* body, const RoughRecord& r);
    void GatherContacts();
    void DrawOrdinary(b2Draw* draw) const;
    void DrawBands(b2Draw* draw) const;
    void DrawTree(b2Draw* draw) const;
    void DrawContacts(b2Draw* draw) const;

    std::unique_ptr<Scene> m_scene;
    std::unique_ptr<Listener> m_listener;
    std::shared_ptr<const pile::ShapeSet> m_rocks; // the spawned rocks' shapes
    std::map<const b2Body*, RoughRecord> m_rough;
    b2Body* m_anchor = nullptr; // static body the mouse joint hangs from
    b2MouseJoint* m_mouse = nullptr;
    std::vector<ContactView> m_contacts;
    Timing m_timing;
    int m_sceneIndex = 0, m_variant = 0;
    bool m_stepOnce = false;
    long m_steps = 0;
    std::uint64_t m_spawnCount = 0;
};

// Colour of a friction coefficient on the contacts' scale (0 blue .. 0.5 green .. 1 red).
b2Color MuColour(float mu);

} // namespace testbed

#endif
