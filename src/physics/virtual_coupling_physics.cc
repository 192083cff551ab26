// SPDX-License-Identifier: Apache-2.0
// Baseline B3, physics half: the dynamic tool stepped at the haptic rate under the coupling.
#include "virtual_coupling_physics.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <chrono>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"
#include "mrh/render/virtual_coupling.h"
#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::physics::internal {
namespace {

// Growth per tick above this is an unstable coupling (1 is the uncoupled tool's drift).
constexpr double kMaxGrowth = 1.0 + 1e-9;

// Gains that keep one axis well inside the stable region: a = 0.05, c = 0.3 (growth 0.77).
double StableStiffness(double inertia, double h) {
  return 0.05 * inertia / (h * h);
}

double StableDamping(double inertia, double h) {
  return 0.3 * inertia / h;
}

// The smallest principal moment of the tool's inertia about its COM (kg·m²): the axis on which
// the rotational coupling is closest to instability.
double WeakestInertia(const Mat3& inertia_B) {
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(0.5 * (inertia_B + inertia_B.transpose()));
  return eigen.eigenvalues().minCoeff();
}

}  // namespace

// Unset rotational gains: the translational a = k h²/m and c = b h/m on the weakest axis.
render::CouplingGains ResolveCouplingGains(const world::BodyInfo& tool,
                                           const settings::RenderingSettings& r) {
  const double ratio = WeakestInertia(tool.inertia_B) / tool.mass;  // m²
  return render::CouplingGains{
      .k = r.coupling_stiffness,
      .b = r.coupling_damping,
      .k_r = r.coupling_rot_stiffness.value_or(r.coupling_stiffness * ratio),
      .b_r = r.coupling_rot_damping.value_or(r.coupling_damping * ratio)};
}

// The free tool under the coupling must not grow (render::CouplingGrowthPerTick): an unstable
// coupling makes MuJoCo reset its state ("bad number in qacc") and the device fade or clamp,
// so it is refused at setup with gains that would work instead.
void CheckCouplingStable(const world::BodyInfo& tool, const render::CouplingGains& g, double h,
                         const std::string& origin) {
  const double m = tool.mass;
  const double growth = render::CouplingGrowthPerTick(g.k * h * h / m, g.b * h / m);
  if (growth > kMaxGrowth) {
    throw InvalidArgument(fmt::format(
        "{}: rendering.coupling_stiffness = {} N/m with coupling_damping = {} N*s/m makes the "
        "{} kg tool '{}' unstable at haptic_dt {} s (its motion grows {}x per tick); expected a "
        "stable pair such as coupling_stiffness {} and coupling_damping {}, or a heavier tool "
        "(rendering.tool_mass)",
        origin, FormatNumber(g.k), FormatNumber(g.b), FormatNumber(m), tool.name, FormatNumber(h),
        FormatNumber(growth), FormatNumber(StableStiffness(m, h)),
        FormatNumber(StableDamping(m, h))));
  }
  const double inertia = WeakestInertia(tool.inertia_B);
  const double rot_growth =
      render::CouplingGrowthPerTick(g.k_r * h * h / inertia, g.b_r * h / inertia);
  if (rot_growth > kMaxGrowth) {
    throw InvalidArgument(fmt::format(
        "{}: rendering.coupling_rot_stiffness = {} N*m/rad with coupling_rot_damping = {} "
        "N*m*s/rad makes the tool '{}' (inertia {} kg*m^2 about its weakest axis) unstable at "
        "haptic_dt {} s (its rotation grows {}x per tick); expected a stable pair such as "
        "coupling_rot_stiffness {} and coupling_rot_damping {}, or a larger "
        "rendering.tool_inertia",
        origin, FormatNumber(g.k_r), FormatNumber(g.b_r), tool.name, FormatNumber(inertia),
        FormatNumber(h), FormatNumber(rot_growth), FormatNumber(StableStiffness(inertia, h)),
        FormatNumber(StableDamping(inertia, h))));
  }
}

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
  CheckCouplingStable(info, ResolveCouplingGains(info, context.settings->rendering),
                      context.settings->haptic_dt, world_->origin());
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

void VirtualCouplingPhysics::PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) {
  ApplyReportImpulses(*world_, report, physics_dt_, tool_);
  const double mass = world_->body(tool_).mass;
  world_->AddWrenchAtCom(tool_, Wrench{-mass * world_->gravity(), Vec3::Zero()});
  const auto t0 = std::chrono::steady_clock::now();
  world_->Step();
  phases_.world_step_ms = MsSince(t0);
  Publish(out);
}

}  // namespace mrh::physics::internal
