// SPDX-License-Identifier: Apache-2.0
// Rotation-vector maps (SO(3) log and exp) shared by the simulated devices.
#pragma once

#include <cmath>

#include "mrh/core/spatial.h"

namespace mrh::device::internal {

// Below this angle (rad) the series forms are exact to double precision: the next terms are
// O(angle^2) relative, i.e. below 1e-16 here.
inline constexpr double kSmallAngle = 1e-8;

/// The rotation vector (axis * angle, rad, angle in [0, pi]) of a unit quaternion, taking the
/// short arc. RT-safe.
inline Vec3 RotationVector(const Quat& q) noexcept {
  // q and -q are the same rotation; w >= 0 selects the representative with angle <= pi.
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const Vec3 v = sign * q.vec();
  const double w = sign * q.w();
  const double s = v.norm();
  if (s < kSmallAngle) return 2.0 * v;
  const double angle = 2.0 * std::atan2(s, w);
  return v * (angle / s);
}

/// The unit quaternion of a rotation vector r (rad). RT-safe.
inline Quat QuatFromRotationVector(const Vec3& r) noexcept {
  const double angle = r.norm();
  if (angle < kSmallAngle) {
    Quat q(1.0, 0.5 * r.x(), 0.5 * r.y(), 0.5 * r.z());
    q.normalize();
    return q;
  }
  return Quat(Eigen::AngleAxisd(angle, r / angle));
}

}  // namespace mrh::device::internal
