// SPDX-License-Identifier: Apache-2.0
// The physics side of a run: one global step per call, exchange bookkeeping and statistics.
#include <algorithm>
#include <chrono>
#include <string>
#include <utility>

#include "engine_impl.h"
#include "mrh/engine/rt_clock.h"

namespace mrh::engine::internal {

PhysicsSide::PhysicsSide(EngineState* state, Recorder* recorder)
    : state_(state), recorder_(recorder) {}

void PhysicsSide::Start() {
  input_ = state_->haptic->InitialReport(0.0);
  ir::PhysicsSnapshot& out = state_->snapshots.write_slot();
  out.status = ir::kStatusOk;
  state_->method->PhysicsStart(input_, &out);
  out.step = -1;
  ir_status_ |= out.status;
  if (recorder_ != nullptr) recorder_->OnSnapshot(out);
  state_->snapshots.Publish();
}

void PhysicsSide::Step(std::int64_t k) {
  for (const ir::BodyImpulse& impulse : input_.impulses) {
    BodyImpulseTotal& total = impulses_[impulse.body];
    total.body = impulse.body;
    total.linear += impulse.linear;
    total.angular += impulse.angular;
  }
  ir_status_ |= input_.status;
  ir::PhysicsSnapshot& out = state_->snapshots.write_slot();
  out.status = ir::kStatusOk;
  const auto t0 = std::chrono::steady_clock::now();
  state_->method->PhysicsStep(input_, &out);
  const auto t1 = std::chrono::steady_clock::now();
  out.step = k;
  ir_status_ |= out.status;
  if (recorder_ != nullptr) recorder_->OnSnapshot(out);

  last_step_.step = k;
  last_step_.t = state_->world.time();
  last_step_.compute_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  last_step_.sim_contacts = state_->world.num_contacts();
  last_step_.neighbors = static_cast<int>(out.bodies.size());
  last_step_.point_contacts = static_cast<int>(out.contacts.size());
  last_step_.solver_iterations = state_->world.solver_iterations();
  step_ms_.push_back(last_step_.compute_ms);
  ++steps_;
}

void PhysicsSide::RunThread(const std::atomic<bool>& done) {
  // The physics thread polls for the end of a haptic period this often while it waits.
  constexpr std::int64_t kPollNs = 100'000;
  for (std::int64_t k = 0;; ++k) {
    Step(k);
    while (TakeReports() == 0) {
      if (done.load(std::memory_order_acquire)) return;
      SleepUntilNs(NowNs() + kPollNs, 0);
    }
    Publish();
    RecordStep();
  }
}

int PhysicsSide::TakeReports() {
  int count = 0;
  input_.impulses.Clear();
  input_.ticks = 0;
  input_.status = ir::kStatusOk;
  while (state_->reports.TryPop(&popped_)) {
    input_.MergeLater(popped_);
    ++count;
  }
  return count;
}

void PhysicsSide::DrainTickRecords() {
  TickRecord record;
  while (state_->tick_records.TryPop(&record)) {
    if (recorder_ != nullptr) recorder_->OnTick(record);
  }
}

void PhysicsSide::RecordStep() {
  DrainTickRecords();
  if (recorder_ != nullptr) recorder_->OnStep(last_step_, state_->world);
}

void PhysicsSide::Finish(RunStats* stats) {
  // Reports of the last periods were never stepped, but their impulses were delivered.
  TakeReports();
  for (const ir::BodyImpulse& impulse : input_.impulses) {
    BodyImpulseTotal& total = impulses_[impulse.body];
    total.body = impulse.body;
    total.linear += impulse.linear;
    total.angular += impulse.angular;
  }
  DrainTickRecords();
  stats->steps = steps_;
  stats->step_ms_p50 = Percentile(step_ms_, 50.0);
  stats->step_ms_p99 = Percentile(step_ms_, 99.0);
  stats->step_ms_max = step_ms_.empty() ? 0.0 : *std::max_element(step_ms_.begin(), step_ms_.end());
  stats->ir_status = ir_status_;
  for (const std::string& line : state_->world.LoadWarnings()) stats->warnings.push_back(line);
  for (std::string& line : state_->world.SimulatorWarnings()) {
    stats->warnings.push_back(std::move(line));
  }
  for (auto& [body, total] : impulses_) {
    total.name = state_->world.body(body).name;
    stats->impulses.push_back(total);
  }
}

void FillHapticStats(const HapticCounters& c, RunStats* stats) {
  stats->ticks = c.ticks;
  stats->max_force = c.max_force;
  stats->max_torque = c.max_torque;
  stats->fault_nonfinite_wrench = c.nonfinite_wrench;
  stats->fault_nonfinite_device = c.nonfinite_device;
  stats->force_clamped = c.force_clamped;
  stats->torque_clamped = c.torque_clamped;
  stats->watchdog_ticks = c.watchdog_ticks;
  stats->final_wrench = c.last_displayed;
  stats->stopped = c.stopped;
  stats->dropped_tick_records = c.dropped_tick_records;
  stats->dropped_reports = c.dropped_reports;
}

double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  const double rank = p / 100.0 * static_cast<double>(values.size() - 1);
  const auto index = static_cast<std::size_t>(std::llround(rank));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                   values.end());
  return values[index];
}

}  // namespace mrh::engine::internal
