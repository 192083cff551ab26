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
  owned_.reserve(capacity);
  owned_before_.reserve(capacity);
  written_.reserve(capacity);
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
  HoldOwnedBodies();
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
  written_.clear();
  // The local simulation owns an island body from the first period in which the pointer pushed
  // the island until the body leaves the island; a never-pushed island is left to MuJoCo and
  // restarts from the world (reset) each period. The local contacts are hard and MuJoCo's are
  // soft, so writing an untouched body's local state into the world moved it off MuJoCo's own
  // resting state every period (a 0.25 mm, 2 mm/s drift of an untouched resting cube).
  const bool touched = !report.impulses.empty();
  owned_before_.swap(owned_);
  owned_.clear();
  for (const ir::LocalBodyState& state : report.local_states) {
    if (!Contains(sent_before_, state.body)) continue;
    if (!touched && !Contains(owned_before_, state.body)) {
      failed_.push_back(state.body);
      continue;
    }
    owned_.push_back(state.body);
    if (world_->SetBodyState(state.body, state.X_WB, state.V_WCm)) {
      ++counters_.overwrites;
      written_.push_back(state);
    } else {
      ++counters_.overwrite_failures;
      failed_.push_back(state.body);
    }
  }
  // The period's reaction as a force J/Δt^G during the global step, for every touched body, so
  // that what the owned bodies touch in the world during the step feels them pushed. An owned
  // body itself ends the step at its written local state (HoldOwnedBodies).
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

// An owned body leaves the global step where the local simulation had it at the step's start
// (the state written in Overwrite); the local simulation is the authority for it (eq. 4.16–4.17
// overwrite it at the next synchronization anyway). The global step's own end state of an owned
// body was not usable: MuJoCo's soft contacts at a 20 ms step, started from the local hard-contact
// state, sink a resting box by up to 4 mm and pitch it by up to 0.08 rad (3–5 rad/s of spin
// for one step). Exported from there, the rows of a level local box's raised edge fell outside the
// 5 mm margin (the local box lost support for a period: the row's force swung 2–10 N); and (in
// a variant that only exported at the local states, the wall case's transient threw the world's
// box out of the pointer's reach, so it was never owned again). The cost: the world shows an
// owned body one physics period (20 ms, 2 mm at 0.1 m/s) late.
void LocalContactPhysics::HoldOwnedBodies() {
  for (const ir::LocalBodyState& s : written_) world_->SetBodyState(s.body, s.X_WB, s.V_WCm);
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
