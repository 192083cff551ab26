// SPDX-License-Identifier: Apache-2.0
// Range checks of the haptic materials; the ranges are those of the rendering.* gains they
// replace (docs/session-format.md, "Ranges").
#include "material_settings.h"

#include <fmt/format.h>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"

namespace mrh::settings::internal {
namespace {

constexpr double kMaxStiffness = 1e6;  // N/m, as rendering.stiffness
constexpr double kMaxDamping = 1e4;    // N*s/m, as rendering.damping
constexpr double kMaxFriction = 10.0;  // as rendering.friction
constexpr double kMaxAmplitude = 1e4;  // N per m/s: 100 N at 1 cm/s is no material
constexpr double kMaxDecay = 1e5;      // 1/s: gone within one tick at 10 kHz

void ValidateVibration(const VibrationSettings& v, const std::string& key, double haptic_dt) {
  RequireNonNegative(v.amplitude, key + ".amplitude", "N*s/m", kMaxAmplitude);
  RequirePositive(v.decay, key + ".decay", "1/s", kMaxDecay);
  // A sinusoid sampled at the haptic rate is only displayed below the Nyquist rate.
  const double nyquist = 0.5 / haptic_dt;
  if (!(v.frequency > 0.0 && v.frequency < nyquist)) {
    throw InvalidArgument(fmt::format(
        "{}.frequency = {} Hz; expected a finite value > 0 and below the haptic Nyquist rate "
        "1 / (2 haptic_dt) = {} Hz",
        key, FormatNumber(v.frequency), FormatNumber(nyquist)));
  }
}

}  // namespace

void ValidateMaterials(const RenderingSettings& r, double haptic_dt) {
  for (const auto& [name, m] : r.materials) {
    const std::string key = "materials." + name;
    if (name.empty()) {
      throw InvalidArgument(
          "materials: an empty material name; expected the name of an MJCF "
          "<material> that scene geoms use");
    }
    if (m.stiffness) RequireNonNegative(*m.stiffness, key + ".stiffness", "N/m", kMaxStiffness);
    if (m.damping) RequireNonNegative(*m.damping, key + ".damping", "N*s/m", kMaxDamping);
    if (m.friction) RequireNonNegative(*m.friction, key + ".friction", "", kMaxFriction);
    if (m.vibration) ValidateVibration(*m.vibration, key + ".vibration", haptic_dt);
  }
}

}  // namespace mrh::settings::internal
