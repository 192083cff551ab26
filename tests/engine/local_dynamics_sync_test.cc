// SPDX-License-Identifier: Apache-2.0
// Method local-dynamics: synchronization of the global and local states across periods, for
// the thesis model and the contact local model.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "haptic/local_contact_haptic.h"
#include "local_dynamics_fixtures.h"
#include "physics/local_contact_physics.h"

namespace mrh::engine::testing {
namespace {

TEST(LocalDynamicsTest, GlobalStepStartsFromTheLocalStateOfTheLastPeriod) {
  // Zero gravity, nothing else to touch: the global step is pure drift, so the state it ends in
  // is the overwritten local state moved by v·Δt^G (eq. 4.16–4.17).
  constexpr double kTol = 1e-12;
  const double duration = 1.0;
  settings::EngineSettings settings = LocalSettings(duration);
  world::World world = world::World::LoadString(kFreeBox);
  const int box = world.FindBody("box");
  // Pushed along −x: the COM drifts at constant velocity between pushes, whatever the spin.
  EngineState state(std::move(world), PushingDevice(Vec3(0.09, 0, 0), -0.05, duration),
                    device::Calibration{}, settings);
  ir::LocalBodyState last;
  int checked = 0;
  RunPeriods(state, 16, [&](int k, int j) {
    const render::LocalBody* local = HapticOf(state).local_body(box);
    if (local == nullptr || j != state.ticks_per_step - 1) return;
    if (k >= 2 && last.body == box) {
      // Step k started from period k−1's local end state (recorded at its last tick).
      const world::BodyState global = state.world.body_state(box);
      const Vec3 expected = last.X_WB.p + last.V_WCm.v * settings.physics_dt;
      EXPECT_LE((global.X_WB.p - expected).norm(), kTol) << "step " << k;
      EXPECT_LE((global.V_WCm.v - last.V_WCm.v).norm(), kTol) << "step " << k;
      ++checked;
    }
    last = ir::LocalBodyState{box, local->X_WB(), local->V_WCm()};
  });
  EXPECT_GT(checked, 10);
  EXPECT_GT(PhysicsOf(state).counters().overwrites, 10);
  EXPECT_GT(last.V_WCm.v.norm(), 0.01);  // the pointer did push the box
}

// The contact model's island solver of `state` and the local index of world body `body`, or -1.
const render::LocalContactSolver& ContactSolverOf(EngineState& state) {
  return static_cast<haptic::internal::LocalContactHaptic*>(state.method.haptic.get())->solver();
}

int LocalIndexOf(const render::LocalContactSolver& solver, int body) {
  for (std::size_t i = 0; i < solver.size(); ++i) {
    if (solver.world_body(i) == body) return static_cast<int>(i);
  }
  return -1;
}

TEST(LocalDynamicsTest, ContactModelWorldHoldsTheOwnedBodyAtTheLocalEndStateOfTheLastPeriod) {
  // The contact model, zero gravity, nothing else to touch: step k overwrites the owned box with
  // period k−1's local end state (eq. 4.16–4.17) and the box ends the global step there
  // (IslandSync::HoldOwned): MuJoCo's own end state of it is not used.
  constexpr double kTol = 1e-12;
  const double duration = 1.0;
  settings::EngineSettings settings = LocalSettings(duration, "contact");
  world::World world = world::World::LoadString(kFreeBox);
  const int box = world.FindBody("box");
  EngineState state(std::move(world), PushingDevice(Vec3(0.09, 0, 0), -0.05, duration),
                    device::Calibration{}, settings);
  ir::LocalBodyState last, before;
  int checked = 0;
  RunPeriods(state, 16, [&](int k, int j) {
    const render::LocalContactSolver& solver = ContactSolverOf(state);
    const int i = LocalIndexOf(solver, box);
    if (i < 0 || j != state.ticks_per_step - 1) return;
    const auto l = static_cast<std::size_t>(i);
    if (k >= 3 && last.body == box && before.body == box) {
      const world::BodyState global = state.world.body_state(box);
      EXPECT_LE((global.X_WB.p - last.X_WB.p).norm(), kTol) << "step " << k;
      EXPECT_LE(global.X_WB.q.angularDistance(last.X_WB.q), 1e-9) << "step " << k;
      EXPECT_LE((global.V_WCm.v - last.V_WCm.v).norm(), kTol) << "step " << k;
      ++checked;
    }
    before = last;
    last = ir::LocalBodyState{box, solver.X_WB(l), solver.V_WCm(l)};
  });
  EXPECT_GT(checked, 10);
  EXPECT_GT(last.V_WCm.v.norm(), 0.01);  // the pointer did push the box
}

// The owned cube ends the step at its local state (IslandSync::HoldOwned) before the rows are
// exported: at MuJoCo's end state of the global step, whose soft contacts (time constant 0.1 s
// at physics_dt 0.05) sink and pitch the overwritten cube, the pushed cube would be launched
// over the pointer and leave the island.
TEST(LocalDynamicsTest, ContactModelSynchronizationMovesNothingOnTheHapticSide) {
  // The contact model on a floor with friction: the local simulation owns the pushed cube, so
  // at every tick, synchronizations included, the pose advances by exactly one tick of the new
  // velocity (semi-implicit Euler), and the world takes the local end state every period. The
  // pointer starts 16 cm off and touches at about 1.6 s, once MuJoCo has settled the cube
  // (pushed during the settling bounce, the contact model launches the cube).
  constexpr double kTol = 1e-12;
  const double duration = 4.0;
  EngineState state(world::World::LoadString(kCubeOnFloor),
                    PushingDevice(Vec3(-0.23, 0, 0.05), 0.1, duration), device::Calibration{},
                    LocalSettings(duration, "contact"));
  const int cube = state.world.FindBody("cube");
  const double dt = state.settings.haptic_dt;
  Vec3 previous_p = Vec3::Constant(std::nan(""));
  int across_syncs = 0;
  RunPeriods(state, 80, [&](int k, int j) {
    const render::LocalContactSolver& solver = ContactSolverOf(state);
    const int i = LocalIndexOf(solver, cube);
    if (i < 0) {  // not in the island (pointer farther than the neighbor margin)
      previous_p = Vec3::Constant(std::nan(""));
      return;
    }
    const auto l = static_cast<std::size_t>(i);
    // Before the first push the island restarts from the world every period.
    if (!std::isnan(previous_p.x()) && k >= 36) {
      const Vec3 step = solver.p_WCm(l) - previous_p;
      EXPECT_LE((step - solver.V_WCm(l).v * dt).norm(), kTol) << k << "," << j;
      if (j == 0) ++across_syncs;
    }
    previous_p = solver.p_WCm(l);
  });
  EXPECT_GT(across_syncs, 30);
  EXPECT_GT(static_cast<physics::internal::LocalContactPhysics*>(state.method.physics.get())
                ->counters()
                .overwrites,
            30);
  EXPECT_GT(previous_p.x(), 0.05);  // the cube was pushed along
}

// Keeps every snapshot the physics side makes: [0] from PhysicsStart, [k + 1] from step k.
// Period p renders snapshots[p].
class SnapshotKeeper final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord&) override {}

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  void OnSnapshot(const ir::PhysicsSnapshot& snapshot) override {
    auto copy = std::make_unique<ir::PhysicsSnapshot>(snapshot);
    snapshots.push_back(std::move(copy));
  }

