// SPDX-License-Identifier: Apache-2.0
// Window: GLFW initialization with a clear no-display error, ImGui setup and PNG output.
#include "viewer/window.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cstdlib>
#include <system_error>

#include "backends/imgui_impl_glfw.h"
#include "backends/imgui_impl_opengl3.h"
#include "mrh/core/error.h"

namespace mrh::viewer::internal {
namespace {

// ImGui's built-in font size at scale 1 (pixels).
constexpr float kBaseFontPixels = 13.0f;

// GLFW reports errors through a callback; keep the last one for the exception message.
std::string& LastGlfwError() {
  static std::string error;
  return error;
}

void StoreGlfwError(int code, const char* description) {
  LastGlfwError() = fmt::format("{} (GLFW error {:#x})", description, code);
}

void InitGlfw() {
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || *display == '\0') {
    throw RuntimeError(NoDisplayMessage("DISPLAY is not set"));
  }
  glfwSetErrorCallback(StoreGlfwError);
  if (glfwInit() != GLFW_TRUE) {
    throw RuntimeError(
        NoDisplayMessage(fmt::format("cannot open display '{}': {}", display, LastGlfwError())));
  }
}

GLFWwindow* CreateGlWindow(const WindowSettings& s) {
  glfwWindowHint(GLFW_VISIBLE, s.visible ? GLFW_TRUE : GLFW_FALSE);
  // MuJoCo's renderer uses the fixed-function pipeline and ImGui's backend GLSL 130: a 3.0
  // context (compatibility profile on Mesa) serves both.
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
  // Multisampling smooths edges on screen; headless frames skip it (software GL is slow).
  glfwWindowHint(GLFW_SAMPLES, s.visible ? 4 : 0);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(s.width, s.height, s.title.c_str(), nullptr, nullptr);
  if (window == nullptr) {
    const std::string error = LastGlfwError();
    glfwTerminate();
    throw RuntimeError(
        fmt::format("cannot create an OpenGL 3.0 window for 'mrh view': {}; check the GL driver "
                    "(glxinfo -B), or try LIBGL_ALWAYS_SOFTWARE=1 or xvfb-run -a",
                    error));
  }
  return window;
}

void InitImGui(GLFWwindow* window, float scale, bool input) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // never write imgui.ini into the user's folder
  ImGui::StyleColorsDark();
  ImGui::GetStyle().ScaleAllSizes(scale);
  ImFontConfig font;
  font.SizePixels = kBaseFontPixels * scale;
  io.Fonts->AddFontDefault(&font);
  ImGui_ImplGlfw_InitForOpenGL(window, input);
  ImGui_ImplOpenGL3_Init("#version 130");
}

}  // namespace

std::string NoDisplayMessage(const std::string& reason) {
  return fmt::format(
      "no display available for 'mrh view' ({}); run it under xvfb-run (xvfb-run -a mrh view "
      "...) or use 'mrh run' for a headless session",
      reason);
}

Window::Window(const WindowSettings& settings) {
  InitGlfw();
  window_ = CreateGlWindow(settings);
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(settings.visible ? 1 : 0);
  float sx = 1.0f, sy = 1.0f;
  glfwGetWindowContentScale(window_, &sx, &sy);
  scale_ = std::max(1.0f, std::max(sx, sy));
  if (settings.install_callbacks != nullptr) {
    settings.install_callbacks(window_, settings.callback_data);
  }
  InitImGui(window_, scale_, settings.input);
}

Window::~Window() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool Window::ShouldClose() const {
  return glfwWindowShouldClose(window_) == GLFW_TRUE;
}

void Window::FramebufferSize(int* width, int* height) const {
  glfwGetFramebufferSize(window_, width, height);
}

void Window::BeginFrame() {
  glfwPollEvents();
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void Window::RenderUi() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Window::Swap() {
  glfwSwapBuffers(window_);
}

void WritePng(const std::filesystem::path& path, int width, int height,
              const std::vector<std::uint8_t>& rgb) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  if (ec || stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3) == 0) {
    throw RuntimeError(
        fmt::format("cannot write the screenshot {}{}; check that the folder is "
                    "writable",
                    path.string(), ec ? ": " + ec.message() : std::string()));
  }
}

}  // namespace mrh::viewer::internal
