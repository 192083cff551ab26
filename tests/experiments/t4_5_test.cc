// SPDX-License-Identifier: Apache-2.0
// T4.5: local-dynamics simulates and renders every neighbor; timings are recorded, not judged.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "experiment_test_util.h"
#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

class T45ExperimentTest : public testing::ExperimentTest<T45ExperimentTest> {
 protected:
  static void SetUpTestSuite() {
    options_.neighbors = {1, 8, 64};
    options_.duration = 0.3;
    RunExperiment("mrh_experiments_test_t4_5_", [](const std::filesystem::path& out) {
      return RunT45(out, /*quiet=*/true, options_);
    });
  }

  inline static T45Options options_;
};

TEST_F(T45ExperimentTest, PassesItsChecks) {
  EXPECT_EQ(exit_code_, 0);
}

TEST_F(T45ExperimentTest, EveryBallIsANeighborInEveryStepAndTouchedInEveryTick) {
  for (const int n : options_.neighbors) {
    const nlohmann::json& run = (*summary_)["runs"]["local-dynamics"][std::to_string(n)];
    EXPECT_EQ(run["min_neighbors"].get<int>(), n);
    EXPECT_EQ(run["min_contacts"].get<double>(), n);
  }
}

TEST_F(T45ExperimentTest, TimingsAreRecordedForEveryNeighborCount) {
  for (const int n : options_.neighbors) {
    const nlohmann::json& run = (*summary_)["runs"]["local-dynamics"][std::to_string(n)];
    for (const char* key : {"tick_p50_us", "tick_p99_us", "worst_tick_us", "occupancy_cpu_p50"}) {
      const double v = run[key].get<double>();
      EXPECT_TRUE(std::isfinite(v) && v > 0.0) << key << " at " << n;
    }
  }
}

}  // namespace
}  // namespace mrh::experiments::internal
