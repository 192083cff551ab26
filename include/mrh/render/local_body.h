// SPDX-License-Identifier: Apache-2.0
// A rigid body simulated in the haptic thread from its dynamic IR (thesis §4.3.2, eq. 4.13–4.15).
#pragma once

#include "mrh/core/spatial.h"
#include "mrh/ir/snapshot.h"
#include "mrh/render/point_penalty.h"

namespace mrh::render {

/// A sphere pointer against a plane fixed on a local body, as evaluated for one tick.

/// A neighbor object simulated locally at the haptic rate (thesis §4.3.2). Its state is the COM
/// position, a unit orientation quaternion (body → world) and the COM twist, all in the world
/// frame. Each tick applies eq. 4.14, u += (A f + b) Δt, then eq. 4.15 with the new velocity
/// (semi-implicit Euler): x += v Δt and q ← exp(ω Δt / 2) ⊗ q for the world-frame ω (the
/// printed Q of eq. 4.15 assumes a body-frame ω),
/// renormalized. A is taken as measured for a force at the IR contact point, so a force given
/// to Step() is treated as acting there. Fixed size, no allocation; every member is RT-safe.
class LocalBody {
 public:
  /// Starts from body pose X_WB, COM offset p_BCm (m, body frame) and COM twist V_WCm (world),
  /// with A = 0 and b = 0. RT-safe.
  void Reset(const Pose& X_WB, const Vec3& p_BCm, const Twist& V_WCm) noexcept;

  /// Sets the accelerance A (1/kg rows 0–2, 1/(kg·m) rows 3–5, world frame) and the bias b
  /// ([m/s²; rad/s²], world frame) used from the next Step() on. RT-safe.
  void SetDynamics(const ir::Mat63& A, const Vec6& b) noexcept;

  /// Adds a velocity jump, e.g. the third term of eq. 4.18 (world frame). RT-safe.
  void AddVelocity(const Twist& dV) noexcept;

  /// Advances one tick of dt (s) with force f_W (N, world) on the body (eq. 4.14–4.15). Returns
  /// false if the result is not finite; the pose is then kept and the twist zeroed. RT-safe.
  [[nodiscard]] bool Step(const Vec3& f_W, double dt) noexcept;

  /// Body frame pose. RT-safe.
  Pose X_WB() const noexcept { return Pose{p_WCm_ - q_WB_ * p_BCm_, q_WB_}; }

  /// Centre of mass (m, world). RT-safe.
  const Vec3& p_WCm() const noexcept { return p_WCm_; }

  /// COM twist (world). RT-safe.
  const Twist& V_WCm() const noexcept { return V_WCm_; }

  const ir::Mat63& A() const noexcept { return A_; }

  const Vec6& b() const noexcept { return b_; }

  /// Velocity of the body's material point at p_W (m, world): v + ω × (p_W − p_WCm). RT-safe.
  Vec3 PointVelocity(const Vec3& p_W) const noexcept {
    return V_WCm_.v + V_WCm_.w.cross(p_W - p_WCm_);
  }

  /// Corrected eq. 4.11 for a sphere of `radius` (m) centred at p_WP moving with V_WP (world,
  /// linear velocity of the centre) against the plane through the body-fixed point p_BC (body
  /// frame) with unit normal n_W (object → pointer): the pointer point is p_WP − radius·n_W and
  /// the object point's velocity comes from this body's twist. k in N/m, d in N·s/m. RT-safe.
  SphereContact TouchSphere(const Vec3& p_BC, const Vec3& n_W, const Vec3& p_WP, const Twist& V_WP,
                            double radius, double k, double d) const noexcept;

 private:
  Vec3 p_WCm_ = Vec3::Zero();
  Quat q_WB_ = Quat::Identity();
  Vec3 p_BCm_ = Vec3::Zero();
  Twist V_WCm_;
  ir::Mat63 A_ = ir::Mat63::Zero();
  Vec6 b_ = Vec6::Zero();
};

/// q advanced by a rotation of ω dt about the world axis ω: exp(ω dt / 2) ⊗ q, normalized.
/// Exact for constant ω. RT-safe.
Quat IntegrateWorldRotation(const Quat& q, const Vec3& w_W, double dt) noexcept;

}  // namespace mrh::render
