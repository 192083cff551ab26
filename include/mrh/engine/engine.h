// SPDX-License-Identifier: Apache-2.0
// The multi-rate engine: one scheduler, lockstep or real-time, driving a Method and a Device.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/device/calibration.h"
#include "mrh/device/device.h"
#include "mrh/engine/settings.h"

namespace mrh::world {
class World;
}

namespace mrh::ir {
struct PhysicsSnapshot;
}

namespace mrh::engine {

/// One haptic tick as recorded (world frame).
struct TickRecord {
  std::int64_t tick = 0;
  double t = 0.0;                 ///< s
  Pose X_WP;                      ///< pointer (device tool) pose
  Pose X_WQ;                      ///< proxy pose; equals X_WP when the method has no proxy
  Wrench displayed_W;             ///< wrench sent to the device, after the safety layer
  Wrench rendered_W;              ///< wrench the method rendered (what the physics saw)
  int contacts = 0;
  std::uint32_t safety_bits = 0;  ///< device::SafetyBits
};

/// One physics step as recorded.
struct StepRecord {
  std::int64_t step = 0;
  double t = 0.0;                 ///< simulation time at the end of the step (s)
  double compute_ms = 0.0;        ///< wall time of the physics step (ms)
  int sim_contacts = 0;           ///< MuJoCo contacts
  int neighbors = 0;              ///< neighbor bodies in the snapshot
  int point_contacts = 0;         ///< IR contacts in the snapshot
  int solver_iterations = 0;
};

/// Receives records on a non-RT thread (the physics thread, or the lockstep loop), in order.
class Recorder {
 public:
  virtual ~Recorder() = default;
  virtual void OnTick(const TickRecord& tick) = 0;
  /// Called after each physics step with the world in its post-step state.
  virtual void OnStep(const StepRecord& step, const world::World& world) = 0;
  /// Called with each snapshot the physics side produces for the haptic thread (the initial one,
  /// then one per physics step, before it is published): the IR the method renders against.
  /// Default: ignored.
  virtual void OnSnapshot(const ir::PhysicsSnapshot& snapshot) { (void)snapshot; }
};

/// Total reaction impulse the pointer delivered to one body over the run (world frame).
struct BodyImpulseTotal {
  int body = -1;
  std::string name;
  Vec3 linear = Vec3::Zero();     ///< N·s
  Vec3 angular = Vec3::Zero();    ///< N·m·s about the COM
};

/// What a run did. Filled by Engine::Run.
struct RunStats {
  std::string method;
  Mode mode = Mode::kLockstep;
  double physics_dt = 0.0, haptic_dt = 0.0;  ///< s, as configured
  double sim_time = 0.0;                     ///< simulated time covered (s)
  double wall_time = 0.0;                    ///< s
  std::int64_t ticks = 0, steps = 0;
  double haptic_rate_hz = 0.0;               ///< achieved (ticks / wall time in real time)
  double physics_rate_hz = 0.0;
  std::int64_t overruns = 0;                 ///< real time: ticks that started a period late
  double jitter_p50_us = 0.0, jitter_p99_us = 0.0, jitter_max_us = 0.0;  ///< |period − dt|
  double step_ms_p50 = 0.0, step_ms_p99 = 0.0, step_ms_max = 0.0;
  double max_force = 0.0;                    ///< N, displayed
  double max_torque = 0.0;                   ///< N·m, displayed
  std::int64_t fault_nonfinite_wrench = 0, fault_nonfinite_device = 0;
  std::int64_t force_clamped = 0, torque_clamped = 0, watchdog_ticks = 0;
  std::int64_t dropped_tick_records = 0, dropped_reports = 0;
  std::uint32_t ir_status = 0;               ///< ir::StatusBits seen
  /// The last wrench sent to the device (world frame, N and N·m): zero when the run ended with
  /// the stop (`stopped`), which commands zero whatever was rendered last.
  Wrench final_wrench;
  bool stopped = false;
  bool realtime_priority = false;            ///< SCHED_FIFO + mlockall granted
  std::vector<BodyImpulseTotal> impulses;
  std::vector<std::string> warnings;
};

/// Runs a session: owns the world, the method and the device.
class Engine {
 public:
  /// @throws mrh::InvalidArgument for bad settings or an unknown method; mrh::SceneError if the
  /// scene lacks the pointer body or the pointer radius cannot be determined.
  Engine(world::World world, std::unique_ptr<device::Device> device,
         const device::Calibration& calibration, const EngineSettings& settings);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  using ProgressFn = std::function<void(double fraction)>;

  /// Runs for settings.duration in the configured mode. `recorder` may be null. `progress` is
  /// called from the calling thread with the fraction done. @throws mrh::RuntimeError on I/O or
  /// an unrecoverable physics failure.
  RunStats Run(Recorder* recorder, const ProgressFn& progress = {});

  /// Embedding in the caller's own servo loop: the calling thread becomes the haptic thread.
  /// Needs a device::ExternalDevice. Real-time mode starts the physics thread; lockstep runs
  /// each physics step inline in Tick() at period boundaries (deterministic, not RT-safe).
  /// @throws mrh::InvalidArgument if the device is not external; mrh::RuntimeError if the engine
  /// has already run.
  void Start(Recorder* recorder = nullptr);

  /// One haptic tick at time t (s since Start): feeds `reading` (device frame) to the external
  /// device, renders, and returns the wrench to display (device frame, after the safety layer).
  /// RT-safe in real-time mode. @pre Start() was called.
  Wrench Tick(double t, const device::DeviceState& reading);

  /// Ends an embedded run (zero output, physics thread joined) and returns its statistics.
  RunStats Stop();

  const world::World& world() const;
  const EngineSettings& settings() const;
  double pointer_radius() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrh::engine
