// SPDX-License-Identifier: Apache-2.0
// Physics half of baselines B1 (single-rate) and B4 (impulse-sending multi-rate).
#pragma once

#include <optional>
#include <vector>

#include "mrh/physics/method_physics.h"
#include "point_ir_builder.h"

namespace mrh::physics::internal {

/// The physics half of the conventional multi-rate method (B4: Hasegawa et al. 1999, thesis
/// ref. [35], §4.5) and, with n = 1, of the
/// single-rate baseline (B1): applies the previous period's reaction impulse J as the constant
/// force J/Δt^G over the step, steps the world, then builds the plane IR of every neighbor.
/// Its haptic half is haptic::internal::PointPenaltyHaptic.
class PointPenaltyPhysics final : public MethodPhysics {
 public:
  explicit PointPenaltyPhysics(const MethodContext& context);

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;
  /// Several pointers (MethodContext::pointers): every pointer's reaction is applied, every
  /// pointer's mocap body moved, the world stepped once, and each pointer gets its own plane IR.
  void PhysicsStartPointers(std::span<const ir::HapticReport* const> initial,
                            std::span<ir::PhysicsSnapshot* const> out) override;
  void PhysicsStepPointers(std::span<const ir::HapticReport* const> reports,
                           std::span<ir::PhysicsSnapshot* const> out) override;

  PhaseTimes last_phases() const noexcept override { return phases_; }

 private:
  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  PhaseTimes phases_;
  std::optional<PointIrBuilder> builder_;
  std::vector<int> pointer_bodies_;       ///< several pointers only
  std::vector<PointIrBuilder> builders_;  ///< one per pointer (several pointers only)
};

}  // namespace mrh::physics::internal
