// SPDX-License-Identifier: Apache-2.0
// Perturbation simulations: analytic accelerance of free bodies, forward skipping against full
// steps, and exact restoration of the world.
#include "mrh/world/perturbation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "perturbation_test_util.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using testing::Bodies;
using testing::kBusy;
using testing::kNoPointer;
using testing::kSkipTol;

// A free 2 kg box (distinct half sizes, so its world inertia is not diagonal), turned and off
// the origin, in zero gravity with nothing to touch.
constexpr char kFreeBox[] = R"(
<mujoco>
  <option timestep="0.05" gravity="0 0 0"/>
  <worldbody>
    <body name="box" pos="0.3 -0.2 0.5" euler="20 -35 50"><freejoint/>
      <geom type="box" size="0.05 0.1 0.15" mass="2"/></body>
  </worldbody>
</mujoco>)";

// Relative tolerance of accelerances that hold to floating-point roundoff (the brief's 1e-9).
constexpr double kAnalyticTol = 1e-9;

Mat3 Cross(const Vec3& r) {
  Mat3 m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

// M⁻¹J of a free body for a force at p_W: linear rows I/m, angular rows I_W⁻¹[r]× (eq. 4.1–4.2).
Mat63 FreeBodyAccelerance(const World& world, int body, const Vec3& p_W) {
  const BodyInfo& info = world.body(body);
  const BodyState state = world.body_state(body);
  const Mat3 R = state.X_WB.q.toRotationMatrix();
  const Mat3 I_W = R * info.inertia_B * R.transpose();
  Mat63 A;
  A.topRows<3>() = Mat3::Identity() / info.mass;
  A.bottomRows<3>() = I_W.inverse() * Cross(p_W - state.p_WCm);
  return A;
}

struct Measured {
  DynamicIr ir;
  bool forward_skip = false;
};

// Measures every listed body with a force `f` at a point 3 cm from its COM.
std::vector<Measured> MeasureAll(World* world, const std::vector<int>& bodies, const Vec3& f,
                                 PerturbationPath path) {
  Perturber perturber(world, path);
  std::vector<Vec3> points;
  for (int b : bodies) points.push_back(world->body_state(b).p_WCm + Vec3(-0.03, 0.02, 0.01));
  perturber.Begin(bodies);
  perturber.ZeroForceRun();
  std::vector<Measured> out;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    out.push_back(Measured{perturber.Measure(i, f, points[i]), perturber.forward_skip()});
  }
  perturber.End();
  return out;
}

std::vector<double> Copy(std::span<const double> values) {
  return std::vector<double>(values.begin(), values.end());
}

TEST(TestForcesTest, ColumnsHaveTheUserForceMagnitudeAndTheDeterminantOfEq410) {
  for (const Vec3& f1 : {Vec3(3, 0, 0), Vec3(0.2, -1.5, 0.7), Vec3(0, 0, -0.5)}) {
    const Mat3 F = TestForces(f1);
    const double m = f1.norm();
    EXPECT_EQ(F.col(0), f1);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(F.col(k).norm(), m, 1e-15 * m);
    // Both extra forces lie 45° from the user's push.
    EXPECT_NEAR(F.col(1).dot(f1), m * m / std::sqrt(2.0), 1e-14 * m * m);
    EXPECT_NEAR(F.col(2).dot(f1), m * m / std::sqrt(2.0), 1e-14 * m * m);
    EXPECT_NEAR(std::abs(F.determinant()), m * m * m / 2.0, 1e-14 * m * m * m);
  }
}

TEST(PerturberTest, FreeBodyAcceleranceIsItsInverseMassAndLeverArmCoupling) {
  for (PerturbationPath path : {PerturbationPath::kAuto, PerturbationPath::kFullStep}) {
    World world = World::LoadString(kFreeBox, kNoPointer);
    const int box = world.FindBody("box");
    const Vec3 p_W = world.body_state(box).p_WCm + Vec3(0.05, -0.08, 0.1);
    const Mat63 expected = FreeBodyAccelerance(world, box, p_W);
    Perturber perturber(&world, path);
    const int bodies[] = {box};
    perturber.Begin(bodies);
    perturber.ZeroForceRun();
    const DynamicIr ir = perturber.Measure(0, Vec3(0.3, -0.4, 0.2), p_W);
    perturber.End();
    EXPECT_LE((ir.A - expected).norm(), kAnalyticTol * expected.norm()) << ir.A << "\n" << expected;
    EXPECT_LE(ir.b.norm(), kAnalyticTol * expected.norm());
  }
}

