// The testbed's window: GLFW, an OpenGL 3.3 core context and Dear ImGui's GLFW and OpenGL 3 backends
// (main.cpp). The headless run (headless_run.cpp) drives the same frames with scripted input.
#ifndef RUGO_TESTBED_APP_HPP
#define RUGO_TESTBED_APP_HPP

#include "testbed.hpp"

#include <functional>
#include <string>
#include <vector>

struct GLFWwindow;

namespace testbed {

struct App {
    GLFWwindow* window = nullptr;
    // One frame: GLFW's events and the backends' new frame, then script (if any), which may replace the
    // mouse and keys ImGui will see (ImGuiIO's MousePos, MouseDown, KeysDown), then ImGui's frame with
    // UiFrame and rendering. With pixels, the framebuffer's RGB picture (top row first, width x height)
    // is read before the buffers are swapped. render false: the frame is built but not drawn (the
    // headless run draws every 10th frame, to keep the test short).
    void Frame(Testbed& tb, const std::function<void()>& script, std::vector<unsigned char>* pixels,
               int* width, int* height, bool render = true);
};

// Every scene (or only the one called `only`) for a fixed number of frames with a scripted drag, spawn
// and toggle; a PNG of each in dir; checks printed and counted (sample_check.h). Returns the exit
// status.
int RunHeadless(App& app, Testbed& tb, const std::string& dir, const std::string& only);

} // namespace testbed

#endif
