// SPDX-License-Identifier: Apache-2.0
// Baseline B3 `virtual-coupling`: the haptic half (the coupling spring–damper).
#pragma once

#include "mrh/haptic/method_haptic.h"
#include "mrh/render/virtual_coupling.h"

namespace mrh::haptic::internal {

/// B3, haptic half (RT-safe): the tool's pose and velocity from the newest snapshot (the end of
/// the previous 1 ms step) and the device pose and velocity of the tick give
/// render::CouplingWrench. The tool receives +(F_c, τ_c) during the next step (as a report
/// impulse on the tool body); the device displays −(F_c, τ_c) (TickOutput::w_W). TickOutput::X_WQ
/// is the tool pose. Its physics half is physics::internal::VirtualCouplingPhysics.
class VirtualCouplingHaptic final : public MethodHaptic {
 public:
  explicit VirtualCouplingHaptic(const render::CouplingGains& gains) : gains_(gains) {}

  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

 private:
  render::CouplingGains gains_;
  ir::BodyMotion tool_state_;
  ir::HapticReport period_;
};

}  // namespace mrh::haptic::internal
