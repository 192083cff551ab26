// SPDX-License-Identifier: Apache-2.0
// Real-time scheduling: a haptic thread at haptic_dt against absolute deadlines and a physics
// thread that synchronizes with it at every period end without ever making it wait.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <string>
#include <thread>

#include "engine_impl.h"
#include "mrh/core/stats.h"
#include "mrh/engine/rt_clock.h"

namespace mrh::engine::internal {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;
// Room for jitter samples beyond the nominal tick count (start-up, rounding).
constexpr std::size_t kJitterSlack = 1024;

struct HapticTiming {
  std::vector<double> jitter_us;  // preallocated; |measured period − dt|
  std::size_t samples = 0;
  std::int64_t overruns = 0;
};

// The haptic thread: never waits on the physics side, never allocates.
void HapticLoop(EngineState& s, HapticTiming* timing, std::atomic<bool>* done,
                std::atomic<bool>* fifo_ok) {
  std::string why;
  if (s.settings.realtime_priority) fifo_ok->store(RequestFifoPriority(kHapticFifoPriority, &why));
  const auto dt_ns = static_cast<std::int64_t>(std::llround(s.settings.haptic_dt * kNsPerS));
  const auto duration_ns = static_cast<std::int64_t>(std::llround(s.settings.duration * kNsPerS));
  PeriodicDeadline clock(dt_ns);
  while (true) {
    const PeriodicDeadline::Wake wake = clock.Next();
    if (wake.overrun) ++timing->overruns;
    if (timing->samples < timing->jitter_us.size()) {
      timing->jitter_us[timing->samples++] = wake.period_error_us;
    }
    if (wake.deadline_ns - clock.start_ns() > duration_ns ||
        s.stop_requested.load(std::memory_order_relaxed)) {
      break;
    }
    s.TickAll(static_cast<double>(wake.deadline_ns - clock.start_ns()) / kNsPerS);
  }
  s.StopAll();
  done->store(true, std::memory_order_release);
}

// Both threads until the haptic one has run the session's duration; progress every 100 ms.
// A MuJoCo error on the physics thread (a RuntimeError) ends the physics side; the watchdog
// fades the force to zero, and the error is rethrown here once both threads are done.
void RunThreads(EngineState& s, PhysicsSide& physics, HapticTiming* timing,
                std::atomic<bool>* fifo_ok, std::int64_t wall0,
                const Engine::ProgressFn& progress) {
  std::atomic<bool> done{false};
  std::exception_ptr physics_error;
  std::thread physics_thread([&] {
    try {
      RunPhysicsThread(physics, done);
    } catch (...) {
      physics_error = std::current_exception();
    }
  });
  std::thread haptic_thread([&] {
    HapticLoop(s, timing, &done, fifo_ok);
  });
  while (!done.load(std::memory_order_acquire)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (progress) {
      progress(std::min(1.0, static_cast<double>(NowNs() - wall0) / kNsPerS / s.settings.duration));
    }
  }
  haptic_thread.join();
  physics_thread.join();
  if (physics_error) std::rethrow_exception(physics_error);
}

void FillJitter(const HapticTiming& timing, RunStats* stats) {
  std::vector<double> jitter(
      timing.jitter_us.begin(),
      timing.jitter_us.begin() + static_cast<std::ptrdiff_t>(timing.samples));
  stats->jitter_p50_us = Percentile(jitter, 50.0);
  stats->jitter_p99_us = Percentile(jitter, 99.0);
  stats->jitter_max_us = jitter.empty() ? 0.0 : *std::max_element(jitter.begin(), jitter.end());
  stats->overruns = timing.overruns;
}

}  // namespace

RunStats RunRealtime(EngineState& s, physics::Recorder* recorder,
                     const Engine::ProgressFn& progress) {
  RunStats stats;
  std::string why;
  const bool locked = s.settings.realtime_priority && LockAllMemory(&why);
  if (s.settings.realtime_priority && !locked) stats.warnings.push_back(why);
  HapticTiming timing;
  timing.jitter_us.resize(static_cast<std::size_t>(s.settings.duration / s.settings.haptic_dt) +
                          kJitterSlack);
  PhysicsSide physics = s.MakePhysicsSide(recorder);
  StartPhysics(s, physics);
  std::atomic<bool> fifo_ok{false};
  const std::int64_t wall0 = NowNs();
  try {
    RunThreads(s, physics, &timing, &fifo_ok, wall0, progress);
  } catch (...) {
    if (locked) UnlockAllMemory();
    throw;
  }
  if (locked) UnlockAllMemory();
  if (s.settings.realtime_priority && !fifo_ok.load()) {
    stats.warnings.push_back(
        "SCHED_FIFO refused for the haptic thread; running at normal priority");
  }
  for (const std::string& w : stats.warnings) spdlog::warn("{}", w);
  const double wall_time = static_cast<double>(NowNs() - wall0) / kNsPerS;
  FillRunStats(s, physics, settings::Mode::kRealtime, 0.0, wall_time, wall_time, &stats);
  stats.sim_time = static_cast<double>(stats.steps) * s.settings.physics_dt;  // as stepped
  FillJitter(timing, &stats);
  stats.realtime_priority = locked && fifo_ok.load();
  if (progress) progress(1.0);
  return stats;
}

}  // namespace mrh::engine::internal
