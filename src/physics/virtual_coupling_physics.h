// SPDX-License-Identifier: Apache-2.0
// Baseline B3 `virtual-coupling`: the physics half (the tool as a dynamic body in MuJoCo).
#pragma once

#include <string>

#include "mrh/physics/method_physics.h"
#include "mrh/render/virtual_coupling.h"
#include "mrh/settings/settings.h"
#include "mrh/world/world.h"

namespace mrh::physics::internal {

/// B3 (Colgate et al. 1995), physics half; single-rate (physics_dt = haptic_dt).
///
/// The scene's pointer body is loaded as a free body (session::LoadWorld sets
/// world::LoadOptions::dynamic_pointer for this method): its geoms collide inside MuJoCo, its
/// mass and inertia come from the MJCF or rendering.tool_mass / tool_inertia. Each step applies
/// the coupling impulse the haptic half reported on the tool and the tool's weight compensation
/// (−m_t g on its COM, so the user feels the tool's inertia, not its weight), steps, and
/// publishes the tool as the snapshot's only body. Its haptic half is
/// haptic::internal::VirtualCouplingHaptic.
/// Refuses coupling gains under which the free tool's motion grows (render::CouplingGrowthPerTick,
/// translation with the tool's mass, rotation about its weakest principal axis) at haptic period
/// h (s). @throws mrh::InvalidArgument naming the scene (`origin`), the keys, their values and
/// a stable pair of gains.
void CheckCouplingStable(const world::BodyInfo& tool, const render::CouplingGains& g, double h,
                         const std::string& origin);

/// rendering.coupling_* with unset rotational gains derived from the tool (see
/// physics::ResolveCouplingGains). Not RT-safe.
render::CouplingGains ResolveCouplingGains(const world::BodyInfo& tool,
                                           const settings::RenderingSettings& r);

class VirtualCouplingPhysics final : public MethodPhysics {
 public:
  /// @throws mrh::SceneError if the pointer body is not a free body (the world was loaded
  /// without LoadOptions::dynamic_pointer); mrh::InvalidArgument for unstable coupling gains
  /// (CheckCouplingStable). Not RT-safe.
  explicit VirtualCouplingPhysics(const MethodContext& context);

  void PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) override;
  void PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) override;

  PhaseTimes last_phases() const noexcept override { return phases_; }

 private:
  void Publish(ir::PhysicsSnapshot* out) const;

  world::World* world_;
  int tool_;
  double physics_dt_;
  PhaseTimes phases_;
};

}  // namespace mrh::physics::internal
