// SPDX-License-Identifier: Apache-2.0
// One haptic tick of 10 pointers (3-DOF) with 500 contacts in total, two ways:
//  - impulse: each pointer, a 0.1 m sphere, is 5 mm deep in 50 small free spheres spread over
//    its surface (10 separate clusters);
//  - local-dynamics (contact local model): the 10 pointers share one island, which holds at most
//    ir::kMaxNeighborBodies = 128 bodies, so the 500 contacts come from pointers sharing bodies:
//    10 pointers, 0.2 mm apart, inside one shell of 50 balls, each pointer 5 mm deep in every
//    ball (several hands pressing one pile). The balls are heavy (1e6 kg) so that the island
//    they form barely moves over the timed ticks and the contacts persist.
// 2000 ticks of all pointers (devices read, rendered, safety, records; local-dynamics also steps
// the island) are timed one by one; the physics step runs once at setup and its snapshots stay
// current (physics_dt spans the ticks). Counters tick_p50_us / tick_p99_us give the tick's
// percentiles, contacts the last tick's total.
// Run with: mrh_bench --benchmark_filter=MultiPointer
// MRH_BENCH_SMOKE=1 (the CI smoke run) runs 2 pointers with 10 contacts each.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "engine/engine_impl.h"
#include "mrh/core/stats.h"
#include "mrh/device/simulated.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

constexpr double kPointerRadius = 0.1;  // m
constexpr double kBallRadius = 0.01;    // m
constexpr double kDepth = 0.005;        // m
constexpr double kSpacing = 0.5;        // m between pointers, separate clusters
constexpr double kSharedStep = 2e-4;    // m between pointers in one shared cluster

bool Smoke() {
  const char* smoke = std::getenv("MRH_BENCH_SMOKE");
  return smoke != nullptr && std::string(smoke) != "0";
}

// `balls` points spread evenly over the unit sphere (the Fibonacci lattice).
Vec3 FibonacciPoint(int k, int balls) {
  const double z = 1.0 - 2.0 * (k + 0.5) / balls;
  const double r = std::sqrt(1.0 - z * z);
  const double phi = k * std::numbers::pi * (3.0 - std::sqrt(5.0));
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// The layout of a benchmark: a method, and whether the pointers share one cluster of balls.
struct Layout {
  const char* method;
  bool shared;
  double ball_mass;  // kg
};

Vec3 PointerCentre(const Layout& layout, int i) {
  return layout.shared ? Vec3(kSharedStep * i, 0.0, 1.0) : Vec3(kSpacing * i, 0.0, 1.0);
}

std::string SceneXml(const Layout& layout, int pointers, int balls) {
  std::string bodies;
  const std::string mass = std::to_string(layout.ball_mass);
  const int clusters = layout.shared ? 1 : pointers;
  for (int i = 0; i < clusters; ++i) {
    for (int k = 0; k < balls; ++k) {
      const Vec3 p = PointerCentre(layout, i) +
                     (kPointerRadius + kBallRadius - kDepth) * FibonacciPoint(k, balls);
      bodies += "<body pos=\"" + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " +
                std::to_string(p.z()) +
                "\"><freejoint/><geom type=\"sphere\" size=\"0.01\" mass=\"" + mass + "\"/></body>";
    }
  }
  for (int i = 0; i < pointers; ++i) {
    bodies += "<body name=\"p" + std::to_string(i) + "\" mocap=\"true\" pos=\"" +
              std::to_string(PointerCentre(layout, i).x()) +
              " 0 1\"><geom type=\"sphere\" size=\"0.1\"/></body>";
  }
  return "<mujoco><option timestep=\"1\" gravity=\"0 0 0\"/><worldbody>" + bodies +
         "</worldbody></mujoco>";
}

// Counts the contacts the pointers rendered in the latest tick (checks the scene's 500).
class ContactCount final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override {
    if (tick.tick != tick_) contacts = 0;
    tick_ = tick.tick;
    contacts += tick.contacts;
  }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  int contacts = 0;

 private:
  std::int64_t tick_ = -1;
};

void BM_MultiPointerTick(benchmark::State& bench, Layout layout) {
  const int pointers = Smoke() ? 2 : 10;
  const int balls = Smoke() ? 10 : 50;
  world::LoadOptions options{.pointer_body = "p0"};
  settings::EngineSettings s;
  s.method = layout.method;
  s.haptic_dt = 0.001;
  s.physics_dt = 1.0;  // one physics step for the whole benchmark
  s.duration = 1.0;
  s.safety.ramp = false;
  s.safety.watchdog_timeout = 10.0;  // above 2 × physics_dt: the one snapshot stays fresh
  s.realtime_priority = false;
  std::vector<std::unique_ptr<device::Device>> devices;
  for (int i = 0; i < pointers; ++i) {
    const std::string body = "p" + std::to_string(i);
    if (i > 0) options.more_pointer_bodies.push_back(body);
    s.pointers.push_back(
        settings::PointerLaneSettings{settings::PointerSettings{body, 0.0}, s.rendering});
    devices.push_back(device::MakeFixedDevice(Pose{PointerCentre(layout, i), Quat::Identity()}));
  }
  internal::EngineState state(world::World::LoadString(SceneXml(layout, pointers, balls), options),
                              std::move(devices), std::vector<device::Calibration>(pointers), s);
  ContactCount count;
  physics::PhysicsSide physics = state.MakePhysicsSide(&count);
  internal::StartPhysics(state, physics);
  physics.Step(0);
  physics.Publish();
  constexpr int kTicks = 2000;
  std::vector<double> tick_us(kTicks);
  for (auto _ : bench) {
    double total = 0.0;
    for (int k = 0; k < kTicks; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      state.TickAll(k * s.haptic_dt);
      const auto t1 = std::chrono::steady_clock::now();
      tick_us[static_cast<std::size_t>(k)] =
          std::chrono::duration<double, std::micro>(t1 - t0).count();
      total += tick_us[static_cast<std::size_t>(k)];
      physics.DrainTickRecords();
    }
    bench.SetIterationTime(total * 1e-6 / kTicks);
  }
  bench.counters["pointers"] = pointers;
  bench.counters["contacts"] = count.contacts;
  bench.counters["tick_p50_us"] = Percentile(tick_us, 50.0);
  bench.counters["tick_p99_us"] = Percentile(tick_us, 99.0);
}

BENCHMARK_CAPTURE(BM_MultiPointerTick, impulse, Layout{"impulse", false, 0.01})
    ->Unit(benchmark::kMicrosecond)
    ->UseManualTime()
    ->Iterations(1);
BENCHMARK_CAPTURE(BM_MultiPointerTick, local_dynamics, Layout{"local-dynamics", true, 1e6})
    ->Unit(benchmark::kMicrosecond)
    ->UseManualTime()
    ->Iterations(1);

}  // namespace
}  // namespace mrh::engine
