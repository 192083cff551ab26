// SPDX-License-Identifier: Apache-2.0
// Physics half of B1 and B4: the reaction impulse as a force over the step, then the plane IR.
#include "point_penalty_physics.h"

#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::physics::internal {

PointPenaltyPhysics::PointPenaltyPhysics(const MethodContext& context)
    : world_(context.world),
      pointer_body_(context.pointer_body),
      physics_dt_(context.settings->physics_dt) {
  builder_.emplace(*world_, pointer_body_, PointerRadiusFor3Dof(context), context.settings->rendering);
}

void PointPenaltyPhysics::PhysicsStart(const ir::HapticReport& initial,
                                       ir::PhysicsSnapshot* out) {
  world_->SetMocapPose(pointer_body_, initial.X_WP);
  builder_->CapturePreviousPoses(*world_);
  builder_->Build(*world_, initial.X_WP, out);
  out->step = -1;
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

void PointPenaltyPhysics::PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) {
  // B4: the impulse of the last haptic period acts as a constant force over this whole step.
  ApplyReportImpulses(*world_, report, physics_dt_);
  world_->SetMocapPose(pointer_body_, report.X_WP);
  builder_->CapturePreviousPoses(*world_);
  auto t0 = std::chrono::steady_clock::now();
  world_->Step();
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  builder_->Build(*world_, report.X_WP, out);
  phases_.ir_ms = MsSince(t0);
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

}  // namespace mrh::physics::internal
