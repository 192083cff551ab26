// SPDX-License-Identifier: Apache-2.0
// Micro-benchmark: one tick of the contact local model (render/local_contact_solver.h)
// with 16 neighbors in contact with friction: a 4 × 4 grid of touching 0.5 kg, 10 cm boxes on a
// floor (μ 0.5; 4 floor rows per box, 4 rows per touching face pair: 160 contact rows), every box
// pushed along +x by a pointer force of 3 N (more than μ m g: the grid slides).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <ctime>
#include <vector>

#include "mrh/core/stats.h"
#include "mrh/render/local_contact_solver.h"

namespace mrh::render {
namespace {

constexpr double kHalf = 0.05;
constexpr double kDt = 1e-3;
constexpr int kGrid = 4;

ir::LocalContactModel Grid() {
  ir::LocalContactModel m;
  m.valid = true;
  m.gravity = Vec3(0, 0, -9.81);
  const double I = 0.5 * (2 * kHalf) * (2 * kHalf) / 6.0;
  for (int i = 0; i < kGrid * kGrid; ++i) {
    ir::LocalIslandBody b;
    b.body = i + 1;
    b.motion = i;
    b.mass = 0.5;
    b.inertia_B = Mat3::Identity() * I;
    b.X_WB.p = Vec3((i % kGrid) * 2 * kHalf, (i / kGrid) * 2 * kHalf, kHalf);
    (void)m.bodies.PushBack(b);
  }
  for (int i = 0; i < kGrid * kGrid; ++i) {
    for (int c = 0; c < 4; ++c) {  // floor corners
      ir::LocalContactRow r;
      r.a = i;
      r.p_A = Vec3((c & 1) ? kHalf : -kHalf, (c & 2) ? kHalf : -kHalf, -kHalf);
      r.p_B = m.bodies[static_cast<std::size_t>(i)].X_WB * r.p_A;
      r.n_B = Vec3::UnitZ();
      r.mu = 0.5;
      (void)m.contacts.PushBack(r);
    }
    for (int axis = 0; axis < 2; ++axis) {  // +x and +y neighbours, B = this box
      const int j = axis == 0 ? ((i % kGrid) + 1 < kGrid ? i + 1 : -1)
                              : (i / kGrid + 1 < kGrid ? i + kGrid : -1);
      if (j < 0) continue;
      for (int c = 0; c < 4; ++c) {
        ir::LocalContactRow r;
        r.a = j;
        r.b = i;
        const double u = (c & 1) ? kHalf : -kHalf, w = (c & 2) ? kHalf : -kHalf;
        r.p_A = axis == 0 ? Vec3(-kHalf, u, w) : Vec3(u, -kHalf, w);
        r.p_B = axis == 0 ? Vec3(kHalf, u, w) : Vec3(u, kHalf, w);
        r.n_B = axis == 0 ? Vec3::UnitX() : Vec3::UnitY();
        r.mu = 0.5;
        (void)m.contacts.PushBack(r);
      }
    }
  }
  return m;
}

// This thread's CPU time (µs): unlike the wall clock it does not count preemption by other
// processes on a shared machine.
double ThreadCpuUs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
}

void BM_LocalContactTick16(benchmark::State& state) {
  const ir::LocalContactModel model = Grid();
  LocalContactSolver solver;
  solver.Adopt(model);
  std::vector<double> samples_us, cpu_us;
  double sweeps = 0.0;
  samples_us.reserve(1 << 20);
  cpu_us.reserve(1 << 20);
  int tick = 0;
  for (auto _ : state) {
    if (++tick % 20 == 0) solver.Adopt(model);  // a new period every 20 ticks
    const double c0 = ThreadCpuUs();
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < solver.size(); ++i) {
      solver.AddForce(i, Vec3(3.0, 0, 0), solver.p_WCm(i) - Vec3(kHalf, 0, 0));
    }
    benchmark::DoNotOptimize(solver.Step(kDt));
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = ThreadCpuUs() - c0;
    sweeps += solver.last_sweeps();
    if (samples_us.size() < samples_us.capacity()) samples_us.push_back(us);
    if (cpu_us.size() < cpu_us.capacity()) cpu_us.push_back(cpu);
  }
  state.counters["rows"] = static_cast<double>(model.contacts.size());
  state.counters["p50_us"] = Percentile(samples_us, 50.0);
  state.counters["p99_us"] = Percentile(samples_us, 99.0);
  state.counters["max_us"] = Percentile(samples_us, 100.0);
  state.counters["sweeps"] = sweeps / static_cast<double>(std::max<std::int64_t>(1, tick));
  state.counters["cpu_p50_us"] = Percentile(cpu_us, 50.0);
  state.counters["cpu_p99_us"] = Percentile(cpu_us, 99.0);
}

BENCHMARK(BM_LocalContactTick16);

}  // namespace
}  // namespace mrh::render
