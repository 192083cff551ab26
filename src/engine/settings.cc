// SPDX-License-Identifier: Apache-2.0
// Validation of the engine settings (the boundary where session values are checked).
#include "mrh/engine/settings.h"

#include <fmt/format.h>

#include <cmath>

#include "mrh/core/error.h"

namespace mrh::engine {
namespace {

// physics_dt must be a whole number of haptic ticks; this tolerance absorbs decimal input such as
// 0.05 / 0.001 = 49.99999999999999.
constexpr double kRatioTolerance = 1e-6;

void RequirePositive(double value, const char* key, const char* unit) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InvalidArgument(
        fmt::format("{} = {} {}; expected a finite value > 0", key, value, unit));
  }
}

void RequireNonNegative(double value, const char* key, const char* unit) {
  if (!std::isfinite(value) || value < 0.0) {
    throw InvalidArgument(
        fmt::format("{} = {} {}; expected a finite value >= 0", key, value, unit));
  }
}

}  // namespace

const char* ModeName(Mode mode) noexcept {
  return mode == Mode::kLockstep ? "lockstep" : "realtime";
}

int EngineSettings::ticks_per_step() const {
  return static_cast<int>(std::lround(physics_dt / haptic_dt));
}

void EngineSettings::Validate() const {
  RequirePositive(haptic_dt, "haptic_dt", "s");
  RequirePositive(physics_dt, "physics_dt", "s");
  RequirePositive(duration, "duration", "s");
  const double ratio = physics_dt / haptic_dt;
  if (ratio < 1.0 - kRatioTolerance || std::abs(ratio - std::round(ratio)) > kRatioTolerance) {
    throw InvalidArgument(fmt::format(
        "physics_dt = {} s is not a whole multiple (>= 1) of haptic_dt = {} s; "
        "choose e.g. physics_dt = {} s",
        physics_dt, haptic_dt, haptic_dt * std::max(1.0, std::round(ratio))));
  }
  if (haptic_dt > 0.1) {
    throw InvalidArgument(fmt::format(
        "haptic_dt = {} s; expected <= 0.1 s (haptic rendering needs ~1 ms)", haptic_dt));
  }
  if (method.empty()) throw InvalidArgument("method is empty; expected a method name");
  RequireNonNegative(pointer.radius, "pointer.radius", "m");
  if (pointer.body.empty()) {
    throw InvalidArgument("pointer.body is empty; expected the name of the scene's mocap body");
  }
  RequireNonNegative(rendering.stiffness, "rendering.stiffness", "N/m");
  RequireNonNegative(rendering.damping, "rendering.damping", "N*s/m");
  RequireNonNegative(rendering.neighbor_distance, "rendering.neighbor_distance", "m");
  RequireNonNegative(rendering.neighbor_margin, "rendering.neighbor_margin", "m");
  safety.Validate();
}

}  // namespace mrh::engine
