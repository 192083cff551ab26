// SPDX-License-Identifier: Apache-2.0
// Baseline B2 `contact-volume`: the whole scene as one penalty simulation at the haptic rate.
#pragma once

#include <memory>
#include <vector>

#include "contact_volume_law.h"
#include "mrh/geometry/distance.h"
#include "mrh/geometry/polyhedron.h"
#include "mrh/physics/method_physics.h"
#include "mrh/world/world.h"

namespace mrh::physics::internal {

/// Work of the latest contact analysis, for tests and experiments.
struct ContactVolumeStats {
  int candidate_pairs = 0;   ///< pairs whose bounding spheres overlapped
  int contacts = 0;          ///< pairs with an intersection volume (penalty applied)
  int pointer_contacts = 0;  ///< of them, pairs with a pointer geom
};

/// B2 (Hasegawa & Sato 2004, thesis ref. [1], §1.2.1), physics half; single-rate
/// (physics_dt = haptic_dt).
///
/// The world is loaded with world::LoadOptions::penalty_contacts (MuJoCo computes no contact).
/// Each step: the pointer (mocap) is put at the device pose of the report; every pair of geoms
/// of different bodies, at least one of which moves, with the pointer's geoms always taking
/// part and the others only if MuJoCo would collide them (GeomInfo::collides), is tested by
/// bounding spheres, then signed distance, then its intersection polyhedron
/// (geometry::IntersectConvex); ContactVolumeForce gives the penalty force, applied to both
/// bodies through World::AddForceAtPoint (the pointer's share is accumulated instead); then the
/// world steps. The snapshot carries the wrench on the pointer (ir::PhysicsSnapshot::
/// pointer_wrench_W, torque about the pointer origin). Known limit: jointed parent/child bodies
/// are not excluded as MuJoCo does. Physics thread only; not RT-safe.
class ContactVolumePhysics final : public MethodPhysics {
 public:
  /// Gains: rendering.stiffness (N/m), damping (N·s/m), friction (μ, static = dynamic).
  /// @throws mrh::SceneError if the world computes its own contacts (loaded without
  /// penalty_contacts) or a geom cannot be made a polyhedron (names the geom).
  explicit ContactVolumePhysics(const MethodContext& context);

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;

  PhaseTimes last_phases() const noexcept override { return phases_; }

  const ContactVolumeStats& stats() const { return stats_; }

 private:
  struct Piece {
    int geom = -1;
    int body = -1;
    bool plane = false;
    double radius = 0.0;  // bounding sphere about the geom origin (m); planes: unused
    geometry::ConvexPolyhedron polyhedron;
    std::unique_ptr<geometry::CollisionShape> shape;
  };

  struct Pair {
    int a = -1;  // index into pieces_ (never a plane)
    int b = -1;  // index into pieces_ (a plane if either is)
    FrictionAnchor anchor;
  };

  void MakePieces(const settings::RenderingSettings& rendering);
  void MakePairs();
  bool Overlap(const Pair& pair) const;
  void Analyse(const Twist& V_WP);
  void AnalysePair(Pair* pair, const Twist& V_WP);
  BodyKinematics Kinematics(int body, const Twist& V_WP) const;
  void Publish(ir::PhysicsSnapshot* out) const;

  world::World* world_;
  int pointer_;
  double physics_dt_;
  PenaltyGains gains_;
  std::vector<Piece> pieces_;
  std::vector<Pair> pairs_;
  std::vector<Pose> X_WG_;  // geom poses of the current analysis (scratch)
  Wrench pointer_wrench_;   // about the pointer origin
  ContactVolumeStats stats_;
  PhaseTimes phases_;
};

}  // namespace mrh::physics::internal
