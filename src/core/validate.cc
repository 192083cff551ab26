// SPDX-License-Identifier: Apache-2.0
// Range checks with one-line messages (setup path).
#include "mrh/core/validate.h"

#include <charconv>
#include <cmath>

#include "mrh/core/error.h"

namespace mrh {
namespace {

std::string Unit(std::string_view unit) {
  return unit.empty() ? std::string() : " " + std::string(unit);
}

[[noreturn]] void Reject(double value, std::string_view key, std::string_view unit,
                         const std::string& expected) {
  throw InvalidArgument(std::string(key) + " = " + FormatNumber(value) + Unit(unit) +
                        "; expected " + expected);
}

std::string UpperBound(double max, std::string_view unit) {
  return std::isinf(max) ? std::string() : " and <= " + FormatNumber(max) + Unit(unit);
}

}  // namespace

std::string FormatNumber(double value) {
  if (std::isnan(value)) return "nan";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::string FormatNumbers(const double* values, int count) {
  std::string text = "[";
  for (int i = 0; i < count; ++i) text += (i > 0 ? ", " : "") + FormatNumber(values[i]);
  return text + "]";
}

void RequirePositive(double value, std::string_view key, std::string_view unit, double max) {
  if (std::isfinite(value) && value > 0.0 && value <= max) return;
  Reject(value, key, unit, "a finite value > 0" + UpperBound(max, unit));
}

void RequireNonNegative(double value, std::string_view key, std::string_view unit, double max) {
  if (std::isfinite(value) && value >= 0.0 && value <= max) return;
  Reject(value, key, unit, "a finite value >= 0" + UpperBound(max, unit));
}

void RequireInRange(double value, double min, double max, std::string_view key,
                    std::string_view unit) {
  if (std::isfinite(value) && value >= min && value <= max) return;
  Reject(value, key, unit,
         "a finite value in [" + FormatNumber(min) + ", " + FormatNumber(max) + "]" + Unit(unit));
}

void RequireIntInRange(long long value, long long min, long long max, std::string_view key) {
  if (value >= min && value <= max) return;
  throw InvalidArgument(std::string(key) + " = " + std::to_string(value) +
                        "; expected a whole number in [" + std::to_string(min) + ", " +
                        std::to_string(max) + "]");
}

Problem PoseProblem(const Vec3& p, const Quat& q) {
  static constexpr const char* kAxes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (std::isfinite(p[i]) && std::abs(p[i]) <= kMaxDevicePosition) continue;
    return {std::string("position ") + kAxes[i] + " = " + FormatNumber(p[i]) + " m",
            "a finite value in [-1000, 1000] m"};
  }
  const double c[4] = {q.w(), q.x(), q.y(), q.z()};
  const std::string text = "quaternion (qw, qx, qy, qz) = (" + FormatNumber(c[0]) + ", " +
                           FormatNumber(c[1]) + ", " + FormatNumber(c[2]) + ", " +
                           FormatNumber(c[3]) + ")";
  for (const double x : c) {
    if (!std::isfinite(x) || std::abs(x) > kMaxQuaternionComponent) {
      return {text, "finite components of magnitude <= 1e+06 (it is normalised on load)"};
    }
  }
  if (!(q.norm() >= kMinQuaternionNorm)) {
    return {text + " has (almost) zero norm", "a rotation, e.g. 1, 0, 0, 0 for none"};
  }
  return {};
}

Problem KeyframeTimeProblem(double t, double previous) {
  if (!std::isfinite(t) || std::abs(t) > kMaxKeyframeTime) {
    return {"t = " + FormatNumber(t) + " s", "a finite time in [-1e+06, 1e+06] s"};
  }
  if (!std::isnan(previous) && !(t - previous >= kMinKeyframeSpacing)) {
    return {"t = " + FormatNumber(t) +
                " s is not 1e-06 s or more after the previous t = " + FormatNumber(previous) + " s",
            "strictly increasing times"};
  }
  return {};
}

}  // namespace mrh
