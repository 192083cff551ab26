// SPDX-License-Identifier: Apache-2.0
// local-dynamics, contact local model, physics half: synchronization, global step, IR, export.
#include "local_contact_physics.h"

#include <algorithm>
#include <chrono>

#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::physics::internal {
namespace {

bool Contains(const std::vector<int>& list, int body) {
  return std::find(list.begin(), list.end(), body) != list.end();
}

}  // namespace

LocalContactPhysics::LocalContactPhysics(const MethodContext& context)
    : world_(context.world),
      pointer_body_(context.pointer_body),
      physics_dt_(context.settings->physics_dt),
      exporter_(context.world) {
  builder_.emplace(*world_, pointer_body_, PointerRadiusFor3Dof(context),
                   context.settings->rendering);
  const auto capacity = static_cast<std::size_t>(world_->num_bodies());
  seeds_.reserve(capacity);
  motions_.reserve(capacity);
  sent_last_.reserve(capacity);
  sent_before_.reserve(capacity);
  failed_.reserve(capacity);
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
  Overwrite(report);
  phases_.sync_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  world_->SetMocapPose(pointer_body_, report.X_WP);
  builder_->CapturePreviousPoses(*world_);
  world_->Step();
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  builder_->Build(*world_, report.X_WP, out);
  phases_.ir_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  Export(out);
  phases_.model_ms = MsSince(t0);
  out->t = world_->time();
  out->physics_dt = physics_dt_;
  ++counters_.steps;
}

// eq. 4.16–4.17 for every island body of the snapshot the report's period rendered. A touched
// body outside the island (no free joint) gets the period's reaction as an impulse (B4).
void LocalContactPhysics::Overwrite(const ir::HapticReport& report) {
  failed_.clear();
  for (const ir::LocalBodyState& state : report.local_states) {
    if (!Contains(sent_before_, state.body)) continue;
    if (world_->SetBodyState(state.body, state.X_WB, state.V_WCm)) {
      ++counters_.overwrites;
    } else {
      ++counters_.overwrite_failures;
      failed_.push_back(state.body);
    }
  }
  // The period's reaction as a force J/Δt^G during the global step, for every touched body:
  // an island body's state is overwritten again at the next synchronization, but its end state
  // here is where its contacts for the next period are found, so it should have been pushed as
  // the local simulation pushes it (without, a decelerating box pitches in the global step and
  // exports tilted contacts).
  ApplyReportImpulses(*world_, report, physics_dt_);
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
  out->status |= exporter_.Export(seeds_, motions_, &out->local_model);
  sent_before_.swap(sent_last_);
  sent_last_.clear();
  for (ir::LocalIslandBody& b : out->local_model.bodies) {
    b.reset = Contains(failed_, b.body);
    sent_last_.push_back(b.body);
  }
  counters_.last_island_bodies = static_cast<int>(out->local_model.bodies.size());
  counters_.last_island_contacts = static_cast<int>(out->local_model.contacts.size());
}

// The contact model simulates free-jointed bodies only: a scene with any other moving body
// (e.g. T4.1's slide-jointed cube) keeps the thesis' perturbation model.
namespace {
bool AllMovingBodiesFree(world::World& world) {
  const world::ContactExporter probe(&world);
  for (int b = 1; b < world.num_bodies(); ++b) {
    const world::BodyInfo& info = world.body(b);
    if (!info.is_static && !info.is_mocap && !probe.IsFreeBody(b)) return false;
  }
  return true;
}
}  // namespace

}  // namespace mrh::physics::internal

namespace mrh::physics {

bool UsesContactLocalModel(const MethodContext& context) {
  return context.settings->rendering.local_model != "perturbation" &&
         internal::AllMovingBodiesFree(*context.world);
}

}  // namespace mrh::physics
