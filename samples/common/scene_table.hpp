// The Box2D-bridge scenes in one table: a scene is (name, variants, create, step, step count). The Box2D
// samples (samples/box2d), the Box2D scenes benchmark (samples/bench/bench_box2d_scenes.cpp) and the
// determinism test (tests/test_determinism.cpp) all build and step their scenes through it, so a pinned
// hash, a sample's checks and a benchmark's times are about one and the same scene. What the scenes
// are is said elsewhere: the thesis' chapter-7 scenes and the README's demo engine-neutrally in
// scenes.h (the simulator samples run those too), the benchmark's pile of rocks in pile_scene.hpp.
#ifndef RUGO_SAMPLES_SCENE_TABLE_HPP
#define RUGO_SAMPLES_SCENE_TABLE_HPP

#include "rugo/box2d.hpp"

#include "scenes.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace pile {
struct ShapeSet;
}

namespace scene_table {

struct Entry;

// What a scene is built from besides its name. Only the pile reads more than the variant; its default
// size is the benchmark's first row (N = 16 at S = 64), where the automatic level is not the finest.
struct Args {
    int variant = 0;               // 0 .. Entry::variants - 1
    int bodies = 16;               // the pile: N bodies
    int segments = 64;             // the pile: S control points per shape
    int maxProxies = 0;            // the pile: BridgeDef::maxProxies (0: the bridge's default)
    double reuseDistance = -1.0;   // the pile: BridgeDef::reuseDistance (< 0: the bridge's default)
    double queryResolution = -1.0; // the pile: BridgeDef::queryResolution (< 0: the bridge's default)
    bool continuous = true;        // the pile: Box2D's continuous collision
    // The pile: its shapes of `segments` control points when built before (the benchmark builds them
    // once for all variants and body counts); null: the scene builds them.
    std::shared_ptr<const pile::ShapeSet> pileShapes;
};

// A scene living in a b2World, as its Entry's create built it. The bridge goes before the world, and
// both before the shapes they use (box2d.hpp: lifetime).
struct World {
    const Entry* entry = nullptr; // the table row that built it
    const scene* sc = nullptr;    // the description (scenes.h) of a scenes.h scene; null for the pile
    std::shared_ptr<const scene> description;         // owns *sc: a sample may keep it beyond the world
    std::shared_ptr<const pile::ShapeSet> pileShapes; // the pile's shapes
    std::unique_ptr<b2World> world;
    std::unique_ptr<rugo::Bridge> bridge; // null when no body is rough (the pile's polygons and circles)
    std::vector<b2Body*> bodies; // the scene's bodies in creation order (of the pile: the rocks, not the
                                 // container); index = scene body index for a scenes.h scene
    std::vector<double> bands; // scenes.h scenes: widest band of each body at its contact level (0: ordinary)
    double time = 0.0;
    long steps = 0;

    World() = default;
    World(const World&) = delete;
    World& operator=(const World&) = delete;
    ~World() {
        bridge.reset();
        world.reset();
    }

    // One step, the scene's own (Entry::step).
    void Step();
    // The scene body index of a body (-1 if none), and the nth body of a role (scenes.h scenes).
    int Index(const b2Body* b) const;
    int Find(scene_role role, int nth = 0) const;
};

struct Entry {
    const char* name;
    int variants;
    // Builds the scene into an empty world; false, with a message, if it cannot.
    bool (*create)(const Args& args, World* world);
    void (*step)(World* world);
    // A full run: what the samples run and the determinism test hashes.
    int stepCount;
};

// The table.
extern const Entry kScenes[];
extern const int kSceneCount;

// The row called name; nullptr if there is none.
const Entry* Find(const char* name);
// Builds a row's scene (world->entry = &entry). The second form finds the row by name.
bool Create(const Entry& entry, const Args& args, World* world);
bool Create(const char* name, int variant, World* world);

// FNV-1a, continuing h, over the float bits of (x, y, angle) of every body of world.bodies in order, as
// Box2D's own determinism test hashes transforms.
std::uint64_t HashBodies(std::uint64_t h, const World& world);

} // namespace scene_table

#endif
