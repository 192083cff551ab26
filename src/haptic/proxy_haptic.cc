// SPDX-License-Identifier: Apache-2.0
// Haptic half of the chapter-3 method: the 6-DOF proxy rendered per tick against the IR.
#include "proxy_haptic.h"

#include <algorithm>

namespace mrh::haptic::internal {

void ProxyHaptic::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  interpolator_.Adopt(snapshot);
}

void ProxyHaptic::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  const double alpha = in.alpha();
  interpolator_.Evaluate(alpha, in.X_WP, &tick_ir_);
  renderer_.Tick(tick_ir_, in.X_WP, in.dt, &output_);
  out->w_W = output_.w_W;
  out->X_WQ = output_.X_WQ;
  out->contacts = output_.diagnostics.contacts;
  out->status = output_.diagnostics.status;
  render::AddReactionImpulses(output_, in.dt, &period_);
  render::TouchPairs(tick_ir_, in.X_WP, in.V_WP, &transients_);
  render::AddTransientForce(in.dt, &transients_, &out->w_W.f);
}

void ProxyHaptic::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses = period_.impulses;
  report->status |= period_.status;
  period_.impulses.Clear();
  period_.status = ir::kStatusOk;
}

}  // namespace mrh::haptic::internal
