// SPDX-License-Identifier: Apache-2.0
// The T3.2 driver shows static/kinetic friction switching with μ = 0.5 (thesis §3.3.3).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "experiment_test_util.h"
#include "mrh/experiments/experiments.h"

namespace mrh::experiments {
namespace {

constexpr double kMu = 0.5;

TEST(T32ExperimentTest, KineticFrictionIsMuTimesNormalAndStaticStaysBelow) {
  const std::filesystem::path out = testing::TempDir("mrh_experiments_test_t3_2_");
  std::filesystem::remove_all(out);
  ASSERT_EQ(experiments::Run("t3.2", out, /*quiet=*/true), 0);
  for (const char* file : {"t3_2.csv", "t3_2_direction.csv", "t3_2.gp", "summary.json"}) {
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
  }
  std::ifstream in(out / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  testing::ExpectAllChecksPass(s);
  const nlohmann::json& n = s["numbers"];
  // ε bounds what the proxy's rotation can bend a row (c_kk − 1 of eq. 3.5); it must be small for
  // the comparison to mean anything.
  const double eps = n["rotation_share_eps"].get<double>();
  ASSERT_LT(eps, 1e-4);
  EXPECT_GT(n["kinetic_ticks"].get<int>(), 1000);
  EXPECT_NEAR(n["kinetic_cone_ratio_min"].get<double>(), kMu, kMu * eps);
  EXPECT_NEAR(n["kinetic_cone_ratio_max"].get<double>(), kMu, kMu * eps);
  EXPECT_LT(n["static_cone_ratio_max"].get<double>(), kMu * (1.0 + eps));
  // Start, three reversals and the end of the strokes.
  EXPECT_GE(n["static_intervals_during_strokes"].get<int>(), 5);
  EXPECT_LE(n["friction_vs_motion_worst_cos"].get<double>(), -(1.0 - eps));
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace mrh::experiments
