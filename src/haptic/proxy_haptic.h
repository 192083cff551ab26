// SPDX-License-Identifier: Apache-2.0
// Haptic half of the chapter-3 method `proxy-6dof`: the 6-DOF proxy at 1 kHz.
#pragma once

#include "mrh/haptic/method_haptic.h"
#include "mrh/render/contact_transients.h"
#include "mrh/render/ir_interpolator.h"
#include "mrh/render/proxy_renderer.h"
#include "mrh/render/tick_ir.h"

namespace mrh::haptic::internal {

/// The haptic half of proxy-6dof (thesis §3.2.2–3.2.4, eq. 3.1–3.10; docs/theory.md).
/// HapticTick (RT-safe): α = min(1, (j+1)/n)
/// (docs/architecture.md: the last tick of a period renders the newest poses),
/// IrInterpolator::Evaluate at the device pose, ProxyRenderer::Tick, and the per-row reactions
/// summed into per-body impulses (render::AddReactionImpulses) for EndPeriod. TickOutput::w_W is
/// the proxy wrench (world frame, torque about the pointer origin); TickOutput::contacts counts
/// the penetrating points (normal rows); TickOutput::status carries render::ProxyStatusBits.
/// Its physics half is physics::internal::ProxyPhysics.
class ProxyHaptic final : public MethodHaptic {
 public:
  /// All buffers are sized here. Not RT-safe.
  explicit ProxyHaptic(const render::ProxyRendererSettings& settings) : renderer_(settings) {}

  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

  /// For tests on the haptic thread (or after a lockstep tick): the last tick's renderer output
  /// (proxy pose, Δr, Δθ, rows, multipliers, diagnostics) and the IR it rendered. Valid until
  /// the next HapticTick.
  const render::ProxyOutput& last_output() const noexcept { return output_; }

  const render::TickIr& last_tick_ir() const noexcept { return tick_ir_; }

  /// The renderer settings in use (R_w included).
  const render::ProxyRendererSettings& renderer_settings() const noexcept {
    return renderer_.settings();
  }

 private:
  render::IrInterpolator interpolator_;
  render::ProxyRenderer renderer_;
  render::TickIr tick_ir_;
  render::ProxyOutput output_;
  ir::HapticReport period_;
  // Material vibration at contact onset, added to the rendered force.
  render::ContactTransients transients_;
};

}  // namespace mrh::haptic::internal
