// The testbed's headless run (app.hpp, RunHeadless): each scene for kFrames frames through the same
// frame function as the window, with a scripted drag of the highest dynamic body, a spawned rock and
// the proxy, band and MOBBtree toggles switched on (the boxes off again), the error budget changed, then a
// PNG of the last frame and checks of it: the picture is not blank, and inside the scene's frame it shows the
// rough curves, the ordinary bodies and the proxy boxes by pixel counts of their colours; the drag lifted the
// body.
#include "app.hpp"
#include "testbed_ui.hpp"

extern "C" {
#include "sample_check.h"
}

#include <stb_image_write.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

namespace testbed {

namespace {

constexpr int kFrames = 100;             // 1.7 s of scene time at 60 Hz
constexpr int kGrab = 10, kRelease = 50; // the drag: frames
constexpr float kLift = 1.2f;            // how far the mouse moves up during the drag (m)
constexpr int kSpawn = 60, kToggle = 70, kTreeOff = 85,
              kDetail = 80;             // the MOBBtree boxes: on at kToggle, off here
constexpr int kRenderEvery = 10;        // frames rendered (the others only step and build the user interface)
constexpr int kMinCurvePixels = 300;    // rough curves (the bridge's yellow)
constexpr int kMinProxyPixels = 100;    // proxy boxes (the bridge's blue), after the toggle
constexpr int kMinOrdinaryPixels = 100; // ordinary dynamic bodies (Box2D's testbed pink)

struct Rgb {
    int r, g, b;
};

bool Near(const unsigned char* p, Rgb c, int tol) {
    return std::abs(p[0] - c.r) <= tol && std::abs(p[1] - c.g) <= tol && std::abs(p[2] - c.b) <= tol;
}

// The picture's figures inside the screen box [x0, x1) x [y0, y1).
struct Counts {
    int curve = 0, proxy = 0, ordinary = 0, background = 0, total = 0;
    size_t colours = 0;
};

Counts Count(const std::vector<unsigned char>& px, int width, int x0, int y0, int x1, int y1) {
    Counts c;
    std::set<int> colours;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const unsigned char* p =
                px.data() +
                (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 3;
            ++c.total;
            c.curve += Near(p, {230, 230, 77}, 30);  // b2Color(0.9, 0.9, 0.3): the bridge's curves
            c.proxy += Near(p, {102, 153, 230}, 30); // b2Color(0.4, 0.6, 0.9): the bridge's proxies
            c.ordinary += Near(p, {230, 179, 179}, 30) || Near(p, {115, 89, 89}, 20); // awake: outline, fill
            c.background += Near(p, {26, 26, 31}, 3);
            if (colours.size() < 1000) colours.insert((p[0] << 16) | (p[1] << 8) | p[2]);
        }
    c.colours = colours.size();
    return c;
}

// The highest dynamic body of the scene, and a point of it to grab (its centre, or a point of its
// curve's inside near it when the centre is outside, as for a letter).
b2Body* Highest(Testbed& tb, b2Vec2* grab) {
    b2Body* best = nullptr;
    for (b2Body* b = tb.Current().w->world->GetBodyList(); b; b = b->GetNext()) {
        if (b->GetType() != b2_dynamicBody) continue;
        const b2Vec2 c = b->GetWorldCenter();
        for (int k = 0; k < 64; ++k) { // a spiral around the centre until the body is under the point
            const float r = 0.01f * static_cast<float>(k), a = 0.7f * static_cast<float>(k);
            const b2Vec2 p = c + r * b2Vec2(std::cos(a), std::sin(a));
            if (tb.Pick(p) == b) {
                if (!best || c.y > best->GetWorldCenter().y) {
                    best = b;
                    *grab = p;
                }
                break;
            }
        }
    }
    return best;
}

// Bodies the bridge calls rough.
int CountRough(const Testbed& tb) {
    const rugo::Bridge* br = tb.Current().w->bridge.get();
    int n = 0;
    for (const b2Body* b = tb.Current().w->world->GetBodyList(); b; b = b->GetNext())
        n += br && br->IsRough(b);
    return n;
}

bool HasOrdinaryDynamic(const Testbed& tb) {
    const rugo::Bridge* br = tb.Current().w->bridge.get();
    for (const b2Body* b = tb.Current().w->world->GetBodyList(); b; b = b->GetNext())
        if (b->GetType() == b2_dynamicBody && !(br && br->IsRough(b))) return true;
    return false;
}

} // namespace

int RunHeadless(App& app, Testbed& tb, const std::string& dir, const std::string& only) {
    if (sample_mkdir(dir.c_str()) != 0) {
        std::fprintf(stderr, "rugo_testbed: cannot create %s\n", dir.c_str());
        return 1;
    }
    const std::vector<SceneInfo>& list = SceneList();
    for (int si = 0; si < static_cast<int>(list.size()); ++si) {
        const SceneInfo& info = list[static_cast<size_t>(si)];
        if (!only.empty() && only != info.name) continue;
        const auto t0 = std::chrono::steady_clock::now();
        char name[160];
        if (!tb.Load(si, 0)) {
            std::snprintf(name, sizeof name, "%s: the scene loads", info.name);
            sample_expect(name, 0);
            continue;
        }
        // One frame first, so that ImGui knows the display size and the camera frames the scene.
        app.Frame(tb, nullptr, false, nullptr, nullptr, nullptr, true);
        tb.camera.Fit(tb.Current().viewLo, tb.Current().viewHi);
        b2Body* dragged = nullptr;
        b2Vec2 grab(0.0f, 0.0f), anchorLocal(0.0f, 0.0f);
        float rise = 0.0f;
        int bodiesBefore = 0, bodiesAfter = 0, roughBeforeDetail = 0, roughAfterDetail = -1;
        b2Body* spawned = nullptr;
        std::vector<unsigned char> px;
        int width = 0, height = 0;
        for (int f = 1; f <= kFrames; ++f) {
            auto script = [&] {
                if (f == kGrab) {
                    dragged = Highest(tb, &grab);
                    if (dragged && tb.MouseDown(grab))
                        anchorLocal = dragged->GetLocalPoint(grab);
                    else
                        dragged = nullptr;
                }
                if (f > kGrab && f <= kRelease && dragged) {
                    const float u = static_cast<float>(f - kGrab) / static_cast<float>(kRelease - kGrab);
                    tb.MouseMove(grab + b2Vec2(0.0f, kLift * u));
                }
                if (f == kRelease && dragged) {
                    rise = dragged->GetWorldPoint(anchorLocal).y - grab.y;
                    tb.MouseUp();
                }
                if (f == kSpawn) {
                    const Scene& s = tb.Current();
                    const b2Vec2 p(0.5f * (s.viewLo.x + s.viewHi.x),
                                   s.viewHi.y - 0.15f * (s.viewHi.y - s.viewLo.y));
                    bodiesBefore = tb.BodyCount();
                    spawned = tb.Spawn(p);
                    bodiesAfter = tb.BodyCount();
                }
                if (f == kToggle) {
                    tb.settings.drawProxies = true;
                    tb.settings.drawBands = true;
                    tb.settings.bandExaggeration = 5.0f;
                    tb.settings.drawTree = true;
                    tb.settings.treeLevel = 3;
                }
                if (f == kTreeOff) tb.settings.drawTree = false; // the picture shows proxies and bands
                if (f == kDetail) { // the error-budget slider: every rough body re-attached at 1 cm
                    roughBeforeDetail = tb.RoughBodyCount();
                    tb.settings.detail = Detail::kBudget;
                    tb.settings.errorBudget = 0.01f;
                    tb.ApplyDetail();
                    roughAfterDetail = CountRough(tb);
                }
            };
            const bool render = f % kRenderEvery == 0 || f == kFrames;
            app.Frame(tb, script, false, f == kFrames ? &px : nullptr, &width, &height, render);
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const std::string png = dir + "/" + info.name + ".png";
        const bool written =
            width > 0 && stbi_write_png(png.c_str(), width, height, 3, px.data(), width * 3) != 0;
        // The scene's frame on the screen, within the world's viewport.
        const b2Vec2 lo = tb.camera.ToScreen(tb.Current().viewLo),
                     hi = tb.camera.ToScreen(tb.Current().viewHi);
        const int vw = static_cast<int>(tb.camera.width);
        const int x0 = std::max(0, static_cast<int>(lo.x)), x1 = std::min(vw, static_cast<int>(hi.x));
        const int y0 = std::max(0, static_cast<int>(hi.y)), y1 = std::min(height, static_cast<int>(lo.y));
        const Counts c = written ? Count(px, width, x0, y0, x1, y1) : Counts();
        std::printf(
            "%s: %.2f s for %d frames; %d x %d px; in the scene's frame %d px: curves %d, proxies %d, "
            "ordinary %d, background %d, %zu colours; drag rise %.3f m; bodies %d -> %d; ms/step %.3f "
            "(bridge %.3f, Box2D %.3f)\n",
            info.name, seconds, kFrames, width, height, c.total, c.curve, c.proxy, c.ordinary, c.background,
            c.colours, static_cast<double>(rise), bodiesBefore, bodiesAfter, tb.GetTiming().stepMs,
            tb.GetTiming().bridgeMs, tb.GetTiming().box2dMs);
        std::snprintf(name, sizeof name, "%s: PNG written (%s)", info.name, png.c_str());
        sample_expect(name, written);
        std::snprintf(name, sizeof name, "%s: not blank: background share of the scene's frame", info.name);
        sample_expect_le(name, c.total > 0 ? static_cast<double>(c.background) / c.total : 1.0, 0.99);
        std::snprintf(name, sizeof name, "%s: not blank: distinct colours >= 8", info.name);
        sample_expect(name, c.colours >= 8);
        std::snprintf(name, sizeof name, "%s: rough curves shown: -(curve-coloured pixels) <= -%d", info.name,
                      kMinCurvePixels);
        sample_expect_le(name, -c.curve, -kMinCurvePixels);
        std::snprintf(name, sizeof name, "%s: proxy toggle shown: -(proxy-coloured pixels) <= -%d", info.name,
                      kMinProxyPixels);
        sample_expect_le(name, -c.proxy, -kMinProxyPixels);
        if (HasOrdinaryDynamic(tb)) {
            std::snprintf(name, sizeof name, "%s: ordinary bodies shown: -(their pixels) <= -%d", info.name,
                          kMinOrdinaryPixels);
            sample_expect_le(name, -c.ordinary, -kMinOrdinaryPixels);
        }
        std::snprintf(name, sizeof name, "%s: a dynamic body was picked under the mouse", info.name);
        sample_expect(name, dragged != nullptr);
        std::snprintf(name, sizeof name, "%s: the drag lifted it: -(rise of the grabbed point) [m] <= -%.2f",
                      info.name, 0.5 * kLift);
        sample_expect_le(name, -rise, -0.5 * kLift);
        std::snprintf(name, sizeof name, "%s: a rough rock was spawned (one more body)", info.name);
        sample_expect(name, spawned != nullptr && bodiesAfter == bodiesBefore + 1);
        std::snprintf(name, sizeof name,
                      "%s: every rough body still rough after the level-of-detail change (%d -> %d)", info.name,
                      roughBeforeDetail, roughAfterDetail);
        sample_expect(name, roughAfterDetail == roughBeforeDetail && roughAfterDetail > 0);
    }
    return sample_finish();
}

} // namespace testbed