TEST(PerturberTest, FreeFallingBodyHasGravityAsBias) {
  World world = World::LoadString(kFreeBox, kNoPointer);
  world.set_gravity(Vec3(0, 0, -9.81));
  const int bodies[] = {world.FindBody("box")};
  Perturber perturber(&world);
  perturber.Begin(bodies);
  perturber.ZeroForceRun();
  const DynamicIr ir = perturber.Measure(0, Vec3(0, 0, -0.5), world.body_state(bodies[0]).p_WCm);
  perturber.End();
  Vec6 g;
  g << 0, 0, -9.81, 0, 0, 0;
  EXPECT_LE((ir.b - g).norm(), kAnalyticTol * 9.81);
}

TEST(PerturberTest, SlideJointedBodyHasNoAngularAccelerance) {
  World world = World::LoadString(kBusy, kNoPointer);
  const std::vector<int> bodies = Bodies(world, {"slider"});
  const Measured m = MeasureAll(&world, bodies, Vec3(0.5, 0.5, 0), PerturbationPath::kAuto)[0];
  EXPECT_TRUE(m.forward_skip);
  EXPECT_EQ(m.ir.A.bottomRows<3>(), Eigen::Matrix3d::Zero());
  // Two slides (x, y) of a 3 kg body: 1/3 kg⁻¹ along them, nothing along z.
  Mat3 expected = Mat3::Zero();
  expected(0, 0) = expected(1, 1) = 1.0 / 3.0;
  EXPECT_LE((m.ir.A.topRows<3>() - expected).norm(), kAnalyticTol);
}

TEST(PerturberTest, ForwardSkipMatchesFullStepsInContactWithFriction) {
  World skip_world = World::LoadString(kBusy, kNoPointer);
  skip_world.ApplyKeyframe("moving");
  for (int i = 0; i < 5; ++i) skip_world.Step();  // settle into contact, warm start non-trivial
  World full_world = World::LoadString(kBusy, kNoPointer);
  full_world.ApplyKeyframe("moving");
  for (int i = 0; i < 5; ++i) full_world.Step();
  ASSERT_GT(skip_world.num_contacts(), 0);
  const std::vector<int> bodies =
      Bodies(skip_world, {"resting", "leaning", "tumbling", "slider", "row1"});
  const Vec3 f(-0.8, 0.3, -0.5);
  const auto skip = MeasureAll(&skip_world, bodies, f, PerturbationPath::kAuto);
  const auto full = MeasureAll(&full_world, bodies, f, PerturbationPath::kFullStep);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    EXPECT_TRUE(skip[i].forward_skip);
    EXPECT_FALSE(full[i].forward_skip);
    const double scale = full[i].ir.A.norm();
    EXPECT_LE((skip[i].ir.A - full[i].ir.A).norm(), kSkipTol * scale) << "body " << bodies[i];
    EXPECT_LE((skip[i].ir.b - full[i].ir.b).norm(), kSkipTol * (1.0 + full[i].ir.b.norm()))
        << "body " << bodies[i];
  }
}

// Measures every listed body with `settings`, as MeasureAll does, and returns the counters.
std::vector<DynamicIr> MeasureWith(World* world, const std::vector<int>& bodies, const Vec3& f,
                                   const PerturberSettings& settings, PerturberCounters* counters) {
  Perturber perturber(world, settings);
  perturber.Begin(bodies);
  perturber.ZeroForceRun();
  std::vector<DynamicIr> out;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    out.push_back(
        perturber.Measure(i, f, world->body_state(bodies[i]).p_WCm + Vec3(-0.03, 0.02, 0.01)));
  }
  perturber.End();
  *counters = perturber.counters();
  return out;
}

