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
#include "mrh/engine/rt_clock.h"

namespace mrh::engine::internal {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;
// Room for jitter samples beyond the nominal tick count (start-up, rounding).
constexpr std::size_t kJitterSlack = 1024;

struct HapticTiming {
  std::vector<double> jitter_us;   // preallocated; |measured period − dt|
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
  const std::int64_t start = NowNs();
  std::int64_t deadline = start;
  std::int64_t last_wake = start;
  while (true) {
    deadline += dt_ns;
    SleepUntilNs(deadline, kDeadlineSpinNs);
    const std::int64_t now = NowNs();
    if (now - deadline > dt_ns) {
      // Overrun: skip the missed ticks instead of bursting to catch up (STYLE §6.5).
      ++timing->overruns;
      deadline = now;
    }
    if (timing->samples < timing->jitter_us.size()) {
      timing->jitter_us[timing->samples++] =
          std::abs(static_cast<double>(now - last_wake - dt_ns)) * 1e-3;
    }
    last_wake = now;
    if (deadline - start > duration_ns) break;
    s.haptic->Tick(static_cast<double>(deadline - start) / kNsPerS);
  }
  s.haptic->Stop();
  done->store(true, std::memory_order_release);
}

}  // namespace

RunStats RunRealtime(EngineState& s, Recorder* recorder, const Engine::ProgressFn& progress) {
  RunStats stats;
  std::string why;
  const bool locked = s.settings.realtime_priority && LockAllMemory(&why);
  if (s.settings.realtime_priority && !locked) {
    stats.warnings.push_back(why);
  }
  HapticTiming timing;
  timing.jitter_us.resize(static_cast<std::size_t>(s.settings.duration / s.settings.haptic_dt) +
                          kJitterSlack);
  PhysicsSide physics = s.MakePhysicsSide(recorder);
  physics.Start(s.haptic->InitialReport(0.0));

  std::atomic<bool> done{false};
  std::atomic<bool> fifo_ok{false};
  const std::int64_t wall0 = NowNs();
  // A MuJoCo error on the physics thread (a RuntimeError) ends the physics side; the watchdog
  // fades the force to zero, and the error is rethrown here once both threads are done.
  std::exception_ptr physics_error;
  std::thread physics_thread([&] {
    try {
      RunPhysicsThread(physics, done);
    } catch (...) {
      physics_error = std::current_exception();
    }
  });
  std::thread haptic_thread([&] { HapticLoop(s, &timing, &done, &fifo_ok); });
  while (!done.load(std::memory_order_acquire)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (progress) {
      progress(std::min(1.0, static_cast<double>(NowNs() - wall0) / kNsPerS / s.settings.duration));
    }
  }
  haptic_thread.join();
  physics_thread.join();
  if (locked) UnlockAllMemory();
  if (physics_error) std::rethrow_exception(physics_error);

  if (s.settings.realtime_priority && !fifo_ok.load()) {
    stats.warnings.push_back("SCHED_FIFO refused for the haptic thread; running at normal priority");
  }
  for (const std::string& w : stats.warnings) spdlog::warn("{}", w);
  FillPhysicsStats(physics, &stats);
  FillHapticStats(s.haptic->counters(), &stats);
  FillMethodStatus(s.haptic->counters(), s.method, &stats);
  std::vector<double> jitter(timing.jitter_us.begin(),
                             timing.jitter_us.begin() + static_cast<std::ptrdiff_t>(timing.samples));
  stats.jitter_p50_us = Percentile(jitter, 50.0);
  stats.jitter_p99_us = Percentile(jitter, 99.0);
  stats.jitter_max_us = jitter.empty() ? 0.0 : *std::max_element(jitter.begin(), jitter.end());
  stats.overruns = timing.overruns;
  stats.realtime_priority = locked && fifo_ok.load();
  stats.method = s.method.name;
  stats.mode = Mode::kRealtime;
  stats.physics_dt = s.settings.physics_dt;
  stats.haptic_dt = s.settings.haptic_dt;
  stats.wall_time = static_cast<double>(NowNs() - wall0) / kNsPerS;
  stats.sim_time = static_cast<double>(stats.steps) * s.settings.physics_dt;
  stats.haptic_rate_hz = static_cast<double>(stats.ticks) / stats.wall_time;
  stats.physics_rate_hz = static_cast<double>(stats.steps) / stats.wall_time;
  if (progress) progress(1.0);
  return stats;
}

}  // namespace mrh::engine::internal
