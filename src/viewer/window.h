// SPDX-License-Identifier: Apache-2.0
// The viewer's window: GLFW with an OpenGL context, Dear ImGui on top, PNG screenshots.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

struct GLFWwindow;

namespace mrh::viewer::internal {

/// The one-line error for a missing display; `reason` goes in parentheses.
std::string NoDisplayMessage(const std::string& reason);

/// How the window is opened.
struct WindowSettings {
  std::string title = "mrh view";
  int width = 1280;  ///< screen coordinates
  int height = 800;
  bool visible = true;  ///< false: headless frames (nothing shown, nothing to click)
  bool input = true;    ///< ImGui receives mouse and keyboard
  /// Called after the window exists and before ImGui installs its callbacks (which chain to the
  /// ones installed here).
  void (*install_callbacks)(GLFWwindow*, void*) = nullptr;
  void* callback_data = nullptr;
};

/// A GLFW window whose OpenGL (compatibility profile, >= 3.0) context is current on the calling
/// thread, with Dear ImGui set up for it. One per process; UI thread only.
class Window {
 public:
  /// @throws mrh::RuntimeError with NoDisplayMessage if there is no display, or naming the GL
  /// problem if no suitable context can be made.
  explicit Window(const WindowSettings& settings);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }

  bool ShouldClose() const;
  /// Framebuffer size in pixels (differs from the window size on HiDPI displays).
  void FramebufferSize(int* width, int* height) const;

  /// The display's scale for text and widgets (1 on a standard display).
  float content_scale() const { return scale_; }

  /// Processes events and starts an ImGui frame.
  void BeginFrame();
  /// Draws the ImGui frame into the current framebuffer.
  void RenderUi();
  /// Shows the frame.
  void Swap();

 private:
  GLFWwindow* window_ = nullptr;
  float scale_ = 1.0f;
};

/// Writes RGB bytes (top row first) as a PNG, creating the parent folder.
/// @throws mrh::RuntimeError naming the file.
void WritePng(const std::filesystem::path& path, int width, int height,
              const std::vector<std::uint8_t>& rgb);

}  // namespace mrh::viewer::internal
