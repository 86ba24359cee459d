// The testbed's panel, mouse and keys (testbed_ui.hpp). Keys follow Box2D's testbed where it has one:
// P pause, O single step, R restart; the rest are listed under "Keys" in the panel and docs/testbed.md.
#include "testbed_ui.hpp"

#include "testbed_draw.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace testbed {

namespace {

b2Vec2 MouseWorld(const Testbed& tb) {
    const ImVec2 m = ImGui::GetIO().MousePos;
    return tb.camera.ToWorld(b2Vec2(m.x, m.y));
}

bool KeyPressed(int glfwKey) { return ImGui::IsKeyPressed(glfwKey, false); }

void Input(Testbed& tb) {
    ImGuiIO& io = ImGui::GetIO();
    if (!io.WantCaptureMouse && ImGui::IsMousePosValid()) {
        const b2Vec2 p = MouseWorld(tb);
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Left)) tb.MouseDown(p);
        if (ImGui::IsMouseClicked(ImGuiMouseButton_Right)) tb.Spawn(p);
        if (io.MouseWheel != 0.0f) {
            // Zoom about the cursor.
            const float f = std::pow(1.1f, io.MouseWheel);
            tb.camera.pixelsPerMetre = std::max(2.0f, std::min(5000.0f, tb.camera.pixelsPerMetre * f));
            const b2Vec2 q = MouseWorld(tb);
            tb.camera.center += p - q;
        }
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Middle)) {
            const ImVec2 d = io.MouseDelta;
            tb.camera.center -= (1.0f / tb.camera.pixelsPerMetre) * b2Vec2(d.x, -d.y);
        }
    }
    if (tb.Dragged() != nullptr) {
        tb.MouseMove(MouseWorld(tb));
        if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) tb.MouseUp();
    }
    if (io.WantCaptureKeyboard) return;
    Settings& s = tb.settings;
    if (KeyPressed(GLFW_KEY_P)) s.pause = !s.pause;
    if (KeyPressed(GLFW_KEY_O)) {
        s.pause = true;
        tb.SingleStep();
    }
    if (KeyPressed(GLFW_KEY_R)) tb.Restart();
    if (KeyPressed(GLFW_KEY_SPACE) && ImGui::IsMousePosValid()) tb.Spawn(MouseWorld(tb));
    if (KeyPressed(GLFW_KEY_C)) s.drawCurves = !s.drawCurves;
    if (KeyPressed(GLFW_KEY_B)) s.drawBands = !s.drawBands;
    if (KeyPressed(GLFW_KEY_X)) s.drawProxies = !s.drawProxies;
    if (KeyPressed(GLFW_KEY_T)) s.drawTree = !s.drawTree;
    if (KeyPressed(GLFW_KEY_N)) s.drawContacts = !s.drawContacts;
    if (KeyPressed(GLFW_KEY_HOME)) tb.camera.Fit(tb.Current().viewLo, tb.Current().viewHi);
    const float pan = 40.0f / tb.camera.pixelsPerMetre;
    if (ImGui::IsKeyDown(GLFW_KEY_LEFT)) tb.camera.center.x -= pan;
    if (ImGui::IsKeyDown(GLFW_KEY_RIGHT)) tb.camera.center.x += pan;
    if (ImGui::IsKeyDown(GLFW_KEY_UP)) tb.camera.center.y += pan;
    if (ImGui::IsKeyDown(GLFW_KEY_DOWN)) tb.camera.center.y -= pan;
}

