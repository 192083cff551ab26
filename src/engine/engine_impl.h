// SPDX-License-Identifier: Apache-2.0
// Private state of the engine shared by the lockstep and real-time schedulers.
#pragma once

#include <atomic>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "haptic_side.h"
#include "mrh/core/spsc_ring.h"
#include "mrh/core/triple_buffer.h"
#include "mrh/engine/engine.h"
#include "mrh/engine/method.h"
#include "mrh/world/world.h"

namespace mrh::engine::internal {

/// Everything a run owns. The physics half (world, method physics calls, recorder) and the
/// haptic half (HapticSide) touch disjoint members; they meet only in the exchange buffers.
struct EngineState {
  EngineState(world::World world, std::unique_ptr<device::Device> device,
              const device::Calibration& calibration, const EngineSettings& settings);
  void MakeMethodForSettings();

  EngineSettings settings;
  world::World world;
  std::unique_ptr<device::Device> device;
  device::Calibration calibration;
  std::unique_ptr<Method> method;
  int pointer_body = -1;
  double pointer_radius = 0.0;
  int ticks_per_step = 1;
  bool has_run = false;

  TripleBuffer<ir::PhysicsSnapshot> snapshots;
  SpscRing<ir::HapticReport> reports;
  SpscRing<TickRecord> tick_records;
  std::optional<HapticSide> haptic;
};

/// The physics side of a run: steps, drains the exchange, records and keeps statistics.
/// Physics thread (or the lockstep loop) only.
class PhysicsSide {
 public:
  PhysicsSide(EngineState* state, Recorder* recorder);

  /// Publishes the snapshot of the initial state (for haptic period 0).
  void Start();
  /// Runs physics step k with `input` (the merged report of period k−1) into the write slot.
  void Step(std::int64_t k);
  /// Pops every pending report into the next step's input; returns how many there were.
  int TakeReports();
  /// Makes the finished step's snapshot current for the haptic side.
  void Publish() { state_->snapshots.Publish(); }
  /// Writes the finished step and all pending tick records to the recorder.
  void RecordStep();
  void DrainTickRecords();
  /// The real-time physics thread's loop: step k, wait (polling, never blocking the haptic
  /// thread) for the end of haptic period k, exchange, record; returns once `done` is set and no
  /// report is pending.
  void RunThread(const std::atomic<bool>& done);
  /// Fills the statistics this side owns.
  void Finish(RunStats* stats);

  std::int64_t steps() const { return steps_; }

 private:
  EngineState* state_;
  Recorder* recorder_;
  ir::HapticReport input_;
  ir::HapticReport popped_;
  StepRecord last_step_;
  std::int64_t steps_ = 0;
  std::vector<double> step_ms_;
  std::uint32_t ir_status_ = 0;
  std::map<int, BodyImpulseTotal> impulses_;
};

/// Fills RunStats fields common to both modes from the haptic counters.
void FillHapticStats(const HapticCounters& counters, RunStats* stats);

/// p-th percentile (0..100) of `values` (copied and partially sorted). 0 for an empty input.
double Percentile(std::vector<double> values, double p);

/// State of an embedded run (Engine::Start / Tick / Stop).
struct EmbeddedRun;
void DestroyEmbeddedRun(EmbeddedRun* run);

RunStats RunLockstep(EngineState& state, Recorder* recorder, const Engine::ProgressFn& progress);
RunStats RunRealtime(EngineState& state, Recorder* recorder, const Engine::ProgressFn& progress);

}  // namespace mrh::engine::internal

namespace mrh::engine {
struct Engine::Impl {
  std::unique_ptr<internal::EngineState> state;
  // Embedded runs (Start / Tick / Stop). Defined in embedded.cc.
  struct EmbeddedDeleter {
    void operator()(internal::EmbeddedRun* run) const { internal::DestroyEmbeddedRun(run); }
  };
  std::unique_ptr<internal::EmbeddedRun, EmbeddedDeleter> embedded;
};
}  // namespace mrh::engine
