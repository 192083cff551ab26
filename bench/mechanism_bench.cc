// SPDX-License-Identifier: Apache-2.0
// One haptic tick of local-dynamics (contact local model) and local-dynamics-6dof with a
// mechanism in the island: scenes/chain6_boxes.xml, a 6-link hinged chain (springs, damping,
// armature, dry friction, limits) lying on a floor with 8 free boxes against it; a sphere
// pointer (r 0.015 m, k 1200 N/m) pushes the chain's tip sideways at 0.05 m/s into the boxes,
// so the island holds the chain and the boxes (14 bodies, 6 joints). The run is lockstep:
// a 20 ms physics step every 20 ticks (not timed), each haptic tick timed on its own (device
// read, rendering, island step, safety, records). Counters tick_p50_us / tick_p99_us give the
// tick's percentiles; island_bodies / island_joints / island_rows the island exported at the
// start.
// Run with: mrh_bench --benchmark_filter=Mechanism
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <vector>

#include "engine/engine_impl.h"
#include "mrh/core/stats.h"
#include "mrh/device/simulated.h"
#include "mrh/render/local_contact_solver.h"
#include "mrh/world/contact_export.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

constexpr int kTicksPerStep = 20;
constexpr int kSteps = 100;  // 2 s

world::World Scene() {
  return world::World::LoadFile(MRH_SOURCE_DIR "/scenes/chain6_boxes.xml");
}

// The island a push on the chain's tip exports from the scene's initial state.
void CountIsland(benchmark::State& bench) {
  world::World world = Scene();
  world::ContactExporter exporter(&world, 0.005, false, /*articulated=*/true);
  auto model = std::make_unique<ir::LocalContactModel>();
  const std::vector<int> seeds{world.FindBody("link5")}, motions{0};
  (void)exporter.Export(seeds, motions, model.get());
  bench.counters["island_bodies"] = static_cast<double>(model->bodies.size());
  bench.counters["island_joints"] = static_cast<double>(model->joints.size());
  bench.counters["island_rows"] = static_cast<double>(model->contacts.size());
  // The island solver alone, the tip pushed sideways: its Gauss–Seidel sweeps per tick.
  render::LocalContactSolver solver;
  solver.Adopt(*model);
  double sweeps = 0.0;
  constexpr int kTicks = 200;
  for (int k = 0; k < kTicks; ++k) {
    solver.AddForce(0, Vec3(0, -2.0, 0), solver.p_WCm(0));
    (void)solver.Step(0.001);
    sweeps += solver.last_sweeps();
  }
  bench.counters["solver_sweeps"] = sweeps / kTicks;
}

void BM_MechanismTick(benchmark::State& bench, const char* method) {
  settings::EngineSettings s;
  s.method = method;
  s.haptic_dt = 0.001;
  s.physics_dt = 0.001 * kTicksPerStep;
  s.duration = s.physics_dt * kSteps;
  s.pointer.radius = 0.015;
  s.rendering.stiffness = 1200.0;
  s.rendering.damping = 3.0;
  s.safety.ramp = false;
  s.realtime_priority = false;
  std::vector<double> tick_us;
  tick_us.reserve(kSteps * kTicksPerStep);
  for (auto _ : bench) {
    auto device = device::MakeScriptedDevice(
        {device::Keyframe{0.0, Pose{Vec3(0.62, 0.04, 0.02), Quat::Identity()}},
         device::Keyframe{2.0, Pose{Vec3(0.62, -0.06, 0.02), Quat::Identity()}}});
    internal::EngineState state(Scene(), std::move(device), device::Calibration{}, s);
    physics::PhysicsSide physics = state.MakePhysicsSide(nullptr);
    internal::StartPhysics(state, physics);
    double total = 0.0;
    for (int k = 0; k < kSteps; ++k) {
      physics.Step(k);
      for (int j = 0; j < kTicksPerStep; ++j) {
        const auto t0 = std::chrono::steady_clock::now();
        state.TickAll((k * kTicksPerStep + j) * s.haptic_dt);
        const double us =
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0)
                .count();
        tick_us.push_back(us);
        total += us;
      }
      physics.TakeReports();
      physics.Publish();
      physics.RecordStep();
    }
    state.StopAll();
    bench.SetIterationTime(total * 1e-6 / (kSteps * kTicksPerStep));
  }
  CountIsland(bench);
  bench.counters["tick_p50_us"] = Percentile(tick_us, 50.0);
  bench.counters["tick_p99_us"] = Percentile(tick_us, 99.0);
  bench.counters["tick_max_us"] = Percentile(tick_us, 100.0);
}

BENCHMARK_CAPTURE(BM_MechanismTick, local_dynamics, "local-dynamics")
    ->Unit(benchmark::kMicrosecond)
    ->UseManualTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_MechanismTick, local_dynamics_6dof, "local-dynamics-6dof")
    ->Unit(benchmark::kMicrosecond)
    ->UseManualTime()
    ->Iterations(1);

}  // namespace
}  // namespace mrh::engine