// The contact under the cursor: what the public API says about it (docs/testbed.md, "Hover").
void HoverTooltip(Testbed& tb) {
    if (ImGui::GetIO().WantCaptureMouse || !ImGui::IsMousePosValid() || !tb.settings.drawContacts) return;
    int k = 0;
    const int i = tb.NearestContact(MouseWorld(tb), 8.0f / tb.camera.pixelsPerMetre, &k);
    if (i < 0) return;
    const ContactView& c = tb.Contacts()[static_cast<size_t>(i)];
    tb.hovered = i;
    ImGui::BeginTooltip();
    ImGui::Text("%s contact, point %d of %d", c.rough ? "rough" : "ordinary", k + 1, c.points);
    ImGui::Text("mu %.3f  eps %.3f  (the contact's, as the bridge set them)", static_cast<double>(c.friction),
                static_cast<double>(c.restitution));
    ImGui::Text("separation %.2f mm (band-adjusted)  normal impulse %.4f N s",
                1e3 * static_cast<double>(c.separation[k]), static_cast<double>(c.normalImpulse[k]));
    if (c.hasInfo) { // the bridge's own values at this point (Bridge::GetPointInfo)
        const rugo::PointInfo& info = c.info[k];
        ImGui::Text("this point: mu %.3f  eps %.3f (its surfaces mixed, docs/box2d.md)", info.friction,
                    info.restitution);
        for (int side = 0; side < 2; ++side) {
            const rugo::SurfacePoint& sp = side == 0 ? info.a : info.b;
            if (!sp.rough) {
                ImGui::Text("%s body: ordinary fixture, mu %.3f, eps %.3f", side == 0 ? "A" : "B",
                            sp.friction, sp.restitution);
                continue;
            }
            ImGui::Text("%s body: level %d, segment %d, t %.3f, lambda %.2f mm, mu(lambda) %.3f",
                        side == 0 ? "A" : "B", sp.level, sp.segment, sp.t, 1e3 * sp.lambda, sp.friction);
        }
    } else {
        for (const b2Body* b : {c.a, c.b}) {
            const SurfacePoint sp = tb.Surface(b, c.p[k]);
            if (!sp.rough) {
                ImGui::Text("%s body: ordinary fixture", b == c.a ? "A" : "B");
                continue;
            }
            ImGui::Text("%s body: level %d, segment %d, t %.3f, lambda %.2f mm, mu(lambda) %.3f, %.2f mm off",
                        b == c.a ? "A" : "B", sp.level, sp.segment, sp.t, 1e3 * sp.lambda, sp.mu,
                        1e3 * sp.distance);
        }
        ImGui::TextDisabled("segment, t, lambda: the closest curve point");
    }
    ImGui::EndTooltip();
}

