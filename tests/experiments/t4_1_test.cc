// SPDX-License-Identifier: Apache-2.0
// The T4.1 driver reproduces the thesis' essential result and writes its artefacts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "experiment_test_util.h"
#include "experiments/experiments_impl.h"
#include "mrh/core/error.h"
#include "mrh/experiments/experiments.h"

namespace mrh::experiments {
namespace {

// Analytic: an undamped bounce returns 2mv = 2 · 60 kg · 0.017 m/s (T4.1, thesis §4.5.3).
constexpr double kElastic = 2.04;
// Single-rate integrates the bounce at 1 ms: within 2 % of 2mv.
constexpr double kSingleRateTolerance = 0.02;
// Local-dynamics within 2 % of single-rate (the thesis' table 4.3 shows both 2.0 N·s).
constexpr double kLocalTolerance = 0.02;
// The impulse method overshoots by one to two physics steps of unopposed approach: the thesis
// measured +60 % (3.2 vs 2.0 N·s); its sizes are not given, so we require a third of that excess.
constexpr double kImpulseMinRatio = 1.2;
// A free slide-jointed cube: MuJoCo integrates Δv = F·Δt/m exactly, so A = I/m to rounding.
constexpr double kAccelTolerance = 1e-9;

class T41ExperimentTest : public testing::ExperimentTest<T41ExperimentTest> {
 protected:
  static void SetUpTestSuite() {
    RunExperiment("mrh_experiments_test_t4_1_", [](const std::filesystem::path& out) {
      internal::T41Options options;  // all three methods; the sweep has its own test
      options.sweep = false;
      return internal::RunT41(out, /*quiet=*/true, options);
    });
  }

  static double Impulse(const char* method) {
    return (*summary_)["methods"][method]["impulse_Ns"].get<double>();
  }
};

TEST_F(T41ExperimentTest, PassesItsChecksAndWritesItsArtefacts) {
  EXPECT_EQ(exit_code_, 0);
  for (const char* file :
       {"force_time.csv", "impulse_table.csv", "impulse_table.md", "summary.json",
        "single-rate/ticks.csv", "impulse/summary.json", "local-dynamics/ticks.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(*out_ / file)) << file;
  }
}

TEST_F(T41ExperimentTest, SingleRateReturnsTheElasticImpulse) {
  EXPECT_NEAR(Impulse("single-rate"), kElastic, kSingleRateTolerance * kElastic);
}

TEST_F(T41ExperimentTest, LocalDynamicsMatchesSingleRate) {
  const double single = Impulse("single-rate");
  EXPECT_NEAR(Impulse("local-dynamics"), single, kLocalTolerance * single);
}

TEST_F(T41ExperimentTest, ImpulseMethodOvershoots) {
  EXPECT_GT(Impulse("impulse"), kImpulseMinRatio * Impulse("single-rate"));
}

TEST_F(T41ExperimentTest, FreeCubeAcceleranceIsInverseMass) {
  for (const nlohmann::json& a : (*summary_)["accelerance_linear_diag_per_kg"]) {
    EXPECT_NEAR(a.get<double>() * 60.0, 1.0, kAccelTolerance);
  }
  EXPECT_EQ((*summary_)["accelerance_angular_max"].get<double>(), 0.0);
}

// Over 15–240 kg and 0.005–0.1 m/s local-dynamics stays at 2mv, and the impulse method's excess
// shrinks as the cube gets heavier (its contact lasts more physics steps, π·sqrt(m/k)).
TEST(T41SweepTest, KeepsLocalDynamicsElasticAndImpulseErrorFallsWithMass) {
  const std::filesystem::path out = testing::TempDir("mrh_experiments_test_t4_1_sweep_");
  std::filesystem::remove_all(out);
  ASSERT_EQ(experiments::Run("t4.1", out, /*quiet=*/true), 0);
  for (const char* file : {"sweep.csv", "sweep_vs_mass.csv", "sweep_vs_speed.csv"}) {
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
  }
  std::ifstream in(out / "sweep.csv");
  std::string line;
  std::getline(in, line);
  std::map<double, double> impulse_error_by_mass;  // at the thesis' speed
  int rows = 0;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string method, cell;
    std::getline(s, method, ',');
    double v[7];
    for (double& x : v) {
      std::getline(s, cell, ',');
      x = std::stod(cell);
    }
    const double mass = v[0], speed = v[1], error = v[4], ended = v[6];
    ++rows;
    EXPECT_EQ(ended, 1.0) << line;
    if (method == "local-dynamics") {
      EXPECT_LT(std::abs(error), kLocalTolerance) << line;
    }
    if (method == "impulse" && speed == 0.017) impulse_error_by_mass[mass] = error;
  }
  EXPECT_EQ(rows, 3 * 25);
  ASSERT_EQ(impulse_error_by_mass.size(), 5u);
  double previous = 1e9;
  for (const auto& [mass, error] : impulse_error_by_mass) {
    EXPECT_LT(error, previous) << mass << " kg";
    previous = error;
  }
  std::filesystem::remove_all(out);
}

TEST(T41OptionsTest, RunsOnlyTheRequestedMethods) {
  const std::filesystem::path out = testing::TempDir("mrh_experiments_test_t4_1_subset_");
  std::filesystem::remove_all(out);
  internal::T41Options options;
  options.methods = {"single-rate", "impulse"};
  options.sweep = false;
  EXPECT_EQ(internal::RunT41(out, true, options), 0);
  EXPECT_FALSE(std::filesystem::exists(out / "local-dynamics"));
  EXPECT_FALSE(std::filesystem::exists(out / "sweep.csv"));
  std::filesystem::remove_all(out);
}

TEST(T41ExperimentListTest, UnknownExperimentListsKnownOnes) {
  EXPECT_THAT(
      [] {
        experiments::Run("t9.9", "/tmp/unused", true);
      },
      ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr("t4.1")));
}

}  // namespace
}  // namespace mrh::experiments
