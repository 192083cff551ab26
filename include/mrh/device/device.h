// SPDX-License-Identifier: Apache-2.0
// The haptic device interface (CHAI3D / Force Dimension style), in SI units.
#pragma once

#include <cstdint>
#include <string>

#include "mrh/core/spatial.h"

namespace mrh::device {

/// What a device can do. Limits are enforced by the SafetyFilter before SetWrench.
struct Specifications {
  std::string model = "simulated";
  double max_force = 20.0;         ///< N
  double max_torque = 1.0;         ///< N·m
  double max_stiffness = 5000.0;   ///< N/m, the largest linear stiffness it renders stably
  Vec3 workspace_min = Vec3::Constant(-1.0);  ///< m, device frame
  Vec3 workspace_max = Vec3::Constant(1.0);   ///< m, device frame
  bool has_torque = true;
};

/// One reading of the device, in the device frame D.
struct DeviceState {
  double t = 0.0;                ///< s, the device clock at the reading
  Pose X_DT;                     ///< tool (grip) pose in the device frame
  Twist V_DT;                    ///< tool velocity (device frame)
  std::uint32_t buttons = 0;     ///< bit i = button i pressed
};

/// A haptic device. Read() and SetWrench() are called from the haptic thread once per tick and
/// must be RT-safe in every implementation (no allocation, locks, I/O or exceptions). Open/Close
/// are setup calls.
class Device {
 public:
  virtual ~Device() = default;

  virtual const Specifications& specifications() const = 0;

  /// Prepares the device. @throws mrh::Error if it cannot be used.
  virtual void Open() {}
  /// Releases the device; a real device must output zero first.
  virtual void Close() {}

  /// Reads the device at time t (s since the session start; simulated devices use it as their
  /// clock, hardware may ignore it). RT-safe.
  virtual DeviceState Read(double t) noexcept = 0;

  /// Commands the wrench to display (device frame, torque about the tool origin). The caller
  /// guarantees finite values within the specifications. RT-safe.
  virtual void SetWrench(const Wrench& w_D) noexcept = 0;
};

}  // namespace mrh::device
