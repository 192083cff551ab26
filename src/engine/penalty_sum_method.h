// SPDX-License-Identifier: Apache-2.0
// Baseline B5 `penalty-sum`: proxy-6dof's geometric IR, rendered as a sum of per-contact springs.
#pragma once

#include <memory>
#include <optional>

#include "geometric_ir_builder.h"
#include "mrh/engine/method.h"
#include "mrh/render/ir_interpolator.h"
#include "mrh/render/penalty_sum.h"
#include "mrh/render/tick_ir.h"

namespace mrh::engine::internal {

/// B5 (Berkelman & Hollis 2000, SPEC §1.4), registered as "penalty-sum".
///
/// Physics half: exactly proxy-6dof's (ProxyMethod): the previous period's reaction impulses
/// J act as the constant wrench J/Δt^G over the step, the world steps, and GeometricIrBuilder
/// builds the geometric IR (planes + pointer contact points) for the report's pointer pose.
///
/// Haptic half (RT-safe): the IR interpolated with α = min(1, (j+1)/n) as proxy-6dof does, then
/// render::PenaltySumRenderer with k = rendering.stiffness, d = rendering.damping: the wrench
/// Σᵢ (kδᵢ + dδ̇ᵢ) nᵢ with torque Σᵢ rᵢ × fᵢ about the pointer origin. There is no proxy
/// (TickOutput::X_WQ stays the pointer pose) and no friction. The per-pair reactions are summed
/// into impulses for the next physics step, as proxy-6dof's.
class PenaltySumMethod final : public Method {
 public:
  /// @throws mrh::InvalidArgument for a negative stiffness/damping, mrh::SceneError from
  /// GeometricIrBuilder (a pointer without convex geoms). Not RT-safe.
  explicit PenaltySumMethod(const MethodContext& context);

  const char* name() const noexcept override { return "penalty-sum"; }

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;
  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

  /// Haptic side: the last tick's output and the IR it rendered. Valid until the next tick.
  const render::PenaltySumOutput& last_output() const noexcept { return output_; }
  const render::TickIr& last_tick_ir() const noexcept { return tick_ir_; }

 private:
  void Build(const Pose& X_WP, ir::PhysicsSnapshot* out);

  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  std::optional<GeometricIrBuilder> builder_;

  render::IrInterpolator interpolator_;
  render::PenaltySumRenderer renderer_;
  render::TickIr tick_ir_;
  render::PenaltySumOutput output_;
  ir::HapticReport period_;
};

/// Factory registered as "penalty-sum".
std::unique_ptr<Method> MakePenaltySumMethod(const MethodContext& context);

}  // namespace mrh::engine::internal
