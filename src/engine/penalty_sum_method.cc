// SPDX-License-Identifier: Apache-2.0
// Baseline B5: proxy-6dof's physics half, per-contact penalty springs on the haptic side.
#include "penalty_sum_method.h"

#include <algorithm>

#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::engine::internal {

PenaltySumMethod::PenaltySumMethod(const MethodContext& context)
    : world_(context.world),
      pointer_body_(context.pointer_body),
      physics_dt_(context.settings->physics_dt),
      renderer_(render::PenaltySumSettings{.k = context.settings->rendering.stiffness,
                                           .d = context.settings->rendering.damping}) {
  builder_.emplace(*world_, pointer_body_, context.settings->rendering);
}

void PenaltySumMethod::Build(const Pose& X_WP, ir::PhysicsSnapshot* out) {
  builder_->Build(*world_, X_WP, out);
  out->contacts.Clear();  // the 3-DOF plane IR is not used by this method
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

void PenaltySumMethod::PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) {
  world_->SetMocapPose(pointer_body_, initial.X_WP);
  builder_->CapturePreviousPoses(*world_);
  Build(initial.X_WP, out);
  out->step = -1;
}

void PenaltySumMethod::PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) {
  ApplyReportImpulses(*world_, report, physics_dt_);  // one step late, as proxy-6dof
  world_->SetMocapPose(pointer_body_, report.X_WP);
  builder_->CapturePreviousPoses(*world_);
  world_->Step();
  Build(report.X_WP, out);
}

void PenaltySumMethod::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  interpolator_.Adopt(snapshot);
}

void PenaltySumMethod::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  const double alpha =
      std::min(1.0, static_cast<double>(in.j + 1) / static_cast<double>(std::max(in.n, 1)));
  interpolator_.Evaluate(alpha, in.X_WP, &tick_ir_);
  renderer_.Tick(tick_ir_, in.X_WP, in.dt, &output_);
  out->w_W = output_.w_W;
  out->contacts = output_.contacts;
  out->status = output_.status;
  render::AddReactionImpulses(output_.reactions, in.dt, &period_);
}

void PenaltySumMethod::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses = period_.impulses;
  report->status |= period_.status;
  period_.impulses.Clear();
  period_.status = ir::kStatusOk;
}

std::unique_ptr<Method> MakePenaltySumMethod(const MethodContext& context) {
  return std::make_unique<PenaltySumMethod>(context);
}

}  // namespace mrh::engine::internal
