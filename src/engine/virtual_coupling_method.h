// SPDX-License-Identifier: Apache-2.0
// Baseline B3 `virtual-coupling` (Colgate et al. 1995): the pointer is a dynamic tool inside
// MuJoCo, joined to the device pose by a spring–damper, stepped at the haptic rate.
#pragma once

#include <memory>

#include "mrh/engine/method.h"

namespace mrh::engine::internal {

/// The coupling wrench of SPEC §1.4 B3 acting on the tool, world frame:
/// F_c = k (x_h − x_t) + b (v_h − v_t) at the tool origin, τ_c = k_r φ + b_r (ω_h − ω_t) with φ the
/// rotation vector of q_h q_t⁻¹. Poses are body-origin poses, v_t the tool origin's velocity.
/// RT-safe.
Wrench CouplingWrench(const Pose& X_Wh, const Twist& V_Wh, const Pose& X_Wt, const Twist& V_Wt,
                      const RenderingSettings& r) noexcept;

/// B3, registered as "virtual-coupling"; single-rate (physics_dt = haptic_dt).
///
/// The scene's pointer body is loaded as a free body (session::LoadWorld sets
/// world::LoadOptions::dynamic_pointer for this method): its geoms collide inside MuJoCo, its
/// mass and inertia come from the MJCF or rendering.tool_mass / tool_inertia. Its weight is
/// compensated (−m_t g on its COM each step), so the user feels the tool's inertia, not its weight.
///
/// Haptic half (RT-safe): the tool's pose and velocity from the newest snapshot (the end of the
/// previous 1 ms step), the device pose and velocity of the tick → CouplingWrench. The tool
/// receives +(F_c, τ_c) during the next step (as a report impulse on the tool body); the device
/// displays −(F_c, τ_c) (TickOutput::w_W, torque about the tool origin). TickOutput::X_WQ is the
/// tool pose. Physics half: applies the impulse and the weight compensation, steps, and
/// publishes the tool as the snapshot's only body.
class VirtualCouplingMethod final : public Method {
 public:
  /// @throws mrh::SceneError if the pointer body is not a free body (the world was loaded
  /// without LoadOptions::dynamic_pointer). Not RT-safe.
  explicit VirtualCouplingMethod(const MethodContext& context);

  const char* name() const noexcept override { return "virtual-coupling"; }
  bool single_rate() const noexcept override { return true; }

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;
  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

 private:
  void Publish(ir::PhysicsSnapshot* out) const;

  world::World* world_;
  int tool_;
  double physics_dt_;
  RenderingSettings rendering_;
  // Haptic half.
  ir::BodyMotion tool_state_;
  ir::HapticReport period_;
};

std::unique_ptr<Method> MakeVirtualCouplingMethod(const MethodContext& context);

}  // namespace mrh::engine::internal
