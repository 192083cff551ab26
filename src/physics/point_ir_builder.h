// SPDX-License-Identifier: Apache-2.0
// Physics side of 3-DOF rendering: neighbor search and Adachi plane IR for a sphere pointer.
#pragma once

#include <vector>

#include "body_motions.h"
#include "material_table.h"
#include "mrh/geometry/distance.h"
#include "mrh/ir/snapshot.h"
#include "mrh/settings/settings.h"

namespace mrh::world {
class World;
}

namespace mrh::physics::internal {

using settings::RenderingSettings;

/// Builds PhysicsSnapshot bodies and point contacts for a sphere pointer (thesis §4.2.1): a
/// bounding sphere broad phase inflated by `neighbor_margin`, then an FCL signed-distance narrow
/// phase; geoms within `neighbor_distance` get a plane through the object's witness point. Owns the
/// prepared collision shapes. Physics thread only; not RT-safe.
class PointIrBuilder {
 public:
  /// @throws mrh::SceneError if a collidable geom cannot be represented.
  PointIrBuilder(const world::World& world, int pointer_body, double radius,
                 const settings::RenderingSettings& rendering);

  /// Remembers every body's pose before a step (the interpolation start).
  void CapturePreviousPoses(const world::World& world);

  /// Fills out->bodies and out->contacts for the pointer at X_WP (world). Bodies keep the poses
  /// captured by CapturePreviousPoses as X_WB_prev.
  void Build(const world::World& world, const Pose& X_WP, ir::PhysicsSnapshot* out) const;

 private:
  struct Candidate {
    int geom;
    geometry::CollisionShape shape;
    double bounding_radius;
  };

  int pointer_body_;
  double radius_;
  settings::RenderingSettings rendering_;
  MaterialTable materials_;
  geometry::CollisionShape pointer_shape_;
  std::vector<Candidate> candidates_;
  BodyMotions motions_;
};

}  // namespace mrh::physics::internal
