// SPDX-License-Identifier: Apache-2.0
// Baseline B3, physics half: the dynamic tool stepped at the haptic rate under the coupling.
#include "virtual_coupling_physics.h"

#include <fmt/format.h>

#include <chrono>

#include "mrh/core/error.h"
#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::physics::internal {

VirtualCouplingPhysics::VirtualCouplingPhysics(const MethodContext& context)
    : world_(context.world),
      tool_(context.pointer_body),
      physics_dt_(context.settings->physics_dt) {
  const world::BodyInfo& info = world_->body(tool_);
  if (info.is_static || info.is_mocap) {
    throw SceneError(fmt::format(
        "pointer body '{}' is not a free body; virtual-coupling needs the world loaded with "
        "world::LoadOptions::dynamic_pointer (session::LoadWorld does this for method "
        "\"virtual-coupling\")",
        info.name));
  }
}

void VirtualCouplingPhysics::Publish(ir::PhysicsSnapshot* out) const {
  const world::BodyState state = world_->body_state(tool_);
  ir::BodyMotion m;
  m.body = tool_;
  m.X_WB_prev = state.X_WB;
  m.X_WB = state.X_WB;
  m.p_BCm = world_->body(tool_).p_BCm;
  m.V_WCm = state.V_WCm;
  out->bodies.Clear();
  (void)out->bodies.PushBack(m);
  out->contacts.Clear();
  out->pairs.Clear();
  out->points.Clear();
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

void VirtualCouplingPhysics::PhysicsStart(const ir::HapticReport& initial,
                                         ir::PhysicsSnapshot* out) {
  // The tool starts at the device pose, at rest.
  (void)world_->SetBodyState(tool_, initial.X_WP, Twist{});
  Publish(out);
  out->step = -1;
}

void VirtualCouplingPhysics::PhysicsStep(const ir::HapticReport& report,
                                        ir::PhysicsSnapshot* out) {
  ApplyReportImpulses(*world_, report, physics_dt_, tool_);
  const double mass = world_->body(tool_).mass;
  world_->AddWrenchAtCom(tool_, Wrench{-mass * world_->gravity(), Vec3::Zero()});
  const auto t0 = std::chrono::steady_clock::now();
  world_->Step();
  phases_.world_step_ms = MsSince(t0);
  Publish(out);
}

}  // namespace mrh::physics::internal
