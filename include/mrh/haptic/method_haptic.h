// SPDX-License-Identifier: Apache-2.0
// The haptic half of a rendering method: what runs at 1 kHz on the haptic thread.
#pragma once

#include <algorithm>
#include <cstdint>

#include "mrh/core/spatial.h"
#include "mrh/ir/snapshot.h"

namespace mrh::haptic {

/// Input of one haptic tick.
struct TickInput {
  std::int64_t tick = 0;  ///< global tick index
  double t = 0.0;         ///< time of the tick (s)
  int j = 0;              ///< ticks since the current snapshot was adopted (0 at adoption)
  int n = 1;              ///< ticks per physics step
  double dt = 0.001;      ///< haptic period (s)
  Pose X_WP;              ///< pointer (device tool) pose, world frame
  Twist V_WP;             ///< pointer velocity, world frame

  /// The blend weight α = min(1, (j + 1) / n) of the interpolated IR (thesis §3.2.2, §4.3.1): 1/n
  /// at a snapshot's first tick, 1 from its last tick on; n < 1 is taken as 1.
  double alpha() const noexcept {
    return std::min(1.0, static_cast<double>(j + 1) / static_cast<double>(std::max(n, 1)));
  }
};

/// Output of one haptic tick.
struct TickOutput {
  /// Wrench rendered on the user's hand (world frame, torque about the pointer origin), before
  /// the safety layer.
  Wrench w_W;
  /// Proxy pose (world frame). The engine sets it to the pointer pose TickInput::X_WP before
  /// the call; a method with a proxy (proxy-6dof) overwrites it, the others leave it.
  Pose X_WQ;
  int contacts = 0;  ///< active contacts this tick
  /// Method status bits: their meaning is the method's own (named by engine::Method::
  /// status_bits); the haptic side records them per tick and counts every bit.
  std::uint32_t status = 0;
};

/// The haptic half of a method (single-rate, impulse, local-dynamics, proxy-6dof, ...). Runs on
/// the haptic thread only; every call is RT-safe (no allocation, lock, throw or I/O). It never
/// sees the world: what it knows of the physics arrives in ir::PhysicsSnapshot, and what it
/// sends back leaves in ir::HapticReport. Its physics counterpart (physics::MethodPhysics)
/// shares no object with it.
class MethodHaptic {
 public:
  virtual ~MethodHaptic() = default;

  /// A new snapshot becomes current.
  virtual void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept = 0;

  /// Renders one tick.
  virtual void HapticTick(const TickInput& in, TickOutput* out) noexcept = 0;

  /// Moves what this period delivered into `report` and starts a new period.
  virtual void EndPeriod(ir::HapticReport* report) noexcept = 0;
};

}  // namespace mrh::haptic
