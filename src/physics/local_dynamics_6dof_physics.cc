// SPDX-License-Identifier: Apache-2.0
// local-dynamics-6dof, physics half: synchronization, global step, geometric IR, island export.
#include "local_dynamics_6dof_physics.h"

#include <algorithm>
#include <chrono>

#include "mrh/world/world.h"
#include "pointer_ahead.h"
#include "pointer_union.h"

namespace mrh::physics::internal {

LocalDynamics6dofPhysics::LocalDynamics6dofPhysics(const MethodContext& context)
    : world_(context.world),
      pointer_body_(context.pointer_body),
      physics_dt_(context.settings->physics_dt),
      exporter_(context.world, kIslandMargin, false, true),
      sync_(context.world, context.settings->physics_dt) {
  builder_.emplace(*world_, pointer_body_, context.settings->rendering);
  const auto capacity = static_cast<std::size_t>(world_->num_bodies());
  seeds_.reserve(capacity);
  motions_.reserve(capacity);
  for (const PointerContext& pointer : context.pointers) {
    pointer_bodies_.push_back(pointer.body);
    builders_.push_back(
        std::make_unique<GeometricIrBuilder>(*world_, pointer.body, *pointer.rendering));
  }
  remap_.resize(ir::kMaxNeighborBodies);
}

void LocalDynamics6dofPhysics::Build(GeometricIrBuilder& builder, const Pose& X_WP,
                                     ir::PhysicsSnapshot* out) {
  builder.Build(*world_, X_WP, out);
  out->contacts.Clear();  // the 3-DOF plane IR is not used by this method
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

void LocalDynamics6dofPhysics::PhysicsStart(const ir::HapticReport& initial,
                                            ir::PhysicsSnapshot* out) {
  world_->SetMocapPose(pointer_body_, initial.X_WP);
  builder_->CapturePreviousPoses(*world_);
  Build(*builder_, initial.X_WP, out);
  Export(out);
  out->step = -1;
}

// (0) overwrite + reaction, (1) global step without the user's force, (2) IR, (3) export.
void LocalDynamics6dofPhysics::PhysicsStep(const ir::HapticReport& report,
                                           ir::PhysicsSnapshot* out) {
  auto t0 = std::chrono::steady_clock::now();
  sync_.Overwrite(report);
  phases_.sync_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  world_->SetMocapPose(pointer_body_, report.X_WP);
  builder_->CapturePreviousPoses(*world_);
  world_->Step();
  // Every owned body ends the step at its local end state coasted over the step: the local
  // simulation, not MuJoCo, moves it (IslandSync::HoldOwned). From MuJoCo's own end state a box
  // the local solver rests exactly on the floor, above MuJoCo's soft resting depth, drops or
  // rolls (1.6 mm, ±2.9 rad/s per 20 ms step on t3_6_push), and the IR, the exported contacts
  // and the recorded state would all come from that transient.
  sync_.HoldOwned(physics_dt_);
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  // This snapshot is rendered in the period after the next one (the timing rule of thesis
  // §4.1.3 and docs/architecture.md: step k reads period
  // k−1's report, period k+1 renders step k's snapshot), so the pointer will be 1–2 Δt^G past
  // the report's pose. The IR is built for it at the end of that period: its contact points then
  // cover the region the pointer will penetrate (built at the report's pose, a pointer that is
  // just arriving gets only its closest point, and the proxy spins about that single point).
  Build(*builder_, PointerAhead(report, 2.0 * physics_dt_), out);
  phases_.ir_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  Export(out);
  phases_.model_ms = MsSince(t0);
  sync_.CountStep();
}

void LocalDynamics6dofPhysics::PhysicsStartPointers(
    std::span<const ir::HapticReport* const> initial, std::span<ir::PhysicsSnapshot* const> out) {
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    world_->SetMocapPose(pointer_bodies_[i], initial[i]->X_WP);
    builders_[i]->CapturePreviousPoses(*world_);
  }
  BuildPointers(initial, 0.0, out);
  for (ir::PhysicsSnapshot* o : out) o->step = -1;
}

// As PhysicsStep, for every pointer over one world step.
void LocalDynamics6dofPhysics::PhysicsStepPointers(std::span<const ir::HapticReport* const> reports,
                                                   std::span<ir::PhysicsSnapshot* const> out) {
  auto t0 = std::chrono::steady_clock::now();
  MergePointerReports(reports, &merged_);
  sync_.Overwrite(merged_);
  phases_.sync_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    world_->SetMocapPose(pointer_bodies_[i], reports[i]->X_WP);
    builders_[i]->CapturePreviousPoses(*world_);
  }
  world_->Step();
  sync_.HoldOwned(physics_dt_);
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  BuildPointers(reports, 2.0 * physics_dt_, out);  // PhysicsStep says why 2 Δt^G ahead
  phases_.ir_ms = MsSince(t0);
  sync_.CountStep();
}

void LocalDynamics6dofPhysics::BuildPointers(std::span<const ir::HapticReport* const> reports,
                                             double ahead,
                                             std::span<ir::PhysicsSnapshot* const> out) {
  ir::PhysicsSnapshot& all = *out[0];
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    ir::PhysicsSnapshot& own = *out[i];
    Build(*builders_[i], PointerAhead(*reports[i], ahead), &own);
    if (i == 0) continue;
    UniteBodies(own, &all, remap_);
    // A pair whose body did not fit the union keeps no body (rendered as static, flagged).
    for (ir::GeometricPair& pair : own.pairs) {
      if (pair.motion >= 0) pair.motion = remap_[static_cast<std::size_t>(pair.motion)];
    }
  }
  seeds_.clear();
  motions_.clear();
  for (const ir::PhysicsSnapshot* o : out) AddSeeds(*o, all);
  all.status |= sync_.Export(exporter_, seeds_, motions_, &all);
  ShareUnion(out);
}

// Seeds: every island body (free, or of a mechanism) with a geometric pair (the pointer may touch
// it this period).
void LocalDynamics6dofPhysics::Export(ir::PhysicsSnapshot* out) {
  seeds_.clear();
  motions_.clear();
  AddSeeds(*out, *out);
  out->status |= sync_.Export(exporter_, seeds_, motions_, out);
}

// The free bodies of `pairs`'s snapshot, its motions indexing `bodies`'s, not yet seeds.
void LocalDynamics6dofPhysics::AddSeeds(const ir::PhysicsSnapshot& pairs,
                                        const ir::PhysicsSnapshot& bodies) {
  for (const ir::GeometricPair& pair : pairs.pairs) {
    if (pair.motion < 0 || static_cast<std::size_t>(pair.motion) >= bodies.bodies.size()) continue;
    const ir::BodyMotion& m = bodies.bodies[static_cast<std::size_t>(pair.motion)];
    if (m.is_static || std::find(seeds_.begin(), seeds_.end(), m.body) != seeds_.end() ||
        !exporter_.IsIslandBody(m.body)) {
      continue;
    }
    seeds_.push_back(m.body);
    motions_.push_back(pair.motion);
  }
}

}  // namespace mrh::physics::internal
