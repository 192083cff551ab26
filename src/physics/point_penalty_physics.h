// SPDX-License-Identifier: Apache-2.0
// Baselines B1 (single-rate) and B4 (impulse-sending multi-rate) with 3-DOF penalty rendering.
#pragma once

#include <array>
#include <memory>
#include <optional>

#include "mrh/engine/method.h"
#include "normal_carry.h"
#include "point_ir_builder.h"

namespace mrh::engine::internal {

/// The conventional multi-rate method (SPEC B4) and, with n = 1, the single-rate baseline (B1).
/// Physics half: applies the previous period's reaction impulse J as the constant force J/Δt^G
/// over the step, steps the world, then builds the plane IR of every neighbor. Haptic half:
/// renders corrected eq. 4.11 against object poses blended from one step behind to the newest
/// (α = min(1, (j+1)/n)), normals blended likewise, and sums the reaction −f_d into impulses.
class PointPenaltyMethod final : public Method {
 public:
  PointPenaltyMethod(const MethodContext& context, bool single_rate);

  const char* name() const noexcept override {
    return single_rate_ ? "single-rate" : "impulse";
  }
  bool single_rate() const noexcept override { return single_rate_; }

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;
  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

 private:
  // Physics half.
  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  std::optional<PointIrBuilder> builder_;

  // Haptic half.
  bool single_rate_;
  double radius_;
  double stiffness_;
  double damping_;
  ir::PhysicsSnapshot snapshot_;
  ContactNormals previous_n_{};
  ContactNormals rendered_n_{};
  std::array<Vec3, ir::kMaxNeighborBodies> tick_force_{};
  std::array<Vec3, ir::kMaxNeighborBodies> tick_torque_{};
  ir::HapticReport period_;
};

/// Factories registered as "single-rate" and "impulse".
std::unique_ptr<Method> MakeSingleRateMethod(const MethodContext& context);
std::unique_ptr<Method> MakeImpulseMethod(const MethodContext& context);

}  // namespace mrh::engine::internal
