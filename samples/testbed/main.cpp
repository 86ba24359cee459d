// The librugo testbed (docs/testbed.md): the scene table's scenes and the testbed's own in a window,
// drawn through the bridge's b2Draw path, with a mouse joint, rock spawning, drawing toggles,
// level-of-detail and world settings and live figures.
//
//   rugo_testbed [--scene NAME] [--variant V]   the window (GLFW, OpenGL 3.3, Dear ImGui)
//   rugo_testbed --headless DIR [--scene NAME]  every scene (or one) with scripted input, PNGs in DIR,
//                                               checks printed; the test testbed_headless runs it
//                                               under xvfb-run
#include "app.hpp"
#include "testbed_ui.hpp"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace testbed {

void App::Frame(Testbed& tb, const std::function<void()>& script, std::vector<unsigned char>* pixels,
                int* width, int* height, bool render) {
    glfwPollEvents();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame(); // the mouse and keys as GLFW has them
    SetViewport(tb);
    if (script) script(); // may replace them (ImGuiIO's MousePos, MouseDown, KeysDown)
    ImGui::NewFrame();
    UiFrame(tb);
    ImGui::Render();
    if (!render) return;
    int w = 0, h = 0;
    glfwGetFramebufferSize(window, &w, &h);
    glViewport(0, 0, w, h);
    glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (pixels) {
        std::vector<unsigned char> rows(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadBuffer(GL_BACK);
        glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
        pixels->resize(rows.size());
        const size_t stride = static_cast<size_t>(w) * 3;
        for (int y = 0; y < h; ++y) // OpenGL's first row is the bottom one
            std::memcpy(pixels->data() + static_cast<size_t>(y) * stride,
                        rows.data() + static_cast<size_t>(h - 1 - y) * stride, stride);
        *width = w;
        *height = h;
    }
    glfwSwapBuffers(window);
}

} // namespace testbed

namespace {

void GlfwError(int code, const char* message) { std::fprintf(stderr, "GLFW error %d: %s\n", code, message); }

int Usage(const char* argv0) {
    std::fprintf(stderr, "usage: %s [--scene NAME] [--variant V] [--headless DIR]\nscenes:", argv0);
    for (const testbed::SceneInfo& s : testbed::SceneList())
        std::fprintf(stderr, " %s", s.name);
    std::fprintf(stderr, "\n");
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    std::string sceneName = "demo", headless;
    int variant = 0;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--scene") == 0 && i + 1 < argc)
            sceneName = argv[++i];
        else if (std::strcmp(argv[i], "--variant") == 0 && i + 1 < argc)
            variant = std::atoi(argv[++i]);
        else if (std::strcmp(argv[i], "--headless") == 0 && i + 1 < argc)
            headless = argv[++i];
        else
            return Usage(argv[0]);
    }
    const bool only = !headless.empty() && sceneName != "demo";
    if (testbed::FindScene(sceneName) < 0) return Usage(argv[0]);

    glfwSetErrorCallback(GlfwError);
    if (!glfwInit()) {
        std::fprintf(stderr,
                     "rugo_testbed: no display (GLFW could not start; headless: xvfb-run -a %s ...)\n",
                     argv[0]);
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    GLFWwindow* window = glfwCreateWindow(1280, 800, "librugo testbed", nullptr, nullptr);
    if (window == nullptr) {
        std::fprintf(stderr, "rugo_testbed: no OpenGL 3.3 core context\n");
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(headless.empty() ? 1 : 0);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini beside the binary
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330");

    int status = 0;
    {
        testbed::Testbed tb;
        int w = 0, h = 0;
        glfwGetFramebufferSize(window, &w, &h);
        tb.camera.width = static_cast<float>(w) - testbed::kPanelWidth;
        tb.camera.height = static_cast<float>(h);
        testbed::App app;
        app.window = window;
        if (!headless.empty()) {
            status = testbed::RunHeadless(app, tb, headless, only ? sceneName : std::string());
        } else if (!tb.Load(testbed::FindScene(sceneName), variant)) {
            status = 1;
        } else {
            while (!glfwWindowShouldClose(window))
                app.Frame(tb, nullptr, nullptr, nullptr, nullptr);
        }
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    return status;
}
