// The testbed's panel and its mouse and keyboard (Dear ImGui): what docs/testbed.md describes.
#ifndef RUGO_TESTBED_TESTBED_UI_HPP
#define RUGO_TESTBED_TESTBED_UI_HPP

#include "testbed.hpp"

namespace testbed {

constexpr float kPanelWidth = 340.0f; // pixels, at the window's right edge

// One frame of the user interface, between ImGui::NewFrame and ImGui::Render: reads the mouse and the
// keys (when ImGui does not want them), steps the testbed (Testbed::Frame), draws the world into the
// background draw list and the panel on top. The camera's viewport is set from the display size.
void UiFrame(Testbed& tb);
// The camera's viewport from ImGui's display size (the window less the panel).
void SetViewport(Testbed& tb);

} // namespace testbed

#endif
