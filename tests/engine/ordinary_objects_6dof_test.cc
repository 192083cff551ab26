// SPDX-License-Identifier: Apache-2.0
// The 6-DOF methods with the contact torque model on ordinary objects pushed off their centre
// (scenes/push_*.json: a box pointer moving along +x at v = 0.1 m/s, 20 ms physics, friction
// 0.5 on the floor, elliptic cones), against what the contact patch allows:
//  - a sphere rolls ahead: no faster than the pointer pushes it (kicks are bounded by 2 v) and
//    rolling without slip at the end (|ω| r = |v|); proxy-6dof here, local-dynamics-6dof's
//    no-throw bar in rolling_island_test.cc;
//  - an upright cylinder slides at Coulomb's force μ m g without spinning up;
//  - a box pushed 4 cm off its centre line turns away from the push (negative yaw).
// The thesis torque model (eq. 3.8's couple given to the objects) fails each: it spins the
// sphere and the cylinder to tens of rad/s and holds the box straight.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

constexpr double kPushSpeed = 0.1;  // m/s, the scripted pointer
constexpr double kGravity = 9.81;   // m/s²

// The pushed body's states (one per step) and the felt force (one per tick).
class ObjectRecorder final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override {
    if (tick.t >= 2.0) forces.push_back(tick.displayed_W.f);
  }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    if (object < 0) object = world.FindBody("object");
    states.push_back(world.body_state(object));
    times.push_back(step.t);
  }

  int object = -1;
  std::vector<Vec3> forces;
  std::vector<double> times;
  std::vector<world::BodyState> states;
};

struct PushRun {
  ObjectRecorder record;
  RunStats stats;
};

PushRun Push(const std::string& scene, const std::string& method, const std::string& model) {
  const session::Session session =
      session::LoadSession(std::string(MRH_SOURCE_DIR) + "/scenes/" + scene + ".json",
                           {"method=" + method, "rendering.torque_model=" + model});
  PushRun run;
  run.stats = session::MakeEngine(session)->Run(&run.record);
  return run;
}

// Largest COM speed and spin after the first contact (1 s).
double PeakSpeed(const PushRun& run) {
  double peak = 0.0;
  for (std::size_t i = 0; i < run.record.states.size(); ++i) {
    if (run.record.times[i] >= 1.0) peak = std::max(peak, run.record.states[i].V_WCm.v.norm());
  }
  return peak;
}

double PeakSpin(const PushRun& run) {
  double peak = 0.0;
  for (std::size_t i = 0; i < run.record.states.size(); ++i) {
    if (run.record.times[i] >= 1.0) peak = std::max(peak, run.record.states[i].V_WCm.w.norm());
  }
  return peak;
}

double MeanPushForce(const PushRun& run) {  // N along −x (the pointer feels the object push back)
  double sum = 0.0;
  for (const Vec3& f : run.record.forces) sum -= f.x();
  return run.record.forces.empty() ? 0.0 : sum / static_cast<double>(run.record.forces.size());
}

double FinalYaw(const PushRun& run) {  // rad about +z
  const Quat& q = run.record.states.back().X_WB.q;
  return 2.0 * std::atan2(q.z(), q.w());
}

class OrdinaryObjectsTest : public ::testing::TestWithParam<std::string> {};

TEST(OrdinaryObjectsProxyTest, SphereRollsAheadWithoutBeingThrown) {
  const PushRun run = Push("push_sphere", "proxy-6dof", "contact");
  ASSERT_FALSE(run.record.states.empty());
  constexpr double kRadius = 0.04;
  const world::BodyState& end = run.record.states.back();
  EXPECT_GT(end.p_WCm.x(), 0.1) << "the sphere was not pushed";
  EXPECT_LT(PeakSpeed(run), 2.0 * kPushSpeed) << "the sphere is thrown";
  // Rolling without slip on the floor at the end: |ω| r = |v| within 10 %.
  const double v = end.V_WCm.v.head<2>().norm();
  EXPECT_NEAR(end.V_WCm.w.norm() * kRadius, v, 0.1 * std::max(v, 0.01));
}

TEST_P(OrdinaryObjectsTest, CylinderSlidesWithoutSpinning) {
  const PushRun run = Push("push_cylinder", GetParam(), "contact");
  ASSERT_FALSE(run.record.states.empty());
  EXPECT_LT(PeakSpeed(run), 2.0 * kPushSpeed) << GetParam();
  EXPECT_LT(PeakSpin(run), 2.0) << GetParam();  // rad/s
  EXPECT_NEAR(run.record.states.back().p_WCm.x(), 0.4, 0.02) << "the cylinder was not pushed";
}

TEST(OrdinaryObjectsLocalDynamicsTest, CylinderIsPushedAtCoulombsForce) {
  const PushRun run = Push("push_cylinder", "local-dynamics-6dof", "contact");
  ASSERT_FALSE(run.record.states.empty());
  // μ m g of the 0.3 kg cylinder on the floor (μ 0.5), within 15 %.
  const double coulomb = 0.5 * 0.3 * kGravity;
  EXPECT_NEAR(MeanPushForce(run), coulomb, 0.15 * coulomb);
}

TEST_P(OrdinaryObjectsTest, BoxPushedOffCentreTurnsAwayFromThePush) {
  const PushRun run = Push("push_box_offcentre", GetParam(), "contact");
  ASSERT_FALSE(run.record.states.empty());
  // Pushed at y = +4 cm along +x: the moment about the COM is −z, so the box yaws negative and
  // slides off the tool face toward −y.
  EXPECT_LT(FinalYaw(run), -20.0 * std::numbers::pi / 180.0) << GetParam();
  EXPECT_LT(run.record.states.back().p_WCm.y(), -0.01) << GetParam();
  EXPECT_LT(PeakSpin(run), 2.0) << GetParam();
}

// "local-dynamics-6dof" → "local_dynamics_6dof" (test names are identifiers).
std::string MethodTestName(const ::testing::TestParamInfo<std::string>& param) {
  std::string name = param.param;
  for (char& c : name) {
    if (c == '-') c = '_';
  }
  return name;
}

// Local-dynamics-6dof is the proposed method; proxy-6dof renders the same proxy against the
// world's 20 ms state. proxy-6dof's steady push force at 20 ms is ~3× Coulomb's (its own open
// fault, as on a square box push), so it is held to the no-throw and turning bars only.
INSTANTIATE_TEST_SUITE_P(SixDof, OrdinaryObjectsTest,
                         ::testing::Values("local-dynamics-6dof", "proxy-6dof"), MethodTestName);

TEST(OrdinaryObjectsThesisModelTest, ThesisModelSpinsTheCylinderTheContactModelDoesNot) {
  // The bars above can fail: eq. 3.8's couple, given to a cylinder through its contact line,
  // spins it, beyond 10 rad/s or (thrown off the floor with 450 rad/s, which MuJoCo's explicit
  // integration of the spinning body then multiplies fourfold every 40 ms) until the
  // simulation diverges, which the engine reports as an error.
  double thesis_spin = 0.0;
  try {
    thesis_spin = PeakSpin(Push("push_cylinder", "local-dynamics-6dof", "thesis"));
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("diverged"), std::string::npos) << e.what();
    thesis_spin = std::numeric_limits<double>::infinity();
  }
  const PushRun contact = Push("push_cylinder", "local-dynamics-6dof", "contact");
  EXPECT_GT(thesis_spin, 10.0);
  EXPECT_LT(PeakSpin(contact), 2.0);
}

}  // namespace
}  // namespace mrh::engine
