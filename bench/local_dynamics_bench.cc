// SPDX-License-Identifier: Apache-2.0
// One local-dynamics physics step (global step, IR, local-model export: the default
// contact model) with 500 cubes resting with friction (condim 3, pyramidal cones, μ = 1) on a
// floor, the pointer pushing the first row at 0.1 m/s. One repetition = one physics period (20
// haptic ticks, one physics step inline, lockstep); its time is the step's own compute time
// (StepRecord). The scene's solver is Newton at tolerance 1e-10: with friction CG stops 3 mm/s
// away from the converged solution (tests/world/solver_reference_test.cc).
// Report p50/p99 with: mrh_bench --benchmark_filter=LocalDynamics
// MRH_BENCH_SMOKE=1 (the CI smoke run) runs 50 cubes for 3 steps instead.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mrh/core/stats.h"
#include "mrh/device/external.h"
#include "mrh/engine/engine.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

constexpr double kPhysicsDt = 0.02;  // s
constexpr double kHapticDt = 0.001;  // s
constexpr int kTicksPerStep = 20;
constexpr double kHalf = 0.05;    // m, cube half size
constexpr double kRadius = 0.02;  // m, pointer sphere
constexpr double kStartX = -kHalf - kRadius - 0.002;
constexpr double kSpeed = 0.1;  // m/s

// The CI smoke run only checks that the benchmark runs: a small world, a few steps.
bool Smoke() {
  const char* smoke = std::getenv("MRH_BENCH_SMOKE");
  return smoke != nullptr && std::string(smoke) != "0";
}

// The t4.3 layout (rows of 10 cubes, 2 cm gaps, rows 0.25 m apart), with friction.
std::string CubesXml(int cubes) {
  std::string bodies;
  for (int i = 0; i < cubes; ++i) {
    bodies += "<body pos=\"" + std::to_string(0.12 * (i % 10)) + " " +
              std::to_string(0.25 * (i / 10)) +
              " 0.05\"><freejoint/><geom type=\"box\" size=\"0.05 0.05 0.05\" mass=\"0.2\"/>"
              "</body>";
  }
  return "<mujoco><option timestep=\"0.02\" solver=\"Newton\" tolerance=\"1e-10\"/><default><geom "
         "condim=\"3\"/>"
         "</default><worldbody><geom type=\"plane\" size=\"20 20 0.1\"/>" +
         bodies + "<body name=\"pointer\" mocap=\"true\" pos=\"" + std::to_string(kStartX) +
         " 0 0.05\"><geom type=\"sphere\" size=\"0.02\" contype=\"0\" conaffinity=\"0\"/></body>"
         "</worldbody></mujoco>";
}

// The device reading at time t: the pointer moving along +x from kStartX.
device::DeviceState Reading(double t) {
  device::DeviceState reading;
  reading.t = t;
  reading.X_DT.p = Vec3(kStartX + kSpeed * t, 0.0, kHalf);
  reading.V_DT.v = Vec3(kSpeed, 0.0, 0.0);
  return reading;
}

class StepTimes final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord&) override {}

  void OnStep(const physics::StepRecord& step, const world::World&) override {
    last_ms = step.compute_ms;
  }

  double last_ms = 0.0;
};

struct Run {
  std::unique_ptr<Engine> engine;
  StepTimes times;
  long tick = 0;
};

// One engine per cube count, kept across repetitions (the push goes on from step to step).
Run& SharedRun(int cubes) {
  static std::map<int, std::unique_ptr<Run>> runs;
  std::unique_ptr<Run>& run = runs[cubes];
  if (run) return *run;
  run = std::make_unique<Run>();
  run->engine = [cubes] {
    settings::EngineSettings s;
    s.method = "local-dynamics";
    s.physics_dt = kPhysicsDt;
    s.haptic_dt = kHapticDt;
    s.duration = 1e3;
    s.pointer.radius = kRadius;
    s.rendering.stiffness = 2000.0;
    s.safety.ramp = false;
    s.realtime_priority = false;
    device::Specifications specs;
    specs.max_force = 100.0;
    // Engine::Start builds the first snapshot from the device's current reading: without this
    // one the pointer starts at the origin, inside cube 0, and the first period launches it.
    auto device = std::make_unique<device::ExternalDevice>(specs);
    device->Feed(Reading(0.0));
    return std::make_unique<Engine>(world::World::LoadString(CubesXml(cubes)), std::move(device),
                                    device::Calibration{}, s);
  }();
  return *run;
}

// One repetition of the push with `cubes` cubes (50 in the smoke run).
void StepFriction(benchmark::State& state, int cubes) {
  Run& run = SharedRun(Smoke() ? 50 : cubes);
  if (run.tick == 0) run.engine->Start(&run.times);
  for (auto _ : state) {
    for (int i = 0; i < kTicksPerStep; ++i, ++run.tick) {
      const double t = static_cast<double>(run.tick) * kHapticDt;
      benchmark::DoNotOptimize(run.engine->Tick(t, Reading(t)));
    }
    state.SetIterationTime(run.times.last_ms * 1e-3);
  }
}

void BM_LocalDynamicsStep500Friction(benchmark::State& state) {
  StepFriction(state, 500);
}

// MuJoCo 3's sparse constraint storage: 1000 and 2000 cubes with friction in one world.
void BM_LocalDynamicsStep1000Friction(benchmark::State& state) {
  StepFriction(state, 1000);
}

void BM_LocalDynamicsStep2000Friction(benchmark::State& state) {
  StepFriction(state, 2000);
}

// 100 steps: the pointer reaches the first cube after ~0.02 s and pushes it for 2 s (row 0's
// cubes join one after another).
BENCHMARK(BM_LocalDynamicsStep500Friction)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(1)
    ->Repetitions(Smoke() ? 3 : 100)
    ->ReportAggregatesOnly(true)
    ->ComputeStatistics("p50",
                        [](const std::vector<double>& v) {
                          return Percentile(v, 50.0);
                        })
    ->ComputeStatistics("p99", [](const std::vector<double>& v) {
      return Percentile(v, 99.0);
    });

BENCHMARK(BM_LocalDynamicsStep1000Friction)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(1)
    ->Repetitions(Smoke() ? 3 : 100)
    ->ReportAggregatesOnly(true)
    ->ComputeStatistics("p50",
                        [](const std::vector<double>& v) {
                          return Percentile(v, 50.0);
                        })
    ->ComputeStatistics("p99", [](const std::vector<double>& v) {
      return Percentile(v, 99.0);
    });

BENCHMARK(BM_LocalDynamicsStep2000Friction)
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(1)
    ->Repetitions(Smoke() ? 3 : 100)
    ->ReportAggregatesOnly(true)
    ->ComputeStatistics("p50",
                        [](const std::vector<double>& v) {
                          return Percentile(v, 50.0);
                        })
    ->ComputeStatistics("p99", [](const std::vector<double>& v) {
      return Percentile(v, 99.0);
    });

}  // namespace
}  // namespace mrh::engine
