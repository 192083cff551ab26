// SPDX-License-Identifier: Apache-2.0
// The T3.5 driver: a small rotation weight lets free vertices penetrate, a large one weakens the
// torque (SPEC §3.10).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "mrh/experiments/experiments.h"

namespace mrh::experiments {
namespace {

TEST(T35ExperimentTest, RotationWeightTradesPenetrationForTorque) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / "mrh_experiments_test_t3_5";
  std::filesystem::remove_all(out);
  ASSERT_EQ(experiments::Run("t3.5", out, /*quiet=*/true), 0);
  std::ifstream in(out / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  for (const auto& [name, pass] : s["checks"].items()) EXPECT_TRUE(pass.get<bool>()) << name;
  const nlohmann::json& points = s["points"];
  ASSERT_GE(points.size(), 2u);
  // Analytic single-edge peak k_r δ h/(R_w + h²) with δ = 3 N / 9000 N/m, h = 0.1 m: the torque
  // ratio between the ends of the sweep is (R_w,max + h²)/(R_w,min + h²).
  const nlohmann::json& small = points.front();
  const nlohmann::json& large = points.back();
  const double h2 = 0.01;
  const double expected =
      (large["R_w_m2"].get<double>() + h2) / (small["R_w_m2"].get<double>() + h2);
  const double measured =
      small["roll_peak_torque_Nm"].get<double>() / large["roll_peak_torque_Nm"].get<double>();
  EXPECT_NEAR(measured, expected, 0.02 * expected);
  EXPECT_GT(small["free_vertex_penetration_m"].get<double>(),
            large["free_vertex_penetration_m"].get<double>());
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace mrh::experiments
