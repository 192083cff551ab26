// SPDX-License-Identifier: Apache-2.0
// t4.latency in lockstep: the touched object responds one tick after the force onset with
// local-dynamics, one to two physics steps later with the impulse method (counted in ticks).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "experiment_test_util.h"
#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

constexpr int kTicksPerStep = 50;  // 50 ms physics, 1 ms haptic

class LatencyExperimentTest : public testing::ExperimentTest<LatencyExperimentTest> {
 protected:
  static void SetUpTestSuite() {
    RunExperiment("mrh_experiments_test_latency_", [](const std::filesystem::path& out) {
      return RunLatency(out, /*quiet=*/true, options_);
    });
  }

  static int Latency(const char* method, int phase) {
    return (*summary_)["runs"][method][std::to_string(phase)]["latency_ticks"].get<int>();
  }

  inline static LatencyOptions options_;
};

TEST_F(LatencyExperimentTest, PassesItsChecks) {
  EXPECT_EQ(exit_code_, 0);
}

TEST_F(LatencyExperimentTest, LocalDynamicsRespondsWithinOneTick) {
  for (const int phase : options_.onset_phases) {
    EXPECT_EQ(Latency("local-dynamics", phase), 1) << "onset at j = " << phase;
  }
}

// The period's impulse reaches the world in the next step and is rendered from the period after:
// 2n − j ticks for an onset at tick j of its period, i.e. between one and two physics steps.
TEST_F(LatencyExperimentTest, ImpulseMethodRespondsAfterOneToTwoPhysicsSteps) {
  for (const int phase : options_.onset_phases) {
    const int latency = Latency("impulse", phase);
    EXPECT_EQ(latency, 2 * kTicksPerStep - phase) << "onset at j = " << phase;
    EXPECT_GT(latency, kTicksPerStep);
    EXPECT_LE(latency, 2 * kTicksPerStep);
  }
}

TEST_F(LatencyExperimentTest, SingleRateRespondsInTwoTicks) {
  EXPECT_EQ(Latency("single-rate", 0), 2);
}

}  // namespace
}  // namespace mrh::experiments::internal
