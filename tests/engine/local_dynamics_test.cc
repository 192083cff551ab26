// SPDX-License-Identifier: Apache-2.0
// Method local-dynamics: accelerance of free bodies and of a row of cubes, felt mass,
// synchronization, rest, T4.1, RT contract and determinism (issue 5).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "engine/engine_impl.h"
#include "haptic/local_contact_haptic.h"
#include "haptic/local_dynamics_haptic.h"
#include "mrh/haptic/methods.h"
#include "physics/local_contact_physics.h"
#include "physics/local_dynamics_physics.h"
#include "engine_test_util.h"
#include "support/hashing_recorder.h"
#include "haptic_alloc_loop.h"

namespace mrh::engine::testing {
namespace {

using haptic::internal::LocalDynamicsHaptic;
using internal::EngineState;
using internal::PhysicsSide;
using physics::internal::CorrectionModel;
using physics::internal::LocalDynamicsOptions;
using physics::internal::LocalDynamicsPhysics;

// A free 2 kg box, turned, in zero gravity, with a pointer 1 cm off its +x face, away from the
// face centre so that a push also turns it.
constexpr char kFreeBox[] = R"(
<mujoco>
  <option timestep="0.05" gravity="0 0 0"/>
  <worldbody>
    <body name="box" pos="0 0 0" euler="0 0 20"><freejoint/>
      <geom type="box" size="0.05 0.1 0.15" mass="2"/></body>
    <body name="pointer" mocap="true" pos="0.08 0.05 0.07">
      <geom type="sphere" size="0.02" contype="0" conaffinity="0"/></body>
  </worldbody>
</mujoco>)";

// A 1 kg cube on a floor with friction, and a pointer 1 cm from its −x face at COM height. The
// cube starts just touching and first settles 0.36 mm into MuJoCo's soft contact: a bounce the
// local simulation must follow without going unstable.
constexpr char kCubeOnFloor[] = R"(
<mujoco>
  <option timestep="0.05" gravity="0 0 -9.81"/>
  <worldbody>
    <geom name="floor" type="plane" size="3 3 0.1" friction="0.5 0.005 0.0001"/>
    <body name="cube" pos="0 0 0.05"><freejoint/>
      <geom type="box" size="0.05 0.05 0.05" mass="1" friction="0.5 0.005 0.0001"/></body>
    <body name="pointer" mocap="true" pos="-0.08 0 0.05">
      <geom type="sphere" size="0.02" contype="0" conaffinity="0"/></body>
  </worldbody>
</mujoco>)";

constexpr double kCubeMassRow = 1.0;     // kg, each cube of scenes/row_of_cubes.xml
constexpr double kRowZ = 0.0499;         // m, COM height of the row (and of the pointer)
constexpr double kRowPointerX = -0.075;  // m, pointer start, 5 mm from the first cube
constexpr double kPushSpeed = 0.05;      // m/s, scripted pointer speed into the row

settings::EngineSettings LocalSettings(double duration, const char* model = "perturbation") {
  settings::EngineSettings s;
  s.method = "local-dynamics";
  s.physics_dt = 0.05;
  s.haptic_dt = 0.001;
  s.duration = duration;
  s.pointer.radius = 0.02;
  s.rendering.stiffness = 1000.0;
  // Most tests check the thesis model (eq. 4.16–4.18 with A, b); the rest and synchronization
  // tests also run the contact model (issue 13).
  s.rendering.local_model = *settings::ParseChoice<settings::LocalModel>(model);
  s.safety.ramp = false;
  s.realtime_priority = false;
  return s;
}

world::World RowWorld(int k) {
  world::World w = world::World::LoadFile(std::string(MRH_SOURCE_DIR) + "/scenes/row_of_cubes.xml");
  w.ApplyKeyframe("row" + std::to_string(k));
  return w;
}

