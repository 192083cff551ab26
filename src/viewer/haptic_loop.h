// SPDX-License-Identifier: Apache-2.0
// The viewer's haptic thread: reads the input device, ticks the embedded engine, commands back.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <thread>

#include "mrh/core/triple_buffer.h"
#include "mrh/device/device.h"
#include "mrh/engine/engine.h"

namespace mrh::viewer::internal {

/// Timing of the haptic thread over its last statistics window.
struct LoopStats {
  std::int64_t ticks = 0;       ///< ticks since Start
  std::int64_t overruns = 0;    ///< periods started more than one period late (skipped ahead)
  double rate_hz = 0.0;         ///< ticks per wall second over the window
  double jitter_mean_us = 0.0;  ///< |period − dt| over the window
  double jitter_p99_us = 0.0;
  double jitter_max_us = 0.0;
  bool fifo = false;  ///< the thread runs with SCHED_FIFO priority
};

/// Runs engine.Tick at the engine's haptic_dt against absolute deadlines on its own thread. The
/// engine must have been Start()ed on the calling thread. Time advances only by ticks run
/// (virtual time t = ticks · dt), so pausing freezes the session and the device together. The
/// UI controls it through atomics and reads LoopStats through a triple buffer: the haptic thread
/// never waits for the UI.
class HapticLoop {
 public:
  HapticLoop() = default;

  ~HapticLoop() { Stop(); }

  HapticLoop(const HapticLoop&) = delete;
  HapticLoop& operator=(const HapticLoop&) = delete;

  /// Starts the thread. Each tick: reading = source.Read(t); w = engine.Tick(t, reading);
  /// source.SetWrench(w). Both must outlive Stop(). With `fifo`, the thread asks for SCHED_FIFO
  /// priority (and runs at normal priority if refused; LoopStats::fifo tells).
  void Start(engine::Engine* engine, device::Device* source, double dt, bool fifo);
  /// Ends the thread (joins). Safe to call when not running.
  void Stop();

  void set_paused(bool paused) { paused_.store(paused, std::memory_order_relaxed); }

  bool paused() const { return paused_.load(std::memory_order_relaxed); }

  /// While paused: run `ticks` more ticks as fast as the period allows.
  void StepTicks(int ticks) { step_budget_.fetch_add(ticks, std::memory_order_relaxed); }

  /// UI thread: the newest statistics.
  const LoopStats& stats() {
    stats_.Update();
    return stats_.read_slot();
  }

 private:
  static constexpr std::size_t kWindow = 1000;  // ticks per statistics window (1 s at 1 kHz)

  void Run(engine::Engine* engine, device::Device* source, double dt, bool fifo) noexcept;
  void Measure(double period_error_us, double window_s) noexcept;

  std::thread thread_;
  std::atomic<bool> quit_{false};
  std::atomic<bool> paused_{false};
  std::atomic<int> step_budget_{0};

  // Haptic-thread state.
  LoopStats current_;
  std::array<double, kWindow> jitter_us_{};
  std::array<double, kWindow> scratch_{};
  std::size_t samples_ = 0;
  TripleBuffer<LoopStats> stats_;
};

}  // namespace mrh::viewer::internal
