// SPDX-License-Identifier: Apache-2.0
// The mouse device: UI targets through a triple buffer, a first-order filter on the haptic side.
#include <cmath>
#include <string>

#include "mrh/core/error.h"
#include "mrh/core/spatial.h"
#include "mrh/core/validate.h"
#include "mrh/device/mouse.h"

namespace mrh::device {
namespace {

// A quaternion shorter than this cannot be normalized meaningfully (it is not a rotation).
constexpr double kMinQuatNorm = 1e-9;

}  // namespace

void MouseDeviceSettings::Validate() const {
  if (!std::isfinite(smoothing) || smoothing <= 0.0) {
    throw InvalidArgument("mouse device: smoothing = " + FormatNumber(smoothing) +
                          " s; expected a finite time constant > 0, e.g. 0.02");
  }
}

Specifications MouseSpecifications() {
  Specifications specs;
  specs.model = "mouse";
  return specs;
}

MouseDevice::MouseDevice(const Pose& X_DT0, const MouseDeviceSettings& settings,
                         const Specifications& specs)
    : settings_(settings), specs_(specs) {
  settings_.Validate();
  if (!(specs_.workspace_min.array() <= specs_.workspace_max.array()).all()) {
    throw InvalidArgument(
        "mouse device: workspace_min exceeds workspace_max on some axis; expected min <= max "
        "per axis");
  }
  Pose X = X_DT0;
  if (!IsFinite(X.p) || !IsFinite(X.q) || X.q.norm() < kMinQuatNorm) {
    throw InvalidArgument(
        "mouse device: initial pose is not finite or its quaternion has zero norm; expected a "
        "finite position and a rotation, e.g. qw = 1 for identity");
  }
  Sanitize(&X);
  X_DT_ = X;
  ui_target_.X_DT = X;
  targets_.write_slot() = ui_target_;
  targets_.Publish();
}

bool MouseDevice::Sanitize(Pose* X) const noexcept {
  if (!IsFinite(X->p) || !IsFinite(X->q) || X->q.norm() < kMinQuatNorm) return false;
  X->p = X->p.cwiseMax(specs_.workspace_min).cwiseMin(specs_.workspace_max);
  X->q.normalize();
  return true;
}

void MouseDevice::SetTarget(const Pose& X_DT, std::uint32_t buttons) noexcept {
  Pose X = X_DT;
  if (!Sanitize(&X)) return;
  ui_target_.X_DT = X;
  ui_target_.buttons = buttons;
  targets_.write_slot() = ui_target_;
  targets_.Publish();
}

void MouseDevice::Teleport(const Pose& X_DT) noexcept {
  Pose X = X_DT;
  if (!Sanitize(&X)) return;
  ui_target_.X_DT = X;
  ++ui_target_.teleports;
  targets_.write_slot() = ui_target_;
  targets_.Publish();
}

Wrench MouseDevice::LatestWrench() noexcept {
  wrenches_.Update();
  return wrenches_.read_slot();
}

DeviceState MouseDevice::Read(double t) noexcept {
  targets_.Update();
  const Target& target = targets_.read_slot();
  DeviceState state;
  state.t = t;
  state.buttons = target.buttons;
  if (target.teleports != seen_teleports_) {
    seen_teleports_ = target.teleports;
    X_DT_ = target.X_DT;
  } else if (has_read_ && t > last_t_) {
    // Exact discretization of ẋ = (x_target − x)/τ over the reading interval.
    const double dt = t - last_t_;
    const double alpha = 1.0 - std::exp(-dt / settings_.smoothing);
    const Pose previous = X_DT_;
    X_DT_ = Interpolate(previous, target.X_DT, alpha);
    state.V_DT.v = (X_DT_.p - previous.p) / dt;
    // The shortest rotation taking the previous orientation to the new one, world axes.
    state.V_DT.w = RotationVectorFromQuat(X_DT_.q * previous.q.conjugate()) / dt;
  }
  last_t_ = t;  // an earlier t restarts the clock (a new session reuses the device)
  has_read_ = true;
  state.X_DT = X_DT_;
  return state;
}

void MouseDevice::SetWrench(const Wrench& w_D) noexcept {
  wrenches_.write_slot() = w_D;
  wrenches_.Publish();
}

}  // namespace mrh::device
