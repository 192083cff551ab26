// SPDX-License-Identifier: Apache-2.0
// local-dynamics, contact local model, physics half: synchronization, global step, IR, export.
#include "local_contact_physics.h"

#include <algorithm>
#include <chrono>

#include "mrh/world/world.h"
#include "pointer_union.h"

namespace mrh::physics::internal {

LocalContactPhysics::LocalContactPhysics(const MethodContext& context)
    : world_(context.world),
      pointer_body_(context.pointer_body),
      physics_dt_(context.settings->physics_dt),
      exporter_(context.world, kIslandMargin, false, true),
      sync_(context.world, context.settings->physics_dt) {
  builder_.emplace(*world_, pointer_body_, PointerRadiusFor3Dof(context),
                   context.settings->rendering);
  const auto capacity = static_cast<std::size_t>(world_->num_bodies());
  seeds_.reserve(capacity);
  motions_.reserve(capacity);
  builders_.reserve(context.pointers.size());
  for (const PointerContext& pointer : context.pointers) {
    pointer_bodies_.push_back(pointer.body);
    builders_.emplace_back(*world_, pointer.body, pointer.radius, *pointer.rendering);
  }
  remap_.resize(ir::kMaxNeighborBodies);
}

void LocalContactPhysics::PhysicsStartPointers(std::span<const ir::HapticReport* const> initial,
                                               std::span<ir::PhysicsSnapshot* const> out) {
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    world_->SetMocapPose(pointer_bodies_[i], initial[i]->X_WP);
    builders_[i].CapturePreviousPoses(*world_);
  }
  BuildPointers(initial, out);
  for (ir::PhysicsSnapshot* o : out) {
    o->step = -1;
    o->t = world_->time();
    o->physics_dt = physics_dt_;
  }
}

void LocalContactPhysics::PhysicsStepPointers(std::span<const ir::HapticReport* const> reports,
                                              std::span<ir::PhysicsSnapshot* const> out) {
  auto t0 = std::chrono::steady_clock::now();
  // The island's end states from the half that stepped it; every pointer's reaction.
  MergePointerReports(reports, &merged_);
  sync_.Overwrite(merged_);
  phases_.sync_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < builders_.size(); ++i) {
    world_->SetMocapPose(pointer_bodies_[i], reports[i]->X_WP);
    builders_[i].CapturePreviousPoses(*world_);
  }
  world_->Step();
  sync_.HoldOwned(0.0);
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  BuildPointers(reports, out);
  phases_.model_ms = MsSince(t0);
  for (ir::PhysicsSnapshot* o : out) {
    o->t = world_->time();
    o->physics_dt = physics_dt_;
  }
  sync_.CountStep();
}

// Pointer 0's snapshot collects the union of the neighbor bodies; each other pointer's contacts
// are renumbered into it. The island is exported once, from every pointer's contacts, and the
// bodies and island are copied into every snapshot.
void LocalContactPhysics::BuildPointers(std::span<const ir::HapticReport* const> reports,
                                        std::span<ir::PhysicsSnapshot* const> out) {
  ir::PhysicsSnapshot& all = *out[0];
  builders_[0].Build(*world_, reports[0]->X_WP, &all);
  for (std::size_t i = 1; i < builders_.size(); ++i) {
    ir::PhysicsSnapshot& own = *out[i];
    builders_[i].Build(*world_, reports[i]->X_WP, &own);
    UniteBodies(own, &all, remap_);
    // A contact whose body did not fit the union is dropped (and the overflow flagged).
    kept_.Clear();
    for (ir::PointContact c : own.contacts) {
      c.motion = remap_[static_cast<std::size_t>(c.motion)];
      if (c.motion >= 0) (void)kept_.PushBack(c);
    }
    own.contacts = kept_;
  }
  seeds_.clear();
  motions_.clear();
  for (const ir::PhysicsSnapshot* o : out) {
    for (const ir::PointContact& c : o->contacts) {
      if (c.motion < 0) continue;
      const ir::BodyMotion& m = all.bodies[static_cast<std::size_t>(c.motion)];
      if (m.is_static || std::find(seeds_.begin(), seeds_.end(), m.body) != seeds_.end()) {
        continue;
      }
      seeds_.push_back(m.body);
      motions_.push_back(c.motion);
    }
  }
  all.status |= sync_.Export(exporter_, seeds_, motions_, &all);
  ShareUnion(out);
}

void LocalContactPhysics::PhysicsStart(const ir::HapticReport& initial, ir::PhysicsSnapshot* out) {
  world_->SetMocapPose(pointer_body_, initial.X_WP);
  builder_->CapturePreviousPoses(*world_);
  builder_->Build(*world_, initial.X_WP, out);
  Export(out);
  out->step = -1;
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

// (0) overwrite, (1) global step without the user's force, (2) IR, (3) export.
void LocalContactPhysics::PhysicsStep(const ir::HapticReport& report, ir::PhysicsSnapshot* out) {
  auto t0 = std::chrono::steady_clock::now();
  sync_.Overwrite(report);
  phases_.sync_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  world_->SetMocapPose(pointer_body_, report.X_WP);
  builder_->CapturePreviousPoses(*world_);
  world_->Step();
  // An owned body leaves the global step where the local simulation had it at the step's start
  // (IslandSync::HoldOwned explains why). The cost: the world shows an owned body one physics
  // period (20 ms, 2 mm at 0.1 m/s) late.
  sync_.HoldOwned(0.0);
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  builder_->Build(*world_, report.X_WP, out);
  phases_.ir_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  Export(out);
  phases_.model_ms = MsSince(t0);
  out->t = world_->time();
  out->physics_dt = physics_dt_;
  sync_.CountStep();
}

// The island of the dynamic neighbors the pointer may touch (every body with a plane IR).
void LocalContactPhysics::Export(ir::PhysicsSnapshot* out) {
  seeds_.clear();
  motions_.clear();
  for (const ir::PointContact& c : out->contacts) {
    const ir::BodyMotion& m = out->bodies[static_cast<std::size_t>(c.motion)];
    if (m.is_static || std::find(seeds_.begin(), seeds_.end(), m.body) != seeds_.end()) continue;
    seeds_.push_back(m.body);
    motions_.push_back(c.motion);
  }
  out->status |= sync_.Export(exporter_, seeds_, motions_, out);
}

}  // namespace mrh::physics::internal

namespace mrh::physics {

bool UsesContactLocalModel(const MethodContext& context) {
  return context.settings->rendering.local_model != settings::LocalModel::kPerturbation;
}

}  // namespace mrh::physics
