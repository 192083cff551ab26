// SPDX-License-Identifier: Apache-2.0
// Physics-thread cost of one pair's geometric IR: signed distance + penetration region (qhull).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "mrh/core/stats.h"
#include "mrh/geometry/contact_region.h"
#include "mrh/geometry/distance.h"
#include "mrh/geometry/polyhedron.h"

namespace mrh::geometry {
namespace {

constexpr int kPoses = 64;  // penetrating configurations cycled through
constexpr std::size_t kMaxSamples = 1 << 20;
constexpr int kCurvedSegments = 16;

Shape Box(double half) {
  Shape shape;
  shape.type = ShapeType::kBox;
  shape.size = Vec3::Constant(half);
  return shape;
}

// Regular icosahedron (20 triangular faces) of circumradius `radius`, outward wound.
Shape Icosahedron(double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  auto mesh = std::make_shared<ConvexMesh>();
  mesh->vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& v : mesh->vertices) v *= radius / v.norm();
  mesh->triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                     {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                     {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                     {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  Shape shape;
  shape.type = ShapeType::kMesh;
  shape.mesh = std::move(mesh);
  return shape;
}

Shape Sphere(double radius) {
  Shape shape;
  shape.type = ShapeType::kSphere;
  shape.size = Vec3(radius, 0, 0);
  return shape;
}

// One pointer/object pair in kPoses penetrating configurations (object at the origin, pointer
// at a random pose 0.8–1.0 of the sum of their sizes away), with their distance results.
struct Scene {
  CollisionShape pointer;
  CollisionShape object;
  ConvexPolyhedron pointer_poly;
  ConvexPolyhedron object_poly;
  std::vector<Pose> X_WP;
  std::vector<DistanceResult> d;
};

std::unique_ptr<Scene> MakeScene(const Shape& pointer, const Shape& object, double reach) {
  auto scene =
      std::unique_ptr<Scene>(new Scene{CollisionShape(pointer),
                                       CollisionShape(object),
                                       ConvexPolyhedron::FromShape(pointer, kCurvedSegments),
                                       ConvexPolyhedron::FromShape(object, kCurvedSegments),
                                       {},
                                       {}});
  std::mt19937 rng(1);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> distance(0.8 * reach, reach);
  while (scene->X_WP.size() < kPoses) {
    const Vec3 direction = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    const Quat q = Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    const Pose X_WP{distance(rng) * direction, q};
    const DistanceResult d = SignedDistance(scene->pointer, X_WP, scene->object, Pose{});
    if (d.distance >= -1e-4) continue;  // keep clear penetrations only
    scene->X_WP.push_back(X_WP);
    scene->d.push_back(d);
  }
  return scene;
}

// Times one pair's IR per iteration; arg "distance": 1 includes SignedDistance, 0 times
// ComputeContactRegion alone on precomputed distance results.
void RunPair(benchmark::State& state, const Scene& scene) {
  const bool with_distance = state.range(0) != 0;
  std::vector<double> samples_us;
  samples_us.reserve(kMaxSamples);
  double points = 0.0;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ % scene.X_WP.size();
    const auto start = std::chrono::steady_clock::now();
    const DistanceResult d =
        with_distance ? SignedDistance(scene.pointer, scene.X_WP[k], scene.object, Pose{})
                      : scene.d[k];
    const ContactRegion r =
        ComputeContactRegion(scene.pointer_poly, scene.X_WP[k], scene.object_poly, Pose{}, d);
    const auto stop = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(r.points_W.data());
    const double seconds = std::chrono::duration<double>(stop - start).count();
    state.SetIterationTime(seconds);
    if (samples_us.size() < kMaxSamples) samples_us.push_back(1e6 * seconds);
    points += static_cast<double>(r.points_W.size());
  }
  state.counters["p50_us"] = Percentile(samples_us, 50.0);
  state.counters["p99_us"] = Percentile(samples_us, 99.0);
  state.counters["points"] = points / static_cast<double>(state.iterations());
}

void BM_ContactRegion_CubeCube(benchmark::State& state) {
  static const std::unique_ptr<Scene> scene = MakeScene(Box(0.1), Box(0.1), 0.2);
  RunPair(state, *scene);
}

void BM_ContactRegion_20Face20Face(benchmark::State& state) {
  static const std::unique_ptr<Scene> scene = MakeScene(Icosahedron(0.1), Icosahedron(0.1), 0.2);
  RunPair(state, *scene);
}

// A curved object at the default resolution (16 segments: a 264-face sphere polyhedron).
void BM_ContactRegion_CubeSphere(benchmark::State& state) {
  static const std::unique_ptr<Scene> scene = MakeScene(Box(0.1), Sphere(0.1), 0.2);
  RunPair(state, *scene);
}

BENCHMARK(BM_ContactRegion_CubeCube)
    ->ArgName("distance")
    ->Arg(0)
    ->Arg(1)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ContactRegion_20Face20Face)
    ->ArgName("distance")
    ->Arg(0)
    ->Arg(1)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ContactRegion_CubeSphere)
    ->ArgName("distance")
    ->Arg(0)
    ->Arg(1)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace mrh::geometry
