// SPDX-License-Identifier: Apache-2.0
// The viewer's haptic thread: reads the input device, ticks the embedded engine, commands back.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <limits>
#include <thread>

#include "mrh/core/triple_buffer.h"
#include "mrh/device/device.h"
#include "mrh/engine/engine.h"

namespace mrh::viewer::internal {

/// Timing of the haptic thread: counters since Start and statistics of its last full window.
struct LoopStats {
  std::int64_t ticks = 0;       ///< ticks since Start
  std::int64_t overruns = 0;    ///< periods started more than one period late (skipped ahead)
  double rate_hz = 0.0;         ///< ticks per wall second over the window
  double jitter_mean_us = 0.0;  ///< |period − dt| over the window
  double jitter_p99_us = 0.0;
  double jitter_max_us = 0.0;
  bool fifo = false;  ///< the thread runs with SCHED_FIFO priority
};

/// Runs engine.Tick at the engine's haptic_dt on its own thread, the way the engine's own
/// real-time mode runs its haptic thread (src/engine/realtime.cc): absolute CLOCK_MONOTONIC
/// deadlines with engine::SleepUntilNs (kernel sleep, then a spin), SCHED_FIFO at
/// engine::kHapticFifoPriority on request, and skip-ahead after an overrun. The engine must have
/// been Start()ed on the calling thread. Time advances only by ticks run (virtual time
/// t = ticks · dt), so pausing freezes the session and the device together.
///
/// The UI controls it through atomics. The haptic thread keeps only raw period samples: it
/// hands each full window of them to the UI thread through a triple buffer, and ReadStats()
/// computes the percentiles there. Neither thread ever waits for the other.
class HapticLoop {
 public:
  /// Period samples per statistics window (1 s at 1 kHz).
  static constexpr std::size_t kWindow = 1000;

  HapticLoop() = default;

  ~HapticLoop() { Stop(); }

  HapticLoop(const HapticLoop&) = delete;
  HapticLoop& operator=(const HapticLoop&) = delete;

  /// Starts the thread (stopping a running one first) with fresh counters; the pause state
  /// carries over. Each tick: reading = source.Read(t); w = engine.Tick(t, reading);
  /// source.SetWrench(w). Both must outlive Stop(). With `fifo`, the thread asks for SCHED_FIFO
  /// priority (and runs at normal priority if refused; LoopStats::fifo tells). `dt` in s, > 0.
  /// Not RT-safe; UI thread.
  void Start(engine::Engine* engine, device::Device* source, double dt, bool fifo);

  /// Ends the thread (joins). Safe to call when not running. UI thread.
  void Stop();

  /// Pauses or resumes. Either way, step requests not yet run are dropped, so that presses
  /// made during one pause never run in the next. UI thread.
  void set_paused(bool paused) {
    step_budget_.store(0);
    paused_.store(paused);
  }

  bool paused() const { return paused_.load(); }

  /// While paused: runs `ticks` more ticks at the loop's period, then holds again. Ignored when
  /// not paused. UI thread.
  void StepTicks(int ticks) {
    if (paused_.load() && ticks > 0) step_budget_.fetch_add(ticks);
  }

  /// Holds the loop, as a pause does, once `ticks` ticks have run since Start: the session then
  /// stands at virtual time ticks · dt, its last reading at (ticks − 1) · dt. Set it before
  /// Start to hold at an exact tick; it carries over restarts. A negative value never holds (the
  /// default). Step requests made while paused still run past it. Any thread.
  void HoldAtTick(std::int64_t ticks) { hold_at_.store(ticks < 0 ? kNever : ticks); }

  /// True once the loop has reached its HoldAtTick tick (any thread).
  bool holding() const { return ticks() >= hold_at_.load(); }

  /// Ticks run since Start (any thread).
  std::int64_t ticks() const { return ticks_.load(std::memory_order_relaxed); }

  /// Periods since Start in which the thread held (paused, no step budget): once it grows after
  /// set_paused(true), the pause has taken effect (any thread).
  std::int64_t held_periods() const { return held_.load(std::memory_order_acquire); }

  /// The counters now and the statistics of the newest full window (computed here, on the
  /// calling thread, from the window's raw samples). Not RT-safe; one thread only (the UI).
  LoopStats ReadStats();

 private:
  // One window of raw |period − dt| samples, as the haptic thread hands it over.
  struct Window {
    std::array<double, kWindow> jitter_us{};
    double duration_s = 0.0;  // wall time the window's kWindow periods took
  };

  void Run(engine::Engine* engine, device::Device* source, double dt) noexcept;
  bool TakeStep() noexcept;
  void Record(double period_error_us, std::int64_t now_ns) noexcept;

  std::thread thread_;
  std::atomic<bool> quit_{false};
  static constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();
  std::atomic<bool> paused_{false};
  std::atomic<std::int64_t> hold_at_{kNever};
  std::atomic<int> step_budget_{0};
  std::atomic<std::int64_t> ticks_{0};
  std::atomic<std::int64_t> overruns_{0};
  std::atomic<std::int64_t> held_{0};
  std::atomic<bool> fifo_{false};
  TripleBuffer<Window> windows_;

  // Haptic-thread state.
  std::size_t samples_ = 0;  // samples in windows_.write_slot()
  std::int64_t window_start_ns_ = 0;

  // UI-thread state.
  std::array<double, kWindow> scratch_{};
  LoopStats window_stats_;
};

}  // namespace mrh::viewer::internal
