// Soak test of the Box2D bridge: the README's demo world (scene table "demo") stepped 100,000 times
// at 60 Hz while, every few steps, a rough body is detached, a detached one attached again, or a body
// destroyed and a new rough body spawned above the container (seeded choices; at most 8 detached at
// once), so the population stays about the same and the bridge's bookkeeping churns the whole time.
// Public bridge API only.
//
//   b2_soak             100,000 steps; checks: resident memory after warm-up (the first 10 %) grows by
//                       at most 1 %, 0 non-finite positions, angles or velocities, no body lost that was
//                       not destroyed (the world holds exactly the bodies alive), worst step <= 20x the
//                       median step (the thread's CPU time per step; the wall time is printed too).
//                       The live heap (glibc's count of bytes in live blocks) is printed beside the
//                       resident memory: a leak grows both, the allocator's fragmentation only the
//                       resident memory. The step-time tally is allocated before the warm-up ends.
//   b2_soak --quick     3,000 steps (the test suite): only the finiteness and body checks; the memory
//                       and time figures are printed, not checked (a loaded machine's timing is no
//                       verdict).
//   --steps N           another step count.
#include "b2_stress.hpp"
#include "scene_table.hpp"

extern "C" {
#include "sample_check.h"
}

#include <cstdlib>
#include <cstring>
#include <string>

namespace {

struct Tracked {
    b2Body* body;
    const rugo_shape* shape; // the shape it had (rough or detached), null for an ordinary body
};

} // namespace

// At most this many bodies detached at once (of the demo's 48 dynamic ones).
constexpr std::size_t kMostDetached = 8;

