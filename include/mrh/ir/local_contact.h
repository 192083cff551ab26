// SPDX-License-Identifier: Apache-2.0
// The contact local model of local-dynamics: the neighbors' contact island as exported
// by the physics step, simulated by the haptic thread at 1 kHz (render/local_contact_solver.h).
#pragma once

#include <cstdint>

#include "mrh/core/fixed_vector.h"
#include "mrh/core/spatial.h"

namespace mrh::ir {

/// Bodies of the local island (the pointer's dynamic neighbors plus every dynamic body they
/// touch, transitively, each with the whole mechanism it belongs to) and their contact rows.
/// Overflow: further bodies are treated as static and kStatusBodiesFull / kStatusContactsFull is
/// set in the snapshot.
inline constexpr std::size_t kMaxLocalBodies = 32;
inline constexpr std::size_t kMaxLocalContacts = 192;

/// A dynamic body of the local island, state at the end of the physics step.
struct LocalIslandBody {
  int body = -1;      ///< world body id
  int motion = -1;    ///< index into PhysicsSnapshot::bodies, -1: not a pointer neighbor
  double mass = 0.0;  ///< kg
  Mat3 inertia_B = Mat3::Zero();  ///< rotational inertia about the COM, body axes (kg·m²)
  /// A jointed body's mobility that MuJoCo's soft contacts are regularised with (its
  /// body_invweight0, translational, 1/kg; 0: a free body's, 1 / mass).
  double inv_weight = 0.0;
  Pose X_WB;                  ///< body pose (world)
  Vec3 p_BCm = Vec3::Zero();  ///< COM in the body frame (m)
  Twist V_WCm;                ///< COM twist (world)
  /// true: the haptic side must restart this body from X_WB / V_WCm even if it simulated it in
  /// the previous period (the world could not take its local state).
  bool reset = false;
};

/// One contact of an island body A with body B (another island body, or the static rest of the
/// world when b < 0), as found by the physics engine at the end of the step with an inflated
/// margin (so contacts about to close are included). Points and normal are fixed on their
/// bodies, so the gap follows the local poses.
struct LocalContactRow {
  int a = -1;                ///< index into LocalContactModel::bodies
  int b = -1;                ///< index into LocalContactModel::bodies, -1: static (world frame)
  Vec3 p_A = Vec3::Zero();   ///< contact point on A's surface, A's body frame (m)
  Vec3 p_B = Vec3::Zero();   ///< contact point on B's surface, B's body frame or world (m)
  Vec3 n_B = Vec3::UnitZ();  ///< unit normal from B toward A, B's body frame or world
  /// Signed distance when exported (m, < 0: penetration). The local solve uses the gap at the
  /// local poses; only its hard model (LocalContactSolverSettings::soft_contacts = false) uses
  /// this, holding the shallowest exported penetration of the body pair's rows (MuJoCo's soft
  /// resting depth) rather than pushing it out.
  double dist0 = 0.0;
  double mu = 0.0;  ///< Coulomb friction coefficient (0: frictionless, condim 1)
  /// The first tangent of MuJoCo's contact frame, in the frame of n_B (zero: none given, any
  /// tangent frame will do). The friction set depends on it when `pyramidal`.
  Vec3 t_B = Vec3::Zero();
  /// The friction set of the scene's cone (mjModel opt.cone): true, MuJoCo's pyramidal cone
  /// |f_t1| + |f_t2| <= mu f_n in the contact frame (n_B, t_B, n_B × t_B), MuJoCo's default;
  /// false, the elliptic cone, a disc |f_t| <= mu f_n.
  bool pyramidal = false;
  /// MuJoCo's soft-constraint parameters of the contact (mjContact solref, solimp; MuJoCo's
  /// defaults here): the local solve reproduces the reference's soft contacts with them.
  double solref[2] = {0.02, 1.0};
  double solimp[5] = {0.9, 0.95, 0.001, 0.5, 2.0};
  /// Round surfaces: r_A > 0 when A's geom is a sphere or a capsule. Its surface is
  /// then the points within r_A of a core point s_A (the sphere's centre, or the point of the
  /// capsule's segment nearest the contact), A's body frame, and the local solve re-derives the
  /// contact point each tick as s_A - r_A n at the local pose: a point fixed on a rolling body
  /// would turn with it, off the support point, and the normal force on it would spin the body.
  /// Likewise r_B / s_B for B (an island body; then the normal follows the two cores when both
  /// are round).
  double r_A = 0.0;
  Vec3 s_A = Vec3::Zero();
  double r_B = 0.0;
  Vec3 s_B = Vec3::Zero();
  /// Ellipsoids: e_A > 0 (semi-axes, m) when A's geom is an ellipsoid centred at s_A with
  /// orientation q_A (A's body frame); the local solve then puts A's contact at the ellipsoid's
  /// support point along −n each tick, for the reason above. Likewise e_B / q_B (support along n).
  Vec3 e_A = Vec3::Zero();
  Quat q_A = Quat::Identity();
  Vec3 e_B = Vec3::Zero();
  Quat q_B = Quat::Identity();
};

/// Joints of the island's mechanisms: one per jointed island body (its joint to its parent).
inline constexpr std::size_t kMaxLocalJoints = kMaxLocalBodies;

/// What a local joint lets the child do relative to its parent. kWeld: nothing (a body with no
/// joint of its own riding on a moving parent).
enum class LocalJointType : std::uint8_t { kHinge, kSlide, kBall, kWeld };

/// The joint of island body `child` to `parent` (another island body, or the static world when
/// parent < 0), with MuJoCo's definitions: the joint frame J is fixed on both bodies; at the
/// reference coordinate qpos0 the two copies coincide, X_WP·X_PJ = X_WC·X_CJ. A hinge rotates
/// the child's copy about `axis` (J's frame) through J's origin by q − qpos0 (rad); a slide
/// translates it along `axis` by q − qpos0 (m); a ball turns it by the unit quaternion q (its
/// qpos0 is the identity). Passive terms act on the joint's coordinates: stiffness k (N·m/rad or
/// N/m) towards the spring reference, damping (N·m·s/rad or N·s/m), frictionloss (N·m or N,
/// the largest dry-friction load), armature (kg·m² or kg, added to the coordinate's inertia);
/// limits on [range[0], range[1]] (hinge, slide) with MuJoCo's soft limit.
struct LocalJoint {
  LocalJointType type = LocalJointType::kHinge;
  int child = -1;             ///< index into LocalContactModel::bodies
  int parent = -1;            ///< index into LocalContactModel::bodies, -1: static (X_PJ in world)
  int joint = -1;             ///< world joint id (-1: kWeld)
  Pose X_PJ;                  ///< joint frame on the parent (parent body frame, or world)
  Pose X_CJ;                  ///< joint frame on the child (child body frame)
  Vec3 axis = Vec3::UnitZ();  ///< unit axis in J (hinge, slide)
  double qpos0 = 0.0;         ///< reference coordinate (hinge, slide)
  double spring_ref = 0.0;    ///< spring reference coordinate (hinge, slide)
  Quat spring_q = Quat::Identity();  ///< spring reference orientation (ball)
  double stiffness = 0.0;
  double damping = 0.0;
  double frictionloss = 0.0;
  double armature = 0.0;
  /// MuJoCo's dof_invweight0 of the (first) coordinate, its mobility at qpos0 (1/kg or
  /// 1/(kg·m²)): the regularisation of its dry friction and limit rows (0: the row's own).
  double inv_weight = 0.0;
  bool limited = false;
  double range[2] = {0.0, 0.0};
  double margin = 0.0;  ///< the limit acts within this distance of the range (rad or m)
  double solref_limit[2] = {0.02, 1.0};
  double solimp_limit[5] = {0.9, 0.95, 0.001, 0.5, 2.0};
  double solref_friction[2] = {0.02, 1.0};
  double solimp_friction[5] = {0.9, 0.95, 0.001, 0.5, 2.0};
};

/// Everything the contact local model needs for one period (physics → haptic, in the snapshot).
struct LocalContactModel {
  bool valid = false;           ///< false: the method does not use the contact model
  Vec3 gravity = Vec3::Zero();  ///< m/s², world
  FixedVector<LocalIslandBody, kMaxLocalBodies> bodies;
  FixedVector<LocalContactRow, kMaxLocalContacts> contacts;
  /// Parents before children (a joint's parent, if an island body, has a lower index).
  FixedVector<LocalJoint, kMaxLocalJoints> joints;
};

}  // namespace mrh::ir
