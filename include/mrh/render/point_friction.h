// SPDX-License-Identifier: Apache-2.0
// Coulomb friction of a 3-DOF point contact through a stick anchor on the object (issue 35).
#pragma once

#include "mrh/core/spatial.h"

namespace mrh::render {

/// Result of RenderPointFriction.
struct PointFrictionResult {
  Vec3 f_W = Vec3::Zero();   ///< tangential force on the pointer (N); the object gets −f_W
  Vec3 p_WA = Vec3::Zero();  ///< the anchor after this tick (m, world frame)
  bool slipping = false;     ///< the spring exceeded the cone and the anchor was dragged
};

/// A point proxy for friction: the anchor p_WA is where the pointer's contact point stuck to the
/// object's surface. A tangential spring k from the pointer's contact point p_WC to the anchor
/// gives f_t = k·e (e the tangential part of p_WA − p_WC, normal n_W unit). Coulomb's cone
/// |f_t| ≤ μ f_n holds: beyond it the anchor slides to the cone's edge behind the pointer
/// (|f_t| = μ f_n, kinetic = static), as the friction cones of proxy-6dof do. Inside the cone
/// the anchor stays. k (N/m, > 0), mu (>= 0), f_n (N, >= 0). RT-safe.
inline PointFrictionResult RenderPointFriction(const Vec3& p_WA, const Vec3& p_WC, const Vec3& n_W,
                                               double k, double mu, double f_n) noexcept {
  PointFrictionResult r;
  const Vec3 offset = p_WA - p_WC;
  const Vec3 e = offset - n_W.dot(offset) * n_W;
  r.f_W = k * e;
  r.p_WA = p_WA;
  const double limit = mu * f_n;
  const double magnitude = r.f_W.norm();
  if (magnitude <= limit) return r;
  // Slip: magnitude > limit >= 0, so e is not zero.
  const Vec3 direction = e / e.norm();
  r.f_W = limit * direction;
  r.p_WA = p_WC + n_W.dot(offset) * n_W + (limit / k) * direction;
  r.slipping = true;
  return r;
}

}  // namespace mrh::render
