// SPDX-License-Identifier: Apache-2.0
// Round bodies in the local island: the island's floor contact follows the
// rolling point, so a ball pushed under local-dynamics (3-DOF) or local-dynamics-6dof rolls
// ahead instead of being kicked and spun by a contact point that turned with it.
//  - Case A, scenes/bump_ball.json: a 0.3 kg ball (r 0.04) bumped by a sphere pointer at
//    0.12 m/s. Single-rate at 1 ms leaves at 0.23 m/s, 5.8 rad/s; a contact point that turns
//    with the ball roughly triples both.
//  - Case B, scenes/push_sphere.json: a box pointer pushes the ball 2 cm off its centre line at
//    0.1 m/s. proxy-6dof: 0.16 m/s peak; a contact point that turns with the ball doubles it.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

constexpr double kRadius = 0.04;  // m, the ball

class BallRecorder final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord&) override {}

  void OnStep(const physics::StepRecord&, const world::World& world) override {
    if (object < 0) object = world.FindBody("object");
    states.push_back(world.body_state(object));
  }

  int object = -1;
  std::vector<world::BodyState> states;
};

BallRecorder RunScene(const std::string& scene, const std::vector<std::string>& overrides) {
  const session::Session session =
      session::LoadSession(std::string(MRH_SOURCE_DIR) + "/scenes/" + scene + ".json", overrides);
  BallRecorder record;
  session::MakeEngine(session)->Run(&record);
  return record;
}

double PeakSpeed(const BallRecorder& r) {
  double peak = 0.0;
  for (const world::BodyState& s : r.states) peak = std::max(peak, s.V_WCm.v.norm());
  return peak;
}

double PeakSpin(const BallRecorder& r) {
  double peak = 0.0;
  for (const world::BodyState& s : r.states) peak = std::max(peak, s.V_WCm.w.norm());
  return peak;
}

TEST(RollingIslandTest, BumpedBallIsNotKickedUnderLocalDynamics) {
  const BallRecorder run = RunScene("bump_ball", {});
  ASSERT_FALSE(run.states.empty());
  constexpr double kPointer = 0.12;  // m/s
  const double v = PeakSpeed(run);
  EXPECT_GT(run.states.back().p_WCm.x(), 0.1) << "the ball was not pushed";
  EXPECT_LT(v, 2.5 * kPointer) << "the ball is kicked";
  EXPECT_LT(PeakSpin(run), 2.5 * v / kRadius) << "the ball is spun";
  EXPECT_LT(PeakSpin(run), 2.5 * 2.0 * kPointer / kRadius);
}

TEST(RollingIslandTest, PushedSphereIsNotThrownUnderLocalDynamics6dof) {
  const BallRecorder run = RunScene("push_sphere", {"method=local-dynamics-6dof"});
  ASSERT_FALSE(run.states.empty());
  constexpr double kPush = 0.1;  // m/s
  EXPECT_GT(run.states.back().p_WCm.x(), 0.1) << "the sphere was not pushed";
  EXPECT_LT(PeakSpeed(run), 2.0 * kPush) << "the sphere is thrown";
}

}  // namespace
}  // namespace mrh::engine
