// SPDX-License-Identifier: Apache-2.0
// Validation of the engine settings (the boundary where session values are checked). The ranges
// are documented in docs/session-format.md ("Ranges"); keep both in step.
#include "mrh/settings/settings.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "material_settings.h"
#include "mrh/core/error.h"
#include "mrh/core/validate.h"

namespace mrh::settings {
namespace {

// physics_dt must be a whole number of haptic ticks; this tolerance absorbs decimal input such as
// 0.05 / 0.001 = 49.99999999999999.
constexpr double kRatioTolerance = 1e-6;
// Bounds of what the engine can run (docs/session-format.md, "Ranges").
constexpr double kMinHapticDt = 1e-5;  // s: 100 kHz
constexpr double kMaxHapticDt = 0.1;   // s: haptic rendering needs ~1 ms
constexpr double kMaxPhysicsDt = 1.0;  // s
constexpr double kMaxTicksPerStep = 1e6;
constexpr double kMaxDuration = 3600.0;    // s
constexpr double kMaxTicks = 1e7;          // duration / haptic_dt
constexpr double kMaxPointerRadius = 1.0;  // m
constexpr double kMaxStiffness = 1e6;      // N/m
constexpr double kMaxDamping = 1e4;        // N*s/m
constexpr double kMaxDistance = 10.0;      // m
constexpr double kMaxRotStiffness = 1e4;   // N*m/rad
constexpr double kMaxRotDamping = 1e3;     // N*m*s/rad
constexpr double kMaxFriction = 10.0;
constexpr double kMaxIterations = 1e6;
constexpr int kMaxCurvedSegments = 1024;

// The contact model derives R_w and the rotational damping from k_t, k_r and d_t; a session that
// sets them means the thesis model.
void ValidateTorqueModel(const RenderingSettings& r) {
  if (r.torque_model == TorqueModel::kThesis) return;
  if (r.rotation_weight || r.rotation_weight_scale != 1.0) {
    throw InvalidArgument(
        "rendering.rotation_weight/rotation_weight_scale is set, but torque_model \"contact\" "
        "uses R_w = rot_stiffness / stiffness; remove it or set rendering.torque_model to "
        "\"thesis\"");
  }
  if (r.rot_damping != 0.0) {
    throw InvalidArgument(fmt::format(
        "rendering.rot_damping = {} N*m*s/rad, but torque_model \"contact\" damps through the "
        "contacts (rendering.damping); set it to 0 or rendering.torque_model to \"thesis\"",
        FormatNumber(r.rot_damping)));
  }
}

void ValidateProxy(const RenderingSettings& r) {
  RequireNonNegative(r.rot_stiffness, "rendering.rot_stiffness", "N*m/rad", kMaxRotStiffness);
  RequireNonNegative(r.rot_damping, "rendering.rot_damping", "N*m*s/rad", kMaxRotDamping);
  RequireInRange(r.rotation_weight_scale, 1e-6, 1e6, "rendering.rotation_weight_scale", "");
  if (r.rotation_weight) {
    for (int i = 0; i < 3; ++i) {
      const double w = (*r.rotation_weight)[i];
      if (std::isfinite(w) && w >= 1e-12 && w <= 1e6) continue;
      throw InvalidArgument(fmt::format(
          "rendering.rotation_weight = {} m^2; expected three finite values in [1e-12, 1e+06] "
          "m^2 (the diagonal of R_w)",
          FormatNumbers(r.rotation_weight->data(), 3)));
    }
  }
  RequireNonNegative(r.friction, "rendering.friction", "", kMaxFriction);
  ValidateTorqueModel(r);
  RequireIntInRange(r.max_iterations, 1, static_cast<long long>(kMaxIterations),
                    "rendering.max_iterations");
  RequireInRange(r.solver_tolerance, 1e-18, 1.0, "rendering.solver_tolerance", "m");
}

void ValidateRendering(const RenderingSettings& r) {
  RequireNonNegative(r.stiffness, "rendering.stiffness", "N/m", kMaxStiffness);
  RequireNonNegative(r.damping, "rendering.damping", "N*s/m", kMaxDamping);
  RequireNonNegative(r.neighbor_distance, "rendering.neighbor_distance", "m", kMaxDistance);
  RequireNonNegative(r.neighbor_margin, "rendering.neighbor_margin", "m", kMaxDistance);
  RequireIntInRange(r.curved_segments, 6, kMaxCurvedSegments, "rendering.curved_segments");
  ValidateProxy(r);
  RequireInRange(r.perturbation_force, 1e-3, 1e3, "rendering.perturbation_force", "N");
  RequireNonNegative(r.coupling_stiffness, "rendering.coupling_stiffness", "N/m", kMaxStiffness);
  RequireNonNegative(r.coupling_damping, "rendering.coupling_damping", "N*s/m", kMaxDamping);
  if (r.coupling_rot_stiffness) {
    RequireNonNegative(*r.coupling_rot_stiffness, "rendering.coupling_rot_stiffness", "N*m/rad",
                       kMaxStiffness);
  }
  if (r.coupling_rot_damping) {
    RequireNonNegative(*r.coupling_rot_damping, "rendering.coupling_rot_damping", "N*m*s/rad",
                       kMaxDamping);
  }
  RequireNonNegative(r.tool_mass, "rendering.tool_mass", "kg", 1e3);
  if (r.tool_inertia) {
    for (int i = 0; i < 3; ++i) {
      RequirePositive((*r.tool_inertia)[i], "rendering.tool_inertia", "kg*m^2", 1e3);
    }
  }
}

// Rates: haptic_dt, physics_dt as a whole number of ticks, and a run of at least one tick.
void ValidateTimes(const EngineSettings& s) {
  RequireInRange(s.haptic_dt, kMinHapticDt, kMaxHapticDt, "haptic_dt", "s");
  RequirePositive(s.physics_dt, "physics_dt", "s", kMaxPhysicsDt);
  const double ratio = s.physics_dt / s.haptic_dt;
  if (ratio < 1.0 - kRatioTolerance || std::abs(ratio - std::round(ratio)) > kRatioTolerance ||
      ratio > kMaxTicksPerStep) {
    throw InvalidArgument(fmt::format(
        "physics_dt = {} s is not a whole multiple (1 to {}) of haptic_dt = {} s; "
        "choose e.g. physics_dt = {} s",
        FormatNumber(s.physics_dt), FormatNumber(kMaxTicksPerStep), FormatNumber(s.haptic_dt),
        FormatNumber(s.haptic_dt * std::clamp(std::round(ratio), 1.0, kMaxTicksPerStep))));
  }
  RequireInRange(s.duration, s.haptic_dt, kMaxDuration, "duration", "s");
  if (s.duration / s.haptic_dt > kMaxTicks) {
    throw InvalidArgument(
        fmt::format("duration = {} s is {} ticks of haptic_dt = {} s; expected at most {} ticks "
                    "(a shorter duration or a longer haptic_dt)",
                    FormatNumber(s.duration), FormatNumber(std::round(s.duration / s.haptic_dt)),
                    FormatNumber(s.haptic_dt), FormatNumber(kMaxTicks)));
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
  ValidateTimes(*this);
  if (method.empty()) throw InvalidArgument("method is empty; expected a method name");
  RequireNonNegative(pointer.radius, "pointer.radius", "m", kMaxPointerRadius);
  if (pointer.body.empty()) {
    throw InvalidArgument("pointer.body is empty; expected the name of the scene's mocap body");
  }
  ValidateRendering(rendering);
  internal::ValidateMaterials(rendering, haptic_dt);
  safety.Validate();
  // Several pointers: each one's own radius and gains, named by its element.
  for (std::size_t i = 0; i < pointers.size(); ++i) {
    try {
      RequireNonNegative(pointers[i].pointer.radius, "radius", "m", kMaxPointerRadius);
      ValidateRendering(pointers[i].rendering);
    } catch (const InvalidArgument& e) {
      throw InvalidArgument(fmt::format("pointers[{}].{}", i, e.what()));
    }
  }
}

}  // namespace mrh::settings