// A pointer moving from p0 at `speed` along +x for the whole run (scripted: the user is an
// infinitely stiff hand, as in T4.1).
std::unique_ptr<device::Device> PushingDevice(const Vec3& p0, double speed, double duration) {
  device::Specifications specs;
  specs.max_force = 100.0;
  return device::MakeScriptedDevice(
      {{0.0, Pose{p0, Quat::Identity()}},
       {duration, Pose{p0 + Vec3(speed * duration, 0, 0), Quat::Identity()}}},
      specs);
}

Vec3 ImpulseOn(const RunStats& stats, int body) {
  for (const physics::BodyImpulseTotal& total : stats.impulses) {
    if (total.body == body) return total.linear;
  }
  return Vec3::Zero();
}

Mat3 Cross(const Vec3& r) {
  Mat3 m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

// The snapshot PhysicsStart makes for period 0: the dynamic IR measured at the initial state
// (with the nominal test force: no user force yet).
ir::PhysicsSnapshot InitialSnapshot(world::World* world, const settings::EngineSettings& settings,
                                    const Pose& X_WP) {
  const physics::MethodContext context{world, &settings, world->pointer_body(),
                                       settings.pointer.radius};
  LocalDynamicsPhysics method(context);
  ir::HapticReport initial;
  initial.X_WP = X_WP;
  auto snapshot = std::make_unique<ir::PhysicsSnapshot>();
  method.PhysicsStart(initial, snapshot.get());
  return *snapshot;
}

const ir::BodyMotion* MotionOf(const ir::PhysicsSnapshot& snapshot, int body) {
  for (const ir::BodyMotion& m : snapshot.bodies) {
    if (m.body == body) return &m;
  }
  return nullptr;
}

// M⁻¹J of a free body for a force at body point p_BA (eq. 4.1–4.2).
ir::Mat63 FreeBodyAccelerance(const world::World& world, int body, const Vec3& p_BA) {
  const world::BodyInfo& info = world.body(body);
  const world::BodyState state = world.body_state(body);
  const Mat3 R = state.X_WB.q.toRotationMatrix();
  ir::Mat63 A;
  A.topRows<3>() = Mat3::Identity() / info.mass;
  A.bottomRows<3>() =
      (R * info.inertia_B * R.transpose()).inverse() * Cross(state.X_WB * p_BA - state.p_WCm);
  return A;
}

TEST(LocalDynamicsTest, FreeBodyAcceleranceIsInverseMassAndLeverArmCoupling) {
  // The issue's tolerance; roundoff of the perturbation runs is ~1e-15.
  constexpr double kTol = 1e-9;
  for (bool perturbation : {true, false}) {
    world::World world = world::World::LoadString(kFreeBox);
    settings::EngineSettings settings = LocalSettings(1.0);
    settings.rendering.perturbation = perturbation;
    const Pose X_WP{Vec3(0.08, 0.05, 0.07), Quat::Identity()};
    const ir::PhysicsSnapshot snapshot = InitialSnapshot(&world, settings, X_WP);
    const int box = world.FindBody("box");
    const ir::BodyMotion* motion = MotionOf(snapshot, box);
    ASSERT_NE(motion, nullptr);
    ASSERT_TRUE(motion->has_dynamics);
    const ir::Mat63 expected = FreeBodyAccelerance(world, box, motion->p_BA);
    EXPECT_LE((motion->A - expected).norm(), kTol * expected.norm())
        << "perturbation " << perturbation;
    EXPECT_LE(motion->b.norm(), kTol);
    EXPECT_GT(expected.bottomRows<3>().norm(), 1.0);  // the lever arm matters here
  }
}

class RowOfCubesTest : public ::testing::TestWithParam<int> {};

TEST_P(RowOfCubesTest, EstimatedMassIsTheWholeRow) {
  // MuJoCo's contacts are soft even at impedance 0.999: each contact passes on slightly less
  // than the whole push (measured 0.1 % per contact); 2 % leaves room for five cubes.
  constexpr double kRelTol = 0.02;
  const int k = GetParam();
  world::World world = RowWorld(k);
  const ir::PhysicsSnapshot snapshot = InitialSnapshot(
      &world, LocalSettings(1.0), Pose{Vec3(kRowPointerX, 0, kRowZ), Quat::Identity()});
  const ir::BodyMotion* first = MotionOf(snapshot, world.FindBody("cube1"));
  ASSERT_NE(first, nullptr);
  EXPECT_NEAR(1.0 / first->A(0, 0), k * kCubeMassRow, kRelTol * k * kCubeMassRow);
}

TEST_P(RowOfCubesTest, FeltMassIsTheWholeRowAndTheGlobalRowMovesAlong) {
  // The pointer moves into the row at v and the row bounces off its spring (k = 1000 N/m, no
  // damper): an elastic bounce of a mass M delivers J = 2Mv, and every cube leaves at 2v. The
  // 1 ms spring–mass discretization and the soft contacts account for ~1 %.
  constexpr double kRelTol = 0.03;
  constexpr double kDuration = 0.8;  // contact lasts π√(M/k) ≤ 0.23 s from t ≈ 0.1 s
  const int k = GetParam();
  for (CorrectionModel model :
       {CorrectionModel::kVelocityResidual, CorrectionModel::kNewContacts}) {
    const std::string name =
        model == CorrectionModel::kNewContacts ? "ld-new-contacts" : "ld-residual";
    LocalDynamicsOptions options;
    options.correction = model;
    RegisterMethod(name, "test", [options](const physics::MethodContext& c) {
      return Method{"local-dynamics", false, std::make_unique<LocalDynamicsPhysics>(c, options),
                    haptic::MakeLocalDynamicsHaptic(c.pointer_radius, c.settings->rendering.stiffness,
                                                    c.settings->rendering.damping),
                    {"local_dynamics.local_body_fault"}};
    });
    settings::EngineSettings settings = LocalSettings(kDuration);
    settings.method = name;
    Engine engine(RowWorld(k), PushingDevice(Vec3(kRowPointerX, 0, kRowZ), kPushSpeed, kDuration),
                  device::Calibration{}, settings);
    const RunStats stats = engine.Run(nullptr);
    const double felt = ImpulseOn(stats, engine.world().FindBody("cube1")).x() / (2 * kPushSpeed);
    EXPECT_NEAR(felt, k * kCubeMassRow, kRelTol * k * kCubeMassRow) << name;
    for (int i = 1; i <= k; ++i) {
      const int cube = engine.world().FindBody("cube" + std::to_string(i));
      EXPECT_NEAR(engine.world().body_state(cube).V_WCm.v.x(), 2 * kPushSpeed,
                  kRelTol * 2 * kPushSpeed)
          << name << " cube " << i;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Cubes, RowOfCubesTest, ::testing::Values(1, 2, 3, 4, 5));

// Runs lockstep periods of `state` by hand (as RunLockstep does), calling `on_tick` after every
// haptic tick.
template <typename OnTick>
void RunPeriods(EngineState& state, int periods, OnTick on_tick) {
  PhysicsSide physics = state.MakePhysicsSide(nullptr);
  physics.Start(state.haptic->InitialReport(0.0));
  std::int64_t tick = 0;
  for (int k = 0; k < periods; ++k) {
    physics.Step(k);
    for (int j = 0; j < state.ticks_per_step; ++j, ++tick) {
      state.haptic->Tick(static_cast<double>(tick) * state.settings.haptic_dt);
      on_tick(k, j);
    }
    physics.TakeReports();
    physics.Publish();
    physics.DrainTickRecords();
  }
}

// The two halves of the state's local-dynamics method.
const LocalDynamicsPhysics& PhysicsOf(EngineState& state) {
  return *static_cast<const LocalDynamicsPhysics*>(state.method.physics.get());
}

const LocalDynamicsHaptic& HapticOf(EngineState& state) {
  return *static_cast<const LocalDynamicsHaptic*>(state.method.haptic.get());
}

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

// Was disabled (issue 13): at physics_dt 0.05 the pushed cube was launched over the pointer and
// left the island. Cause: the rows were exported at MuJoCo's end state of the global step, whose
// soft contacts (time constant 0.1 s at this step) sank and pitched the overwritten cube; the
// owned cube now ends the step at its local state (IslandSync::HoldOwned).
TEST(LocalDynamicsTest, ContactModelSynchronizationMovesNothingOnTheHapticSide) {
  // The contact model on a floor with friction: the local simulation owns the pushed cube, so
  // at every tick, synchronizations included, the pose advances by exactly one tick of the new
  // velocity (semi-implicit Euler), and the world takes the local end state every period. The
  // pointer starts 16 cm off and touches at about 1.6 s, once MuJoCo has settled the cube
  // (pushed during the settling bounce, the contact model launches the cube: see issue 13).
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
  EXPECT_GT(
      static_cast<physics::internal::LocalContactPhysics*>(state.method.physics.get())
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
  // correction (SPEC §4.11) the global velocity after the step is exactly
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
        jump_bound[static_cast<std::size_t>(k)] =
            local->A().norm() * dt + local->b().norm() * dt;
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
    const Vec6 expected = Stack(end_velocity[static_cast<std::size_t>(k - 1)]) +
                          Stack(sent.dV_n) + sent.b * state.settings.physics_dt +
                          Stack(next.dV_n);
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

// Counts the steps whose snapshot held a neighbor.
class NeighborCounter final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord&) override {}

  void OnStep(const physics::StepRecord& step, const world::World&) override {
    ++steps;
    if (step.neighbors > 0) ++with_neighbor;
  }
  int steps = 0, with_neighbor = 0;
};

class RestTest : public ::testing::TestWithParam<const char*> {};

TEST_P(RestTest, PointerNearButNotTouchingFeelsNothing) {
  // The pointer glides past the cube's −x face with a 2 cm gap, inside the 5 cm neighbor
  // margin: the cube is a neighbor every step (simulated locally, perturbed with the nominal
  // force into it, overwritten), yet nothing touches, so no force may be displayed or applied.
  constexpr double kGap = 0.02;  // m, pointer surface to the face
  // Long enough for the cube's initial settling bounce to die out (as in the test below).
  const double duration = 5.0;
  const double x = -0.05 - 0.02 - kGap;  // face at −0.05, pointer radius 0.02
  device::Specifications specs;
  specs.max_force = 100.0;
  auto device = device::MakeScriptedDevice({{0.0, Pose{Vec3(x, -0.04, 0.05), Quat::Identity()}},
                                            {duration, Pose{Vec3(x, 0.04, 0.05), Quat::Identity()}}},
                                           specs);
  settings::EngineSettings settings = LocalSettings(duration, GetParam());
  ASSERT_GT(settings.rendering.neighbor_margin, kGap);
  Engine engine(world::World::LoadString(kCubeOnFloor), std::move(device), device::Calibration{},
                settings);
  NeighborCounter counter;
  const RunStats stats = engine.Run(&counter);
  EXPECT_EQ(counter.with_neighbor, counter.steps);
  EXPECT_GT(counter.steps, 10);
  EXPECT_EQ(stats.max_force, 0.0);
  EXPECT_TRUE(stats.impulses.empty());
  // The cube comes to rest in its soft contact where it does with no pointer at all.
  constexpr double kRestTol = 1e-6;  // m and m/s
  world::World reference = world::World::LoadString(kCubeOnFloor);
  reference.set_timestep(settings.physics_dt);
  for (int i = 0; i < counter.steps; ++i) reference.Step();
  const int id = engine.world().FindBody("cube");
  const world::BodyState cube = engine.world().body_state(id);
  EXPECT_LE((cube.p_WCm - reference.body_state(id).p_WCm).norm(), kRestTol);
  EXPECT_LE((cube.V_WCm.v - reference.body_state(id).V_WCm.v).norm(), kRestTol);
}

TEST_P(RestTest, UntouchedRestingNeighborStaysAtRest) {
  // The cube is a neighbor (pointer 1 cm away, never touching): it is simulated locally,
  // perturbed every step and overwritten every step, and must not move more than MuJoCo's own
  // resting contact does.
  constexpr double kRestTol = 1e-6;  // m and m/s
  const double duration = 5.0;
  Engine engine(world::World::LoadString(kCubeOnFloor),
                PushingDevice(Vec3(-0.08, 0, 0.05), 0.0, duration), device::Calibration{},
                LocalSettings(duration, GetParam()));
  world::World reference = world::World::LoadString(kCubeOnFloor);
  reference.set_timestep(0.05);
  for (int i = 0; i < 100; ++i) reference.Step();
  const RunStats stats = engine.Run(nullptr);
  const int cube = engine.world().FindBody("cube");
  const world::BodyState state = engine.world().body_state(cube);
  EXPECT_EQ(stats.max_force, 0.0);
  EXPECT_LE((state.p_WCm - reference.body_state(cube).p_WCm).norm(), kRestTol);
  EXPECT_LE(state.V_WCm.v.norm(), kRestTol);
  EXPECT_LE(state.V_WCm.w.norm(), kRestTol);
}

INSTANTIATE_TEST_SUITE_P(Models, RestTest, ::testing::Values("perturbation", "contact"));

TEST(LocalDynamicsTest, T41ImpulseMatchesTheElasticBounceAndTheCubeMomentum) {
  // SPEC T4.1: the proposed method's impulse is within a few percent of B1's (2.0466 N·s here)
  // and of the elastic 2mv = 2.04 N·s; momentum bookkeeping holds to roundoff.
  constexpr double kRelTol = 0.02;
  constexpr double kMomentumTol = 1e-9;
  auto engine = T41Engine(T41Settings("local-dynamics"));
  const RunStats stats = engine->Run(nullptr);
  const int cube = engine->world().FindBody("cube");
  const double impulse = -ImpulseOn(stats, cube).x();
  const double elastic = 2.0 * kCubeMass * kCubeSpeed;
  EXPECT_NEAR(impulse, elastic, kRelTol * elastic);
  const double dp = kCubeMass * (engine->world().body_state(cube).V_WCm.v.x() - kCubeSpeed);
  EXPECT_NEAR(dp, -impulse, kMomentumTol * elastic);
  EXPECT_EQ(stats.fault_nonfinite_wrench, 0);
}

TEST(LocalDynamicsTest, CountsOneMeasuredNeighborAndFourForwardSkipRunsPerStepInT41) {
  EngineState state(T41World(), device::MakeFixedDevice(Pose{}), device::Calibration{},
                    T41Settings("local-dynamics"));
  state.world.ApplyKeyframe("approach");
  const int periods = 10;
  RunPeriods(state, periods, [](int, int) {});
  const LocalDynamicsPhysics& method = PhysicsOf(state);
  // PhysicsStart and every step measure the cube: one zero-force and three test-force runs,
  // all by forward skipping (slide joints on the world).
  const std::int64_t measurements = periods + 1;
  EXPECT_EQ(method.counters().steps, periods);
  EXPECT_EQ(method.counters().perturbed_bodies, measurements);
  EXPECT_EQ(method.perturber_counters().forward_skip_runs, 4 * measurements);
  EXPECT_EQ(method.perturber_counters().full_step_runs, 0);
  EXPECT_EQ(method.counters().overwrites, periods - 1);  // step 0 has no local state yet
  EXPECT_GT(method.counters().total.perturbation_ms, 0.0);
}

TEST(LocalDynamicsTest, HingedBodyFallsBackToImpulsesAndStillTurns) {
  // A door on a hinge: its free local motion leaves the hinge's circle, so the world cannot
  // take the local state; the period's reaction then acts as a force (as in B4) and the local
  // simulation restarts from the global state.
  constexpr char kDoor[] = R"(
<mujoco><option timestep="0.05" gravity="0 0 0"/><worldbody>
  <body name="door" pos="0 0 0"><joint type="hinge" axis="0 0 1"/>
    <geom type="box" size="0.3 0.02 0.2" pos="0.3 0 0" mass="2"/></body>
  <body name="pointer" mocap="true" pos="0.5 -0.05 0">
    <geom type="sphere" size="0.02" contype="0" conaffinity="0"/></body>
</worldbody></mujoco>)";
  const double duration = 1.0;
  Engine engine(
      world::World::LoadString(kDoor),
      [] {
        device::Specifications specs;
        specs.max_force = 100.0;
        return device::MakeScriptedDevice({{0.0, Pose{Vec3(0.5, -0.05, 0), Quat::Identity()}},
                                           {1.0, Pose{Vec3(0.5, 0.05, 0), Quat::Identity()}}},
                                          specs);
      }(),
      device::Calibration{}, LocalSettings(duration));
  const RunStats stats = engine.Run(nullptr);
  const world::BodyState door = engine.world().body_state(engine.world().FindBody("door"));
  EXPECT_GT(stats.max_force, 0.0);
  EXPECT_EQ(stats.fault_nonfinite_wrench, 0);
  EXPECT_GT(door.V_WCm.w.z(), 0.0);  // pushed along +y at x = 0.5: turns about +z
  EXPECT_LT(door.V_WCm.w.head<2>().norm(), 1e-9);
}

TEST(LocalDynamicsTest, RealtimeModeDeliversTheT41BounceImpulse) {
  // Real-time mode is not deterministic (late ticks, a physics step that may finish after some
  // ticks of the period), but the physics is the same: the spring bounces the 60 kg cube
  // elastically, delivering 2mv = 2.04 N·s, which lockstep meets within 2 %. A late or
  // repeated tick changes the impulse by at most one tick of the peak force, ~4 N × 1 ms
  // = 0.2 % each; 15 % allows for dozens of them (this VM stalls for milliseconds) while still
  // failing a lost sync or a doubled push (0 or ~2× the impulse) or the impulse method's +60 %.
  constexpr double kRelTol = 0.15;
  settings::EngineSettings settings = T41Settings("local-dynamics");
  settings.mode = settings::Mode::kRealtime;
  settings.duration = 1.4;  // contact from ~0.29 s for π√(m/k) ≈ 0.77 s
  auto engine = T41Engine(settings);
  const RunStats stats = engine->Run(nullptr);
  const int cube = engine->world().FindBody("cube");
  const double elastic = 2.0 * kCubeMass * kCubeSpeed;
  EXPECT_GT(stats.steps, 0);
  EXPECT_NEAR(-ImpulseOn(stats, cube).x(), elastic, kRelTol * elastic);
  EXPECT_EQ(stats.fault_nonfinite_wrench, 0);
}

TEST(LocalDynamicsTest, HapticTicksNeverAllocateInContact) {
  for (int scene = 0; scene < 2; ++scene) {
    const double duration = 1.0;
    settings::EngineSettings settings =
        scene == 0 ? T41Settings("local-dynamics") : LocalSettings(duration);
    world::World world = scene == 0 ? T41World() : RowWorld(3);
    if (scene == 0) world.ApplyKeyframe("approach");
    auto device = scene == 0 ? device::MakeFixedDevice(Pose{})
                             : PushingDevice(Vec3(kRowPointerX, 0, kRowZ), kPushSpeed, duration);
    EngineState state(std::move(world), std::move(device), device::Calibration{}, settings);
    const std::int64_t allocations = HapticAllocations(state, 20);  // adoption included
    EXPECT_EQ(allocations, 0) << "scene " << scene;
    EXPECT_GT(state.haptic->counters().max_force, 1.0) << "scene " << scene;
  }
}

using mrh::testing::HashingRecorder;

std::uint64_t RowRunHash() {
  HashingRecorder recorder;
  Engine engine(RowWorld(3), PushingDevice(Vec3(kRowPointerX, 0, kRowZ), kPushSpeed, 0.6),
                device::Calibration{}, LocalSettings(0.6));
  (void)engine.Run(&recorder);
  return recorder.hash();
}

TEST(LocalDynamicsTest, LockstepRerunIsBitIdentical) {
  EXPECT_EQ(RowRunHash(), RowRunHash());
}

}  // namespace
}  // namespace mrh::engine::testing
