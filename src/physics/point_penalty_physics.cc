// SPDX-License-Identifier: Apache-2.0
// Physics half of B1 and B4: the reaction impulse as a force over the step, then the plane IR.
#include "point_penalty_physics.h"

#include "mrh/core/assert.h"
#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::physics::internal {

PointPenaltyPhysics::PointPenaltyPhysics(const MethodContext& context)
    : world_(context.world),
      pointer_body_(context.pointer_body),
      physics_dt_(context.settings->physics_dt) {
  builder_.emplace(*world_, pointer_body_, PointerRadiusFor3Dof(context),
                   context.settings->rendering);
  builders_.reserve(context.pointers.size());
  for (const PointerContext& pointer : context.pointers) {
    pointer_bodies_.push_back(pointer.body);
    builders_.emplace_back(*world_, pointer.body, pointer.radius, *pointer.rendering);
  }
}

void PointPenaltyPhysics::PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) {
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

namespace mrh::physics::internal {

void PointPenaltyPhysics::PhysicsStartPointers(std::span<const ir::HapticReport* const> initial,
                                               std::span<ir::PhysicsSnapshot* const> out) {
  MRH_DEMAND(initial.size() == builders_.size() && out.size() == builders_.size());
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    world_->SetMocapPose(pointer_bodies_[i], initial[i]->X_WP);
  }
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    builders_[i].CapturePreviousPoses(*world_);
    builders_[i].Build(*world_, initial[i]->X_WP, out[i]);
    out[i]->step = -1;
    out[i]->t = world_->time();
    out[i]->physics_dt = physics_dt_;
  }
}

// One world step for all pointers: an object two pointers push receives both reactions in the
// same step (the impulses add up in the world's applied forces).
void PointPenaltyPhysics::PhysicsStepPointers(std::span<const ir::HapticReport* const> reports,
                                              std::span<ir::PhysicsSnapshot* const> out) {
  MRH_DEMAND(reports.size() == builders_.size() && out.size() == builders_.size());
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    ApplyReportImpulses(*world_, *reports[i], physics_dt_);
    world_->SetMocapPose(pointer_bodies_[i], reports[i]->X_WP);
  }
  for (PointIrBuilder& builder : builders_) builder.CapturePreviousPoses(*world_);
  auto t0 = std::chrono::steady_clock::now();
  world_->Step();
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    builders_[i].Build(*world_, reports[i]->X_WP, out[i]);
    out[i]->t = world_->time();
    out[i]->physics_dt = physics_dt_;
  }
  phases_.ir_ms = MsSince(t0);
}

}  // namespace mrh::physics::internal
