// SPDX-License-Identifier: Apache-2.0
// The safety layer: NaN/inf guard, engage ramp, watchdog fade, force/torque clamp and stop.
#include "mrh/device/safety.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"

namespace mrh::device {
namespace {

// Documented ranges (docs/session-format.md, "Ranges").
constexpr double kMaxRampTime = 60.0;           // s
constexpr double kMaxWatchdogTimeout = 3600.0;  // s
constexpr double kMaxWatchdogFade = 60.0;       // s
constexpr double kMaxBodySpeed = 1e4;           // m/s
constexpr double kMaxForce = 1e4;               // N
constexpr double kMaxTorque = 1e3;              // N*m

// Clamps x to [0, 1]; NaN maps to 0, the safe side for a gain.
double ClampGain(double x) noexcept {
  return x > 0.0 ? std::min(x, 1.0) : 0.0;
}

// Scales v down to length `limit` if it is longer, keeping its direction. stableNorm() avoids
// the overflow of a plain norm for huge finite components (a plain norm would give inf and a
// zero vector, losing the direction). Returns true if v was clamped.
bool ClampLength(Vec3& v, double limit) noexcept {
  const double length = v.stableNorm();
  if (length <= limit && v.norm() <= limit) return false;
  v *= limit / length;
  // Rounding can leave |v| an ulp or two above the limit (20.000000000000007 for 20 N): shrink
  // by a few ulps until neither norm exceeds it.
  constexpr double kShrink = 1.0 - 4.0 * std::numeric_limits<double>::epsilon();
  for (int i = 0; i < 8 && (v.norm() > limit || v.stableNorm() > limit); ++i) v *= kShrink;
  if (v.norm() > limit) v.setZero();  // unreachable for a finite limit; never exceed it
  return true;
}

// Engage ramp gain at session time t, in [0, 1].
double RampGain(const SafetySettings& settings, double t, std::uint32_t* status) noexcept {
  if (!settings.ramp || settings.ramp_time == 0.0) return 1.0;
  const double gain = ClampGain(t / settings.ramp_time);
  if (gain < 1.0) *status |= kSafetyRamping;
  return gain;
}

// Moves the watchdog gain by dt / watchdog_fade toward 0 while the physics side is stale and
// toward 1 once it is fresh again, so neither the stall nor the recovery steps the output. A NaN
// age counts as stale.
double UpdateWatchdogGain(const SafetySettings& settings, double gain, double dt,
                          double physics_age, std::uint32_t* status) noexcept {
  const bool stale = !(physics_age <= settings.watchdog_timeout);
  if (settings.watchdog_fade == 0.0) {
    gain = stale ? 0.0 : 1.0;
  } else {
    gain = ClampGain(gain + (stale ? -dt : dt) / settings.watchdog_fade);
  }
  if (stale || gain < 1.0) *status |= kSafetyWatchdog;
  return gain;
}

std::uint32_t ClampWrench(const Specifications& specs, Wrench& w) noexcept {
  std::uint32_t status = kSafetyOk;
  if (ClampLength(w.f, specs.max_force)) status |= kSafetyForceClamped;
  if (ClampLength(w.tau, specs.max_torque)) status |= kSafetyTorqueClamped;
  return status;
}

}  // namespace

void SafetySettings::Validate() const {
  RequireNonNegative(ramp_time, "safety.ramp_time", "s", kMaxRampTime);
  RequireNonNegative(watchdog_timeout, "safety.watchdog_timeout", "s", kMaxWatchdogTimeout);
  RequireNonNegative(watchdog_fade, "safety.watchdog_fade", "s", kMaxWatchdogFade);
  RequireNonNegative(max_body_speed, "safety.max_body_speed", "m/s", kMaxBodySpeed);
}

// The const-reference parameters are the public signature; one copy at setup is free.
// NOLINTNEXTLINE(modernize-pass-by-value)
SafetyFilter::SafetyFilter(const Specifications& specs, const SafetySettings& settings)
    : specs_(specs), settings_(settings) {
  settings_.Validate();
  RequireNonNegative(specs_.max_force, "device.limits.max_force", "N", kMaxForce);
  RequireNonNegative(specs_.max_torque, "device.limits.max_torque", "N*m", kMaxTorque);
}

Wrench SafetyFilter::Apply(const Wrench& rendered, double t, double physics_age, bool device_ok,
                           std::uint32_t* bits) noexcept {
  std::uint32_t status = kSafetyOk;
  Wrench out;  // zero unless every check below passes
  if (stopped_) {
    status = kSafetyStopped;
  } else if (!device_ok) {
    status = kSafetyNonFiniteDevice;
  } else if (!IsFinite(rendered)) {
    status = kSafetyNonFiniteWrench;
  } else {
    // Time between shaped ticks drives the watchdog; a non-finite t does not advance it.
    double dt = 0.0;
    if (std::isfinite(t)) {
      dt = std::max(t - last_t_, 0.0);
      last_t_ = t;
    }
    watchdog_gain_ = UpdateWatchdogGain(settings_, watchdog_gain_, dt, physics_age, &status);
    const double gain = RampGain(settings_, t, &status) * watchdog_gain_;
    out = Wrench{gain * rendered.f, gain * rendered.tau};
    status |= ClampWrench(specs_, out);
    // Belt and braces: the output is finite by construction, but a device must never see NaN.
    if (!IsFinite(out)) {
      out = Wrench{};
      status |= kSafetyNonFiniteWrench;
    }
  }
  if (bits != nullptr) *bits = status;
  return out;
}

}  // namespace mrh::device
