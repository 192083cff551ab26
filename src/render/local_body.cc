// SPDX-License-Identifier: Apache-2.0
// Local rigid-body simulation of the haptic thread: eq. 4.14–4.15 and the sphere penalty contact.
#include "mrh/render/local_body.h"

#include <cmath>

namespace mrh::render {
namespace {

// Below this half-angle (rad) sin(h)/h is replaced by its series 1 − h²/6, exact to double
// precision there (the next term, h⁴/120, is < 1e-34).
constexpr double kSmallHalfAngle = 1e-8;

}  // namespace

Quat IntegrateWorldRotation(const Quat& q, const Vec3& w_W, double dt) noexcept {
  const double half_angle = 0.5 * w_W.norm() * dt;
  const double sinc = half_angle > kSmallHalfAngle ? std::sin(half_angle) / half_angle
                                                   : 1.0 - half_angle * half_angle / 6.0;
  // exp(ω dt/2) = (cos h, sin(h) ω/|ω|) = (cos h, sinc(h) · ω dt/2), h = |ω| dt/2.
  const Vec3 axis_part = (0.5 * dt * sinc) * w_W;
  const Quat dq(std::cos(half_angle), axis_part.x(), axis_part.y(), axis_part.z());
  // World-frame ω multiplies from the left (eq. 4.15's Q assumes a body-frame ω).
  return (dq * q).normalized();
}

void LocalBody::Reset(const Pose& X_WB, const Vec3& p_BCm, const Twist& V_WCm) noexcept {
  q_WB_ = X_WB.q.normalized();
  p_BCm_ = p_BCm;
  p_WCm_ = X_WB.p + q_WB_ * p_BCm;
  V_WCm_ = V_WCm;
  A_.setZero();
  b_.setZero();
}

void LocalBody::SetDynamics(const ir::Mat63& A, const Vec6& b) noexcept {
  A_ = A;
  b_ = b;
}

void LocalBody::AddVelocity(const Twist& dV) noexcept {
  V_WCm_.v += dV.v;
  V_WCm_.w += dV.w;
}

bool LocalBody::Step(const Vec3& f_W, double dt) noexcept {
  // eq. 4.14: u += (A f + b) Δt.
  const Vec6 du = (A_ * f_W + b_) * dt;
  const Twist V{V_WCm_.v + du.head<3>(), V_WCm_.w + du.tail<3>()};
  // eq. 4.15 with the new velocity.
  const Vec3 p = p_WCm_ + V.v * dt;
  const Quat q = IntegrateWorldRotation(q_WB_, V.w, dt);
  if (!IsFinite(V) || !IsFinite(p) || !IsFinite(q)) {
    V_WCm_ = Twist{};
    return false;
  }
  V_WCm_ = V;
  p_WCm_ = p;
  q_WB_ = q;
  return true;
}

SphereContact LocalBody::TouchSphere(const Vec3& p_BC, const Vec3& n_W, const Vec3& p_WP,
                                     const Twist& V_WP, double radius, double k,
                                     double d) const noexcept {
  const Vec3 p_WO = p_WCm_ + q_WB_ * (p_BC - p_BCm_);
  return TouchSpherePlane(p_WO, PointVelocity(p_WO), n_W, p_WP, V_WP, radius, k, d);
}

}  // namespace mrh::render
