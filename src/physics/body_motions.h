// SPDX-License-Identifier: Apache-2.0
// The bodies of a physics snapshot: each touched body's pose before and after the step.
#pragma once

#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/ir/snapshot.h"

namespace mrh::world {
class World;
}

namespace mrh::physics::internal {

/// Remembers every body's pose before a physics step (the start of the haptic side's
/// interpolation) and adds ir::BodyMotion entries to snapshots. Shared by the point and the
/// geometric IR builders. Physics thread only; not RT-safe.
class BodyMotions {
 public:
  /// Sizes the table for the world's bodies and captures their current poses.
  explicit BodyMotions(const world::World& world);

  /// Remembers every body's pose (call before World::Step).
  void CapturePreviousPoses(const world::World& world);

  /// Index of `body` in out->bodies, adding it (previous pose, current pose and twist) if it is
  /// not there yet; -1 with ir::kStatusBodiesFull set if the snapshot is full.
  int Add(const world::World& world, int body, ir::PhysicsSnapshot* out) const;

 private:
  std::vector<Pose> previous_X_WB_;
};

}  // namespace mrh::physics::internal
