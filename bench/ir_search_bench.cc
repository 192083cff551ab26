// SPDX-License-Identifier: Apache-2.0
// Benchmarks of the 6-DOF physics-side IR work: neighbor search + IR, and sweep-and-prune updates.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "mrh/geometry/broadphase.h"
#include "mrh/world/world.h"
#include "physics/geometric_ir_builder.h"

namespace mrh {
namespace {

constexpr double kPitch = 0.25;  // grid spacing of the cubes (m)

// n free 0.1 m cubes resting on a floor on a square grid, and a 0.2 m cube pointer.
std::string GridScene(int n) {
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  std::ostringstream xml;
  // Frictionless contacts and CG, as in the frictionless T4.3 scenes.
  const int rows = 4 * n + 400;
  xml << "<mujoco><option timestep='0.02' solver='CG'/><size njmax='" << rows << "' nconmax='"
      << rows << "' nstack='" << std::max(1'000'000, 3000 * n)
      << "'/><default><geom condim='1'/></default><worldbody>"
         "<geom type='plane' size='50 50 0.1'/>";
  for (int i = 0; i < n; ++i) {
    xml << "<body pos='" << kPitch * (i % side) << " " << kPitch * (i / side)
        << " 0.05'><freejoint/><geom type='box' size='0.05 0.05 0.05' mass='0.5'/></body>";
  }
  xml << "<body name='pointer' mocap='true' pos='0 0 1'><geom type='box' size='0.1 0.1 0.1' "
         "contype='0' conaffinity='0'/></body></worldbody></mujoco>";
  return xml.str();
}

// The pointer 2 mm into the floor between two cubes of the grid's middle row, overlapping each
// by 2.5 cm, wobbling ±1 cm so that its box crosses other boxes' endpoints.
Pose PointerPose(int n, std::int64_t iteration) {
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const double wobble = 0.01 * std::sin(0.3 * static_cast<double>(iteration));
  return Pose{Vec3(kPitch * (side / 2) + 0.5 * kPitch, kPitch * (side / 2) + wobble, 0.098),
              Quat::Identity()};
}

void BM_NeighborSearchAndIr(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  world::World world = world::World::LoadString(GridScene(n));
  const int pointer = world.pointer_body();
  physics::internal::GeometricIrBuilder builder(world, pointer, settings::RenderingSettings{});
  auto snapshot = std::make_unique<ir::PhysicsSnapshot>();
  std::int64_t iteration = 0;
  double broad = 0.0, narrow = 0.0, region = 0.0, pairs = 0.0, points = 0.0, candidates = 0.0;
  for (auto _ : state) {
    const Pose X_WP = PointerPose(n, iteration++);
    builder.CapturePreviousPoses(world);
    builder.Build(world, X_WP, snapshot.get());
    benchmark::DoNotOptimize(snapshot->pairs.size());
    const physics::internal::GeometricIrStats& s = builder.stats();
    broad += s.broad_phase_s;
    narrow += s.narrow_phase_s;
    region += s.region_s;
    candidates += s.candidates;
    pairs += static_cast<double>(snapshot->pairs.size());
    points += static_cast<double>(snapshot->points.size());
  }
  const double count = static_cast<double>(state.iterations());
  state.counters["broad_us"] = 1e6 * broad / count;
  state.counters["narrow_us"] = 1e6 * narrow / count;
  state.counters["region_us"] = 1e6 * region / count;
  state.counters["candidates"] = candidates / count;
  state.counters["pairs"] = pairs / count;
  state.counters["points"] = points / count;
}

BENCHMARK(BM_NeighborSearchAndIr)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

// The MuJoCo step of the same scene, for the 20 ms budget the IR work shares.
void BM_GridWorldStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  world::World world = world::World::LoadString(GridScene(n));
  world.SetMocapPose(world.pointer_body(), PointerPose(n, 0));
  for (int i = 0; i < 10; ++i) world.Step();  // settle the contacts
  for (auto _ : state) world.Step();
}

BENCHMARK(BM_GridWorldStep)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

// n boxes of 2–20 cm random-walking 5 mm per update in a box sized for ~1 overlap per box.
void BM_SapUpdate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::mt19937 rng(1);
  const double extent = 0.2 * std::cbrt(static_cast<double>(n));
  std::uniform_real_distribution<double> pos(0.0, extent), half(0.01, 0.1), step(-0.005, 0.005);
  std::vector<geometry::Aabb> boxes;
  geometry::SweepAndPrune sap;
  for (int i = 0; i < n; ++i) {
    const Vec3 c(pos(rng), pos(rng), pos(rng));
    const Vec3 h(half(rng), half(rng), half(rng));
    boxes.push_back(geometry::Aabb{c - h, c + h});
    sap.Add(boxes.back());
  }
  (void)sap.Update();
  std::vector<Vec3> moves(1024);
  for (Vec3& m : moves) m = Vec3(step(rng), step(rng), step(rng));
  std::size_t k = 0;
  std::int64_t swaps = 0;
  for (auto _ : state) {
    for (int i = 0; i < n; ++i) {
      geometry::Aabb& b = boxes[static_cast<std::size_t>(i)];
      const Vec3& m = moves[k++ % moves.size()];
      b = geometry::Aabb{b.min + m, b.max + m};
      sap.SetBox(i, b);
    }
    swaps += sap.Update();
  }
  state.counters["swaps"] = static_cast<double>(swaps) / static_cast<double>(state.iterations());
  state.counters["pairs"] = static_cast<double>(sap.num_pairs());
  state.SetItemsProcessed(state.iterations() * n);
}

BENCHMARK(BM_SapUpdate)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace mrh
