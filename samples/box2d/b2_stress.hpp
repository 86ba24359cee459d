// Helpers of the Box2D stress samples (b2_soak.cpp, b2_adversarial.cpp): a tally of step times, the
// process's resident memory, the world's non-finite values and the accounting of bodies, and rough
// shapes of any size. Public bridge API only (rugo/box2d.hpp). Header-only; C++17.
#ifndef RUGO_SAMPLES_B2_STRESS_HPP
#define RUGO_SAMPLES_B2_STRESS_HPP

#include "rugo/box2d.hpp"

extern "C" {
#include "sample_shapes.h"
}

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <set>
#include <vector>

#include <time.h>
#if __has_include(<malloc.h>)
#include <malloc.h>
#endif
#include <unistd.h>

namespace b2stress {

// This thread's CPU time in seconds (what a step costs, without the time the machine gave to others).
inline double ThreadSeconds() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Wall time and this thread's CPU time of every step; medians and worsts. On a shared machine the wall
// time's worst step is mostly the scheduler (a 0.1 ms step descheduled for 40 ms), so the spike checks use
// the CPU time, and both are printed. Reserve(n) allocates and touches the room for n steps at once: a
// tally that grew as it went would itself be resident memory growing through a soak run (16 bytes a
// step, 1.6 MB over 100,000 steps).
struct StepTimes {
    std::vector<double> wall, cpu;
    std::size_t count = 0;
    void Reserve(std::size_t n) {
        wall.assign(n, 0.0);
        cpu.assign(n, 0.0);
        count = 0;
    }
    template <class F> void Time(F&& step) {
        const double c0 = ThreadSeconds();
        const auto t0 = std::chrono::steady_clock::now();
        step();
        const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const double c = ThreadSeconds() - c0;
        if (count < wall.size()) {
            wall[count] = w;
            cpu[count] = c;
        } else {
            wall.push_back(w);
            cpu.push_back(c);
        }
        ++count;
    }
    // The recorded steps of a tally.
    std::vector<double> Wall() const { return Head(wall); }
    std::vector<double> Cpu() const { return Head(cpu); }
    std::vector<double> Head(const std::vector<double>& v) const {
        return std::vector<double>(v.begin(),
                                   v.begin() + static_cast<std::ptrdiff_t>(std::min(count, v.size())));
    }
    static double Median(const std::vector<double>& v) {
        if (v.empty()) return 0.0;
        std::vector<double> s = v;
        std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2), s.end());
        return s[s.size() / 2];
    }
    static double Worst(const std::vector<double>& v) {
        return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
    }
    static double Total(const std::vector<double>& v) {
        double t = 0.0;
        for (double x : v)
            t += x;
        return t;
    }
};

// Resident memory of this process in bytes (Linux /proc/self/statm; 0 where it cannot be read).
inline double ResidentBytes() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (f == nullptr) return 0.0;
    long size = 0, resident = 0;
    const int n = std::fscanf(f, "%ld %ld", &size, &resident);
    std::fclose(f);
    return n == 2 ? static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) : 0.0;
}

// Bytes the process holds in live heap blocks (glibc's mallinfo2: in-use arena bytes plus mmap'ed
// blocks); -1 where that is not known. Against ResidentBytes it tells a leak (live bytes grow) from
// the allocator's fragmentation (resident memory grows, live bytes do not).
inline double LiveHeapBytes() {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
    const struct mallinfo2 mi = mallinfo2();
    return static_cast<double>(mi.uordblks) + static_cast<double>(mi.hblkhd);
#else
    return -1.0;
#endif
}

// Non-finite positions, angles and velocities over every body of the world.
inline long NonFinite(const b2World& world) {
    long n = 0;
    for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        const b2Vec2 p = b->GetPosition(), v = b->GetLinearVelocity();
        const float vals[6] = {p.x, p.y, b->GetAngle(), v.x, v.y, b->GetAngularVelocity()};
        for (float x : vals)
            n += !std::isfinite(x);
    }
    return n;
}

// Bodies the world holds that are not in `expected`, plus those of `expected` it does not hold.
inline long BodiesAmiss(const b2World& world, const std::set<const b2Body*>& expected) {
    long amiss = 0;
    std::size_t held = 0;
    for (const b2Body* b = world.GetBodyList(); b; b = b->GetNext()) {
        ++held;
        amiss += expected.count(b) == 0;
    }
    amiss += static_cast<long>(expected.size() > held ? expected.size() - held : 0);
    return amiss + (static_cast<std::size_t>(world.GetBodyCount()) != expected.size());
}

struct ShapeDeleter {
    void operator()(rugo_shape* s) const { rugo_shape_destroy(s); }
};
using ShapePtr = std::unique_ptr<rugo_shape, ShapeDeleter>;

// A rough "object" outline (sample_object: irregular, partly concave) of n control points and mean
// radius `radius` metres about its origin, with a band of relative width lambda (λ = lambda * radius on
// every segment). Null if the shape cannot be built (the status is printed).
inline ShapePtr RoughShape(int n, double radius, double lambda) {
    std::vector<rugo_vec2> pts(static_cast<std::size_t>(n));
    sample_object(n, rugo_v2(0.0, 0.0), radius, pts.data());
    std::vector<rugo_real> lam(static_cast<std::size_t>(n), lambda * radius);
    rugo_shape_def def = rugo_default_shape_def();
    def.points = pts.data();
    def.count = n;
    def.tolerances = lam.data();
    rugo_shape* s = nullptr;
    const rugo_status st = rugo_shape_create(&def, &s, nullptr);
    if (st != RUGO_OK)
        std::fprintf(stderr, "shape of %d points, radius %g: %s\n", n, radius, rugo_status_string(st));
    return ShapePtr(s);
}

// splitmix64: the samples' seeded choices.
struct Rng {
    std::uint64_t s;
    std::uint64_t Next() {
        std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    double Uniform(double lo, double hi) {
        return lo + (hi - lo) * static_cast<double>(Next() >> 11) * 0x1p-53;
    }
    std::size_t Below(std::size_t n) { return static_cast<std::size_t>(Next() % n); }
};

} // namespace b2stress

#endif
