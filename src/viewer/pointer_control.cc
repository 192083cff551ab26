// SPDX-License-Identifier: Apache-2.0
// PointerControl: drags scaled by the pointer's depth so the pointer follows the cursor.
#include "viewer/pointer_control.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <numbers>

namespace mrh::viewer::internal {
namespace {

// Closest depth (m) used to scale drags, so a pointer at the eye does not freeze the mouse.
constexpr double kMinDepth = 0.05;
// One wheel notch moves the pointer this fraction of its depth.
constexpr double kWheelFraction = 0.02;
// A drag over the full window height turns the pointer half a turn.
constexpr double kTurnPerHeight = std::numbers::pi;
// Arrow-key nudge (m); with Shift, a fine nudge.
constexpr double kNudge = 0.005;
constexpr double kFineNudge = 0.001;
// MuJoCo simulate's zoom per wheel notch (in viewport heights).
constexpr double kCameraZoomPerNotch = 0.05;

PointerControl* Self(GLFWwindow* w) {
  return static_cast<PointerControl*>(glfwGetWindowUserPointer(w));
}

bool Held(GLFWwindow* w, int left, int right) {
  return glfwGetKey(w, left) == GLFW_PRESS || glfwGetKey(w, right) == GLFW_PRESS;
}

// Arrows move in the view plane, Page Up/Down in depth; other keys do not move the pointer.
Vec3 NudgeDirection(int key, const ViewAxes& a) {
  switch (key) {
    case GLFW_KEY_LEFT:
      return -a.right;
    case GLFW_KEY_RIGHT:
      return a.right;
    case GLFW_KEY_UP:
      return a.up;
    case GLFW_KEY_DOWN:
      return -a.up;
    case GLFW_KEY_PAGE_UP:
      return a.forward;
    case GLFW_KEY_PAGE_DOWN:
      return -a.forward;
    default:
      return Vec3::Zero();
  }
}

}  // namespace

ViewAxes AxesAt(const world::CameraFrame& cam, const Vec3& p_W) {
  ViewAxes a;
  a.forward = cam.forward_W;
  a.up = cam.up_W;
  a.right = a.forward.cross(a.up).normalized();
  a.depth = std::max(kMinDepth, (p_W - cam.p_WC).dot(a.forward));
  a.metres_per_height = cam.frustum_height * a.depth;
  return a;
}

void MovePointer(const ViewAxes& a, const PointerDrag& d, Pose* X_WT) {
  if (d.left) {
    if (d.shift) {
      X_WT->p -= d.ry * a.metres_per_height * a.forward;  // drag up: away from the eye
    } else {
      X_WT->p += a.metres_per_height * (d.rx * a.right - d.ry * a.up);
    }
  }
  if (d.right && (d.rx != 0.0 || d.ry != 0.0)) {
    const Quat turn = Quat(Eigen::AngleAxisd(d.ry * kTurnPerHeight, a.right)) *
                      Quat(Eigen::AngleAxisd(d.rx * kTurnPerHeight, a.up));
    X_WT->q = (turn * X_WT->q).normalized();
  }
  X_WT->p += d.scroll * kWheelFraction * a.depth * a.forward;  // wheel up: away from the eye
}

void PointerControl::Install(GLFWwindow* window, void* self) {
  glfwSetWindowUserPointer(window, self);
  glfwSetMouseButtonCallback(window, ButtonCallback);
  glfwSetScrollCallback(window, ScrollCallback);
  glfwSetKeyCallback(window, KeyCallback);
}

void PointerControl::ButtonCallback(GLFWwindow* w, int button, int action, int /*mods*/) {
  Self(w)->OnButton(button, action);
}

void PointerControl::ScrollCallback(GLFWwindow* w, double /*x*/, double y) {
  Self(w)->OnScroll(y);
}

void PointerControl::KeyCallback(GLFWwindow* w, int key, int /*scancode*/, int action, int mods) {
  Self(w)->OnKey(key, action, mods);
}

void PointerControl::OnButton(int button, int action) {
  if (button < 0 || button > 2) return;
  // A drag belongs to the scene only if it began outside ImGui's windows.
  drag_[button] = action == GLFW_PRESS && !ImGui::GetIO().WantCaptureMouse;
}

void PointerControl::OnScroll(double y) {
  if (!ImGui::GetIO().WantCaptureMouse) scroll_ += y;
}

void PointerControl::OnKey(int key, int action, int mods) {
  if (action == GLFW_RELEASE || ImGui::GetIO().WantCaptureKeyboard) return;
  keys_.emplace_back(key, mods);
}

KeyActions PointerControl::Process(GLFWwindow* window, world::SceneRenderer& renderer,
                                   bool camera_drag, Pose* X_WT) {
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window, &x, &y);
  int width = 0, height = 0;
  glfwGetWindowSize(window, &width, &height);
  const double h = std::max(1, height);
  const double rx = have_cursor_ ? (x - last_x_) / h : 0.0;
  const double ry = have_cursor_ ? (y - last_y_) / h : 0.0;
  last_x_ = x;
  last_y_ = y;
  have_cursor_ = true;
  const bool shift = Held(window, GLFW_KEY_LEFT_SHIFT, GLFW_KEY_RIGHT_SHIFT);
  const bool camera = camera_drag != Held(window, GLFW_KEY_LEFT_CONTROL, GLFW_KEY_RIGHT_CONTROL);
  const ViewAxes axes = AxesAt(renderer.camera_frame(), X_WT->p);
  if (camera) {
    MoveCamera(renderer, rx, ry, shift);
  } else {
    MovePointer(axes,
                PointerDrag{.left = drag_[GLFW_MOUSE_BUTTON_LEFT],
                            .right = drag_[GLFW_MOUSE_BUTTON_RIGHT],
                            .shift = shift,
                            .rx = rx,
                            .ry = ry,
                            .scroll = scroll_},
                X_WT);
  }
  if (drag_[GLFW_MOUSE_BUTTON_MIDDLE] && ry != 0.0) {
    renderer.MoveCamera(world::CameraMotion::kZoom, 0, ry);
  }
  scroll_ = 0.0;
  return ApplyKeys(axes, X_WT);
}

