// SPDX-License-Identifier: Apache-2.0
// Baseline B3, haptic half: the spring–damper between the device and the dynamic tool.
#include "virtual_coupling_haptic.h"

#include "mrh/haptic/methods.h"

namespace mrh::haptic::internal {

void VirtualCouplingHaptic::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  if (!snapshot.bodies.empty()) tool_state_ = snapshot.bodies[0];
}

void VirtualCouplingHaptic::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  if (tool_state_.body < 0) {  // no snapshot adopted yet: no tool to couple to
    out->w_W = Wrench{};
    out->contacts = 0;
    return;
  }
  const Pose& X_Wt = tool_state_.X_WB;
  // Velocity of the tool's origin from its COM twist.
  const Vec3 r_CmO = X_Wt.p - X_Wt * tool_state_.p_BCm;
  const Twist V_Wt{tool_state_.V_WCm.v + tool_state_.V_WCm.w.cross(r_CmO), tool_state_.V_WCm.w};
  const Wrench c = render::CouplingWrench(in.X_WP, in.V_WP, X_Wt, V_Wt, gains_);
  if (!c.f.allFinite() || !c.tau.allFinite()) {
    out->w_W = Wrench{};
    out->status = kVirtualCouplingBadInput;
    return;
  }
  out->w_W = Wrench{-c.f, -c.tau};
  out->X_WQ = X_Wt;
  out->contacts = 0;
  // On the tool during the next step: the force at its origin, the moment about its COM.
  const Vec3 angular = c.tau + (-r_CmO).cross(c.f);
  period_.AddImpulse(tool_state_.body, c.f * in.dt, angular * in.dt, c.f);
}

void VirtualCouplingHaptic::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses = period_.impulses;
  period_.impulses.Clear();
}

}  // namespace mrh::haptic::internal
