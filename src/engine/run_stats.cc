// SPDX-License-Identifier: Apache-2.0
// What every scheduler shares: the physics thread's loop and the statistics tail of a run.
#include <algorithm>
#include <string>
#include <utility>

#include "engine_impl.h"
#include "mrh/engine/rt_clock.h"

namespace mrh::engine::internal {

PhysicsSide EngineState::MakePhysicsSide(physics::Recorder* recorder) {
  body_pose_tap.set_next(recorder);
  PhysicsSide::Exchange exchange{&snapshots, &reports, &tick_records};
  for (const auto& lane : lanes) {
    exchange.more_snapshots.push_back(&lane->snapshots);
    exchange.more_reports.push_back(&lane->reports);
  }
  return PhysicsSide(method.physics.get(), &world, exchange, &body_pose_tap,
                     settings.safety.max_body_speed);
}

void RunPhysicsThread(PhysicsSide& physics, const std::atomic<bool>& done) {
  // The physics thread polls for the end of a haptic period this often while it waits.
  constexpr std::int64_t kPollNs = 100'000;
  for (std::int64_t k = 0;; ++k) {
    physics.Step(k);
    while (physics.TakeReports() == 0) {
      if (done.load(std::memory_order_acquire)) return;
      // The period's ticks reach the recorder as they come (still before OnStep of step k):
      // a live view then lags the haptic thread by a poll, not a period, and shows the ticks
      // of a haptic loop that holds mid-period (`mrh view --at`).
      physics.DrainTickRecords();
      SleepUntilNs(NowNs() + kPollNs, 0);
    }
    physics.Publish();
    physics.RecordStep();
  }
}

namespace {

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

void FillMethodStatus(const HapticCounters& c, const Method& method, RunStats* stats) {
  for (std::size_t i = 0; i < c.method_status_ticks.size(); ++i) {
    const bool named = i < method.status_bits.size() && !method.status_bits[i].empty();
    if (!named && c.method_status_ticks[i] == 0) continue;
    stats->method_status.emplace_back(
        named ? method.status_bits[i] : method.name + ".bit" + std::to_string(i),
        c.method_status_ticks[i]);
  }
}

void FillPhysicsStats(PhysicsSide& physics, RunStats* stats) {
  physics::PhysicsStats p;
  physics.Finish(&p);
  stats->steps = p.steps;
  stats->step_ms_p50 = p.step_ms_p50;
  stats->step_ms_p99 = p.step_ms_p99;
  stats->step_ms_max = p.step_ms_max;
  stats->ir_status = p.ir_status;
  stats->phase_ms = p.phase_total;
  for (std::string& w : p.warnings) stats->warnings.push_back(std::move(w));
  stats->impulses = std::move(p.impulses);
}

PointerRunStats PointerStats(const HapticCounters& c, const std::string& body,
                             const device::Device& device) {
  PointerRunStats p;
  p.body = body;
  p.max_force = c.max_force;
  p.max_torque = c.max_torque;
  p.mean_force = c.ticks > 0 ? c.sum_force / static_cast<double>(c.ticks) : 0.0;
  p.force_clamped = c.force_clamped;
  p.torque_clamped = c.torque_clamped;
  p.watchdog_ticks = c.watchdog_ticks;
  p.fault_nonfinite_wrench = c.nonfinite_wrench;
  p.fault_nonfinite_device = c.nonfinite_device;
  p.final_wrench = c.last_displayed;
  p.device = device.counters();
  return p;
}

// Several pointers: the totals count every pointer (the tick count stays pointer 0's: one tick
// renders all pointers), and each pointer gets its own block.
void FillPointerStats(EngineState& state, RunStats* stats) {
  stats->pointers.push_back(PointerStats(state.haptic->counters(),
                                         state.world.body(state.pointer_body).name, *state.device));
  for (const auto& lane : state.lanes) {
    const HapticCounters& c = lane->haptic->counters();
    stats->pointers.push_back(
        PointerStats(c, state.world.body(lane->pointer_body).name, *lane->device));
    stats->max_force = std::max(stats->max_force, c.max_force);
    stats->max_torque = std::max(stats->max_torque, c.max_torque);
    stats->fault_nonfinite_wrench += c.nonfinite_wrench;
    stats->fault_nonfinite_device += c.nonfinite_device;
    stats->force_clamped += c.force_clamped;
    stats->torque_clamped += c.torque_clamped;
    stats->watchdog_ticks += c.watchdog_ticks;
    stats->dropped_tick_records += c.dropped_tick_records;
    stats->dropped_reports += c.dropped_reports;
  }
}

}  // namespace

void FillRunStats(EngineState& state, PhysicsSide& physics, settings::Mode mode, double sim_time,
                  double wall_time, double rate_time, RunStats* stats) {
  FillPhysicsStats(physics, stats);
  FillHapticStats(state.haptic->counters(), stats);
  FillMethodStatus(state.haptic->counters(), state.method, stats);
  if (!state.lanes.empty()) FillPointerStats(state, stats);
  stats->method = state.method.name;
  stats->device = state.device->counters();
  stats->mode = mode;
  stats->physics_dt = state.settings.physics_dt;
  stats->haptic_dt = state.settings.haptic_dt;
  stats->sim_time = sim_time;
  stats->wall_time = wall_time;
  if (rate_time > 0.0) {
    stats->haptic_rate_hz = static_cast<double>(stats->ticks) / rate_time;
    stats->physics_rate_hz = static_cast<double>(stats->steps) / rate_time;
  }
}

}  // namespace mrh::engine::internal
