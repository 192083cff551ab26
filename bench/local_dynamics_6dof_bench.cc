// SPDX-License-Identifier: Apache-2.0
// Micro-benchmark: one haptic tick of local-dynamics-6dof with 1000 contacts with
// friction over 8 moving objects. Eight 0.5 kg, 10 cm boxes stand apart on a floor (4 floor rows
// each, μ 0.5) in a 2 × 4 grid; one flat pointer presses 1 mm into all eight tops with 125
// contact points per box (1000 normal rows plus their friction rows) and rubs to and fro along x
// (±1 cm at 1 Hz), so every tick re-poses 8 planes on the moving local boxes, solves the proxy,
// pushes the boxes and steps the island. A new period (Adopt of the same snapshot) every 20 ticks.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <numbers>
#include <vector>

#include "mrh/core/stats.h"
#include "mrh/haptic/methods.h"

namespace mrh::haptic {
namespace {

constexpr double kHalf = 0.05;   // box half size (m)
constexpr double kPitch = 0.12;  // box spacing (m)
constexpr int kBoxes = 8;
constexpr int kSide = 5;  // 5 × 5 × 5 = 125 points per box, in 5 rows
constexpr double kDt = 1e-3;

Vec3 BoxCentre(int i) {
  return Vec3((i % 4) * kPitch, (i / 4) * kPitch, kHalf);
}

// Pointer origin at t = 0: above the grid's centre, at the boxes' top face height.
Vec3 PointerOrigin() {
  return Vec3(1.5 * kPitch, 0.5 * kPitch, 2 * kHalf);
}

void AddBox(int i, ir::PhysicsSnapshot* s) {
  ir::BodyMotion m;
  m.body = i + 1;
  m.X_WB.p = BoxCentre(i);
  m.X_WB_prev = m.X_WB;
  (void)s->bodies.PushBack(m);
  ir::GeometricPair pair;
  pair.motion = i;
  pair.object_geom = i + 1;
  pair.pointer_geom = 0;
  pair.n_W = Vec3::UnitZ();
  pair.p_BC = Vec3(0, 0, kHalf);
  pair.first_point = static_cast<int>(s->points.size());
  pair.num_points = kSide * kSide * kSide;
  pair.penetrating = true;
  (void)s->pairs.PushBack(pair);
  for (int k = 0; k < pair.num_points; ++k) {  // a 25 × 5 grid of points 1 mm below the top
    const double u = (k % 25) / 24.0 - 0.5, v = (k / 25) / 4.0 - 0.5;
    const Vec3 p_W = BoxCentre(i) + Vec3(1.6 * kHalf * u, 1.6 * kHalf * v, kHalf - 0.001);
    (void)s->points.PushBack(ir::PairPoint{p_W - PointerOrigin(), 0.001});
  }
  ir::LocalIslandBody b;
  b.body = i + 1;
  b.motion = i;
  b.mass = 0.5;
  b.inertia_B = Mat3::Identity() * (0.5 * 4 * kHalf * kHalf / 6.0);
  b.X_WB = m.X_WB;
  (void)s->local_model.bodies.PushBack(b);
  for (int c = 0; c < 4; ++c) {
    ir::LocalContactRow r;
    r.a = i;
    r.p_A = Vec3((c & 1) ? kHalf : -kHalf, (c & 2) ? kHalf : -kHalf, -kHalf);
    r.p_B = b.X_WB * r.p_A;
    r.n_B = Vec3::UnitZ();
    r.mu = 0.5;
    (void)s->local_model.contacts.PushBack(r);
  }
}

std::unique_ptr<ir::PhysicsSnapshot> Snapshot() {
  auto s = std::make_unique<ir::PhysicsSnapshot>();
  s->step = 0;
  s->physics_dt = 0.02;
  s->local_model.valid = true;
  s->local_model.gravity = Vec3(0, 0, -9.81);
  for (int i = 0; i < kBoxes; ++i) AddBox(i, s.get());
  return s;
}

// k_t, d_t, k_r and μ of the T3.4 benchmark; R_w by the thesis recipe (§3.4.1) for a
// 0.46 × 0.22 × 0.02 m plate pointer, × 500.
render::ProxyRendererSettings Settings() {
  const double a = 0.46, b = 0.22, c = 0.02;
  const Vec3 inertia((b * b + c * c) / 12, (a * a + c * c) / 12, (a * a + b * b) / 12);
  render::ProxyRendererSettings s;
  s.k_t = 9000.0;
  s.d_t = 10.0;
  s.k_r = 300.0;
  s.rotation_weight =
      render::RotationWeightFromInertia(inertia.asDiagonal().toDenseMatrix(), 500.0);
  s.mu = 0.5;
  s.max_iterations = 50;
  s.tolerance = 1e-7;
  return s;
}

double ThreadCpuUs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

haptic::TickInput Input(std::int64_t tick) {
  haptic::TickInput in;
  in.tick = tick;
  in.t = static_cast<double>(tick) * kDt;
  in.j = static_cast<int>(tick % 20);
  in.n = 20;
  in.dt = kDt;
  const double w = 2 * std::numbers::pi;
  in.X_WP = Pose{PointerOrigin() + Vec3(0.01 * std::sin(w * in.t), 0, 0), Quat::Identity()};
  in.V_WP.v = Vec3(0.01 * w * std::cos(w * in.t), 0, 0);
  return in;
}

// Argument: 0 the thesis torque model, 1 the contact model (the sessions' default).
void BM_LocalDynamics6dofTick1000Contacts8Objects(benchmark::State& state) {
  const auto snapshot = Snapshot();
  render::ProxyRendererSettings settings = Settings();
  if (state.range(0) == 1) settings.torque_model = render::ProxyTorqueModel::kContact;
  const auto method = MakeLocalDynamics6dofHaptic(settings);
  auto report = std::make_unique<ir::HapticReport>();
  std::vector<double> wall_us, cpu_us, switch_us;
  wall_us.reserve(1 << 20);
  cpu_us.reserve(1 << 20);
  switch_us.reserve(1 << 16);
  const render::LocalContactSolver& solver = *LocalDynamics6dofSolver(*method);
  double contacts = 0.0, sweeps = 0.0, fz_jump = 0.0, fz_before = 0.0;
  std::int64_t tick = 0;
  for (auto _ : state) {
    const haptic::TickInput in = Input(tick);
    haptic::TickOutput out;
    const double c0 = ThreadCpuUs();
    const auto t0 = std::chrono::steady_clock::now();
    if (in.j == 0) {
      method->EndPeriod(report.get());
      method->Adopt(*snapshot);
    }
    method->HapticTick(in, &out);
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = ThreadCpuUs() - c0;
    benchmark::DoNotOptimize(out.w_W);
    contacts += out.contacts;
    sweeps += solver.last_sweeps();
    if (tick > 0) fz_jump = std::max(fz_jump, std::abs(out.w_W.f.z() - fz_before));
    fz_before = out.w_W.f.z();
    if (wall_us.size() < wall_us.capacity()) wall_us.push_back(us);
    if (cpu_us.size() < cpu_us.capacity()) cpu_us.push_back(cpu);
    if (in.j == 0 && switch_us.size() < switch_us.capacity()) switch_us.push_back(us);
    ++tick;
  }
  double z = 0.0, tilt = 0.0;
  for (std::size_t i = 0; i < solver.size(); ++i) {
    z = std::max(z, std::abs(solver.p_WCm(i).z() - kHalf));
    tilt = std::max(tilt, 2.0 * std::acos(std::min(1.0, std::abs(solver.X_WB(i).q.w()))));
  }
  state.counters["box_dz_max_m"] = z;  // a diverging island shows here
  state.counters["box_tilt_max_rad"] = tilt;
  state.counters["contacts"] = contacts / static_cast<double>(std::max<std::int64_t>(1, tick));
  // The island's Gauss–Seidel sweeps per tick (at most LocalContactSolverSettings::iterations).
  state.counters["island_sweeps"] = sweeps / static_cast<double>(std::max<std::int64_t>(1, tick));
  // The largest tick-to-tick change of the felt normal force (N): the rub is horizontal and
  // the press steady, so a change of more than a few hundredths of a newton is chatter.
  state.counters["fz_jump_max_N"] = fz_jump;
  state.counters["p50_us"] = Percentile(wall_us, 50.0);
  state.counters["p99_us"] = Percentile(wall_us, 99.0);
  state.counters["cpu_p50_us"] = Percentile(cpu_us, 50.0);
  state.counters["cpu_p99_us"] = Percentile(cpu_us, 99.0);
  // The period's first tick (EndPeriod, Adopt and the tick), one in 20: what sets p99.
  state.counters["switch_p50_us"] = Percentile(switch_us, 50.0);
}

BENCHMARK(BM_LocalDynamics6dofTick1000Contacts8Objects)->ArgName("contact_model")->Arg(0)->Arg(1);

}  // namespace
}  // namespace mrh::haptic