void Panel(Testbed& tb) {
    ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - kPanelWidth, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, io.DisplaySize.y));
    ImGui::Begin("librugo testbed", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(170.0f);
    Settings& s = tb.settings;
    const std::vector<SceneInfo>& list = SceneList();
    int scene = tb.SceneIndex(), variant = tb.Variant();
    if (ImGui::BeginCombo("scene", list[static_cast<size_t>(scene)].title)) {
        for (int i = 0; i < static_cast<int>(list.size()); ++i)
            if (ImGui::Selectable(list[static_cast<size_t>(i)].title, i == scene)) tb.Load(i, 0);
        ImGui::EndCombo();
    }
    const int variants = list[static_cast<size_t>(tb.SceneIndex())].variants;
    if (variants > 1 && ImGui::SliderInt("variant", &variant, 0, variants - 1))
        tb.Load(tb.SceneIndex(), variant);
    ImGui::TextWrapped("%s", tb.Current().note.c_str());
    if (!tb.status.empty()) ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "%s", tb.status.c_str());

    ImGui::Checkbox("pause (P)", &s.pause);
    ImGui::SameLine();
    if (ImGui::Button("step (O)")) {
        s.pause = true;
        tb.SingleStep();
    }
    ImGui::SameLine();
    if (ImGui::Button("restart (R)")) tb.Restart();

    if (ImGui::CollapsingHeader("Draw", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::Checkbox("curves (C)", &s.drawCurves);
        ImGui::SameLine();
        ImGui::Checkbox("ordinary fixtures", &s.drawOrdinary);
        ImGui::Checkbox("bands (B)", &s.drawBands);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(120.0f);
        ImGui::SliderFloat("x band", &s.bandExaggeration, 1.0f, 50.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
        ImGui::Checkbox("proxies (X)", &s.drawProxies);
        ImGui::Checkbox("MOBBtree boxes (T)", &s.drawTree);
        ImGui::SameLine();
        ImGui::SetNextItemWidth(100.0f);
        ImGui::SliderInt("level##tree", &s.treeLevel, 2, 8);
        ImGui::Checkbox("contacts by mu (N)", &s.drawContacts);
        ImGui::SameLine();
        ImGui::Checkbox("bridge's", &s.drawBridgeContacts);
        // The μ scale of the contact colours.
        ImDrawList* dl = ImGui::GetWindowDrawList();
        const ImVec2 p0 = ImGui::GetCursorScreenPos();
        const float w = ImGui::GetContentRegionAvail().x - 70.0f;
        for (int i = 0; i < 32; ++i) {
            const b2Color c = MuColour(static_cast<float>(i) / 31.0f);
            dl->AddRectFilled(ImVec2(p0.x + w * static_cast<float>(i) / 32.0f, p0.y),
                              ImVec2(p0.x + w * static_cast<float>(i + 1) / 32.0f, p0.y + 10.0f),
                              ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
        }
        ImGui::Dummy(ImVec2(w, 10.0f));
        ImGui::SameLine();
        ImGui::TextUnformatted("mu 0..1");
    }
    if (ImGui::CollapsingHeader("Level of detail", ImGuiTreeNodeFlags_DefaultOpen)) {
        int mode = static_cast<int>(s.detail);
        bool changed = ImGui::RadioButton("scene", &mode, 0);
        ImGui::SameLine();
        changed |= ImGui::RadioButton("error budget", &mode, 1);
        ImGui::SameLine();
        changed |= ImGui::RadioButton("level", &mode, 2);
        s.detail = static_cast<Detail>(mode);
        if (s.detail == Detail::kBudget)
            changed |= ImGui::SliderFloat("budget (m)", &s.errorBudget, 1e-4f, 0.05f, "%.4f",
                                          ImGuiSliderFlags_Logarithmic);
        if (s.detail == Detail::kLevel) changed |= ImGui::SliderInt("level (0 finest)", &s.level, -5, 0);
        if (changed) tb.ApplyDetail();
    }
    if (ImGui::CollapsingHeader("World", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (ImGui::SliderFloat("gravity y", &s.gravity, -30.0f, 10.0f, "%.1f m/s2")) tb.ApplyGravity();
        ImGui::SliderInt("velocity iter.", &s.velocityIterations, 1, 50);
        ImGui::SliderInt("position iter.", &s.positionIterations, 0, 20);
    }
    if (ImGui::CollapsingHeader("Figures", ImGuiTreeNodeFlags_DefaultOpen)) {
        const Timing& t = tb.GetTiming();
        ImGui::Text("ms/step %.3f: bridge %.3f, Box2D %.3f", t.stepMs, t.bridgeMs, t.box2dMs);
        ImGui::Text("Box2D collide %.3f solve %.3f TOI %.3f", t.collideMs, t.solveMs, t.toiMs);
        int rough = 0, points = 0;
        for (const ContactView& c : tb.Contacts()) {
            rough += c.rough;
            points += c.points;
        }
        ImGui::Text("bodies %d (%d rough)", tb.BodyCount(), tb.RoughBodyCount());
        ImGui::Text("contacts %d (%d rough), %d points", static_cast<int>(tb.Contacts().size()), rough,
                    points);
        if (tb.Current().w->bridge) {
            const rugo::BridgeStats st = tb.Current().w->bridge->GetStats();
            ImGui::Text("queries %ld, cache hits %ld", st.queries, st.cacheHits);
        }
        ImGui::Text("t = %.2f s, step %ld, %.0f frames/s", tb.Current().w->time, tb.Steps(),
                    static_cast<double>(io.Framerate));
    }
    if (ImGui::CollapsingHeader("Keys")) {
        ImGui::TextWrapped("left drag: pull a body (mouse joint); right click or Space: a rough rock at the "
                           "cursor; wheel: zoom; middle drag or arrows: pan; Home: frame the scene; hover a "
                           "contact point: its figures. P pause, O step, R restart, C curves, B bands, "
                           "X proxies, T MOBBtree boxes, N contacts.");
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

} // namespace

void SetViewport(Testbed& tb) {
    const ImGuiIO& io = ImGui::GetIO();
    tb.camera.width = std::max(1.0f, io.DisplaySize.x - kPanelWidth);
    tb.camera.height = std::max(1.0f, io.DisplaySize.y);
}

void UiFrame(Testbed& tb) {
    SetViewport(tb);
    tb.hovered = -1;
    Input(tb);
    tb.Frame();
    ImDebugDraw draw(ImGui::GetBackgroundDrawList(), tb.camera);
    tb.Draw(&draw);
    HoverTooltip(tb);
    Panel(tb);
}

} // namespace testbed
