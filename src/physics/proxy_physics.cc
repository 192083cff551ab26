// SPDX-License-Identifier: Apache-2.0
// Physics half of the chapter-3 method: geometric IR built per physics step.
#include "proxy_physics.h"

#include <fmt/format.h>

#include "mrh/core/error.h"
#include "mrh/physics/methods.h"
#include "mrh/world/world.h"
#include "pointer_ahead.h"
#include "report_impulses.h"

namespace mrh::physics {

Mat3 PointerRotationWeight(const world::World& world, int pointer_body,
                           const settings::RenderingSettings& rendering) {
  if (rendering.rotation_weight) return rendering.rotation_weight->asDiagonal();
  const world::BodyInfo& pointer = world.body(pointer_body);
  if (!(pointer.mass > 0.0)) {
    throw SceneError(fmt::format(
        "{}: pointer body '{}' has mass {} kg, so its unit-mass inertia (the default rotation "
        "weight) is undefined; expected a body with mass > 0: give its geoms a mass or "
        "density, or set rendering.rotation_weight",
        world.origin(), pointer.name, pointer.mass));
  }
  // Parallel-axis shift from the COM to the body origin, where the lever arms start.
  const Vec3& c = pointer.p_BCm;
  const Mat3 unit_inertia_origin =
      pointer.inertia_B / pointer.mass + c.squaredNorm() * Mat3::Identity() - c * c.transpose();
  // The body-axes tensor R diag Rᵀ is symmetric only up to rounding.
  return render::RotationWeightFromInertia(
      0.5 * (unit_inertia_origin + unit_inertia_origin.transpose()),
      rendering.rotation_weight_scale);
}

render::ProxyRendererSettings ProxySettingsFor(const world::World& world, int pointer_body,
                                               const settings::RenderingSettings& rendering) {
  if (rendering.max_iterations > render::kMaxProxyIterations) {
    throw InvalidArgument(
        fmt::format("rendering.max_iterations = {}; expected 1..{} for proxy-6dof (the solver's "
                    "compile-time ceiling); set a sweep budget such as 20-50",
                    rendering.max_iterations, render::kMaxProxyIterations));
  }
  render::ProxyRendererSettings s;
  s.k_t = rendering.stiffness;
  s.d_t = rendering.damping;
  s.k_r = rendering.rot_stiffness;
  s.d_r = rendering.rot_damping;
  s.torque_model = rendering.torque_model == settings::TorqueModel::kThesis
                       ? render::ProxyTorqueModel::kThesis
                       : render::ProxyTorqueModel::kContact;
  if (s.torque_model == render::ProxyTorqueModel::kThesis) {
    s.rotation_weight = PointerRotationWeight(world, pointer_body, rendering);
  } else if (!(s.k_t > 0.0 && s.k_r > 0.0)) {
    throw InvalidArgument(fmt::format(
        "rendering.stiffness = {} N/m, rendering.rot_stiffness = {} N*m/rad; the 6-DOF proxy's "
        "contact torque model needs both > 0 (its rotation weight is their ratio)",
        rendering.stiffness, rendering.rot_stiffness));
  }
  s.mu = rendering.friction;
  s.solver = rendering.proxy_solver == settings::ProxySolver::kPgs
                 ? render::ProxySolverKind::kPgs
                 : render::ProxySolverKind::kActiveSet;
  s.max_iterations = rendering.max_iterations;
  s.tolerance = rendering.solver_tolerance;
  return s;
}

render::ProxyRendererSettings ProxySettingsFor(const MethodContext& context) {
  render::ProxyRendererSettings s =
      ProxySettingsFor(*context.world, context.pointer_body, context.settings->rendering);
  s.max_pair_force = context.max_pair_force;
  return s;
}

}  // namespace mrh::physics

