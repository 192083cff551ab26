// SPDX-License-Identifier: Apache-2.0
// Baseline B5 `penalty-sum`: the haptic half (per-contact penalty springs on the geometric IR).
#pragma once

#include "mrh/haptic/method_haptic.h"
#include "mrh/render/contact_transients.h"
#include "mrh/render/ir_interpolator.h"
#include "mrh/render/penalty_sum.h"

namespace mrh::haptic::internal {

/// B5 (Berkelman & Hollis 2000, thesis ref. [43], §3.1.1), haptic half (RT-safe): the geometric IR
/// interpolated with α as proxy-6dof does, then render::PenaltySumRenderer: the wrench
/// Σᵢ (kδᵢ + dδ̇ᵢ) nᵢ with torque Σᵢ rᵢ × fᵢ about the pointer origin. There is no proxy
/// (TickOutput::X_WQ stays the pointer pose) and no friction. The per-pair reactions are summed
/// into impulses for the next physics step. Its physics half is proxy-6dof's
/// (physics::MakeProxyPhysics): the reaction one step late, then the geometric IR.
class PenaltySumHaptic final : public MethodHaptic {
 public:
  explicit PenaltySumHaptic(const render::PenaltySumSettings& settings) : renderer_(settings) {}

  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

  /// The last tick's output and the IR it rendered. Valid until the next tick.
  const render::PenaltySumOutput& last_output() const noexcept { return output_; }

  const render::TickIr& last_tick_ir() const noexcept { return tick_ir_; }

 private:
  render::IrInterpolator interpolator_;
  render::PenaltySumRenderer renderer_;
  render::TickIr tick_ir_;
  render::PenaltySumOutput output_;
  ir::HapticReport period_;
  // Material vibration at contact onset, added to the rendered force.
  render::ContactTransients transients_;
};

}  // namespace mrh::haptic::internal
