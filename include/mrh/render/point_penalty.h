// SPDX-License-Identifier: Apache-2.0
// 3-DOF penalty rendering of a point against a plane IR (thesis §4.3.1, eq. 4.11 with the sign
// fixed: as printed it pulls the hand into the object).
#pragma once

#include "mrh/core/spatial.h"
#include "mrh/ir/snapshot.h"

namespace mrh::render {

/// One plane contact as the haptic thread evaluates it (world frame).
struct PlaneContactState {
  Vec3 p_WO = Vec3::Zero();  ///< plane point on the object (m)
  Vec3 n_W = Vec3::UnitZ();  ///< unit normal, object → pointer
  Vec3 v_WO = Vec3::Zero();  ///< velocity of the object's material point at p_WO (m/s)
  Vec3 p_WC = Vec3::Zero();  ///< pointer contact point (for a sphere: centre − radius·n) (m)
  Vec3 v_WC = Vec3::Zero();  ///< pointer velocity at that point (m/s)
};

/// Result of RenderPointPenalty.
struct PointPenaltyResult {
  double depth = 0.0;      ///< δ = n·(p_WO − p_WC) (m); > 0 when penetrating
  double magnitude = 0.0;  ///< max(0, kδ + dδ̇) (N); 0 when not penetrating
  /// Force displayed on the pointer, f_d = magnitude·n (N). The object receives −f_d (eq. 4.12).
  Vec3 f_W = Vec3::Zero();
};

/// Corrected eq. 4.11: f_d = {k(x_o − x_p) + d(ẋ_o − ẋ_p)}·n n while δ > 0, else 0; the scalar is
/// clamped at ≥ 0 so the damper never pulls the hand into the object.
/// @param k spring (N/m) @param d damper (N·s/m). RT-safe.
inline PointPenaltyResult RenderPointPenalty(const PlaneContactState& c, double k,
                                             double d) noexcept {
  PointPenaltyResult r;
  r.depth = c.n_W.dot(c.p_WO - c.p_WC);
  if (!(r.depth > 0.0)) return r;
  const double depth_rate = c.n_W.dot(c.v_WO - c.v_WC);
  r.magnitude = k * r.depth + d * depth_rate;
  if (r.magnitude < 0.0) r.magnitude = 0.0;
  r.f_W = r.magnitude * c.n_W;
  return r;
}

/// One sphere-pointer contact: the plane state and its penalty result.
struct SphereContact {
  PlaneContactState state;    ///< plane point and velocity on the body, pointer point, normal
  PointPenaltyResult result;  ///< f_W acts on the pointer; the body receives −f_W at state.p_WO
};

/// The 3-DOF rendering every point method shares: a sphere pointer (centre p_WP, twist V_WP,
/// radius r in m) against the plane (point p_WO moving with v_WO, unit normal n_W) by corrected
/// eq. 4.11. The pointer's contact point is p_WP − r n. RT-safe.
inline SphereContact TouchSpherePlane(const Vec3& p_WO, const Vec3& v_WO, const Vec3& n_W,
                                      const Vec3& p_WP, const Twist& V_WP, double radius, double k,
                                      double d) noexcept {
  SphereContact c;
  c.state.p_WO = p_WO;
  c.state.n_W = n_W;
  c.state.v_WO = v_WO;
  c.state.p_WC = p_WP - radius * n_W;
  c.state.v_WC = V_WP.v + V_WP.w.cross(c.state.p_WC - p_WP);
  c.result = RenderPointPenalty(c.state, k, d);
  return c;
}

/// Plane point of a body that the haptic thread does not simulate (static, kinematic, or B4's
/// dynamic body), blended between its step poses with weight alpha (thesis §4.3.1, after
/// Hasegawa et al. 1999): the point p_BC
/// (body frame) in the world, its velocity from the step-end COM twist, and the COM. RT-safe.
struct BlendedPoint {
  Vec3 p_WO = Vec3::Zero();   ///< m
  Vec3 v_WO = Vec3::Zero();   ///< m/s
  Vec3 p_WCm = Vec3::Zero();  ///< the body's COM (m), the reaction's moment point
};

inline BlendedPoint BlendBodyPoint(const ir::BodyMotion& body, const Vec3& p_BC,
                                   double alpha) noexcept {
  const Pose X_WB = Interpolate(body.X_WB_prev, body.X_WB, alpha);
  BlendedPoint b;
  b.p_WCm = X_WB * body.p_BCm;
  b.p_WO = X_WB * p_BC;
  b.v_WO = body.V_WCm.v + body.V_WCm.w.cross(b.p_WO - b.p_WCm);
  return b;
}

/// The blended normal (thesis §4.3.1): from the last rendered n_prev to the snapshot's n, unit.
inline Vec3 BlendNormal(const Vec3& n_prev, const Vec3& n, double alpha) noexcept {
  return ((1.0 - alpha) * n_prev + alpha * n).normalized();
}

/// The contact's normal approach speed n·(v_WO − v_WC) (m/s; > 0 while the pointer closes in).
inline double ApproachSpeed(const SphereContact& c) noexcept {
  return c.state.n_W.dot(c.state.v_WO - c.state.v_WC);
}

/// The wrench a contact's force puts on the user's hand, torque about the pointer origin p_WP.
inline Wrench PointerWrench(const SphereContact& c, const Vec3& p_WP) noexcept {
  return Wrench{c.result.f_W, (c.state.p_WC - p_WP).cross(c.result.f_W)};
}

}  // namespace mrh::render
