// SPDX-License-Identifier: Apache-2.0
// A device driven by a desktop mouse and keyboard: the UI thread sets targets, the haptic thread
// reads.
#pragma once

#include <cstdint>

#include "mrh/core/triple_buffer.h"
#include "mrh/device/device.h"

namespace mrh::device {

/// How a MouseDevice turns the UI's target poses into a smooth tool motion.
struct MouseDeviceSettings {
  /// Time constant of the first-order filter from the target to the tool pose (s, > 0). The UI
  /// moves the target at its frame rate (~60 Hz); the filter spreads each jump over many haptic
  /// ticks so that the tool velocity, and the damping force it drives, stays bounded.
  double smoothing = 0.02;

  /// @throws mrh::InvalidArgument naming the field if smoothing is not finite and > 0.
  void Validate() const;
};

/// The default specifications of a mouse: no force can be felt, so the limits only bound what is
/// drawn; the workspace is a 2 m cube around the device origin.
Specifications MouseSpecifications();

/// A virtual 6-DOF device fed by a user interface. One UI thread calls SetTarget, Teleport and
/// LatestWrench; the haptic thread calls Read and SetWrench. The two sides meet only in lock-free
/// triple buffers, so neither ever waits for the other.
///
/// The tool follows the newest target through a first-order filter per axis (position by lerp,
/// orientation by slerp with the same factor 1 − exp(−Δt/τ) per reading), and its velocity is
/// the finite difference of consecutive readings. Targets are clamped to the workspace.
class MouseDevice final : public Device {
 public:
  /// Starts at X_DT0 (device frame) at rest. @throws mrh::InvalidArgument for bad settings, a
  /// non-finite or non-unit pose, or a workspace with min > max.
  explicit MouseDevice(const Pose& X_DT0, const MouseDeviceSettings& settings = {},
                       const Specifications& specs = MouseSpecifications());

  const Specifications& specifications() const override { return specs_; }

  /// UI thread: the pose the tool should move to (device frame). A non-finite or zero quaternion
  /// is ignored (the previous target stays); the position is clamped to the workspace and the
  /// quaternion normalized. RT-safe.
  void SetTarget(const Pose& X_DT, std::uint32_t buttons = 0) noexcept;

  /// UI thread: moves the tool to X_DT at once, at rest (a reset, not a motion). Same checks as
  /// SetTarget. RT-safe.
  void Teleport(const Pose& X_DT) noexcept;

  /// UI thread: the newest wrench the haptic thread commanded (device frame; zero before the
  /// first). RT-safe.
  Wrench LatestWrench() noexcept;

  /// Haptic thread: advances the filter to time t (s) and returns the tool state. A reading at a
  /// time not after the previous one returns the previous pose at zero velocity; an earlier time
  /// restarts the clock from there (a new run reusing the device). RT-safe.
  DeviceState Read(double t) noexcept override;

  /// Haptic thread: hands the wrench to the UI (it cannot be felt). RT-safe.
  void SetWrench(const Wrench& w_D) noexcept override;

 private:
  struct Target {
    Pose X_DT;
    std::uint32_t buttons = 0;
    std::uint64_t teleports = 0;  ///< bumped by Teleport; the reader snaps when it changes
  };

  bool Sanitize(Pose* X_DT) const noexcept;

  MouseDeviceSettings settings_;
  Specifications specs_;

  // UI side.
  Target ui_target_;
  TripleBuffer<Target> targets_;
  TripleBuffer<Wrench> wrenches_;

  // Haptic side.
  Pose X_DT_;
  double last_t_ = 0.0;
  bool has_read_ = false;
  std::uint64_t seen_teleports_ = 0;
};

}  // namespace mrh::device
