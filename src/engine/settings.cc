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

void RequireAtLeast(int value, int minimum, const char* key) {
  if (value < minimum) {
    throw InvalidArgument(
        fmt::format("{} = {}; expected an integer >= {}", key, value, minimum));
  }
}

void ValidateProxy(const RenderingSettings& r) {
  RequireNonNegative(r.rot_stiffness, "rendering.rot_stiffness", "N*m/rad");
  RequireNonNegative(r.rot_damping, "rendering.rot_damping", "N*m*s/rad");
  RequirePositive(r.rotation_weight_scale, "rendering.rotation_weight_scale", "");
  if (r.rotation_weight) {
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite((*r.rotation_weight)[i]) || (*r.rotation_weight)[i] <= 0.0) {
        throw InvalidArgument(fmt::format(
            "rendering.rotation_weight = [{}, {}, {}] m^2; expected three finite values > 0 "
            "(the diagonal of R_w)",
            r.rotation_weight->x(), r.rotation_weight->y(), r.rotation_weight->z()));
      }
    }
  }
  RequireNonNegative(r.friction, "rendering.friction", "");
  if (r.proxy_solver != "active-set" && r.proxy_solver != "pgs") {
    throw InvalidArgument(fmt::format(
        "rendering.proxy_solver = \"{}\"; expected \"active-set\" (exact, default) or \"pgs\" "
        "(the thesis' projected Gauss-Seidel)",
        r.proxy_solver));
  }
  RequireAtLeast(r.max_iterations, 1, "rendering.max_iterations");
  RequirePositive(r.solver_tolerance, "rendering.solver_tolerance", "m");
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
  RequireAtLeast(rendering.curved_segments, 6, "rendering.curved_segments");
  ValidateProxy(rendering);
  RequirePositive(rendering.perturbation_force, "rendering.perturbation_force", "N");
  if (rendering.local_model != "contact" && rendering.local_model != "perturbation") {
    throw InvalidArgument(fmt::format(
        "rendering.local_model = \"{}\"; expected \"contact\" (default) or \"perturbation\"",
        rendering.local_model));
  }
  safety.Validate();
}

}  // namespace mrh::engine