int main(int argc, char** argv) {
    bool quick = false;
    long steps = 100000;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) {
            quick = true;
            steps = 3000;
        } else if (std::strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
            steps = std::strtol(argv[++i], nullptr, 10);
        } else {
            std::fprintf(stderr, "usage: b2_soak [--quick] [--steps N]\n");
            return 2;
        }
    }
    if (steps < 100) steps = 100;

    scene_table::World w;
    if (!scene_table::Create("demo", 0, &w)) return 1;
    const scene& sc = *w.sc;
    std::vector<const rugo_shape*> shapes;
    double density = 1.0;
    int level = 0;
    std::vector<Tracked> dynamic; // the dynamic bodies alive
    std::set<const b2Body*> alive;
    for (int i = 0; i < sc.body_count; ++i) {
        alive.insert(w.bodies[static_cast<std::size_t>(i)]);
        if (sc.bodies[i].kind == SCENE_ROUGH) {
            shapes.push_back(sc.bodies[i].shape);
            density = sc.bodies[i].density;
            level = sc.bodies[i].level;
        }
        if (!sc.bodies[i].is_static)
            dynamic.push_back({w.bodies[static_cast<std::size_t>(i)],
                               sc.bodies[i].kind == SCENE_ROUGH ? sc.bodies[i].shape : nullptr});
    }
    std::vector<Tracked> detached;
    const double x0 = sc.view_lo.x, x1 = sc.view_hi.x, top = sc.view_hi.y;
    const double spawnLo = x0 + 0.3 * (x1 - x0), spawnHi = x0 + 0.7 * (x1 - x0);
    const double lost = sc.ground_top - 20.0; // below: fallen out (a detached body falls through)
    b2stress::Rng rng{25};
    auto spawnPoint = [&]() {
        return b2Vec2(static_cast<float>(rng.Uniform(spawnLo, spawnHi)), static_cast<float>(top - 1.0));
    };

    long detaches = 0, attaches = 0, destroys = 0, spawns = 0, recycled = 0, refused = 0;
    long nonFinite = 0, amiss = 0;
    const long warm = steps / 10;
    double rssWarm = 0.0, rssMax = 0.0, heapWarm = 0.0, heapMax = 0.0;
    int contactsMax = 0, contactsMaxWarm = 0;
    std::size_t attachedMost = 0, attachedMostWarm = 0; // dynamic bodies not detached
    b2stress::StepTimes times;
    times.Reserve(static_cast<std::size_t>(steps));
    for (long k = 0; k < steps; ++k) {
        if (k % 4 == 3) {
            int what = static_cast<int>(rng.Below(3));
            // Detach only while few are detached, attach again otherwise: detaches and attaches alone
            // would walk the detached count at random across 0..48, and every new high of bodies with
            // proxies would grow the world's high-water marks (contacts, broad-phase nodes, caches)
            // long after the warm-up.
            if (what == 0 && detached.size() >= kMostDetached) what = 1;
            if (what == 0 && !dynamic.empty()) { // detach a rough body
                const std::size_t i = rng.Below(dynamic.size());
                if (w.bridge->IsRough(dynamic[i].body)) {
                    if (w.bridge->Detach(dynamic[i].body) != RUGO_OK) sample_expect("Detach", 0);
                    detached.push_back(dynamic[i]);
                    dynamic.erase(dynamic.begin() + static_cast<std::ptrdiff_t>(i));
                    ++detaches;
                }
            } else if (what == 1 && !detached.empty()) { // attach a detached body again, above the pile
                const std::size_t i = rng.Below(detached.size());
                Tracked t = detached[i];
                detached.erase(detached.begin() + static_cast<std::ptrdiff_t>(i));
                t.body->SetTransform(spawnPoint(), static_cast<float>(rng.Uniform(-3.0, 3.0)));
                t.body->SetLinearVelocity(b2Vec2(0.0f, 0.0f));
                t.body->SetAngularVelocity(0.0f);
                rugo::RoughBodyDef rd;
                rd.shape = t.shape;
                rd.density = density;
                rd.lod = level;
                if (w.bridge->Attach(t.body, rd) != RUGO_OK) sample_expect("Attach again", 0);
                dynamic.push_back(t);
                ++attaches;
            } else if (what == 2 && !dynamic.empty()) { // destroy a body, spawn a new rough one
                const std::size_t i = rng.Below(dynamic.size());
                b2Body* victim = dynamic[i].body;
                dynamic.erase(dynamic.begin() + static_cast<std::ptrdiff_t>(i));
                alive.erase(victim);
                w.world->DestroyBody(victim);
                ++destroys;
                b2BodyDef bd;
                bd.type = b2_dynamicBody;
                bd.position = spawnPoint();
                bd.angle = static_cast<float>(rng.Uniform(-3.0, 3.0));
                b2Body* body = w.world->CreateBody(&bd);
                alive.insert(body);
                rugo::RoughBodyDef rd;
                rd.shape = shapes[rng.Below(shapes.size())];
                rd.density = density;
                rd.lod = level;
                if (w.bridge->Attach(body, rd) == RUGO_OK) {
                    dynamic.push_back({body, rd.shape});
                    ++spawns;
                } else {
                    ++refused;
                }
            }
        }
        // Detached bodies fall through everything: put those that left the container back on top.
        for (Tracked& t : detached)
            if (t.body->GetPosition().y < lost) {
                t.body->SetTransform(spawnPoint(), 0.0f);
                t.body->SetLinearVelocity(b2Vec2(0.0f, 0.0f));
                ++recycled;
            }
        times.Time([&] { w.Step(); });
        nonFinite += b2stress::NonFinite(*w.world);
        amiss += b2stress::BodiesAmiss(*w.world, alive);
        contactsMax = std::max(contactsMax, w.world->GetContactCount());
        attachedMost = std::max(attachedMost, dynamic.size());
        if (k + 1 == warm) {
            attachedMostWarm = attachedMost;
            rssWarm = b2stress::ResidentBytes();
            heapWarm = b2stress::LiveHeapBytes();
            contactsMaxWarm = contactsMax;
        }
        if (k + 1 > warm && (k + 1) % 500 == 0) {
            rssMax = std::max(rssMax, b2stress::ResidentBytes());
            heapMax = std::max(heapMax, b2stress::LiveHeapBytes());
        }
        if ((k + 1) % 10000 == 0 && k + 1 < steps) { // progress of a long run, in case it is cut short
            const std::vector<double> cpu = times.Cpu();
            std::printf(
                "  at step %ld: resident %.3f MiB, live heap %.3f MiB, %d contacts (most %d), %zu bodies "
                "detached, %ld non-finite, %ld amiss, step CPU median %.1f us, worst %.1f us, %.0f s CPU\n",
                k + 1, b2stress::ResidentBytes() / 1048576.0, b2stress::LiveHeapBytes() / 1048576.0,
                w.world->GetContactCount(), contactsMax, detached.size(), nonFinite, amiss,
                1e6 * b2stress::StepTimes::Median(cpu), 1e6 * b2stress::StepTimes::Worst(cpu),
                b2stress::StepTimes::Total(cpu));
        }
        if ((k + 1) % 10000 == 0) std::fflush(stdout);
    }
    const double rssEnd = b2stress::ResidentBytes(), heapEnd = b2stress::LiveHeapBytes();
    rssMax = std::max(rssMax, rssEnd);
    heapMax = std::max(heapMax, heapEnd);
    const double growth = rssWarm > 0.0 ? (rssMax - rssWarm) / rssWarm : 0.0;
    const double heapGrowth = heapWarm > 0.0 ? (heapMax - heapWarm) / heapWarm : 0.0;
    const std::vector<double> cpu = times.Cpu(), wall = times.Wall();
    const double median = b2stress::StepTimes::Median(cpu), worst = b2stress::StepTimes::Worst(cpu);
    const double wallMedian = b2stress::StepTimes::Median(wall), wallWorst = b2stress::StepTimes::Worst(wall);
    const rugo::BridgeStats st = w.bridge->GetStats();

    std::printf("b2_soak: %ld steps of the demo world (%d bodies at the start, %zu dynamic alive at the end, "
                "%zu of them detached)\n",
                steps, sc.body_count, dynamic.size() + detached.size(), detached.size());
    std::printf("  churn: %ld detaches, %ld attaches, %ld destroys, %ld spawns (%ld refused), %ld detached "
                "bodies recycled from below the container\n",
                detaches, attaches, destroys, spawns, refused, recycled);
    std::printf("  bridge: %ld queries, %ld pre-solves\n", st.queries, st.preSolves);
    std::printf("  resident memory: %.1f MiB after warm-up (%ld steps), %.1f MiB largest after, %.1f MiB at "
                "the end: growth %.3f %%\n",
                rssWarm / 1048576.0, warm, rssMax / 1048576.0, rssEnd / 1048576.0, 100.0 * growth);
    std::printf(
        "  live heap (mallinfo2): %.3f MiB after warm-up, %.3f MiB largest after, %.3f MiB at the end: "
        "growth %.3f %%; Box2D contacts: at most %d during warm-up, %d in the whole run; dynamic bodies not "
        "detached: at most %zu during warm-up, %zu in the whole run\n",
        heapWarm / 1048576.0, heapMax / 1048576.0, heapEnd / 1048576.0, 100.0 * heapGrowth, contactsMaxWarm,
        contactsMax, attachedMostWarm, attachedMost);
    std::printf(
        "  step CPU time: median %.1f us, worst %.1f us (%.1fx the median), total %.1f s; wall time: median "
        "%.1f us, worst %.1f us (%.1fx)\n",
        1e6 * median, 1e6 * worst, median > 0.0 ? worst / median : 0.0, b2stress::StepTimes::Total(cpu),
        1e6 * wallMedian, 1e6 * wallWorst, wallMedian > 0.0 ? wallWorst / wallMedian : 0.0);
    sample_expect_le("non-finite positions, angles, velocities", static_cast<double>(nonFinite), 0.0);
    sample_expect_le("bodies lost or added (step-body pairs)", static_cast<double>(amiss), 0.0);
    sample_expect("some churn of every kind", detaches > 0 && attaches > 0 && destroys > 0 && spawns > 0);
    if (!quick) {
        sample_expect_le("resident memory growth after warm-up", growth, 0.01);
        sample_expect_le("worst step / median step (CPU time)", median > 0.0 ? worst / median : 0.0, 20.0);
    }
    return sample_finish();
}
