// SPDX-License-Identifier: Apache-2.0
// The allocation-guarded lockstep loop: proves a method's haptic ticks never allocate.
#pragma once

#include <cstdint>

#include "engine/engine_impl.h"
#include "support/alloc_guard.h"

namespace mrh::engine::testing {

/// Runs `periods` lockstep periods of `state` (physics step k, then the period's haptic ticks,
/// then the exchange) and returns the heap allocations made inside the haptic ticks only:
/// adoption of a new snapshot included, the physics step and the exchange excluded. After every
/// tick, outside the guard, calls on_tick(tick index); it may inspect the method.
template <typename OnTick>
std::int64_t HapticAllocations(internal::EngineState& state, int periods, OnTick&& on_tick) {
  internal::PhysicsSide physics = state.MakePhysicsSide(nullptr);
  internal::StartPhysics(state, physics);
  std::int64_t allocations = 0;
  std::int64_t tick = 0;
  for (int k = 0; k < periods; ++k) {
    physics.Step(k);
    for (int j = 0; j < state.ticks_per_step; ++j, ++tick) {
      std::int64_t count = 0;
      {
        const mrh::testing::AllocGuard guard;
        state.TickAll(static_cast<double>(tick) * state.settings.haptic_dt);
        count = guard.count();
      }
      allocations += count;
      on_tick(tick);
    }
    physics.TakeReports();
    physics.Publish();
    physics.DrainTickRecords();
  }
  return allocations;
}

inline std::int64_t HapticAllocations(internal::EngineState& state, int periods) {
  return HapticAllocations(state, periods, [](std::int64_t) {});
}

}  // namespace mrh::engine::testing
