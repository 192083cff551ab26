// SPDX-License-Identifier: Apache-2.0
// Baseline B5, haptic half: per-contact penalty springs on the interpolated geometric IR.
#include "penalty_sum_haptic.h"

namespace mrh::haptic::internal {

void PenaltySumHaptic::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  interpolator_.Adopt(snapshot);
}

void PenaltySumHaptic::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  interpolator_.Evaluate(in.alpha(), in.X_WP, &tick_ir_);
  renderer_.Tick(tick_ir_, in.X_WP, in.dt, &output_);
  out->w_W = output_.w_W;
  out->contacts = output_.contacts;
  out->status = output_.status;
  render::TouchPairs(tick_ir_, in.X_WP, in.V_WP, &transients_);
  render::AddTransientForce(in.dt, &transients_, &out->w_W.f);
  render::AddReactionImpulses(output_.reactions, in.dt, &period_);
}

void PenaltySumHaptic::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses = period_.impulses;
  report->status |= period_.status;
  period_.impulses.Clear();
  period_.status = ir::kStatusOk;
}

}  // namespace mrh::haptic::internal
