// SPDX-License-Identifier: Apache-2.0
// T4.5: local-dynamics simulates and renders every neighbor; timings are recorded, not judged.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
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

class T45ExperimentTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    out_ = new std::filesystem::path(TempDir("mrh_experiments_test_t4_5_"));
    std::filesystem::remove_all(*out_);
    options_.neighbors = {1, 8, 64};
    options_.duration = 0.3;
    exit_code_ = RunT45(*out_, /*quiet=*/true, options_);
    std::ifstream in(*out_ / "summary.json");
    summary_ = new nlohmann::json(nlohmann::json::parse(in));
  }

  static void TearDownTestSuite() {
    std::filesystem::remove_all(*out_);
    delete summary_;
    delete out_;
  }

  static std::filesystem::path* out_;
  static nlohmann::json* summary_;
  static T45Options options_;
  static int exit_code_;
};

std::filesystem::path* T45ExperimentTest::out_ = nullptr;
nlohmann::json* T45ExperimentTest::summary_ = nullptr;
T45Options T45ExperimentTest::options_;
int T45ExperimentTest::exit_code_ = -1;

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
