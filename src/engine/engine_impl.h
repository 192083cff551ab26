// SPDX-License-Identifier: Apache-2.0
// Private state of the engine shared by the lockstep, real-time and embedded schedulers.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "mrh/core/spsc_ring.h"
#include "mrh/core/stats.h"
#include "mrh/core/triple_buffer.h"
#include "mrh/engine/engine.h"
#include "mrh/engine/method.h"
#include "mrh/haptic/haptic_side.h"
#include "mrh/physics/physics_side.h"
#include "mrh/world/world.h"
#include "pose_tap.h"

namespace mrh::engine::internal {

using haptic::HapticCounters;
using haptic::HapticSide;
using physics::PhysicsSide;

/// Everything a run owns. The physics half (world, method.physics, recorder) and the haptic
/// half (HapticSide over method.haptic) touch disjoint members; they meet only in the exchange
/// buffers.
/// Pointer i >= 1 of a several-pointer run: its own device, haptic half, safety
/// layer and exchange buffers. Pointer 0 lives in EngineState itself.
struct PointerLane {
  PointerLane(std::unique_ptr<device::Device> device, const device::Calibration& calibration);

  settings::EngineSettings settings;  ///< the engine's, with this pointer's body and rendering
  std::unique_ptr<device::Device> device;
  device::Calibration calibration;
  std::unique_ptr<haptic::MethodHaptic> haptic_method;
  int pointer_body = -1;
  double pointer_radius = 0.0;
  TripleBuffer<ir::PhysicsSnapshot> snapshots;
  SpscRing<ir::HapticReport> reports;
  std::optional<HapticSide> haptic;
};

struct EngineState {
  /// devices[i] and calibrations[i] drive pointer i (one of each for one pointer).
  EngineState(world::World world, std::vector<std::unique_ptr<device::Device>> devices,
              const std::vector<device::Calibration>& calibrations,
              const settings::EngineSettings& settings);
  /// One pointer.
  EngineState(world::World world, std::unique_ptr<device::Device> device,
              const device::Calibration& calibration, const settings::EngineSettings& settings);
  void MakeMethodForSettings();
  /// Builds pointers 1, 2, ...'s haptic halves (after MakeMethodForSettings).
  void MakeLaneMethods();

  /// One haptic tick of every pointer, pointer 0 first. RT-safe.
  void TickAll(double t) noexcept;
  /// Stops every pointer's haptic side. RT-safe.
  void StopAll() noexcept;
  /// Opens / closes every device.
  void OpenDevices();
  void CloseDevices();

  /// A physics side over this state's world, method and exchange.
  PhysicsSide MakePhysicsSide(physics::Recorder* recorder);

  settings::EngineSettings settings;
  world::World world;
  std::unique_ptr<device::Device> device;
  device::Calibration calibration;
  Method method;
  int pointer_body = -1;
  double pointer_radius = 0.0;
  int ticks_per_step = 1;
  bool has_run = false;
  /// Engine::RequestStop: read by the lockstep loop per period and the haptic thread per tick.
  std::atomic<bool> stop_requested{false};
  static_assert(std::atomic<bool>::is_always_lock_free, "RequestStop must be signal-safe");

  TripleBuffer<ir::PhysicsSnapshot> snapshots;
  SpscRing<ir::HapticReport> reports;
  SpscRing<ir::TickRecord> tick_records;
  std::optional<HapticSide> haptic;
  /// Pointers 1, 2, ... (empty with one pointer).
  std::vector<std::unique_ptr<PointerLane>> lanes;
  /// physics side → Engine::ReadBodyPoses (one reader thread), written by body_pose_tap, which
  /// every physics side records through first.
  TripleBuffer<BodyPoses> body_poses;
  PoseTap body_pose_tap{&body_poses};
};

/// The real-time physics thread's loop: step k, wait (polling, never blocking the haptic
/// thread) for the end of haptic period k, exchange, record; returns once `done` is set and no
/// report is pending.
void RunPhysicsThread(PhysicsSide& physics, const std::atomic<bool>& done);

/// Starts the physics side from every pointer's initial device reading.
void StartPhysics(EngineState& state, PhysicsSide& physics);

/// The statistics tail common to every scheduler: the physics side's and the haptic counters'
/// share, the method's status bits, the method, mode and time steps, sim_time and wall_time (s),
/// and the tick and step rates per `rate_time` s (sim time in lockstep, wall time otherwise; no
/// rates when it is 0). Moves the physics side's warnings and impulses into `stats`.
void FillRunStats(EngineState& state, PhysicsSide& physics, settings::Mode mode, double sim_time,
                  double wall_time, double rate_time, RunStats* stats);

using mrh::Percentile;

/// State of an embedded run (Engine::Start / Tick / Stop).
struct EmbeddedRun;
void DestroyEmbeddedRun(EmbeddedRun* run);

RunStats RunLockstep(EngineState& state, physics::Recorder* recorder,
                     const Engine::ProgressFn& progress);
RunStats RunRealtime(EngineState& state, physics::Recorder* recorder,
                     const Engine::ProgressFn& progress);

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
