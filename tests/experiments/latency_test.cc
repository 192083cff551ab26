// SPDX-License-Identifier: Apache-2.0
// t4.latency in lockstep: the touched object responds one tick after the force onset with
// local-dynamics, one to two physics steps later with the impulse method (counted in ticks).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

// Each test runs in its own process (ctest, maybe in parallel): one folder per process.
std::filesystem::path TempDir(const std::string& stem) {
  return std::filesystem::temp_directory_path() / (stem + std::to_string(getpid()));
}

constexpr int kTicksPerStep = 50;  // 50 ms physics, 1 ms haptic

class LatencyExperimentTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    out_ = new std::filesystem::path(TempDir("mrh_experiments_test_latency_"));
    std::filesystem::remove_all(*out_);
    exit_code_ = RunLatency(*out_, /*quiet=*/true, options_);
    std::ifstream in(*out_ / "summary.json");
    summary_ = new nlohmann::json(nlohmann::json::parse(in));
  }

  static void TearDownTestSuite() {
    std::filesystem::remove_all(*out_);
    delete summary_;
    delete out_;
  }

  static int Latency(const char* method, int phase) {
    return (*summary_)["runs"][method][std::to_string(phase)]["latency_ticks"].get<int>();
  }

  static std::filesystem::path* out_;
  static nlohmann::json* summary_;
  static LatencyOptions options_;
  static int exit_code_;
};

std::filesystem::path* LatencyExperimentTest::out_ = nullptr;
nlohmann::json* LatencyExperimentTest::summary_ = nullptr;
LatencyOptions LatencyExperimentTest::options_;
int LatencyExperimentTest::exit_code_ = -1;

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
