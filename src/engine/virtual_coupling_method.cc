// SPDX-License-Identifier: Apache-2.0
// Baseline B3: virtual coupling of the device to a dynamic tool simulated at the haptic rate.
#include "virtual_coupling_method.h"

#include <fmt/format.h>

#include "mrh/core/error.h"
#include "mrh/render/proxy_renderer.h"
#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::engine::internal {

Wrench CouplingWrench(const Pose& X_Wh, const Twist& V_Wh, const Pose& X_Wt, const Twist& V_Wt,
                      const RenderingSettings& r) noexcept {
  Wrench w;
  w.f = r.coupling_stiffness * (X_Wh.p - X_Wt.p) + r.coupling_damping * (V_Wh.v - V_Wt.v);
  const Vec3 phi = RotationVectorFromQuat(X_Wh.q * X_Wt.q.conjugate());
  w.tau = r.coupling_rot_stiffness * phi + r.coupling_rot_damping * (V_Wh.w - V_Wt.w);
  return w;
}

VirtualCouplingMethod::VirtualCouplingMethod(const MethodContext& context)
    : world_(context.world),
      tool_(context.pointer_body),
      physics_dt_(context.settings->physics_dt),
      rendering_(context.settings->rendering) {
  const world::BodyInfo& info = world_->body(tool_);
  if (info.is_static || info.is_mocap) {
    throw SceneError(fmt::format(
        "pointer body '{}' is not a free body; virtual-coupling needs the world loaded with "
        "world::LoadOptions::dynamic_pointer (session::LoadWorld does this for method "
        "\"virtual-coupling\")",
        info.name));
  }
}

void VirtualCouplingMethod::Publish(ir::PhysicsSnapshot* out) const {
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

void VirtualCouplingMethod::PhysicsStart(const ir::HapticReport& initial,
                                         ir::PhysicsSnapshot* out) {
  // The tool starts at the device pose, at rest.
  (void)world_->SetBodyState(tool_, initial.X_WP, Twist{});
  Publish(out);
  out->step = -1;
}

void VirtualCouplingMethod::PhysicsStep(const ir::HapticReport& report,
                                        ir::PhysicsSnapshot* out) {
  ApplyReportImpulses(*world_, report, physics_dt_, tool_);
  const double mass = world_->body(tool_).mass;
  world_->AddWrenchAtCom(tool_, Wrench{-mass * world_->gravity(), Vec3::Zero()});
  world_->Step();
  Publish(out);
}

void VirtualCouplingMethod::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  if (!snapshot.bodies.empty()) tool_state_ = snapshot.bodies[0];
}

void VirtualCouplingMethod::HapticTick(const TickInput& in, TickOutput* out) noexcept {
  const Pose& X_Wt = tool_state_.X_WB;
  // Velocity of the tool's origin from its COM twist.
  const Vec3 r_CmO = X_Wt.p - X_Wt * tool_state_.p_BCm;
  const Twist V_Wt{tool_state_.V_WCm.v + tool_state_.V_WCm.w.cross(r_CmO), tool_state_.V_WCm.w};
  const Wrench c = CouplingWrench(in.X_WP, in.V_WP, X_Wt, V_Wt, rendering_);
  if (!c.f.allFinite() || !c.tau.allFinite()) {
    out->w_W = Wrench{};
    out->status = render::kProxyStatusBadInput;
    return;
  }
  out->w_W = Wrench{-c.f, -c.tau};
  out->X_WQ = X_Wt;
  out->contacts = 0;
  // On the tool during the next step: the force at its origin, the moment about its COM.
  const Vec3 angular = c.tau + (-r_CmO).cross(c.f);
  period_.AddImpulse(tool_, c.f * in.dt, angular * in.dt, c.f);
}

void VirtualCouplingMethod::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses = period_.impulses;
  period_.impulses.Clear();
}

std::unique_ptr<Method> MakeVirtualCouplingMethod(const MethodContext& context) {
  return std::make_unique<VirtualCouplingMethod>(context);
}

}  // namespace mrh::engine::internal
