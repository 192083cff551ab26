// SPDX-License-Identifier: Apache-2.0
// Mouse and keyboard → camera motion (as in MuJoCo's simulate) or pointer motion (6-DOF).
#pragma once

#include <utility>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/world/scene_renderer.h"

struct GLFWwindow;

namespace mrh::viewer::internal {

/// Keyboard requests other than pointer nudges, for one frame.
struct KeyActions {
  bool toggle_pause = false;   ///< Space
  bool step = false;           ///< S: one physics period while paused
  bool reset = false;          ///< Backspace
  bool toggle_panel = false;   ///< H
  bool toggle_camera = false;  ///< C: swap the roles of plain and Ctrl drags
  bool reset_camera = false;   ///< Home
};

/// The camera's axes at the pointer (world frame), for turning mouse motion into motion.
struct ViewAxes {
  Vec3 right = Vec3::UnitX();
  Vec3 up = Vec3::UnitY();
  Vec3 forward = -Vec3::UnitZ();
  double depth = 1.0;              ///< pointer distance along forward (m), at least a minimum
  double metres_per_height = 1.0;  ///< pointer motion per viewport height of mouse motion (m)
};

/// Turns GLFW input into camera moves and pointer-target moves. Plain drags move the pointer
/// (left: in the view plane, Shift+left: in depth, right: rotate) and the wheel pushes it in
/// depth; with Ctrl held (or with camera_drag set, without Ctrl) drags and wheel move the camera
/// like MuJoCo's simulate (left orbit, right pan, wheel and middle zoom; Shift: horizontal).
/// Arrow keys and Page Up/Down nudge the pointer. Input ImGui wants is left to ImGui.
/// UI thread only.
class PointerControl {
 public:
  /// Sets GLFW callbacks on `window`, bound to `self` (a PointerControl*), through the window's
  /// user pointer. Install before ImGui so that ImGui's callbacks chain to these.
  static void Install(GLFWwindow* window, void* self);

  /// Applies this frame's drags, wheel and keys to the renderer's camera and to X_WT, the
  /// pointer target (world frame), and returns the other key requests.
  KeyActions Process(GLFWwindow* window, world::SceneRenderer& renderer, bool camera_drag,
                     Pose* X_WT);

 private:
  void MoveCamera(world::SceneRenderer& renderer, double rx, double ry, bool shift) const;
  void MovePointer(const ViewAxes& axes, double rx, double ry, bool shift, Pose* X_WT) const;
  KeyActions ApplyKeys(const ViewAxes& axes, Pose* X_WT);
  void OnButton(int button, int action);
  void OnScroll(double y);
  void OnKey(int key, int action, int mods);
  static void ButtonCallback(GLFWwindow* w, int button, int action, int mods);
  static void ScrollCallback(GLFWwindow* w, double x, double y);
  static void KeyCallback(GLFWwindow* w, int key, int scancode, int action, int mods);

  bool drag_[3] = {false, false, false};  ///< left, right, middle drags that began on the scene
  bool have_cursor_ = false;
  double last_x_ = 0.0, last_y_ = 0.0;
  double scroll_ = 0.0;
  std::vector<std::pair<int, int>> keys_;  ///< (key, mods) pressed or repeated since last frame
};

}  // namespace mrh::viewer::internal
