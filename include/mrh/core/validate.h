// SPDX-License-Identifier: Apache-2.0
// The shared range checks of the setup path: one number formatter, one message shape.
#pragma once

#include <limits>
#include <string>
#include <string_view>

#include "mrh/core/spatial.h"

namespace mrh {

/// The shortest decimal text that reads back as `value`: "5e-324", "1e+308", "inf", "-inf",
/// "nan". Setup path only (allocates).
std::string FormatNumber(double value);

/// "[x, y, z]" with FormatNumber for each component.
std::string FormatNumbers(const double* values, int count);

/// Throws InvalidArgument "<key> = <value> <unit>; expected a finite value > 0[ and <= max]"
/// unless 0 < value <= max and value is finite. `max` = +inf means no upper bound.
void RequirePositive(double value, std::string_view key, std::string_view unit,
                     double max = std::numeric_limits<double>::infinity());

/// Same for 0 <= value <= max.
void RequireNonNegative(double value, std::string_view key, std::string_view unit,
                        double max = std::numeric_limits<double>::infinity());

/// Same for min <= value <= max (both finite; the documented range of the key).
void RequireInRange(double value, double min, double max, std::string_view key,
                    std::string_view unit);

/// Integers: min <= value <= max.
void RequireIntInRange(long long value, long long min, long long max, std::string_view key);

// Device data, the same rules for every device type and source (session keys, trajectory CSV,
// replayed ticks.csv, `mrh ir --pose`); docs/session-format.md, "Ranges".
inline constexpr double kMaxDevicePosition = 1e3;       ///< m, per component
inline constexpr double kMinQuaternionNorm = 1e-6;      ///< below: a typo, not a rotation
inline constexpr double kMaxQuaternionComponent = 1e6;  ///< above: overflow when normalising
inline constexpr double kMaxKeyframeTime = 1e6;         ///< s, |t|
inline constexpr double kMinKeyframeSpacing = 1e-6;     ///< s between successive keyframes

/// A rule a value breaks: what is wrong ("position x = 1e+308 m") and what is expected.
struct Problem {
  std::string what;
  std::string expected;

  explicit operator bool() const { return !what.empty(); }

  /// "<what>; expected <expected>".
  std::string Text() const { return what + "; expected " + expected; }
};

/// What is wrong with a device pose (position p in m, quaternion (qw, qx, qy, qz) not yet
/// normalised); empty if it is usable. On success the caller normalises q.
Problem PoseProblem(const Vec3& p, const Quat& q);

/// What is wrong with keyframe time `t` after `previous` (NaN for the first one); empty if fine.
Problem KeyframeTimeProblem(double t, double previous);

}  // namespace mrh
