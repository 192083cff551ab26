// SPDX-License-Identifier: Apache-2.0
// 3-DOF penalty rendering of a point against a plane IR (SPEC §4.6, eq. 4.11 with the sign fixed).
#pragma once

#include "mrh/core/spatial.h"

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
/// clamped at ≥ 0 so the damper never pulls the hand into the object (SPEC I19).
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

}  // namespace mrh::render