namespace mrh::physics::internal {

ProxyPhysics::ProxyPhysics(const MethodContext& context)
    : world_(context.world),
      pointer_body_(context.pointer_body),
      physics_dt_(context.settings->physics_dt) {
  builder_.emplace(*world_, pointer_body_, context.settings->rendering);
  const settings::RenderingSettings& rendering = context.settings->rendering;
  // "local" at every rate: even at physics_dt = haptic_dt a reaction applied one step late
  // acts as a negative damper k_t·Δt on the pushed object (2 of the default 5 N·s/m), and the
  // tick's split of the load among its contact points reaches it a step after the pose that
  // made it; a box pushed square then wobbles in yaw and slides 7 % below Coulomb's force.
  const double haptic_dt = context.settings->haptic_dt;
  if (rendering.proxy_reaction == settings::ProxyReaction::kLocal) {
    local_.emplace(*world_, pointer_body_, rendering, ProxySettingsFor(context), physics_dt_,
                   haptic_dt);
  }
  for (std::size_t i = 0; i < context.pointers.size(); ++i) {
    const PointerContext& pointer = context.pointers[i];
    pointer_bodies_.push_back(pointer.body);
    builders_.push_back(
        std::make_unique<GeometricIrBuilder>(*world_, pointer.body, *pointer.rendering));
    if (local_ && i > 0) {
      render::ProxyRendererSettings settings =
          ProxySettingsFor(*world_, pointer.body, *pointer.rendering);
      settings.max_pair_force = context.max_pair_force;
      local_->AddPointer(*world_, pointer.body, *pointer.rendering, settings);
    }
  }
}

void ProxyPhysics::Build(GeometricIrBuilder& builder, const Pose& X_WP, ir::PhysicsSnapshot* out) {
  builder.Build(*world_, X_WP, out);
  out->contacts.Clear();  // the 3-DOF plane IR is not used by this method
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

void ProxyPhysics::PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) {
  world_->SetMocapPose(pointer_body_, initial.X_WP);
  builder_->CapturePreviousPoses(*world_);
  Build(*builder_, initial.X_WP, out);
  out->step = -1;
}

void ProxyPhysics::PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) {
  // What the user pushed during the last period acts as a constant wrench over this whole step,
  // so the objects answer one physics step late (the chapter-3 design, thesis §3.5).
  if (local_) {
    local_->Apply(*world_, report);
  } else {
    ApplyReportImpulses(*world_, report, physics_dt_);
  }
  world_->SetMocapPose(pointer_body_, report.X_WP);
  builder_->CapturePreviousPoses(*world_);
  auto t0 = std::chrono::steady_clock::now();
  world_->Step();
  if (local_) local_->AfterStep(*world_);
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  // With the local reaction the objects move with the pointer's push, so at the report's pose
  // a pushing pointer is often just arriving at them and gets only its closest point, about
  // which the haptic proxy then spins (a torque spike, then a twist that friction holds). As
  // local-dynamics-6dof does, the IR is built for where the pointer will be when the snapshot is
  // rendered (1–2 Δt^G past the report, by the timing rule of thesis §4.1.3 and
  // docs/architecture.md).
  Build(*builder_, local_ ? PointerAhead(report, 2.0 * physics_dt_) : report.X_WP, out);
  phases_.ir_ms = MsSince(t0);
}

void ProxyPhysics::PhysicsStartPointers(std::span<const ir::HapticReport* const> initial,
                                        std::span<ir::PhysicsSnapshot* const> out) {
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    world_->SetMocapPose(pointer_bodies_[i], initial[i]->X_WP);
    builders_[i]->CapturePreviousPoses(*world_);
  }
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    Build(*builders_[i], initial[i]->X_WP, out[i]);
    out[i]->step = -1;
  }
}

// As PhysicsStep, for every pointer over one world step.
void ProxyPhysics::PhysicsStepPointers(std::span<const ir::HapticReport* const> reports,
                                       std::span<ir::PhysicsSnapshot* const> out) {
  if (local_) {
    local_->Apply(*world_, reports);
  } else {
    for (const ir::HapticReport* report : reports) {
      ApplyReportImpulses(*world_, *report, physics_dt_);
    }
  }
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    world_->SetMocapPose(pointer_bodies_[i], reports[i]->X_WP);
    builders_[i]->CapturePreviousPoses(*world_);
  }
  auto t0 = std::chrono::steady_clock::now();
  world_->Step();
  if (local_) local_->AfterStep(*world_);
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    Build(*builders_[i], local_ ? PointerAhead(*reports[i], 2.0 * physics_dt_) : reports[i]->X_WP,
          out[i]);
  }
  phases_.ir_ms = MsSince(t0);
}

}  // namespace mrh::physics::internal
