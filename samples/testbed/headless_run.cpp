// The testbed's headless run (app.hpp, RunHeadless): each scene for kFrames frames through the same
// frame function as the window, with scripted mouse and keys given to ImGui as the user's would be (so
// the panel's own input code runs): a drag of the highest dynamic body, a right click spawning a rock,
// the proxy, band and MOBBtree keys (the boxes off again), the error budget changed, pause, one step
// and a hovered contact. A PNG before the hover, which is checked, and one with the tooltip. Checks:
// the picture is not blank, and inside the scene's frame it shows the rough curves, the ordinary bodies
// and the proxy boxes by pixel counts of their colours; the drag lifted the body; the spawn, the level
// change, pause and step took effect; the tooltip showed.
#include "app.hpp"
#include "testbed_ui.hpp"

extern "C" {
#include "sample_check.h"
}

#include <GLFW/glfw3.h>
#include <imgui.h>
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
constexpr int kSpawn = 60, kToggle = 70, kDetail = 80, kPause = 90;
constexpr int kTreeOff = 85;            // the MOBBtree boxes: on at kToggle, off here
constexpr int kPicture = 97;            // the checked picture (paused since kPause, before the hover)
constexpr int kRenderEvery = 10;        // frames drawn (the others only step and build the interface)
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
    int hoverScenes = 0;
    for (int si = 0; si < static_cast<int>(list.size()); ++si) {
        const SceneInfo& info = list[static_cast<size_t>(si)];
        if (!only.empty() && only != info.name) continue;
        const auto t0 = std::chrono::steady_clock::now();
        char name[160];
        tb.settings = Settings(); // each scene from the defaults: the keys toggle
        if (!tb.Load(si, 0)) {
            std::snprintf(name, sizeof name, "%s: the scene loads", info.name);
            sample_expect(name, 0);
            continue;
        }
        // One frame first, so that ImGui knows the display size and the camera frames the scene.
        app.Frame(tb, nullptr, nullptr, nullptr, nullptr, true);
        tb.camera.Fit(tb.Current().viewLo, tb.Current().viewHi);
        b2Body* dragged = nullptr;
        b2Vec2 grab(0.0f, 0.0f), anchorLocal(0.0f, 0.0f);
        float rise = 0.0f;
        int bodiesBefore = 0, bodiesAfter = 0, roughBeforeDetail = 0, roughAfterDetail = -1;
        bool picked = false, released = false, hoverTried = false;
        long stepsPaused = -1, stepsAfterStep = -1;
        std::vector<unsigned char> px, pxHover;
        int width = 0, height = 0;
        for (int f = 1; f <= kFrames; ++f) {
            // The input ImGui sees this frame, as the user's mouse and keys would give it.
            auto script = [&] {
                ImGuiIO& io = ImGui::GetIO();
                auto mouse = [&](b2Vec2 world, bool left, bool right) {
                    const b2Vec2 sp = tb.camera.ToScreen(world);
                    io.MousePos = ImVec2(sp.x, sp.y);
                    io.MouseDown[ImGuiMouseButton_Left] = left;
                    io.MouseDown[ImGuiMouseButton_Right] = right;
                };
                for (int key : {GLFW_KEY_X, GLFW_KEY_B, GLFW_KEY_T, GLFW_KEY_P, GLFW_KEY_O})
                    io.KeysDown[key] = false;
                if (f == kGrab) {
                    dragged = Highest(tb, &grab);
                    if (dragged) {
                        anchorLocal = dragged->GetLocalPoint(grab);
                        mouse(grab, true, false); // press: the panel's Input picks the body
                    }
                }
                if (f == kGrab + 1) picked = dragged != nullptr && tb.Dragged() == dragged;
                if (f > kGrab && f < kRelease && dragged) {
                    const float u = static_cast<float>(f - kGrab) / static_cast<float>(kRelease - kGrab);
                    mouse(grab + b2Vec2(0.0f, kLift * u), true, false);
                }
                if (f == kRelease && dragged) {
                    rise = dragged->GetWorldPoint(anchorLocal).y - grab.y;
                    mouse(grab + b2Vec2(0.0f, kLift), false, false); // release
                }
                if (f == kRelease + 1) released = tb.Dragged() == nullptr;
                if (f == kSpawn) { // a right click
                    const Scene& sc = tb.Current();
                    bodiesBefore = tb.BodyCount();
                    mouse(b2Vec2(0.5f * (sc.viewLo.x + sc.viewHi.x),
                                 sc.viewHi.y - 0.15f * (sc.viewHi.y - sc.viewLo.y)),
                          false, true);
                }
                if (f == kSpawn + 1) bodiesAfter = tb.BodyCount();
                if (f == kToggle) { // keys X, B, T; the exaggeration slider
                    io.KeysDown[GLFW_KEY_X] = io.KeysDown[GLFW_KEY_B] = io.KeysDown[GLFW_KEY_T] = true;
                    tb.settings.bandExaggeration = 5.0f;
                    tb.settings.treeLevel = 3;
                }
                if (f == kTreeOff) io.KeysDown[GLFW_KEY_T] = true; // the picture shows proxies and bands
                if (f == kDetail) { // the error-budget slider: every rough body re-attached at 1 cm
                    roughBeforeDetail = tb.RoughBodyCount();
                    tb.settings.detail = Detail::kBudget;
                    tb.settings.errorBudget = 0.01f;
                    tb.ApplyDetail();
                    roughAfterDetail = CountRough(tb);
                }
                if (f == kPause) io.KeysDown[GLFW_KEY_P] = true;
                if (f == kPause + 1) stepsPaused = tb.Steps();
                if (f == kPause + 2) io.KeysDown[GLFW_KEY_O] = true; // one step
                if (f >= kFrames - 2) { // ImGui shows a new tooltip from its second frame
                    stepsAfterStep = tb.Steps();
                    // Hover the leftmost rough contact point (paused: the contacts stay as they are),
                    // so that the tooltip, right of the mouse, covers little of the scene.
                    const ContactView* left = nullptr;
                    for (const ContactView& c : tb.Contacts())
                        if (c.rough && (!left || c.p[0].x < left->p[0].x)) left = &c;
                    if (left) {
                        mouse(left->p[0], false, false);
                        hoverTried = true;
                    }
                }
            };
            // The checked picture before the hover, and the last frame with the tooltip.
            const bool render = f % kRenderEvery == 0 || f >= kPicture;
            std::vector<unsigned char>* read = f == kPicture ? &px : f == kFrames ? &pxHover : nullptr;
            app.Frame(tb, script, read, &width, &height, render);
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const std::string png = dir + "/" + info.name + ".png",
                          pngHover = dir + "/" + info.name + "_hover.png";
        const bool written =
            width > 0 && stbi_write_png(png.c_str(), width, height, 3, px.data(), width * 3) != 0 &&
            (pxHover.empty() ||
             stbi_write_png(pngHover.c_str(), width, height, 3, pxHover.data(), width * 3) != 0);
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
        std::snprintf(name, sizeof name, "%s: PNGs written (%s, and _hover)", info.name, png.c_str());
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
        sample_expect(name, picked);
        std::snprintf(name, sizeof name, "%s: releasing the button ends the drag", info.name);
        sample_expect(name, released);
        std::snprintf(name, sizeof name, "%s: the drag lifted it: -(rise of the grabbed point) [m] <= -%.2f",
                      info.name, 0.5 * kLift);
        sample_expect_le(name, -rise, -0.5 * kLift);
        std::snprintf(name, sizeof name, "%s: a rough rock was spawned (one more body)", info.name);
        sample_expect(name, bodiesAfter == bodiesBefore + 1);
        std::snprintf(name, sizeof name, "%s: P pauses and O steps once (%ld -> %ld steps)", info.name,
                      stepsPaused, stepsAfterStep);
        sample_expect(name, stepsPaused > 0 && stepsAfterStep == stepsPaused + 1);
        if (hoverTried) { // a ball in flight at the last frame has no contact to hover
            std::snprintf(name, sizeof name, "%s: hovering a rough contact point shows its tooltip",
                          info.name);
            sample_expect(name, tb.hovered >= 0);
            ++hoverScenes;
        } else {
            std::printf("%s: no rough contact at the last frame: hover not tried\n", info.name);
        }
        std::snprintf(name, sizeof name,
                      "%s: every rough body still rough after the level-of-detail change (%d -> %d)",
                      info.name, roughBeforeDetail, roughAfterDetail);
        sample_expect(name, roughAfterDetail == roughBeforeDetail && roughAfterDetail > 0);
    }
    // Most scenes end with a rough contact to hover (all but the two whose body is in flight).
    if (only.empty()) sample_expect_le("scenes where the hover was tried: -(count) <= -5", -hoverScenes, -5);
    return sample_finish();
}

} // namespace testbed
