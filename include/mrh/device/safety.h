// SPDX-License-Identifier: Apache-2.0
// The safety layer between every rendering method and every device.
#pragma once

#include <cstdint>

#include "mrh/core/spatial.h"
#include "mrh/device/device.h"

namespace mrh::device {

/// Fault and shaping bits reported per tick (ORed into run statistics).
enum SafetyBits : std::uint32_t {
  kSafetyOk = 0,
  kSafetyNonFiniteWrench = 1u << 0,  ///< the rendered wrench had NaN/inf: zero output
  kSafetyNonFiniteDevice = 1u << 1,  ///< the device reading had NaN/inf: zero output
  kSafetyForceClamped = 1u << 2,     ///< |f| limited to Specifications::max_force
  kSafetyTorqueClamped = 1u << 3,    ///< |tau| limited to Specifications::max_torque
  kSafetyRamping = 1u << 4,          ///< engage ramp still below full scale
  kSafetyWatchdog = 1u << 5,         ///< physics side stalled: output fading or faded out
  kSafetyStopped = 1u << 6,          ///< Stop() was called: zero output
};

/// Settings of the safety layer. Session key: `safety`.
struct SafetySettings {
  /// Engage ramp: output scales linearly from 0 to 1 over `ramp_time` after start (s).
  bool ramp = true;
  double ramp_time = 0.5;
  /// Watchdog: if the physics side has not delivered a snapshot for `watchdog_timeout` (s), the
  /// output fades linearly to zero over `watchdog_fade` (s); it recovers when snapshots return.
  double watchdog_timeout = 0.25;
  double watchdog_fade = 0.1;
  /// Divergence guard (m/s): a free body whose centre of mass moves faster than this ends the
  /// run as a fault (the physics side stops, the watchdog fades the output, exit code 1). 0
  /// disables the speed test; a non-finite state or MuJoCo resetting it always ends the run.
  double max_body_speed = 20.0;

  /// @throws mrh::InvalidArgument naming the key for a non-finite or negative time.
  void Validate() const;
};

/// Shapes the rendered wrench into what the device displays: NaN/inf guard, engage ramp,
/// watchdog fade, force/torque clamp to the device limits, zero after Stop(). It never changes
/// what the physics sees. Single-threaded (the haptic thread). RT-safe except the constructor.
class SafetyFilter {
 public:
  SafetyFilter(const Specifications& specs, const SafetySettings& settings);

  /// Returns the wrench to send to the device (same frame as `rendered`).
  /// @param t              time since the session start (s)
  /// @param physics_age    time since the last physics snapshot arrived (s)
  /// @param device_ok      false if the device reading this tick was not finite
  /// @param bits           receives SafetyBits for this tick (overwritten)
  Wrench Apply(const Wrench& rendered, double t, double physics_age, bool device_ok,
               std::uint32_t* bits) noexcept;

  /// From now on every output is zero. RT-safe.
  void Stop() noexcept { stopped_ = true; }

  bool stopped() const noexcept { return stopped_; }

 private:
  Specifications specs_;
  SafetySettings settings_;
  double watchdog_gain_ = 1.0;
  double last_t_ = 0.0;
  bool stopped_ = false;
};

}  // namespace mrh::device