  std::vector<std::unique_ptr<ir::PhysicsSnapshot>> snapshots;
};

Vec6 Stack(const Twist& t) {
  Vec6 out;
  out << t.v, t.w;
  return out;
}

TEST(LocalDynamicsTest, SynchronizationKeepsGlobalAndLocalStatesConsistent) {
  // A cube pushed across a floor with friction: contacts and friction make the correction of
  // eq. 4.18 non-zero. (1) Local → global (eq. 4.16–4.17): step k starts from period k−1's
  // local end state u^L plus the correction sent for period k (dV_k), so with the residual
  // correction (Springhead's realization of eq. 4.18) the global velocity after the step is exactly
  // u^G = u^L + dV_k + b_k Δt^G + dV_{k+1}: |u^G − u^L| is what the correction accounts for.
  // (2) Global → local (eq. 4.18): the local velocity jumps at tick 0 by dV_k plus one tick of
  // (A f + b), and the pose moves by one tick of the new velocity.
  constexpr double kTol = 1e-12;
  const double duration = 2.0;
  const int periods = 40;
  EngineState state(world::World::LoadString(kCubeOnFloor),
                    PushingDevice(Vec3(-0.08, 0, 0.05), 0.1, duration), device::Calibration{},
                    LocalSettings(duration));
  const int cube = state.world.FindBody("cube");
  const double dt = state.settings.haptic_dt;
  SnapshotKeeper keeper;
  PhysicsSide physics = state.MakePhysicsSide(&keeper);
  physics.Start(state.haptic->InitialReport(0.0));
  std::vector<Twist> end_velocity(periods);
  std::vector<double> jump_residual(periods, 0.0), jump_bound(periods, 0.0);
  Vec3 previous_p = Vec3::Constant(std::nan(""));
  Twist previous_u;
  double largest_correction = 0.0;
  std::int64_t tick = 0;
  for (int k = 0; k < periods; ++k) {
    physics.Step(k);
    for (int j = 0; j < state.ticks_per_step; ++j, ++tick) {
      state.haptic->Tick(static_cast<double>(tick) * dt);
      const render::LocalBody* local = HapticOf(state).local_body(cube);
      ASSERT_NE(local, nullptr);
      if (!std::isnan(previous_p.x())) {
        const Vec3 step = local->p_WCm() - previous_p;
        EXPECT_LE((step - local->V_WCm().v * dt).norm(), kTol) << k << "," << j;
      }
      if (j == 0 && k >= 1) {
        const ir::BodyMotion* m = MotionOf(*keeper.snapshots[static_cast<std::size_t>(k)], cube);
        ASSERT_NE(m, nullptr);
        ASSERT_TRUE(m->continues);
        const Vec6 jump = Stack(local->V_WCm()) - Stack(previous_u) - Stack(m->dV_n);
        jump_residual[static_cast<std::size_t>(k)] = jump.norm();
        // The tick's own u̇ = A f + b, with |f| at most the largest force of the run (below)
        // and the Frobenius norm bounding |A f| / |f|.
        jump_bound[static_cast<std::size_t>(k)] = local->A().norm() * dt + local->b().norm() * dt;
        largest_correction = std::max(largest_correction, Stack(m->dV_n).norm());
      }
      previous_p = local->p_WCm();
      previous_u = local->V_WCm();
    }
    end_velocity[static_cast<std::size_t>(k)] = previous_u;
    physics.TakeReports();
    physics.Publish();
    physics.DrainTickRecords();
  }
  const double f_max = state.haptic->counters().max_force;
  int checked = 0;
  for (int k = 1; k + 1 < periods; ++k) {
    const ir::BodyMotion& sent = *MotionOf(*keeper.snapshots[static_cast<std::size_t>(k)], cube);
    const ir::BodyMotion& next =
        *MotionOf(*keeper.snapshots[static_cast<std::size_t>(k + 1)], cube);
    const Vec6 expected = Stack(end_velocity[static_cast<std::size_t>(k - 1)]) + Stack(sent.dV_n) +
                          sent.b * state.settings.physics_dt + Stack(next.dV_n);
    EXPECT_LE((Stack(next.V_WCm) - expected).norm(), kTol) << "step " << k;
    const auto i = static_cast<std::size_t>(k);
    EXPECT_LE(jump_residual[i], jump_bound[i] * std::max(1.0, f_max) + kTol) << "period " << k;
    ++checked;
  }
  EXPECT_EQ(checked, periods - 2);
  EXPECT_GT(largest_correction, 1e-4);  // the corrections are not trivially zero
  EXPECT_GT(HapticOf(state).haptic_counters().corrections, 30);
  EXPECT_GT(previous_p.x(), 0.05);  // the cube was pushed along
}

}  // namespace
}  // namespace mrh::engine::testing
