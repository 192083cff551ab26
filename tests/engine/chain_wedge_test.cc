// SPDX-License-Identifier: Apache-2.0
// scenes/chain_wedge.json: a sphere pointer pushes a cylinder into a wedge mesh at 0.1 m/s.
// Every method that renders it finishes the push without a fault (a diverging body ends the run
// with an error), moves both bodies, and throws neither faster than 2.5 × the pointer's speed
// (a rigid push leaves at most twice it; single-rate at 1 ms peaks at 0.196 m/s).
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>

#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::engine {
namespace {

constexpr double kPointerSpeed = 0.5 / 5.0;  // m/s, the session's keyframes
constexpr double kMaxSpeed = 2.5 * kPointerSpeed;

class PeakSpeed final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord&) override {}

  void OnStep(const physics::StepRecord&, const world::World& world) override {
    for (const char* name : {"mug", "target"}) {
      const int b = world.FindBody(name);
      if (b < 0) continue;
      const world::BodyState s = world.body_state(b);
      if (start.count(name) == 0) start[name] = s.p_WCm;
      peak[name] = std::max(peak[name], s.V_WCm.v.norm());
      moved[name] = (s.p_WCm - start[name]).norm();
    }
  }

  std::map<std::string, Vec3> start;
  std::map<std::string, double> peak, moved;
};

class ChainWedgeTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ChainWedgeTest, PushesTheChainWithoutAFault) {
  const session::Session session = session::LoadSession(
      std::string(MRH_SOURCE_DIR) + "/scenes/chain_wedge.json", {"method=" + GetParam()});
  PeakSpeed record;
  RunStats stats;
  ASSERT_NO_THROW(stats = session::MakeEngine(session)->Run(&record));
  EXPECT_NEAR(stats.sim_time, 5.0, 1e-6);
  EXPECT_TRUE(stats.warnings.empty()) << stats.warnings.front();
  for (const char* name : {"mug", "target"}) {
    EXPECT_LT(record.peak[name], kMaxSpeed) << name << " is thrown";
    EXPECT_GT(record.moved[name], 0.05) << name << " was not pushed";
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, ChainWedgeTest,
                         ::testing::Values("single-rate", "local-dynamics", "local-dynamics-6dof",
                                           "proxy-6dof"),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                           std::string name = p.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace mrh::engine
