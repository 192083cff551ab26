// SPDX-License-Identifier: Apache-2.0
// The multi-rate engine: one scheduler, lockstep or real-time, driving a Method and a Device.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/device/calibration.h"
#include "mrh/device/device.h"
#include "mrh/engine/body_poses.h"
#include "mrh/haptic/method_haptic.h"
#include "mrh/ir/tick_record.h"
#include "mrh/physics/method_physics.h"
#include "mrh/physics/recorder.h"
#include "mrh/settings/settings.h"

namespace mrh::world {
class World;
}

namespace mrh::engine {

/// One pointer's share of a run with several pointers (RunStats::pointers).
struct PointerRunStats {
  std::string body;         ///< the pointer's mocap body
  double max_force = 0.0;   ///< N, displayed
  double max_torque = 0.0;  ///< N·m, displayed
  double mean_force = 0.0;  ///< N, mean |displayed force| over the ticks
  std::int64_t force_clamped = 0, torque_clamped = 0, watchdog_ticks = 0;
  std::int64_t fault_nonfinite_wrench = 0, fault_nonfinite_device = 0;
  Wrench final_wrench;            ///< world frame
  device::DeviceCounters device;  ///< this pointer's device's counters
};

/// What a run did. Filled by Engine::Run.
struct RunStats {
  std::string method;
  settings::Mode mode = settings::Mode::kLockstep;
  double physics_dt = 0.0, haptic_dt = 0.0;  ///< s, as configured
  double sim_time = 0.0;                     ///< simulated time covered (s)
  double wall_time = 0.0;                    ///< s
  std::int64_t ticks = 0, steps = 0;
  double haptic_rate_hz = 0.0;  ///< achieved (ticks / wall time in real time)
  double physics_rate_hz = 0.0;
  std::int64_t overruns = 0;  ///< real time: ticks that started a period late
  double jitter_p50_us = 0.0, jitter_p99_us = 0.0, jitter_max_us = 0.0;  ///< |period − dt|
  double step_ms_p50 = 0.0, step_ms_p99 = 0.0, step_ms_max = 0.0;
  double max_force = 0.0;   ///< N, displayed
  double max_torque = 0.0;  ///< N·m, displayed
  std::int64_t fault_nonfinite_wrench = 0, fault_nonfinite_device = 0;
  std::int64_t force_clamped = 0, torque_clamped = 0, watchdog_ticks = 0;
  std::int64_t dropped_tick_records = 0, dropped_reports = 0;
  std::uint32_t ir_status = 0;  ///< ir::StatusBits seen
  /// The last wrench sent to the device (world frame, N and N·m): zero when the run ended with
  /// the stop (`stopped`), which commands zero whatever was rendered last.
  Wrench final_wrench;
  bool stopped = false;
  /// Method status (TickOutput::status), namespaced per method: for each bit the method names
  /// (Method::status_bits, e.g. "proxy.not_converged"), the ticks on which it was set.
  std::vector<std::pair<std::string, std::int64_t>> method_status;
  /// The physics phases (MuJoCo step, IR build, local-model export, sync) summed over the run
  /// (ms, wall clock); per step in StepRecord / steps.csv.
  physics::PhaseTimes phase_ms;
  bool realtime_priority = false;  ///< SCHED_FIFO + mlockall granted
  /// The device's own counters at the end of the run (vendor errors, network packets).
  device::DeviceCounters device;
  std::vector<physics::BodyImpulseTotal> impulses;
  std::vector<std::string> warnings;
  /// Several pointers: one entry per pointer, in order; the fields above then sum
  /// the pointers' counters and take the largest force and pointer 0's device and final
  /// wrench. Empty with one pointer.
  std::vector<PointerRunStats> pointers;
};

/// Runs a session: owns the world, the method and the device.
class Engine {
 public:
  /// @throws mrh::InvalidArgument for bad settings or an unknown method; mrh::SceneError if the
  /// scene lacks the pointer body or the pointer radius cannot be determined.
  Engine(world::World world, std::unique_ptr<device::Device> device,
         const device::Calibration& calibration, const settings::EngineSettings& settings);
  /// Several pointers: devices[i] and calibrations[i] drive settings.pointers[i]
  /// (one each; a single device is the one-pointer engine above). @throws as above, and
  /// mrh::InvalidArgument when the counts differ or the method renders only one pointer.
  Engine(world::World world, std::vector<std::unique_ptr<device::Device>> devices,
         const std::vector<device::Calibration>& calibrations,
         const settings::EngineSettings& settings);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  using ProgressFn = std::function<void(double fraction)>;

