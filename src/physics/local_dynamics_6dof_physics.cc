// SPDX-License-Identifier: Apache-2.0
// local-dynamics-6dof, physics half: synchronization, global step, geometric IR, island export.
#include "local_dynamics_6dof_physics.h"

#include <algorithm>
#include <chrono>

#include "mrh/world/world.h"
#include "report_impulses.h"

namespace mrh::physics::internal {
namespace {

bool Contains(const std::vector<int>& list, int body) {
  return std::find(list.begin(), list.end(), body) != list.end();
}

// The pointer `t` seconds after the report: its pose moved on with its velocity.
Pose PointerAhead(const ir::HapticReport& report, double t) {
  return Pose{
      report.X_WP.p + t * report.V_WP.v,
      (QuatFromRotationVector(t * report.V_WP.w) * report.X_WP.q.normalized()).normalized()};
}

}  // namespace

LocalDynamics6dofPhysics::LocalDynamics6dofPhysics(const MethodContext& context)
    : world_(context.world),
      pointer_body_(context.pointer_body),
      physics_dt_(context.settings->physics_dt),
      exporter_(context.world) {
  builder_.emplace(*world_, pointer_body_, context.settings->rendering);
  const auto capacity = static_cast<std::size_t>(world_->num_bodies());
  for (std::vector<int>* v :
       {&seeds_, &motions_, &sent_last_, &sent_before_, &failed_, &owned_, &owned_before_}) {
    v->reserve(capacity);
  }
  owned_states_.reserve(capacity);
}

void LocalDynamics6dofPhysics::Build(const Pose& X_WP, ir::PhysicsSnapshot* out) {
  builder_->Build(*world_, X_WP, out);
  out->contacts.Clear();  // the 3-DOF plane IR is not used by this method
  out->t = world_->time();
  out->physics_dt = physics_dt_;
}

void LocalDynamics6dofPhysics::PhysicsStart(const ir::HapticReport& initial,
                                            ir::PhysicsSnapshot* out) {
  world_->SetMocapPose(pointer_body_, initial.X_WP);
  builder_->CapturePreviousPoses(*world_);
  Build(initial.X_WP, out);
  Export(out);
  out->step = -1;
}

// A rigid body's pose `t` seconds on with constant COM twist V (no forces).
Pose Coast(const Pose& X_WB, const Vec3& p_BCm, const Twist& V, double t) {
  const Quat q = (QuatFromRotationVector(t * V.w) * X_WB.q).normalized();
  const Vec3 p_WCm = X_WB * p_BCm + t * V.v;
  return Pose{p_WCm - q * p_BCm, q};
}

// After the global step, every body the local simulation owns is set to its local end state
// coasted over the step: the local simulation, not MuJoCo, moves it (the next synchronization
// overwrites it anyway). MuJoCo's step from the overwritten state is a transient: a box the
// local solver rests exactly on the floor is above MuJoCo's soft resting depth, finds no
// contact at the step's start and drops or rolls (1.6 mm, ±2.9 rad/s per 20 ms step on
// t3_6_push), and the IR, the exported contacts and the recorded state would all come from it.
void LocalDynamics6dofPhysics::CoastOwned() {
  for (const ir::LocalBodyState& state : owned_states_) {
    const Pose X_WB = Coast(state.X_WB, world_->body(state.body).p_BCm, state.V_WCm, physics_dt_);
    (void)world_->SetBodyState(state.body, X_WB, state.V_WCm);
  }
}

// (0) overwrite + reaction, (1) global step without the user's force, (2) IR, (3) export.
void LocalDynamics6dofPhysics::PhysicsStep(const ir::HapticReport& report,
                                           ir::PhysicsSnapshot* out) {
  auto t0 = std::chrono::steady_clock::now();
  Overwrite(report);
  phases_.sync_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  world_->SetMocapPose(pointer_body_, report.X_WP);
  builder_->CapturePreviousPoses(*world_);
  world_->Step();
  CoastOwned();
  phases_.world_step_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  // This snapshot is rendered in the period after the next one (SPEC §4.9: step k reads period
  // k−1's report, period k+1 renders step k's snapshot), so the pointer will be 1–2 Δt^G past
  // the report's pose. The IR is built for it at the end of that period: its contact points then
  // cover the region the pointer will penetrate (built at the report's pose, a pointer that is
  // just arriving gets only its closest point, and the proxy spins about that single point).
  Build(PointerAhead(report, 2.0 * physics_dt_), out);
  phases_.ir_ms = MsSince(t0);
  t0 = std::chrono::steady_clock::now();
  Export(out);
  phases_.model_ms = MsSince(t0);
  ++counters_.steps;
}

// eq. 4.16–4.17 for the island bodies of the snapshot the report's period rendered, owned by
// the local simulation from the first pushed period on (LocalContactPhysics::Overwrite explains
// why an untouched island is left to MuJoCo); then the period's reaction as J/Δt^G.
void LocalDynamics6dofPhysics::Overwrite(const ir::HapticReport& report) {
  failed_.clear();
  const bool touched = !report.impulses.empty();
  owned_before_.swap(owned_);
  owned_.clear();
  owned_states_.clear();
  for (const ir::LocalBodyState& state : report.local_states) {
    if (!Contains(sent_before_, state.body)) continue;
    if (!touched && !Contains(owned_before_, state.body)) {
      failed_.push_back(state.body);
      continue;
    }
    owned_.push_back(state.body);
    if (world_->SetBodyState(state.body, state.X_WB, state.V_WCm)) {
      ++counters_.overwrites;
      owned_states_.push_back(state);
    } else {
      ++counters_.overwrite_failures;
      failed_.push_back(state.body);
    }
  }
  ApplyReportImpulses(*world_, report, physics_dt_);
}

// Seeds: every dynamic body with a geometric pair (the pointer may touch it this period).
void LocalDynamics6dofPhysics::Export(ir::PhysicsSnapshot* out) {
  seeds_.clear();
  motions_.clear();
  for (const ir::GeometricPair& pair : out->pairs) {
    if (pair.motion < 0 || static_cast<std::size_t>(pair.motion) >= out->bodies.size()) continue;
    const ir::BodyMotion& m = out->bodies[static_cast<std::size_t>(pair.motion)];
    if (m.is_static || Contains(seeds_, m.body) || !exporter_.IsFreeBody(m.body)) continue;
    seeds_.push_back(m.body);
    motions_.push_back(pair.motion);
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

}  // namespace mrh::physics::internal
