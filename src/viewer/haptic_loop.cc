// SPDX-License-Identifier: Apache-2.0
// HapticLoop: the engine's PeriodicDeadline at the haptic rate, raw jitter windows for the UI.
#include "viewer/haptic_loop.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "mrh/engine/rt_clock.h"

namespace mrh::viewer::internal {
namespace {

constexpr double kNsPerS = 1e9;

}  // namespace

void HapticLoop::Start(engine::Engine* engine, device::Device* source, double dt, bool fifo) {
  Stop();
  quit_.store(false);
  step_budget_.store(0);
  ticks_.store(0);
  overruns_.store(0);
  held_.store(0);
  fifo_.store(false);
  window_stats_ = LoopStats{};
  thread_ = std::thread([this, engine, source, dt, fifo] {
    // Refusal (no privileges) is not an error: the loop runs at normal priority and says so.
    std::string why;
    fifo_.store(fifo && engine::RequestFifoPriority(engine::kHapticFifoPriority, &why));
    Run(engine, source, dt);
  });
}

void HapticLoop::Stop() {
  quit_.store(true);
  if (thread_.joinable()) thread_.join();
}

bool HapticLoop::TakeStep() noexcept {
  // A compare-exchange, not load + fetch_sub: set_paused may zero the budget in between, and a
  // budget driven negative would swallow the next step request.
  int budget = step_budget_.load();
  while (budget > 0 && !step_budget_.compare_exchange_weak(budget, budget - 1)) {
  }
  return budget > 0;
}

void HapticLoop::Run(engine::Engine* engine, device::Device* source, double dt) noexcept {
  engine::PeriodicDeadline clock(static_cast<std::int64_t>(std::llround(dt * kNsPerS)));
  samples_ = 0;
  window_start_ns_ = clock.start_ns();
  std::int64_t ticks = 0;
  while (!quit_.load(std::memory_order_relaxed)) {
    const engine::PeriodicDeadline::Wake wake = clock.Next();
    if (wake.overrun) overruns_.fetch_add(1, std::memory_order_relaxed);
    const bool hold = paused_.load() || ticks >= hold_at_.load(std::memory_order_relaxed);
    if (hold && !TakeStep()) {
      window_start_ns_ = wake.now_ns;  // a pause is not slowness: restart the rate window
      samples_ = 0;
      held_.fetch_add(1, std::memory_order_release);  // orders the ticks_ store before it
      continue;
    }
    const double t = static_cast<double>(ticks) * dt;
    const device::DeviceState reading = source->Read(t);
    source->SetWrench(engine->Tick(t, reading));
    ++ticks;
    ticks_.store(ticks, std::memory_order_relaxed);
    Record(wake.period_error_us, wake.now_ns);
  }
}

void HapticLoop::Record(double period_error_us, std::int64_t now_ns) noexcept {
  Window& window = windows_.write_slot();
  window.jitter_us[samples_++] = period_error_us;
  if (samples_ < kWindow) return;
  // The window is full: hand it over as it is. Sorting for the percentile is the UI's work.
  window.duration_s = static_cast<double>(now_ns - window_start_ns_) / kNsPerS;
  windows_.Publish();
  samples_ = 0;
  window_start_ns_ = now_ns;
}

LoopStats HapticLoop::ReadStats() {
  if (windows_.Update()) {
    const Window& window = windows_.read_slot();
    std::copy(window.jitter_us.begin(), window.jitter_us.end(), scratch_.begin());
    const auto p99 = scratch_.begin() + static_cast<std::ptrdiff_t>(kWindow * 99 / 100);
    std::nth_element(scratch_.begin(), p99, scratch_.end());
    window_stats_.jitter_p99_us = *p99;
    window_stats_.jitter_max_us = *std::max_element(scratch_.begin(), scratch_.end());
    window_stats_.jitter_mean_us =
        std::accumulate(scratch_.begin(), scratch_.end(), 0.0) / static_cast<double>(kWindow);
    window_stats_.rate_hz =
        window.duration_s > 0.0 ? static_cast<double>(kWindow) / window.duration_s : 0.0;
  }
  LoopStats stats = window_stats_;
  stats.ticks = ticks_.load(std::memory_order_relaxed);
  stats.overruns = overruns_.load(std::memory_order_relaxed);
  stats.fifo = fifo_.load();
  return stats;
}

}  // namespace mrh::viewer::internal
