// SPDX-License-Identifier: Apache-2.0
// The physics side of a run: one global step per call, exchange bookkeeping and statistics.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <string>
#include <utility>

#include "mrh/core/error.h"
#include "mrh/core/stats.h"
#include "mrh/physics/physics_side.h"
#include "mrh/world/world.h"

namespace mrh::physics {

PhysicsSide::PhysicsSide(MethodPhysics* method, world::World* world, const Exchange& exchange,
                         Recorder* recorder, double max_body_speed)
    : method_(method),
      world_(world),
      exchange_(exchange),
      recorder_(recorder),
      max_body_speed_(max_body_speed) {}

void PhysicsSide::Start(const ir::HapticReport& initial) {
  input_ = initial;
  ir::PhysicsSnapshot& out = exchange_.snapshots->write_slot();
  out.status = ir::kStatusOk;
  method_->PhysicsStart(input_, &out);
  out.step = -1;
  ir_status_ |= out.status;
  if (recorder_ != nullptr) recorder_->OnSnapshot(out);
  exchange_.snapshots->Publish();
}

void PhysicsSide::AddToTotals(const ir::HapticReport& report) {
  for (const ir::BodyImpulse& impulse : report.impulses) {
    // A haptic half reports world body ids; one out of range is its bug, not a body to name.
    if (impulse.body < 0 || impulse.body >= world_->num_bodies()) continue;
    BodyImpulseTotal& total = impulses_[impulse.body];
    total.body = impulse.body;
    total.linear += impulse.linear;
    total.angular += impulse.angular;
  }
}

void PhysicsSide::Step(std::int64_t k) {
  ir_status_ |= input_.status;
  ir::PhysicsSnapshot& out = exchange_.snapshots->write_slot();
  out.status = ir::kStatusOk;
  const auto t0 = std::chrono::steady_clock::now();
  method_->PhysicsStep(input_, &out);
  const auto t1 = std::chrono::steady_clock::now();
  if (std::string diverged = world_->FindDivergence(max_body_speed_); !diverged.empty()) {
    throw RuntimeError(std::move(diverged));
  }
  const ir::HapticReport* applied = method_->applied_reaction();
  AddToTotals(applied != nullptr ? *applied : input_);
  out.step = k;
  ir_status_ |= out.status;
  if (recorder_ != nullptr) recorder_->OnSnapshot(out);

  last_step_.step = k;
  last_step_.t = world_->time();
  last_step_.compute_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  last_step_.sim_contacts = world_->num_contacts();
  last_step_.neighbors = static_cast<int>(out.bodies.size());
  last_step_.point_contacts = static_cast<int>(out.contacts.size());
  last_step_.solver_iterations = world_->solver_iterations();
  const PhaseTimes phases = method_->last_phases();
  last_step_.world_step_ms = phases.world_step_ms;
  last_step_.ir_ms = phases.ir_ms;
  last_step_.model_ms = phases.model_ms;
  last_step_.sync_ms = phases.sync_ms;
  phase_total_.world_step_ms += phases.world_step_ms;
  phase_total_.ir_ms += phases.ir_ms;
  phase_total_.model_ms += phases.model_ms;
  phase_total_.sync_ms += phases.sync_ms;
  step_ms_.push_back(last_step_.compute_ms);
  ++steps_;
}

int PhysicsSide::TakeReports() {
  int count = 0;
  input_.impulses.Clear();
  input_.ticks = 0;
  input_.status = ir::kStatusOk;
  while (exchange_.reports->TryPop(&popped_)) {
    input_.MergeLater(popped_);
    ++count;
  }
  return count;
}

void PhysicsSide::DrainTickRecords() {
  haptic::TickRecord record;
  while (exchange_.tick_records->TryPop(&record)) {
    if (recorder_ != nullptr) recorder_->OnTick(record);
  }
}

void PhysicsSide::RecordStep() {
  DrainTickRecords();
  if (recorder_ != nullptr) recorder_->OnStep(last_step_, *world_);
}

void PhysicsSide::Finish(PhysicsStats* stats) {
  // Reports of the last periods were never stepped, but their impulses were delivered (unless
  // the method applies its own reaction instead of the reports').
  TakeReports();
  if (method_->applied_reaction() == nullptr) AddToTotals(input_);
  DrainTickRecords();
  stats->steps = steps_;
  stats->step_ms_p50 = Percentile(step_ms_, 50.0);
  stats->step_ms_p99 = Percentile(step_ms_, 99.0);
  stats->step_ms_max = step_ms_.empty() ? 0.0 : *std::max_element(step_ms_.begin(), step_ms_.end());
  stats->ir_status = ir_status_;
  stats->phase_total = phase_total_;
  for (const std::string& line : world_->LoadWarnings()) stats->warnings.push_back(line);
  for (std::string& line : world_->SimulatorWarnings()) {
    stats->warnings.push_back(std::move(line));
  }
  for (auto& [body, total] : impulses_) {
    total.name = world_->body(body).name;
    stats->impulses.push_back(total);
  }
}


}  // namespace mrh::physics
