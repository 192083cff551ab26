// SPDX-License-Identifier: Apache-2.0
// T3.3: the thesis' ordering of the real-time computation ratio (proxy-6dof below the
// contact-volume penalty simulation at every cube count, the penalty growing with the count).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiment_test_util.h"
#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

class T33ExperimentTest : public testing::ExperimentTest<T33ExperimentTest> {
 protected:
  static void SetUpTestSuite() {
    options_.cubes = {3, 12};
    options_.duration = 0.2;
    RunExperiment("mrh_experiments_test_t3_3_", [](const std::filesystem::path& out) {
      return RunT33(out, /*quiet=*/true, options_);
    });
  }

  inline static T33Options options_;
};

TEST_F(T33ExperimentTest, PassesItsChecks) {
  EXPECT_EQ(exit_code_, 0);
  testing::ExpectAllChecksPass(*summary_);
}

// The thesis' ordering in max real-time cubes: the proxy handles at least as many as the
// penalty simulation and the virtual coupling.
TEST_F(T33ExperimentTest, ProxyHoldsAtLeastAsManyCubesAsThePenaltyMethods) {
  const nlohmann::json& max = (*summary_)["max_realtime_cubes"];
  EXPECT_GE(max["proxy-6dof"].get<int>(), max["contact-volume"].get<int>());
  EXPECT_GE(max["proxy-6dof"].get<int>(), max["virtual-coupling"].get<int>());
  EXPECT_GT(max["proxy-6dof"].get<int>(), 0);
}

TEST_F(T33ExperimentTest, ReportsMaxRealtimeCubesForEveryMethod) {
  for (const std::string& m : options_.methods) {
    EXPECT_TRUE((*summary_)["max_realtime_cubes"].contains(m)) << m;
    EXPECT_TRUE(std::isfinite((*summary_)["cost_vs_proxy_at_max_cubes"][m].get<double>())) << m;
  }
}

// --full grows each method's count until its ratio passes 1: by 3 up to 30, then by half.
TEST(T33GrowToLimitTest, StopsAtTheFirstCountOverRealTime) {
  std::vector<int> measured;
  const T33Limit limit = GrowToLimit(3, 600, [&](int n) {
    measured.push_back(n);
    return n / 100.0;
  });
  EXPECT_EQ(limit.max_realtime, 69);
  EXPECT_EQ(limit.first_over, 105);
  const std::vector<int> expected = {3, 6, 9, 12, 15, 18, 21, 24, 27, 30, 45, 69, 105};
  EXPECT_EQ(measured, expected);
}

TEST(T33GrowToLimitTest, ReportsTheSceneLimitWhenNothingPassesRealTime) {
  const T33Limit limit = GrowToLimit(3, 50, [](int) {
    return 0.5;
  });
  EXPECT_EQ(limit.max_realtime, 45);
  EXPECT_EQ(limit.first_over, 0);
  EXPECT_EQ(GrowToLimit(3, 600,
                        [](int) {
                          return 1.5;
                        })
                .max_realtime,
            0);
}

}  // namespace
}  // namespace mrh::experiments::internal
