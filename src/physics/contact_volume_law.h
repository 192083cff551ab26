// SPDX-License-Identifier: Apache-2.0
// Contact-volume penalty law of one convex pair (B2, Hasegawa & Sato 2004; thesis ref. [1],
// §1.2.1, fig. 1.4).
#pragma once

#include <optional>

#include "mrh/core/spatial.h"
#include "mrh/geometry/contact_volume.h"

namespace mrh::physics::internal {

/// Gains of the contact-volume penalty (rendering.stiffness, damping, friction).
struct PenaltyGains {
  double k = 1000.0;  ///< N/m: normal spring on the mean depth V / A, and tangential spring
  double d = 0.0;     ///< N·s/m: normal damper on the relative velocity, and tangential damper
  double mu_static = 0.0;
  double mu_dynamic = 0.0;
};

/// Where a body is and how it moves (world frame). A static body has a zero twist.
struct BodyKinematics {
  Pose X_WB;
  Vec3 p_WCm = Vec3::Zero();  ///< point the twist's linear velocity is of (m)
  Twist V_WCm;

  /// Velocity of the material point at p_W (m/s).
  Vec3 VelocityAt(const Vec3& p_W) const { return V_WCm.v + V_WCm.w.cross(p_W - p_WCm); }
};

/// Friction state of a pair, kept between steps: the anchored tangential spring (Springhead
/// PHPenaltyEngine). `active` false: not in contact last step (the next contact re-anchors).
struct FrictionAnchor {
  bool active = false;
  bool sliding = false;
  Vec3 p_A = Vec3::Zero();  ///< anchor fixed on A (A's body frame, m)
  Vec3 p_B = Vec3::Zero();  ///< anchor fixed on B (B's body frame, m)
};

/// The pair's penalty force on A (its negative acts on B), acting at `p_W`.
struct PairForce {
  Vec3 f_W = Vec3::Zero();  ///< N, world
  Vec3 p_W = Vec3::Zero();  ///< centre of pressure on the contact plane (m, world)
  double normal = 0.0;      ///< normal force N >= 0 (N)
  bool sliding = false;
};

/// The contact-volume penalty on A from the intersection `v` of A and B:
/// - normal: (k ∫δ − d ∫ v_rel·n) / A_proj along n, i.e. k·V/A_proj for the spring (a face pressed
///   to depth δ gives k δ whatever its area), the damper averaged over B's surface inside A;
///   never pulling (N >= 0: the damper is dropped when it would make N negative);
/// - its point: the centre of pressure of the spring integral (moment about c / N);
/// - friction: a tangential spring k·u + damper d·v_t between anchors fixed on A and B at first
///   contact, capped at μ_s N while sticking and μ_k N while sliding; while capped, A's anchor is
///   moved so the spring alone carries the cap.
/// `anchor` is updated (re-anchored when it was inactive). Not RT-safe (allocates a little).
PairForce ContactVolumeForce(const geometry::IntersectionVolume& v, const BodyKinematics& a,
                             const BodyKinematics& b, const PenaltyGains& gains,
                             FrictionAnchor* anchor);

}  // namespace mrh::physics::internal