void PointerControl::MoveCamera(world::SceneRenderer& renderer, double rx, double ry,
                                bool shift) const {
  using world::CameraMotion;
  const bool moved = rx != 0.0 || ry != 0.0;
  if (drag_[GLFW_MOUSE_BUTTON_LEFT] && moved) {
    renderer.MoveCamera(shift ? CameraMotion::kRotateHorizontal : CameraMotion::kRotateVertical, rx,
                        ry);
  }
  if (drag_[GLFW_MOUSE_BUTTON_RIGHT] && moved) {
    renderer.MoveCamera(shift ? CameraMotion::kMoveHorizontal : CameraMotion::kMoveVertical, rx,
                        ry);
  }
  if (scroll_ != 0.0) renderer.MoveCamera(CameraMotion::kZoom, 0, -kCameraZoomPerNotch * scroll_);
}

KeyActions PointerControl::ApplyKeys(const ViewAxes& a, Pose* X_WT) {
  KeyActions actions;
  for (const auto& [key, mods] : keys_) {
    const double step = (mods & GLFW_MOD_SHIFT) != 0 ? kFineNudge : kNudge;
    X_WT->p += step * NudgeDirection(key, a);
    if (key == GLFW_KEY_SPACE) actions.toggle_pause = true;
    if (key == GLFW_KEY_S) actions.step = true;
    if (key == GLFW_KEY_BACKSPACE) actions.reset = true;
    if (key == GLFW_KEY_H) actions.toggle_panel = true;
    if (key == GLFW_KEY_C) actions.toggle_camera = true;
    if (key == GLFW_KEY_HOME) actions.reset_camera = true;
  }
  keys_.clear();
  return actions;
}

}  // namespace mrh::viewer::internal
