// SPDX-License-Identifier: Apache-2.0
// Spatial types: poses, twists and wrenches in SI units, with monogram frame notation (X_WB).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace mrh {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// A rigid transform X_AB: position p (m) of B's origin in A and orientation q (unit, B→A).
/// RT-safe.
struct Pose {
  Vec3 p = Vec3::Zero();
  Quat q = Quat::Identity();

  /// Maps a point expressed in B to A: p_A = p + R(q) p_B.
  Vec3 operator*(const Vec3& p_B) const { return p + q * p_B; }

  /// Composition X_AC = X_AB * X_BC.
  Pose operator*(const Pose& X_BC) const { return Pose{p + q * X_BC.p, q * X_BC.q}; }

  /// X_BA.
  Pose Inverse() const {
    const Quat qi = q.conjugate();
    return Pose{-(qi * p), qi};
  }

  static Pose Identity() { return Pose{}; }
};

/// Spatial velocity: linear velocity v (m/s) of a reference point and angular velocity w (rad/s),
/// both expressed in the world frame. RT-safe.
struct Twist {
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
};

/// A wrench: force f (N) and torque tau (N·m) about a stated point, expressed in a stated frame.
/// RT-safe.
struct Wrench {
  Vec3 f = Vec3::Zero();
  Vec3 tau = Vec3::Zero();
};

/// Blends two poses: position by lerp, orientation by slerp along the short arc. alpha in [0, 1].
/// RT-safe.
inline Pose Interpolate(const Pose& a, const Pose& b, double alpha) {
  return Pose{a.p + alpha * (b.p - a.p), a.q.slerp(alpha, b.q)};
}

namespace internal {
// Below this rotation angle (rad) the exp and log maps use their first-order series forms,
// which are exact to double precision there: the next terms are O(angle²) relative, < 1e-16.
inline constexpr double kSmallRotationAngle = 1e-8;
}  // namespace internal

/// The unit quaternion of the rotation vector theta (axis × angle, rad): the exponential map of
/// SO(3), exp(θ) = (cos(|θ|/2), sin(|θ|/2) θ/|θ|). θ is expressed in the frame the quaternion
/// rotates into (a world rotation vector gives q_W, applied as exp(θ) * q). Any |θ| is accepted;
/// angles beyond π wrap around. Below internal::kSmallRotationAngle it returns (1, θ/2)
/// normalized (no division by a vanishing angle); the zero vector gives the identity exactly.
/// @pre theta is finite. RT-safe.
inline Quat QuatFromRotationVector(const Vec3& theta) noexcept {
  const double angle = theta.norm();
  if (angle < internal::kSmallRotationAngle) {
    return Quat(1.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z()).normalized();
  }
  return Quat(Eigen::AngleAxisd(angle, theta / angle));
}

/// The rotation vector (axis × angle, rad, angle in [0, π]) of the unit quaternion q: the
/// logarithmic map of SO(3), the inverse of QuatFromRotationVector. q and −q are the same
/// rotation; the short arc is taken. Below a half-angle sine of internal::kSmallRotationAngle
/// it returns 2 q.vec() (the limit of 2 atan2(s, w) q.vec()/s).
/// @pre q is finite and of unit norm. RT-safe.
inline Vec3 RotationVectorFromQuat(const Quat& q) noexcept {
  // w >= 0 selects the representative with angle <= π.
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const Vec3 v = sign * q.vec();
  const double w = sign * q.w();
  const double s = v.norm();
  if (s < internal::kSmallRotationAngle) return 2.0 * v;
  const double angle = 2.0 * std::atan2(s, w);
  return v * (angle / s);
}

/// True when every component is finite. RT-safe.
inline bool IsFinite(const Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

inline bool IsFinite(const Quat& q) {
  return std::isfinite(q.w()) && std::isfinite(q.x()) && std::isfinite(q.y()) &&
         std::isfinite(q.z());
}

inline bool IsFinite(const Pose& X) {
  return IsFinite(X.p) && IsFinite(X.q);
}

inline bool IsFinite(const Wrench& w) {
  return IsFinite(w.f) && IsFinite(w.tau);
}

inline bool IsFinite(const Twist& t) {
  return IsFinite(t.v) && IsFinite(t.w);
}

}  // namespace mrh