  /// Runs for settings.duration in the configured mode. `recorder` may be null. `progress` is
  /// called from the calling thread with the fraction done. @throws mrh::RuntimeError on I/O or
  /// an unrecoverable physics failure.
  RunStats Run(physics::Recorder* recorder, const ProgressFn& progress = {});

  /// Asks Run() to end early, from any thread or a signal handler: lockstep stops before its next
  /// physics period, real time at its next haptic tick, and Run then returns the statistics of
  /// what ran (sim_time says how far it got). A request made before Run() ends that run at once.
  /// Embedded runs (Start/Tick/Stop) ignore it: their caller owns the loop. Thread-safe,
  /// async-signal-safe and RT-safe (one lock-free atomic store).
  void RequestStop() noexcept;

  /// Embedding in the caller's own servo loop: the calling thread becomes the haptic thread.
  /// Needs a device::ExternalDevice; with several pointers exactly one pointer has it (the one
  /// the caller's loop drives) and the others read their own devices in every Tick. Real-time
  /// mode starts the physics thread; lockstep runs each physics step inline in Tick() at period
  /// boundaries (deterministic, not RT-safe).
  /// @throws mrh::InvalidArgument if no device, or more than one, is external;
  /// mrh::RuntimeError if the engine has already run.
  void Start(physics::Recorder* recorder = nullptr);

  /// One haptic tick at time t (s since Start): feeds `reading` (device frame) to the external
  /// device, renders every pointer, and returns the external device's pointer's wrench to display
  /// (device frame, after the safety layer).
  /// RT-safe in real-time mode. @pre Start() was called.
  Wrench Tick(double t, const device::DeviceState& reading) noexcept;

  /// Ends an embedded run (zero output, physics thread joined) and returns its statistics.
  RunStats Stop();

  /// The newest body poses, for a renderer running beside the engine: copies the poses the
  /// physics side published after its latest step into *out and returns true if they are newer
  /// than those of the previous call. Before the first step (or without a run) it gives the
  /// scene's initial poses (step -1). Works in every mode (Run, and Start/Tick/Stop); poses
  /// change once per physics step (physics_dt), not per haptic tick.
  /// Thread safety: lock-free and wait-free through a triple buffer: it never blocks, and is
  /// never blocked by, the haptic or physics thread. Call it from one thread at a time (a single
  /// reader, e.g. your render thread; hand copies to others). It allocates only when *out has
  /// less capacity than the scene's body count (the first call): keep one BodyPoses and reuse it.
  bool ReadBodyPoses(BodyPoses* out);

  /// Scales the wrench displayed on the device from now on: the haptic thread reads the gain at
  /// the start of every tick and multiplies the method's rendered force and torque by it before
  /// the safety layer (which still clamps to the device's limits and ramps the start). 1 (the
  /// default) displays the rendered wrench; 0.5 halves it; 0 displays none. The objects still
  /// receive the full rendered reaction, and ticks.csv's displayed wrench is the scaled one.
  /// Thread safety: any thread, any time (before, during or after a run); one atomic store, so
  /// it never blocks the haptic thread, and the haptic thread never blocks on it.
  /// @throws mrh::InvalidArgument if gain is negative or not finite (the gain is unchanged).
  void SetDisplayGain(double gain);
  /// The gain set by SetDisplayGain (1 until set). Any thread.
  double display_gain() const;

  const world::World& world() const;
  /// What the method does not simulate as a user would expect, found at setup (e.g. a
  /// mechanism the local simulation cannot take); RunStats::warnings repeats them.
  std::vector<std::string> setup_warnings() const;
  const settings::EngineSettings& settings() const;
  double pointer_radius() const;
  /// Number of pointers (1 unless settings.pointers lists several) and their body names.
  int num_pointers() const;
  std::vector<std::string> pointer_names() const;

  /// The method's two halves, for observers (experiments, tests) that read a method's own
  /// details through the public accessors of mrh/haptic/methods.h and mrh/physics/*.h. Read the
  /// haptic half only from the haptic thread (in lockstep: the calling thread, e.g. inside the
  /// device's SetWrench) and the physics half only between steps or after the run.
  const haptic::MethodHaptic& haptic_method() const;
  const physics::MethodPhysics& physics_method() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mrh::engine
