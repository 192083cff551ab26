// SPDX-License-Identifier: Apache-2.0
// The chapter-3 method `proxy-6dof`: geometric IR on the physics side, 6-DOF proxy at 1 kHz.
#pragma once

#include <memory>
#include <optional>

#include "geometric_ir_builder.h"
#include "mrh/engine/method.h"
#include "mrh/render/ir_interpolator.h"
#include "mrh/render/proxy_renderer.h"
#include "mrh/render/tick_ir.h"

namespace mrh::engine::internal {

/// The rotation weight R_w (m², world frame) the method uses for `rendering` (SPEC §3.10):
/// diag(rendering.rotation_weight) when given, else rotation_weight_scale × the pointer's
/// unit-mass inertia about its body origin, I_O/m = I_Cm/m + |c|²·1 − c cᵀ (c = p_BCm), in the
/// pointer's body axes taken as world axes.
///
/// Why these choices: the renderer's R_w is one constant world-frame matrix and the lever arms
/// r_i are measured from the pointer origin X_WP.p, so the weight that matches its translation
/// weight of 1 is the unit-mass inertia block about that origin; the body axes are used as if the
/// pointer were at its reference orientation (identity), which is exact for an isotropic pointer
/// (the T3.1 cube) and for a pointer held near its reference orientation (the T3.2 stick).
/// @throws mrh::SceneError if the pointer body has no mass (nothing to take an inertia from).
/// @throws mrh::InvalidArgument if its inertia is not positive definite. Not RT-safe.
Mat3 PointerRotationWeight(const world::World& world, int pointer_body,
                           const RenderingSettings& rendering);

/// The proxy renderer's settings for an engine configuration: k_t = stiffness,
/// d_t = damping, k_r = rot_stiffness, d_r = rot_damping, R_w = PointerRotationWeight,
/// μ = friction, max_iterations, tolerance = solver_tolerance.
/// @throws mrh::InvalidArgument naming the session key (rendering.max_iterations above
/// render::kMaxProxyIterations) and the errors of PointerRotationWeight. Not RT-safe.
render::ProxyRendererSettings ProxySettingsFor(const world::World& world, int pointer_body,
                                               const RenderingSettings& rendering);

/// The chapter-3 method (SPEC §3.1–3.11), registered as "proxy-6dof".
///
/// Physics half (PhysicsStep k): applies the reaction impulses J of haptic period k−1 as the
/// constant wrench J/Δt^G about each body's COM over this step (SPEC §3.6, I5: the reaction
/// arrives one physics step late, as in the thesis), remembers the poses before the step, steps
/// the world, and builds the geometric IR for the pointer pose of the report
/// (GeometricIrBuilder). PhysicsStart builds from the initial state without stepping.
///
/// Haptic half (HapticTick, RT-safe): α = min(1, (j+1)/n) (docs/architecture.md: the last tick
/// of a period renders the newest poses), IrInterpolator::Evaluate at the device pose,
/// ProxyRenderer::Tick, and the per-row reactions summed into per-body impulses
/// (render::AddReactionImpulses) for EndPeriod. TickOutput::w_W is the proxy wrench (world
/// frame, torque about the pointer origin); TickOutput::contacts counts the penetrating points
/// (normal rows); TickOutput::status carries render::ProxyStatusBits. The haptic half never
/// touches the world.
class ProxyMethod final : public Method {
 public:
  /// @throws as ProxySettingsFor, and mrh::SceneError from GeometricIrBuilder (a pointer
  /// without convex geoms). Not RT-safe.
  explicit ProxyMethod(const MethodContext& context);

  const char* name() const noexcept override { return "proxy-6dof"; }

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;
  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

  /// Haptic side, for experiments and tests on the haptic thread (or after a lockstep tick):
  /// the last tick's renderer output (proxy pose, Δr, Δθ, rows, multipliers, diagnostics) and
  /// the IR it rendered. Valid until the next HapticTick.
  const render::ProxyOutput& last_output() const noexcept { return output_; }

  const render::TickIr& last_tick_ir() const noexcept { return tick_ir_; }

  /// The renderer settings in use (R_w included).
  const render::ProxyRendererSettings& renderer_settings() const noexcept {
    return renderer_.settings();
  }

  /// Physics side: the work of the last IR build.
  const GeometricIrStats& ir_stats() const { return builder_->stats(); }

 private:
  void Build(const Pose& X_WP, ir::PhysicsSnapshot* out);

  // Physics half.
  world::World* world_;
  int pointer_body_;
  double physics_dt_;
  std::optional<GeometricIrBuilder> builder_;

  // Haptic half: all buffers sized here, at construction.
  render::IrInterpolator interpolator_;
  render::ProxyRenderer renderer_;
  render::TickIr tick_ir_;
  render::ProxyOutput output_;
  ir::HapticReport period_;
};

/// Factory registered as "proxy-6dof".
std::unique_ptr<Method> MakeProxyMethod(const MethodContext& context);

}  // namespace mrh::engine::internal