TEST(PerturberTest, IslandSolveMatchesConvergedMuJoCoAndFallsBackBeyondItsCap) {
  // The exact island minimizer against MuJoCo's solver run to roundoff (friction, a slider, a
  // touching row). MuJoCo's Newton at tolerance 1e-15 agrees to ~1e-12.
  constexpr double kTol = 1e-9;
  World world = World::LoadString(kBusy, kNoPointer);
  world.ApplyKeyframe("moving");
  for (int i = 0; i < 5; ++i) world.Step();
  const std::vector<int> bodies = Bodies(world, {"resting", "leaning", "slider", "row1"});
  const Vec3 f(-0.8, 0.3, -0.5);
  PerturberCounters island{}, converged{}, capped{};
  const auto a = MeasureWith(&world, bodies, f, {}, &island);
  const auto b = MeasureWith(&world, bodies, f,
                             {.island_solve = false,
                              .warm_start = TestRunWarmStart::kSaved,
                              .solver_tolerance = 1e-15,
                              .solver_iterations = 1000},
                             &converged);
  // A cap of 2 dofs: only the slider's island fits; the free bodies' go to MuJoCo's solver
  // (the model's Newton at its own tolerance, hence the looser 1e-6 below).
  const auto c = MeasureWith(&world, bodies, f, {.max_island_dofs = 2}, &capped);
  EXPECT_EQ(island.island_runs, 3 * static_cast<std::int64_t>(bodies.size()));
  EXPECT_EQ(island.island_fallbacks, 0);
  EXPECT_EQ(island.force_run_solver_iterations, 0);
  EXPECT_GT(converged.force_run_solver_iterations, 0);
  EXPECT_EQ(capped.island_runs, 3);  // only the slider (2 dofs) fits
  EXPECT_EQ(capped.island_fallbacks, 3);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    EXPECT_LE((a[i].A - b[i].A).norm(), kTol * b[i].A.norm()) << "body " << bodies[i];
    EXPECT_LE((a[i].A - c[i].A).norm(), 1e-6 * b[i].A.norm()) << "body " << bodies[i];
  }
}

TEST(PerturberTest, GroupHoldsTheTouchingBodyWithItsCrossAccelerance) {
  // Two 1 kg boxes touching along x (0.1 mm overlap) in zero gravity, a third far away:
  // pushing the first along +x moves the second too, and the contact conserves momentum, so
  // m (a_1 + a_2) = f exactly; MuJoCo's soft contact passes on about half (impedance 0.9).
  constexpr char kPair[] = R"(
<mujoco><option timestep="0.05" gravity="0 0 0"/><worldbody>
  <body name="a" pos="0 0 0"><freejoint/><geom type="box" size="0.1 0.1 0.1" mass="1"/></body>
  <body name="b" pos="0.1999 0 0"><freejoint/><geom type="box" size="0.1 0.1 0.1" mass="1"/></body>
  <body name="far" pos="0 3 0"><freejoint/><geom type="box" size="0.1 0.1 0.1" mass="1"/></body>
</worldbody></mujoco>)";
  for (PerturbationPath path : {PerturbationPath::kAuto, PerturbationPath::kFullStep}) {
    World world = World::LoadString(kPair, kNoPointer);
    const std::vector<int> bodies = Bodies(world, {"a"});
    Perturber perturber(&world, path);
    perturber.Begin(bodies);
    perturber.ZeroForceRun();
    const Vec3 p_W = world.body_state(bodies[0]).p_WCm + Vec3(-0.1, 0, 0);
    const DynamicIr ir = perturber.Measure(0, Vec3(2.0, 0, 0), p_W);
    perturber.End();
    ASSERT_EQ(perturber.group().size(), 1u);
    const GroupResponse& other = perturber.group()[0];
    EXPECT_EQ(other.body, world.FindBody("b"));
    EXPECT_NEAR(ir.A(0, 0) + other.A(0, 0), 1.0, kAnalyticTol);
    EXPECT_GT(other.A(0, 0), 0.4);
  }
}

