// SPDX-License-Identifier: Apache-2.0
// The T3.5 driver: a small rotation weight lets free vertices penetrate, a large one weakens the
// torque (thesis §3.4.1). The torque reference is derived here from the scene's numbers, sharing
// no code with the driver.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "experiment_test_util.h"
#include "experiments/experiment_util.h"
#include "mrh/experiments/experiments.h"
#include "mrh/session/session.h"

namespace mrh::experiments {
namespace {

constexpr double kHalf = 0.1;  // m, half side of the cube (scenes/t3_1.xml: size 0.1 0.1 0.1)

// What the scripted roll of scenes/t3_1_trajectory.csv does: the edge depth δ (the held
// height is √2·h − δ) and the largest angle step between two rows of the roll (rad).
struct Roll {
  double depth = 0.0;
  double step = 0.0;
};

Roll ReadRoll(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // t,x,y,z,qw,qx,qy,qz,angle_deg
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  Roll roll;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (rows[i][0] == 1.5) roll.depth = std::sqrt(2.0) * kHalf - rows[i][3];  // start of roll
    if (rows[i][0] > 1.5 && rows[i][0] <= 3.8) {
      roll.step = std::max(roll.step, std::abs(rows[i][8] - rows[i - 1][8]) * M_PI / 180.0);
    }
  }
  return roll;
}

// The peak of the one-edge torque over the roll in closed form (eq. 3.2–3.5): one edge at depth δ
// and lever r gives τ = k_r δ r/(R_w + r²), the lever going 0 → h. Its maximum over r is
// k_r δ/(2√R_w) at r = √R_w if √R_w < h, else k_r δ h/(R_w + h²) at the flat end.
double PeakTorque(double k_r, double depth, double R_w) {
  const double r = std::min(std::sqrt(R_w), kHalf);
  return k_r * depth * r / (R_w + r * r);
}

TEST(T35ExperimentTest, RotationWeightTradesPenetrationForTorque) {
  const std::filesystem::path out = testing::TempDir("mrh_experiments_test_t3_5_");
  std::filesystem::remove_all(out);
  ASSERT_EQ(experiments::Run("t3.5", out, /*quiet=*/true), 0);
  const nlohmann::json s = testing::ReadSummary(out);
  testing::ExpectAllChecksPass(s);
  const nlohmann::json& points = s["points"];
  ASSERT_GE(points.size(), 2u);
  const std::filesystem::path scenes = internal::ScenesDir();
  const double k_r = session::LoadSession(scenes / "t3_5.json").engine.rendering.rot_stiffness;
  const Roll roll = ReadRoll(scenes / "t3_1_trajectory.csv");
  ASSERT_NEAR(roll.depth, 3.0 / 9000.0, 1e-9);  // 3 N at k_t = 9000 N/m
  // How far the ticks may stray from the closed form: between two rows the edge cuts the chord
  // of its arc about the centre (radius √2·h), up to √2·h·Δθ²/8 deeper than δ; the one-edge
  // contact ends when the second edge reaches the floor, at θ = δ/(2h) (lever h(cos θ − sin θ)
  // ≈ h(1 − θ)); the last one-edge tick may come one tick's angle (Δθ/12.8 ticks per row)
  // before that.
  const double tol = std::sqrt(2.0) * kHalf * roll.step * roll.step / 8.0 / roll.depth +
                     roll.depth / (2.0 * kHalf) + roll.step / 12.0;
  for (const nlohmann::json& p : points) {
    const double multiplier = p["multiplier"].get<double>();
    const double R_w = multiplier * (2.0 * kHalf) * (2.0 * kHalf) / 6.0;  // unit mass: m a²/6
    EXPECT_NEAR(p["R_w_m2"].get<double>(), R_w, 1e-12 * R_w) << "multiplier " << multiplier;
    const double expected = PeakTorque(k_r, roll.depth, R_w);
    EXPECT_GT(p["one_edge_ticks_compared"].get<int>(), 0) << "multiplier " << multiplier;
    EXPECT_NEAR(p["one_edge_peak_torque_Nm"].get<double>(), expected, tol * expected)
        << "multiplier " << multiplier;
  }
  // Across the four decades of R_w (1e4) the peak falls ~4000× (h² = 0.01 m²).
  EXPECT_GT(points.front()["one_edge_peak_torque_Nm"].get<double>(),
            1000.0 * points.back()["one_edge_peak_torque_Nm"].get<double>());
  EXPECT_GT(points.front()["free_vertex_penetration_m"].get<double>(),
            points.back()["free_vertex_penetration_m"].get<double>());
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace mrh::experiments
