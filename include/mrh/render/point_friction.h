// SPDX-License-Identifier: Apache-2.0
// Coulomb friction of a 3-DOF point contact through a stick anchor on the object.
#pragma once

#include <array>
#include <cstddef>

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

/// The stick anchors of one 3-DOF pointer's contacts, one per touched geom, fixed capacity N.
/// An anchor is made where the pointer's contact point first touched the geom, is kept in the
/// object's body frame (so it follows the object between ticks) and is forgotten once the geom
/// leaves contact (touching it again sticks anew). RT-safe; one thread.
template <std::size_t N>
class PointFrictionAnchors {
 public:
  /// The friction force on the pointer (N, world) at contact point p_WC on `geom` of a body at
  /// X_WB (normal n unit; k, mu, f_n as RenderPointFriction), moving the geom's anchor. Zero
  /// when N anchors are held already.
  Vec3 Friction(int geom, const Pose& X_WB, const Vec3& p_WC, const Vec3& n, double k, double mu,
                double f_n) noexcept {
    Anchor* anchor = nullptr;
    for (std::size_t a = 0; a < count_; ++a) {
      if (anchors_[a].geom == geom) anchor = &anchors_[a];
    }
    if (anchor == nullptr) {
      if (count_ == N) return Vec3::Zero();
      anchor = &anchors_[count_++];
      anchor->geom = geom;
      anchor->p_BA = X_WB.Inverse() * p_WC;
    }
    anchor->touched = true;
    const PointFrictionResult r = RenderPointFriction(X_WB * anchor->p_BA, p_WC, n, k, mu, f_n);
    anchor->p_BA = X_WB.Inverse() * r.p_WA;
    return r.f_W;
  }

  /// Forgets the anchors of geoms not touched since the previous call.
  void ReleaseUntouched() noexcept {
    std::size_t kept = 0;
    for (std::size_t a = 0; a < count_; ++a) {
      if (!anchors_[a].touched) continue;
      anchors_[kept] = anchors_[a];
      anchors_[kept++].touched = false;
    }
    count_ = kept;
  }

 private:
  struct Anchor {
    int geom = -1;
    Vec3 p_BA = Vec3::Zero();  ///< body frame of the geom's object
    bool touched = false;
  };

  std::array<Anchor, N> anchors_{};
  std::size_t count_ = 0;
};

}  // namespace mrh::render
