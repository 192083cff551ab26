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
  double max_force = 20.0;        ///< N
  double max_torque = 1.0;        ///< N·m
  double max_stiffness = 5000.0;  ///< N/m, the largest linear stiffness it renders stably
  Vec3 workspace_min = Vec3::Constant(-1.0);  ///< m, device frame
  Vec3 workspace_max = Vec3::Constant(1.0);   ///< m, device frame
  bool has_torque = true;
};

/// One reading of the device, in the device frame D.
struct DeviceState {
  double t = 0.0;             ///< s, the device clock at the reading
  Pose X_DT;                  ///< tool (grip) pose in the device frame
  Twist V_DT;                 ///< tool velocity (device frame)
  std::uint32_t buttons = 0;  ///< bit i = button i pressed
};

/// Faults a device counted itself (hardware and network devices; simulated ones count none).
/// Read from a non-RT thread; the values are snapshots of atomics.
struct DeviceCounters {
  std::int64_t vendor_errors = 0;      ///< vendor calls that returned an error
  std::int64_t torque_dropped = 0;     ///< ticks whose nonzero torque a 3-DOF device could not show
  std::int64_t packets_malformed = 0;  ///< network: wrong size, magic or version, non-finite
  std::int64_t pose_timeouts = 0;      ///< network: ticks with no pose for longer than the timeout
  std::int64_t poses_received = 0;     ///< network: well-formed pose packets
  std::int64_t wrenches_sent = 0;      ///< network: wrench packets sent
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

  /// The safety layer's bits (device::SafetyBits) for the wrench about to be commanded, so that a
  /// device can pass them on (the UDP device sends them). Default: ignored. RT-safe.
  virtual void SetSafetyBits(std::uint32_t bits) noexcept { (void)bits; }

  /// What the device counted so far. Not RT-safe (may be called while it runs).
  virtual DeviceCounters counters() const { return {}; }

  /// The vendor's last error text, or "" (for messages after a run). Not RT-safe.
  virtual std::string last_error() const { return {}; }
};

}  // namespace mrh::device
