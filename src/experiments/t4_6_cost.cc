// SPDX-License-Identifier: Apache-2.0
// T4.6: the estimates at one state, and their cost per physics step with 10 and 100 cubes.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "experiment_util.h"
#include "mrh/world/perturbation.h"
#include "t4_3_impl.h"
#include "t4_6_impl.h"

namespace mrh::experiments::internal::t4_6 {
namespace {

// t4.3's scene: 0.1 m cubes of 0.2 kg; the pushed cube is cube0, pushed along +x at its −x face
// centre with 0.5 N, below its friction limit (μ = 1: 1.96 N), so it rests.
constexpr double kCubeHalf = 0.05;  // m
constexpr double kCostPush = 0.5;   // N
constexpr int kSettleSteps = 25;    // 0.5 s at 20 ms

double Ms(std::int64_t ns) {
  return static_cast<double>(ns) * 1e-6;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// The thesis' chapter-4 estimate through the Perturber: zero run + 3 test forces, whole steps
// from the saved warm start as the thesis' simulator does.
Result Thesis3dof(world::World* world, int body, const Push& push) {
  const auto t0 = std::chrono::steady_clock::now();
  world::Perturber perturber(
      world, world::PerturberSettings{.path = world::PerturbationPath::kFullStep,
                                      .warm_start = world::TestRunWarmStart::kSaved});
  const int bodies[] = {body};
  perturber.Begin(bodies);
  perturber.ZeroForceRun();
  const world::DynamicIr ir = perturber.Measure(0, push.f, push.p_W);
  perturber.End();
  Result r;
  const Vec3 arm = push.p_W - world->body_state(body).p_WCm;
  // Point acceleration a_p = a + α × r = [I, −[r]×] u̇.
  for (int c = 0; c < 3; ++c) {
    r.point.col(c) = ir.A.col(c).head<3>() + ir.A.col(c).tail<3>().cross(arm);
  }
  r.ok = r.point.allFinite();
  r.cost.steps = static_cast<int>(perturber.counters().full_step_runs);
  r.cost.wall_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0)
          .count();
  return r;
}

Result FromEstimate(const world::AcceleranceEstimate& e, const Vec3& arm) {
  Result r;
  r.ok = e.ok;
  r.A = e.A;
  r.point = world::PointAccelerance(e.A, arm);
  r.cost = e.cost;
  r.island_dofs = e.island_dofs;
  r.active_rows = e.active_rows;
  return r;
}

}  // namespace

double Lever(const world::World& world, int body) {
  const world::BodyInfo& info = world.body(body);
  return std::sqrt(info.inertia_B.trace() / (3.0 * info.mass));
}

Wrench PushWrench(const world::World& world, int body, const Push& push) {
  const Vec3 arm = push.p_W - world.body_state(body).p_WCm;
  return Wrench{push.f, arm.cross(push.f)};
}

std::array<Result, kNumEstimates> RunEstimates(world::World* world, int body, const Push& push) {
  const Vec3 arm = push.p_W - world->body_state(body).p_WCm;
  const Wrench user = PushWrench(*world, body, push);
  std::array<Result, kNumEstimates> out;
  const double torque = push.f.norm() * Lever(*world, body);
  out[kFull18] = FromEstimate(world::EstimateFull18(world, body, push.f, torque), arm);
  out[kTwoRun] = FromEstimate(world::EstimateTwoRun(world, body, user), arm);
  out[kAnalytic] = FromEstimate(world::EstimateAnalytic(world, body, user), arm);
  out[kThesis3dof] = Thesis3dof(world, body, push);
  return out;
}

Result RunReference(world::World* world, int body, const Push& push) {
  const Vec3 arm = push.p_W - world->body_state(body).p_WCm;
  const Wrench user = PushWrench(*world, body, push);
  // ε: 1e-3 of the push (and of its torque at the lever): deep inside the operating point's
  // contact regime, far above the converged solve's rounding.
  world::ConvergedSettings settings;
  settings.epsilon_force = 1e-3 * push.f.norm();
  settings.epsilon_torque = settings.epsilon_force * Lever(*world, body);
  return FromEstimate(world::MeasureConvergedAccelerance(world, body, user, settings), arm);
}

std::vector<CostRow> MeasureCost(const std::filesystem::path& out, int cubes, int repetitions) {
  std::filesystem::create_directories(out / "scenes");
  const std::filesystem::path scene = out / "scenes" / fmt::format("cost_{}.xml", cubes);
  WriteText(scene, t4_3::SceneXml(cubes, 3));
  world::World world = world::World::LoadFile(scene);
  const int body = world.FindBody("cube0");
  for (int i = 0; i < kSettleSteps; ++i) world.Step();
  std::vector<double> global;
  std::array<std::vector<double>, kNumEstimates> est;
  std::array<Result, kNumEstimates> last;
  std::vector<double> shared;  // analytic without its forward pass (shared with the global step)
  for (int rep = 0; rep < repetitions; ++rep) {
    const Vec3 c = world.body_state(body).p_WCm;
    const Push push{Vec3(kCostPush, 0.0, 0.0), c - Vec3(kCubeHalf, 0.0, 0.0)};
    last = RunEstimates(&world, body, push);
    for (int e = 0; e < kNumEstimates; ++e) est[e].push_back(Ms(last[e].cost.wall_ns));
    shared.push_back(Ms(last[kAnalytic].cost.wall_ns - last[kAnalytic].cost.forward_ns));
    const auto t0 = std::chrono::steady_clock::now();
    world.AddForceAtPoint(body, push.f, push.p_W);
    world.Step();
    global.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  const double dt = world.timestep(), g = Median(global);
  std::vector<CostRow> rows;
  rows.push_back({cubes, "global-only", 0, 0, 0.0, g, g * 1e-3 / dt, dt});
  for (int e = 0; e < kNumEstimates; ++e) {
    const double m = Median(est[e]);
    rows.push_back({cubes, kEstimateNames[e], last[e].cost.steps, last[e].cost.forwards, m, g,
                    (g + m) * 1e-3 / dt, dt});
  }
  const double m = Median(shared);
  rows.push_back({cubes, kSharedForward, 0, 0, m, g, (g + m) * 1e-3 / dt, dt});
  return rows;
}

}  // namespace mrh::experiments::internal::t4_6
