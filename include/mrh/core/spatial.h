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

/// True when every component is finite. RT-safe.
inline bool IsFinite(const Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

inline bool IsFinite(const Quat& q) {
  return std::isfinite(q.w()) && std::isfinite(q.x()) && std::isfinite(q.y()) &&
         std::isfinite(q.z());
}

inline bool IsFinite(const Pose& X) { return IsFinite(X.p) && IsFinite(X.q); }

inline bool IsFinite(const Wrench& w) { return IsFinite(w.f) && IsFinite(w.tau); }

inline bool IsFinite(const Twist& t) { return IsFinite(t.v) && IsFinite(t.w); }

}  // namespace mrh
