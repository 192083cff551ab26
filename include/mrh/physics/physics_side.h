// SPDX-License-Identifier: Apache-2.0
// The physics thread's side of a run: one global step per call, exchange and statistics.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "mrh/core/spsc_ring.h"
#include "mrh/core/triple_buffer.h"
#include "mrh/ir/snapshot.h"
#include "mrh/ir/tick_record.h"
#include "mrh/physics/method_physics.h"
#include "mrh/physics/recorder.h"

namespace mrh::world {
class World;
}

namespace mrh::physics {

/// What the physics side contributes to a run's statistics (RunStats).
struct PhysicsStats {
  std::int64_t steps = 0;
  double step_ms_p50 = 0.0, step_ms_p99 = 0.0, step_ms_max = 0.0;
  std::uint32_t ir_status = 0;  ///< ir::StatusBits seen
  PhaseTimes phase_total;       ///< MethodPhysics::last_phases summed over the steps (ms)
  std::vector<BodyImpulseTotal> impulses;
  std::vector<std::string> warnings;
};

/// The physics side of a run: steps the method's physics half, drains the exchange, records and
/// keeps statistics. Physics thread (or the lockstep loop) only; not RT-safe. It meets the
/// haptic side only in the exchange buffers.
class PhysicsSide {
 public:
  struct Exchange {
    TripleBuffer<ir::PhysicsSnapshot>* snapshots;  ///< physics → haptic
    SpscRing<ir::HapticReport>* reports;           ///< haptic → physics
    SpscRing<ir::TickRecord>* tick_records;        ///< haptic → recorder
    /// Several pointers: pointers 1, 2, ...'s own snapshot buffers and report rings
    /// (pointer 0 uses the two above). Empty with one pointer.
    std::vector<TripleBuffer<ir::PhysicsSnapshot>*> more_snapshots = {};
    std::vector<SpscRing<ir::HapticReport>*> more_reports = {};
  };

  /// `recorder` may be null. `max_body_speed` (m/s) is the divergence guard of Step (see
  /// world::World::FindDivergence; <= 0: no speed test).
  PhysicsSide(MethodPhysics* method, world::World* world, const Exchange& exchange,
              Recorder* recorder, double max_body_speed);

  /// Publishes the snapshot of the initial state (for haptic period 0); `initial` carries the
  /// pointer's initial pose, and `more` those of pointers 1, 2, ... (one per
  /// Exchange::more_reports; empty with one pointer).
  void Start(const ir::HapticReport& initial, std::span<const ir::HapticReport> more = {});
  /// Runs physics step k with `input` (the merged report of period k−1) into the write slot.
  /// @throws mrh::RuntimeError (one line naming the scene, body, time and likely causes) when
  /// the simulation has diverged: the run ends as a fault, never goes on from a reset state.
  void Step(std::int64_t k);
  /// Pops every pending report into the next step's input; returns how many there were.
  int TakeReports();
  /// Makes the finished step's snapshots current for the haptic side.
  void Publish();
  /// Writes the finished step and all pending tick records to the recorder.
  void RecordStep();
  void DrainTickRecords();
  /// Fills the statistics this side owns (after the run).
  void Finish(PhysicsStats* stats);

  std::int64_t steps() const { return steps_; }

 private:
  void AddToTotals(const ir::HapticReport& report);
  void GatherLanes();
  void NoteStep(std::int64_t k, const ir::PhysicsSnapshot& out, double compute_ms);

  MethodPhysics* method_;
  world::World* world_;
  Exchange exchange_;
  Recorder* recorder_;
  double max_body_speed_;
  /// Pops lane `lane`'s pending reports into `input` (cleared first); returns how many.
  int TakeLaneReports(SpscRing<ir::HapticReport>* ring, ir::HapticReport* input);

  ir::HapticReport input_;
  std::vector<ir::HapticReport> more_input_;  ///< pointers 1, 2, ... (sized at construction)
  std::vector<const ir::HapticReport*> inputs_;
  std::vector<ir::PhysicsSnapshot*> outputs_;
  ir::HapticReport popped_;
  StepRecord last_step_;
  std::int64_t steps_ = 0;
  std::vector<double> step_ms_;
  std::uint32_t ir_status_ = 0;
  PhaseTimes phase_total_;
  std::map<int, BodyImpulseTotal> impulses_;
};

}  // namespace mrh::physics
