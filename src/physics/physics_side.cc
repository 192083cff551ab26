// SPDX-License-Identifier: Apache-2.0
// The physics side of a run: one global step per call, exchange bookkeeping and statistics.
#include "mrh/physics/physics_side.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "mrh/core/assert.h"
#include "mrh/core/error.h"
#include "mrh/core/stats.h"
#include "mrh/world/world.h"

namespace mrh::physics {

PhysicsSide::PhysicsSide(MethodPhysics* method, world::World* world, const Exchange& exchange,
                         Recorder* recorder, double max_body_speed)
    : method_(method),
      world_(world),
      exchange_(exchange),
      recorder_(recorder),
      max_body_speed_(max_body_speed) {
  MRH_DEMAND(exchange_.more_snapshots.size() == exchange_.more_reports.size());
  more_input_.resize(exchange_.more_reports.size());
  inputs_.resize(more_input_.size() + 1);
  outputs_.resize(more_input_.size() + 1);
}

// Several pointers: every lane's report in and write slot out, pointer 0 first.
void PhysicsSide::GatherLanes() {
  inputs_[0] = &input_;
  outputs_[0] = &exchange_.snapshots->write_slot();
  for (std::size_t i = 0; i < more_input_.size(); ++i) {
    inputs_[i + 1] = &more_input_[i];
    outputs_[i + 1] = &exchange_.more_snapshots[i]->write_slot();
  }
  for (ir::PhysicsSnapshot* out : outputs_) out->status = ir::kStatusOk;
}

void PhysicsSide::Start(const ir::HapticReport& initial, std::span<const ir::HapticReport> more) {
  MRH_DEMAND(more.size() == more_input_.size());
  input_ = initial;
  for (std::size_t i = 0; i < more.size(); ++i) more_input_[i] = more[i];
  ir::PhysicsSnapshot& out = exchange_.snapshots->write_slot();
  out.status = ir::kStatusOk;
  if (more_input_.empty()) {
    method_->PhysicsStart(input_, &out);
  } else {
    GatherLanes();
    method_->PhysicsStartPointers(inputs_, outputs_);
    for (std::size_t i = 1; i < outputs_.size(); ++i) {
      outputs_[i]->step = -1;
      ir_status_ |= outputs_[i]->status;
    }
  }
  out.step = -1;
  ir_status_ |= out.status;
  if (recorder_ != nullptr) recorder_->OnSnapshot(out);
  Publish();
}

void PhysicsSide::Publish() {
  exchange_.snapshots->Publish();
  for (TripleBuffer<ir::PhysicsSnapshot>* lane : exchange_.more_snapshots) lane->Publish();
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
  if (more_input_.empty()) {
    method_->PhysicsStep(input_, &out);
  } else {
    for (const ir::HapticReport& lane : more_input_) ir_status_ |= lane.status;
    GatherLanes();
    method_->PhysicsStepPointers(inputs_, outputs_);
  }
  const auto t1 = std::chrono::steady_clock::now();
  if (std::string diverged = world_->FindDivergence(max_body_speed_); !diverged.empty()) {
    throw RuntimeError(std::move(diverged));
  }
  // A method that applies its own reaction reports all of it, every pointer's included.
  const ir::HapticReport* applied = method_->applied_reaction();
  AddToTotals(applied != nullptr ? *applied : input_);
  for (std::size_t i = 0; i < more_input_.size(); ++i) {
    if (applied == nullptr) AddToTotals(more_input_[i]);
    outputs_[i + 1]->step = k;
    ir_status_ |= outputs_[i + 1]->status;
  }
  out.step = k;
  ir_status_ |= out.status;
  if (recorder_ != nullptr) recorder_->OnSnapshot(out);

  NoteStep(k, out, std::chrono::duration<double, std::milli>(t1 - t0).count());
}

// Step k's record (last_step_) and its share of the run's totals.
void PhysicsSide::NoteStep(std::int64_t k, const ir::PhysicsSnapshot& out, double compute_ms) {
  last_step_.step = k;
  last_step_.t = world_->time();
  last_step_.compute_ms = compute_ms;
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

int PhysicsSide::TakeLaneReports(SpscRing<ir::HapticReport>* ring, ir::HapticReport* input) {
  int count = 0;
  input->impulses.Clear();
  input->ticks = 0;
  input->status = ir::kStatusOk;
  while (ring->TryPop(&popped_)) {
    input->MergeLater(popped_);
    ++count;
  }
  return count;
}

int PhysicsSide::TakeReports() {
  if (more_input_.empty()) return TakeLaneReports(exchange_.reports, &input_);
  // The haptic loop ends its period for pointer 0 first and the last pointer last: popping the
  // last lane first means that when it has a report, every other lane's of that period is
  // already pushed (its push happened before, in the haptic thread's order).
  const int count = TakeLaneReports(exchange_.more_reports.back(), &more_input_.back());
  for (std::size_t i = 0; i + 1 < more_input_.size(); ++i) {
    TakeLaneReports(exchange_.more_reports[i], &more_input_[i]);
  }
  TakeLaneReports(exchange_.reports, &input_);
  return count;
}

void PhysicsSide::DrainTickRecords() {
  ir::TickRecord record;
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
  if (method_->applied_reaction() == nullptr) {
    AddToTotals(input_);
    for (const ir::HapticReport& lane : more_input_) AddToTotals(lane);
  }
  DrainTickRecords();
  stats->steps = steps_;
  stats->step_ms_p50 = Percentile(step_ms_, 50.0);
  stats->step_ms_p99 = Percentile(step_ms_, 99.0);
  stats->step_ms_max = step_ms_.empty() ? 0.0 : *std::max_element(step_ms_.begin(), step_ms_.end());
  stats->ir_status = ir_status_;
  stats->phase_total = phase_total_;
  for (const std::string& line : world_->LoadWarnings()) stats->warnings.push_back(line);
  for (std::string& line : method_->setup_warnings()) stats->warnings.push_back(std::move(line));
  for (std::string& line : world_->SimulatorWarnings()) {
    stats->warnings.push_back(std::move(line));
  }
  for (auto& [body, total] : impulses_) {
    total.name = world_->body(body).name;
    stats->impulses.push_back(total);
  }
}

}  // namespace mrh::physics
