// SPDX-License-Identifier: Apache-2.0
// Embedded runs: the caller's servo loop is the haptic thread (Engine::Start / Tick / Stop).
#include <atomic>
#include <chrono>
#include <thread>

#include "engine_impl.h"
#include "mrh/core/assert.h"
#include "mrh/core/error.h"
#include "mrh/device/external.h"

namespace mrh::engine {
namespace internal {
struct EmbeddedRun {
  EmbeddedRun(EngineState* state, physics::Recorder* recorder)
      : physics(state->MakePhysicsSide(recorder)) {}

  PhysicsSide physics;
  device::ExternalDevice* device = nullptr;
  std::int64_t period = 0;
  int ticks_in_period = 0;
  double last_t = 0.0;
  std::chrono::steady_clock::time_point wall0 = std::chrono::steady_clock::now();
  std::atomic<bool> done{false};
  std::thread physics_thread;
};

void DestroyEmbeddedRun(EmbeddedRun* run) {
  delete run;
}

}  // namespace internal

namespace {

// The one external device of an embedded run: pointer 0's, or with several pointers any one
// pointer's (the one the caller's loop drives; the others read their own devices each tick).
device::ExternalDevice* FindExternal(internal::EngineState& s) {
  device::ExternalDevice* found = dynamic_cast<device::ExternalDevice*>(s.device.get());
  for (const auto& lane : s.lanes) {
    auto* external = dynamic_cast<device::ExternalDevice*>(lane->device.get());
    if (external == nullptr) continue;
    if (found != nullptr) {
      throw InvalidArgument(
          "Engine::Start drives one pointer from the caller's loop; give exactly one pointer an "
          "external device (the others their own devices)");
    }
    found = external;
  }
  if (found == nullptr) {
    throw InvalidArgument(
        "Engine::Start needs an external device (device.type = \"external\"); use Run() for "
        "simulated devices");
  }
  return found;
}

}  // namespace

void Engine::Start(physics::Recorder* recorder) {
  internal::EngineState& s = *impl_->state;
  device::ExternalDevice* external = FindExternal(s);
  if (s.has_run) throw RuntimeError("engine already ran; build a new engine for another run");
  s.has_run = true;
  s.OpenDevices();
  impl_->embedded.reset(new internal::EmbeddedRun(&s, recorder));
  internal::EmbeddedRun& run = *impl_->embedded;
  run.device = external;
  internal::StartPhysics(s, run.physics);
  if (s.settings.mode == settings::Mode::kRealtime) {
    run.physics_thread = std::thread([&run] {
      internal::RunPhysicsThread(run.physics, run.done);
    });
  }
}

Wrench Engine::Tick(double t, const device::DeviceState& reading) noexcept {
  internal::EngineState& s = *impl_->state;
  MRH_DEMAND(impl_->embedded != nullptr);
  internal::EmbeddedRun& run = *impl_->embedded;
  const bool lockstep = s.settings.mode == settings::Mode::kLockstep;
  // Lockstep: the same order as RunLockstep — step k, the n ticks of period k, then exchange.
  if (lockstep && run.ticks_in_period == 0) run.physics.Step(run.period);
  run.device->Feed(reading);
  s.TickAll(t);
  run.last_t = t;
  if (lockstep && ++run.ticks_in_period == s.ticks_per_step) {
    run.physics.TakeReports();
    run.physics.Publish();
    run.physics.RecordStep();
    run.ticks_in_period = 0;
    ++run.period;
  }
  return run.device->commanded();
}

RunStats Engine::Stop() {
  internal::EngineState& s = *impl_->state;
  MRH_DEMAND(impl_->embedded != nullptr);
  internal::EmbeddedRun& run = *impl_->embedded;
  s.StopAll();
  run.done.store(true, std::memory_order_release);
  if (run.physics_thread.joinable()) run.physics_thread.join();
  s.CloseDevices();
  RunStats stats;
  const double wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - run.wall0).count();
  internal::FillRunStats(s, run.physics, s.settings.mode, run.last_t + s.settings.haptic_dt,
                         wall_time, wall_time, &stats);
  return stats;
}

}  // namespace mrh::engine
