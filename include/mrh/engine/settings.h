// SPDX-License-Identifier: Apache-2.0
// Settings of the multi-rate engine (the `session` module fills them from a session file).
#pragma once

#include <optional>
#include <string>

#include "mrh/core/spatial.h"
#include "mrh/device/safety.h"

namespace mrh::engine {

/// How the two halves are scheduled. Both modes run the same data flow (SPEC §4.9).
enum class Mode {
  kLockstep,  ///< one thread, virtual time, bit-identical on rerun
  kRealtime,  ///< a physics thread and a haptic thread at haptic_dt against the wall clock
};

/// Returns "lockstep" / "realtime".
const char* ModeName(Mode mode) noexcept;

/// The haptic pointer. Session key: `pointer`.
struct PointerSettings {
  std::string body = "pointer";  ///< mocap body of the scene
  /// Sphere radius for 3-DOF rendering (m). 0: take it from the pointer body's sphere geom.
  double radius = 0.0;
};

/// Rendering parameters. Session key: `rendering`.
struct RenderingSettings {
  double stiffness = 1000.0;        ///< k of eq. 4.11 (N/m)
  double damping = 0.0;             ///< d of eq. 4.11 (N·s/m)
  /// Objects whose signed distance to the pointer is at most this become neighbors (m).
  double neighbor_distance = 0.05;
  /// Broad-phase inflation of the pointer's bounds (m); at least the distance the hand can move
  /// in one physics step.
  double neighbor_margin = 0.05;
};

/// Everything the engine needs besides the world and the device.
struct EngineSettings {
  std::string method = "impulse";
  Mode mode = Mode::kLockstep;
  double physics_dt = 0.05;   ///< s; forced to haptic_dt by single-rate methods
  double haptic_dt = 0.001;   ///< s
  double duration = 10.0;     ///< s of simulated (lockstep) or wall (realtime) time
  PointerSettings pointer;
  RenderingSettings rendering;
  device::SafetySettings safety;
  /// Ask for SCHED_FIFO + mlockall in real-time mode (a warning, once, if refused).
  bool realtime_priority = true;

  /// @throws mrh::InvalidArgument naming the key: non-finite or non-positive times,
  /// physics_dt not a whole multiple of haptic_dt, negative gains.
  void Validate() const;
  /// Haptic ticks per physics step, n = physics_dt / haptic_dt (rounded).
  int ticks_per_step() const;
};

}  // namespace mrh::engine
