// SPDX-License-Identifier: Apache-2.0
// Lockstep scheduling: the two-thread schedule of thesis §4.1.3 (fig. 4.5; the timing rule in
// docs/architecture.md) reproduced on one thread.
#include <chrono>
#include <cmath>

#include "engine_impl.h"

namespace mrh::engine::internal {
namespace {

// Progress callbacks at most this often (s of wall time).
constexpr double kProgressInterval = 0.1;

}  // namespace

// Physics step k and haptic period k are independent (step k reads period k−1's report; period k
// renders step k−1's snapshot), so running step k and then the n ticks of period k, and only
// then exchanging, reproduces the concurrent schedule exactly and deterministically.
RunStats RunLockstep(EngineState& state, physics::Recorder* recorder,
                     const Engine::ProgressFn& progress) {
  const auto wall0 = std::chrono::steady_clock::now();
  const int n = state.ticks_per_step;
  const double dt = state.settings.haptic_dt;
  const auto total_ticks = static_cast<std::int64_t>(std::llround(state.settings.duration / dt));
  const std::int64_t periods = (total_ticks + n - 1) / n;

  PhysicsSide physics = state.MakePhysicsSide(recorder);
  StartPhysics(state, physics);
  auto last_progress = wall0;
  std::int64_t tick = 0;
  for (std::int64_t k = 0; k < periods && !state.stop_requested.load(std::memory_order_relaxed);
       ++k) {
    physics.Step(k);
    for (int j = 0; j < n; ++j, ++tick) state.TickAll(static_cast<double>(tick) * dt);
    physics.TakeReports();  // S_{k+1}: period k's report for step k+1 ...
    physics.Publish();      // ... and step k's snapshot for period k+1.
    physics.RecordStep();
    const auto now = std::chrono::steady_clock::now();
    if (progress &&
        std::chrono::duration<double>(now - last_progress).count() > kProgressInterval) {
      progress(static_cast<double>(k + 1) / static_cast<double>(periods));
      last_progress = now;
    }
  }
  state.StopAll();

  RunStats stats;
  const double sim_time = static_cast<double>(tick) * dt;
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  FillRunStats(state, physics, settings::Mode::kLockstep, sim_time, wall_time, sim_time, &stats);
  if (progress) progress(1.0);
  return stats;
}

}  // namespace mrh::engine::internal
