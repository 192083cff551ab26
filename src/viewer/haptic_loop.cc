// SPDX-License-Identifier: Apache-2.0
// HapticLoop: absolute-deadline periods, skip-ahead on overrun, windowed jitter statistics.
#include "viewer/haptic_loop.h"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

namespace mrh::viewer::internal {
namespace {

using Clock = std::chrono::steady_clock;

// The priority the engine gives its own haptic thread (src/engine/realtime.cc): above the
// physics and UI threads, which stay at normal priority.
constexpr int kFifoPriority = 80;

bool RequestFifo() noexcept {
  sched_param param{};
  param.sched_priority = kFifoPriority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
}

double Micros(Clock::duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

}  // namespace

void HapticLoop::Start(engine::Engine* engine, device::Device* source, double dt, bool fifo) {
  Stop();
  quit_.store(false);
  current_ = LoopStats{};
  samples_ = 0;
  thread_ = std::thread([this, engine, source, dt, fifo] {
    Run(engine, source, dt, fifo);
  });
}

void HapticLoop::Stop() {
  quit_.store(true);
  if (thread_.joinable()) thread_.join();
}

void HapticLoop::Run(engine::Engine* engine, device::Device* source, double dt,
                     bool fifo) noexcept {
  // Refusal (no privileges) is not an error: the loop runs at normal priority and says so.
  current_.fifo = fifo && RequestFifo();
  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt));
  Clock::time_point deadline = Clock::now();
  Clock::time_point last_wake = deadline;
  Clock::time_point window_start = deadline;
  std::int64_t ticks = 0;
  while (!quit_.load(std::memory_order_relaxed)) {
    deadline += period;
    std::this_thread::sleep_until(deadline);
    const Clock::time_point now = Clock::now();
    if (now - deadline > period) {
      // Overrun: skip the missed periods instead of bursting to catch up (STYLE §6.5).
      ++current_.overruns;
      deadline = now;
    }
    const double error_us = std::abs(Micros(now - last_wake - period));
    last_wake = now;
    if (paused_.load(std::memory_order_relaxed)) {
      if (step_budget_.load(std::memory_order_relaxed) <= 0) {
        window_start = now;  // a pause is not slowness: restart the rate window
        samples_ = 0;
        continue;
      }
      step_budget_.fetch_sub(1, std::memory_order_relaxed);
    }
    const double t = static_cast<double>(ticks) * dt;
    const device::DeviceState reading = source->Read(t);
    source->SetWrench(engine->Tick(t, reading));
    ++ticks;
    current_.ticks = ticks;
    Measure(error_us, std::chrono::duration<double>(now - window_start).count());
    if (samples_ == 0) window_start = now;
  }
}

void HapticLoop::Measure(double period_error_us, double window_s) noexcept {
  jitter_us_[samples_++] = period_error_us;
  if (samples_ < kWindow) return;
  // The window is full: publish its statistics (no allocation: fixed scratch array).
  std::copy(jitter_us_.begin(), jitter_us_.end(), scratch_.begin());
  const auto p99 = scratch_.begin() + static_cast<std::ptrdiff_t>(kWindow * 99 / 100);
  std::nth_element(scratch_.begin(), p99, scratch_.end());
  current_.jitter_p99_us = *p99;
  current_.jitter_max_us = *std::max_element(jitter_us_.begin(), jitter_us_.end());
  current_.jitter_mean_us =
      std::accumulate(jitter_us_.begin(), jitter_us_.end(), 0.0) / static_cast<double>(kWindow);
  current_.rate_hz = window_s > 0.0 ? static_cast<double>(kWindow) / window_s : 0.0;
  stats_.write_slot() = current_;
  stats_.Publish();
  samples_ = 0;
}

}  // namespace mrh::viewer::internal