TEST(PerturberTest, StepAfterPerturbationsIsBitIdenticalToStepWithout) {
  for (PerturbationPath path : {PerturbationPath::kAuto, PerturbationPath::kFullStep}) {
    World perturbed = World::LoadString(kBusy, kNoPointer);
    World reference = World::LoadString(kBusy, kNoPointer);
    perturbed.ApplyKeyframe("moving");
    reference.ApplyKeyframe("moving");
    const std::vector<int> bodies = Bodies(perturbed, {"resting", "leaning", "row1", "row2"});
    for (int step = 0; step < 8; ++step) {
      perturbed.Step();
      reference.Step();
      // The same state queries on both: MuJoCo's kinematics renormalizes free-joint quaternions
      // in qpos in place, so a query alone changes the next step at roundoff.
      for (int b : bodies) (void)reference.body_state(b);
      (void)MeasureAll(&perturbed, bodies, Vec3(0.5, -0.2, -1.0), path);
    }
    perturbed.Step();
    reference.Step();
    EXPECT_EQ(perturbed.time(), reference.time());
    EXPECT_EQ(Copy(perturbed.qpos()), Copy(reference.qpos()));
    EXPECT_EQ(Copy(perturbed.qvel()), Copy(reference.qvel()));
  }
}

TEST(PerturberTest, ZeroForceRunLeavesTheStateUntouched) {
  World world = World::LoadString(kBusy, kNoPointer);
  world.ApplyKeyframe("moving");
  world.Step();
  const std::vector<double> qvel = Copy(world.qvel());
  Perturber perturber(&world);
  const std::vector<int> bodies = Bodies(world, {"tumbling", "resting"});
  perturber.Begin(bodies);
  perturber.ZeroForceRun();
  EXPECT_EQ(Copy(world.qvel()), qvel);
  perturber.End();
  // The zero-force run predicts the next real step (here: spinning free fall, and sliding on
  // the floor with friction).
  const std::vector<Twist> predicted = {perturber.zero_force_velocity(0),
                                        perturber.zero_force_velocity(1)};
  world.Step();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Twist actual = world.body_state(bodies[i]).V_WCm;
    EXPECT_LE((actual.v - predicted[i].v).norm(), kSkipTol) << bodies[i];
    EXPECT_LE((actual.w - predicted[i].w).norm(), kSkipTol) << bodies[i];
  }
}

TEST(PerturberTest, FallsBackToFullStepsWhereSkippingIsNotExact) {
  const std::string hinge = R"(
<mujoco><option timestep="0.02"/><worldbody>
  <body name="door" pos="0 0 1"><joint type="hinge" axis="0 0 1"/>
    <geom type="box" size="0.3 0.02 0.5" pos="0.3 0 0"/></body>
</worldbody></mujoco>)";
  std::string rk4 = kFreeBox;
  rk4.replace(rk4.find("<option "), 8, "<option integrator=\"RK4\" ");
  std::string damped = kFreeBox;
  damped.replace(damped.find("<freejoint/>"), 12, "<joint type=\"free\" damping=\"0.1\"/>");
  for (const std::string& xml : {hinge, rk4, damped}) {
    World world = World::LoadString(xml, kNoPointer);
    Perturber perturber(&world);
    const int bodies[] = {1};
    perturber.Begin(bodies);
    EXPECT_FALSE(perturber.forward_skip()) << xml;
    perturber.ZeroForceRun();
    (void)perturber.Measure(0, Vec3(0, 1, 0), world.body_state(1).p_WCm + Vec3(0.1, 0, 0));
    perturber.End();
    EXPECT_EQ(perturber.counters().full_step_runs, 4);
    EXPECT_EQ(perturber.counters().forward_skip_runs, 0);
  }
}

TEST(PerturberTest, CountsOneZeroForceRunAndThreeRunsPerMeasuredBody) {
  World world = World::LoadString(kBusy, kNoPointer);
  const std::vector<int> bodies = Bodies(world, {"resting", "leaning", "row1"});
  Perturber perturber(&world);
  perturber.Begin(bodies);
  perturber.ZeroForceRun();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    (void)perturber.Measure(i, Vec3(0, 0, -1), world.body_state(bodies[i]).p_WCm);
  }
  perturber.End();
  const PerturberCounters& c = perturber.counters();
  EXPECT_EQ(c.begins, 1);
  EXPECT_EQ(c.zero_force_runs, 1);
  EXPECT_EQ(c.force_runs, 9);
  EXPECT_EQ(c.forward_skip_runs, 10);
  EXPECT_EQ(c.full_step_runs, 0);
}

}  // namespace
}  // namespace mrh::world
