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

/// The camera's axes at p_W, the pointer target (world frame), for `camera`; the depth used to
/// scale drags is at least 5 cm, so a pointer at the eye does not freeze the mouse.
ViewAxes AxesAt(const world::CameraFrame& camera, const Vec3& p_W);

/// One frame of pointer input: which drags are on (they began on the scene) and how far the
/// cursor moved, in viewport heights (x right, y down, as GLFW's cursor), plus wheel notches.
struct PointerDrag {
  bool left = false;   ///< left button: move in the view plane (Shift: in depth)
  bool right = false;  ///< right button: turn
  bool shift = false;
  double rx = 0.0, ry = 0.0;  ///< cursor motion / viewport height
  double scroll = 0.0;        ///< wheel notches, up > 0
};

/// Moves the pointer target X_WT (world frame) for one frame of input, so that it follows the
/// cursor at its depth: a left drag of (rx, ry) moves it metres_per_height · (rx right − ry up);
/// Shift + left moves it −ry · metres_per_height along forward (drag up: away from the eye); a
/// right drag turns it by π per viewport height about up (rx) and right (ry); each wheel notch
/// moves it 2 % of its depth along forward.
void MovePointer(const ViewAxes& axes, const PointerDrag& drag, Pose* X_WT);

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
