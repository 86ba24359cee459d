// Determinism of the samples' scenes, pinned: every scene of the scene table (samples/common/
// scene_table.hpp: the README's demo and the chapter-7 scenes through the Box2D bridge, and the Box2D
// scenes benchmark's pile in its four variants) and the chapter-7 scenes in librugo's own simulator run
// twice in this process. Both runs must give the same hash of every body's transform after every step,
// and it must equal the value pinned below. The normal and the sanitizer build pin the same values, so a
// pin also holds across processes, builds and commits, not only within one run (docs/determinism.md).
//
// Why a pinned hash changes: any change that moves a body by one bit (a contact rule, an iteration
// order, a bug fixed, the shapes or the placement of a scene) changes its scene's hash, and so does a
// different libbox2d binary or C library (docs/determinism.md, "Limits"). Such a change may be right. To
// re-pin: run the scene's sample (samples/box2d/b2_<name>, samples/simulator/sim_<name>) and check that
// its physical checks still pass, find out why the trajectory moved, say so in the commit message, and
// copy the value this test reports ("got ...") into the tables below. A scene added to the table fails
// here until it is pinned.
#include "scene_table.hpp"

extern "C" {
#include "sample_check.h"
#include "sim_sample.h"
#include "test_util.h"
}

#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

namespace {

struct Pin {
    const char* scene; // a row of the scene table (scene_table::kScenes)
    int variant;
    std::uint64_t hash;
};

// Box2D: FNV-1a over the float bits of (x, y, angle) of every body after every step
// (scene_table::HashBodies), over the row's stepCount steps.
const Pin kBox2dPins[] = {
    {"demo", 0, 0x4579cd6492f86168ULL},
    {"fig7_5_ball", 0, 0x8a6d724680ff5ea5ULL},
    {"fig7_5_ball", 1, 0x20769c029898ed66ULL},
    {"fig7_5_ball", 2, 0xccee96ceecc2e412ULL},
    {"fig7_5_ball", 3, 0xeb6525b02a90d670ULL},
    {"fig7_5_ball", 4, 0x6807451207f863a0ULL},
    {"fig7_5_ball", 5, 0x195adbc5fc13160dULL},
    {"fig7_8_thrown", 0, 0x569a15ed4c50d485ULL},
    {"fig7_8_thrown", 1, 0xd03f8b660937365bULL},
    {"fig7_9_four_bodies", 0, 0xaf5244f743fe976bULL},
    {"fig7_10_grafica", 0, 0xca23ee0343e7bbe1ULL},
    {"fig7_10_grafica", 1, 0xcdb85e99dee3c0c8ULL},
    {"fig7_13_levels", 0, 0xee91a4dd59d56505ULL},
    {"fig7_13_levels", 1, 0xc7a1b405d9732e87ULL},
    {"fig7_13_levels", 2, 0xbe04e9d422fc531cULL},
    // N = 16 bodies of S = 64 segments (scene_table::Args' defaults): auto, finest, polygon, circle
    {"rock_pile", 0, 0xb2dd05f043676621ULL},
    {"rock_pile", 1, 0x47596e15a10131c9ULL},
    {"rock_pile", 2, 0xbf2b20157d62dc08ULL},
    {"rock_pile", 3, 0xab8771cb6172483bULL},
};

// The simulator (rugo_world, samples/simulator/sim_sample.h): the same scenes.h scenes, FNV-1a over the
// double bits of (p.x, p.y, q.c, q.s) of every body at the start and after every step, over the scene's
// duration. The simulator has rough bodies only, so the demo is not one of them.
struct SimPin {
    const char* scene;
    scene_id id;
    int variant;
    std::uint64_t hash;
};
const SimPin kSimPins[] = {
    {"fig7_5_ball", SCENE_BALL, 0, 0xd91fe8f92fb43c1eULL},
    {"fig7_5_ball", SCENE_BALL, 1, 0x5820cc343cf8f0d4ULL},
    {"fig7_5_ball", SCENE_BALL, 2, 0x25147ecb10bf7863ULL},
    {"fig7_5_ball", SCENE_BALL, 3, 0xc0f01c2ce6d4f6bdULL},
    {"fig7_5_ball", SCENE_BALL, 4, 0xd6b58840b664f1e3ULL},
    {"fig7_5_ball", SCENE_BALL, 5, 0x3af52a519c7df205ULL},
    {"fig7_8_thrown", SCENE_THROWN, 0, 0x6a9a194d88b7c744ULL},
    {"fig7_8_thrown", SCENE_THROWN, 1, 0x9e749c836f2e848dULL},
    {"fig7_9_four_bodies", SCENE_FOUR_BODIES, 0, 0xd36a33c0584b649fULL},
    {"fig7_10_grafica", SCENE_GRAFICA, 0, 0x77ed0a1445bd32d6ULL},
    {"fig7_10_grafica", SCENE_GRAFICA, 1, 0xaabf7cc3fb0604faULL},
    {"fig7_13_levels", SCENE_LEVELS, 0, 0xcbb664e804bf8ecfULL},
    {"fig7_13_levels", SCENE_LEVELS, 1, 0x1ee4b421cfc02439ULL},
    {"fig7_13_levels", SCENE_LEVELS, 2, 0xe8fcd66077d414a3ULL},
};

constexpr int kBox2dPinCount = static_cast<int>(sizeof kBox2dPins / sizeof kBox2dPins[0]);
constexpr int kSimPinCount = static_cast<int>(sizeof kSimPins / sizeof kSimPins[0]);

// Every (row, variant) of the scene table, in table order: the loop index of the Box2D test.
struct Case {
    const scene_table::Entry* entry;
    int variant;
};
std::vector<Case> TableCases() {
    std::vector<Case> cases;
    for (int i = 0; i < scene_table::kSceneCount; ++i)
        for (int v = 0; v < scene_table::kScenes[i].variants; ++v)
            cases.push_back({&scene_table::kScenes[i], v});
    return cases;
}

const Pin* FindPin(const char* scene, int variant) {
    for (const Pin& p : kBox2dPins)
        if (std::strcmp(p.scene, scene) == 0 && p.variant == variant) return &p;
    return nullptr;
}

// One run of a table scene: its hash, or false if it could not be built. The first run also checks the
// row against the scene's own description.
bool RunBox2d(const scene_table::Entry& e, int variant, bool checkRow, std::uint64_t* hash) {
    scene_table::World w;
    scene_table::Args args;
    args.variant = variant;
    if (!scene_table::Create(e, args, &w)) return false;
    if (checkRow && w.sc != nullptr) {
        // The row's step count is the scene's duration, its variants are the scene's (scenes.c).
        ck_assert_int_eq(e.stepCount, std::lround(w.sc->duration / w.sc->time_step));
        ck_assert_int_eq(e.variants, scene_variant_count(w.sc->id));
    }
    std::uint64_t h = SAMPLE_FNV_OFFSET;
    for (int k = 0; k < e.stepCount; ++k) {
        w.Step();
        h = scene_table::HashBodies(h, w);
    }
    *hash = h;
    return true;
}

START_TEST(test_box2d_scene) {
    const std::vector<Case> cases = TableCases();
    ck_assert_int_lt(_i, static_cast<int>(cases.size()));
    const Case& c = cases[static_cast<std::size_t>(_i)];
    std::uint64_t h1 = 0, h2 = 0;
    ck_assert_msg(RunBox2d(*c.entry, c.variant, true, &h1), "%s variant %d: not built", c.entry->name,
                  c.variant);
    ck_assert_msg(RunBox2d(*c.entry, c.variant, false, &h2), "%s variant %d: not built again", c.entry->name,
                  c.variant);
    std::printf("box2d %-20s variant %d: %d steps, hash %016" PRIx64 "\n", c.entry->name, c.variant,
                c.entry->stepCount, h1);
    ck_assert_msg(h1 == h2, "%s variant %d: two runs in one process differ: %016" PRIx64 " and %016" PRIx64,
                  c.entry->name, c.variant, h1, h2);
    const Pin* pin = FindPin(c.entry->name, c.variant);
    ck_assert_msg(pin != nullptr, "%s variant %d: no pinned hash; got %016" PRIx64, c.entry->name, c.variant,
                  h1);
    ck_assert_msg(pin->hash == h1, "%s variant %d: pinned %016" PRIx64 ", got %016" PRIx64, c.entry->name,
                  c.variant, pin->hash, h1);
}
END_TEST

// One run of a scene in the simulator: its hash, or false if it could not be built or stepped.
bool RunSim(scene_id id, int variant, std::uint64_t* hash) {
    static scene s;
    if (scene_create(id, variant, &s) != RUGO_OK) return false;
    sim_run r;
    bool ok = sim_build(&r, &s, nullptr) == 0;
    const long n = std::lround(s.duration / s.time_step);
    for (long k = 0; ok && k < n; ++k)
        ok = sim_step(&r) == 0;
    *hash = r.hash;
    sim_destroy(&r);
    scene_destroy(&s);
    return ok;
}

START_TEST(test_simulator_scene) {
    const SimPin& p = kSimPins[_i];
    std::uint64_t h1 = 0, h2 = 0;
    ck_assert_msg(RunSim(p.id, p.variant, &h1), "%s variant %d: did not run", p.scene, p.variant);
    ck_assert_msg(RunSim(p.id, p.variant, &h2), "%s variant %d: did not run again", p.scene, p.variant);
    std::printf("simulator %-16s variant %d: hash %016" PRIx64 "\n", p.scene, p.variant, h1);
    ck_assert_msg(h1 == h2, "%s variant %d: two runs in one process differ: %016" PRIx64 " and %016" PRIx64,
                  p.scene, p.variant, h1, h2);
    ck_assert_msg(p.hash == h1, "%s variant %d: pinned %016" PRIx64 ", got %016" PRIx64, p.scene, p.variant,
                  p.hash, h1);
}
END_TEST

// Every pin names a scene that exists, once: a renamed or removed scene must take its pin along.
START_TEST(test_pins_name_scenes) {
    for (int i = 0; i < kBox2dPinCount; ++i) {
        const Pin& p = kBox2dPins[i];
        const scene_table::Entry* e = scene_table::Find(p.scene);
        ck_assert_msg(e != nullptr && p.variant >= 0 && p.variant < e->variants,
                      "pin %s variant %d: no such scene", p.scene, p.variant);
        ck_assert_msg(FindPin(p.scene, p.variant) == &p, "pin %s variant %d: pinned twice", p.scene,
                      p.variant);
    }
    for (int i = 0; i < kSimPinCount; ++i) {
        const SimPin& p = kSimPins[i];
        ck_assert_msg(p.variant >= 0 && p.variant < scene_variant_count(p.id),
                      "simulator pin %s variant %d: no such scene", p.scene, p.variant);
        for (int j = 0; j < i; ++j)
            ck_assert_msg(kSimPins[j].id != p.id || kSimPins[j].variant != p.variant,
                          "simulator pin %s variant %d: pinned twice", p.scene, p.variant);
    }
}
END_TEST

} // namespace

int main(void) {
    Suite* s = suite_create("determinism");
    TCase* tc = tcase_create("pinned");
    tcase_set_timeout(tc, 1200);
    tcase_add_test(tc, test_pins_name_scenes);
    tcase_add_loop_test(tc, test_box2d_scene, 0, static_cast<int>(TableCases().size()));
    tcase_add_loop_test(tc, test_simulator_scene, 0, kSimPinCount);
    suite_add_tcase(s, tc);
    return test_run_suite(s);
}
