// SPDX-License-Identifier: Apache-2.0
// D2, articulated mechanisms: the single-rate reference (1 ms) feels a drawer's damping and
// frictionloss as d v + F, and the 20 ms local methods feel the lamp, door, drawer and lever as
// the reference does (the acceptance bars of d2_impl.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "experiment_test_util.h"
#include "experiments/d2_impl.h"

namespace mrh::experiments::internal {
namespace {

D2Case Case(const D2Options& o, const std::string& name) {
  for (const D2Case& c : o.cases) {
    if (c.name == name) return c;
  }
  ADD_FAILURE() << "no case " << name;
  return {};
}

// A steady push at v on a slide with damping d and frictionloss F takes d v + F (Newton, the
// drawer's acceleration zero). The measured window starts 1.5 s after the touch: the impact's
// oscillation on the contact spring (about v sqrt(k m) = 1.2 N) decays with the time constant
// 2 m / (d + rendering damping) = 0.2 s, so less than 1e-3 N of it is left. 5 % is the
// experiment's bar (0.03 N): MuJoCo's soft joint friction and the integrator's damping must not
// take more than that.
TEST(D2Test, DrawerSingleRateForceIsDampingTimesSpeedPlusFrictionloss) {
  const D2Options o = DefaultD2Options();
  const D2Case drawer = Case(o, "drawer");
  ASSERT_GT(drawer.frictionloss, 0.0);
  ASSERT_EQ(o.runs.front().method, "single-rate");
  const D2Trace trace = RunD2Case({}, o, drawer, o.runs.front());
  const D2Metrics m = AnalyzeD2(o, drawer, trace, trace);
  const double analytic = D2AnalyticForce(drawer, o.speed);
  EXPECT_NEAR(m.steady_force, analytic, 0.05 * analytic);
  EXPECT_EQ(m.contact_lost, 0.0);
}

class D2ExperimentTest : public testing::ExperimentTest<D2ExperimentTest> {
 protected:
  static void SetUpTestSuite() {
    RunExperiment("mrh_experiments_test_d2_", [](const std::filesystem::path& out) {
      return RunD2(out, /*quiet=*/true);
    });
  }

  // Every mechanism's run of `method` meets each bar against the single-rate reference.
  static void ExpectBars(const std::string& method) {
    for (const char* name : {"lamp", "door", "drawer", "lever"}) {
      const nlohmann::json& row = (*summary_)["cases"][name][method];
      ASSERT_TRUE(row.contains("bars")) << name << " / " << method << ": " << row.dump();
      for (const auto& [bar, pass] : row["bars"].items()) {
        EXPECT_TRUE(pass.get<bool>())
            << name << " / " << method << ": bar " << bar << " fails; " << row.dump();
      }
    }
  }
};

TEST_F(D2ExperimentTest, LocalDynamicsFeelsTheMechanismsLikeSingleRate) {
  ExpectBars("local-dynamics");
}

TEST_F(D2ExperimentTest, LocalDynamics6dofFeelsTheMechanismsLikeSingleRate) {
  ExpectBars("local-dynamics-6dof");
}

TEST_F(D2ExperimentTest, PassesItsChecks) {
  EXPECT_EQ(exit_code_, 0);
  testing::ExpectAllChecksPass(*summary_);
  EXPECT_TRUE(std::filesystem::exists(*out_ / "d2.csv"));
}

}  // namespace
}  // namespace mrh::experiments::internal
