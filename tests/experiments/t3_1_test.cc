// SPDX-License-Identifier: Apache-2.0
// The T3.1 driver reproduces edge → roll → face against the analytic proxy (eq. 3.2–3.5 in
// closed form).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "experiment_test_util.h"
#include "mrh/experiments/experiments.h"

namespace mrh::experiments {
namespace {

// The T3.1 parameters (thesis §3.3.2): k_t = k_r = 9000, R_w = 3.33 m², 0.2 m cube; the
// trajectory's edge and face depths are 3 N and 3.5 N over k_t.
constexpr double kKt = 9000.0, kKr = 9000.0, kRw = 3.33, kHalf = 0.1;
constexpr double kEdgeDepth = 3.0 / kKt, kFaceDepth = 3.5 / kKt;

nlohmann::json RunAndRead(const std::filesystem::path& out) {
  std::filesystem::remove_all(out);
  EXPECT_EQ(experiments::Run("t3.1", out, /*quiet=*/true), 0);
  for (const char* file :
       {"t3_1.csv", "t3_1.gp", "summary.json", "run/ticks.csv", "run/summary.json"}) {
    EXPECT_TRUE(std::filesystem::exists(out / file)) << file;
  }
  std::ifstream in(out / "summary.json");
  return nlohmann::json::parse(in);
}

TEST(T31ExperimentTest, EdgeRollFaceMatchesTheAnalyticProxy) {
  const std::filesystem::path out = testing::TempDir("mrh_experiments_test_t3_1_");
  const nlohmann::json s = RunAndRead(out);
  testing::ExpectAllChecksPass(s);
  // Just before the face lands one edge carries the load at lever h: |τ| = k_r δ h/(R_w + h²).
  const double peak = kKr * kEdgeDepth * kHalf / (kRw + kHalf * kHalf);
  EXPECT_NEAR(s["numbers"]["torque_peak_Nm"].get<double>(), peak, 0.01 * peak);
  EXPECT_LT(s["numbers"]["torque_peak_angle_deg"].get<double>(), 5.0);
  // Face flat at depth δ_f: f = k_t δ_f (eq. 3.2–3.5), centre at h − δ_f, no torque. PGS leaves at
  // most m·(R_w/h²)·tol = 1.3e-7 m of displacement error.
  const double kDisplacementTol = 4.0 * (kRw / (kHalf * kHalf)) * 1e-10;
  EXPECT_NEAR(s["final"]["f_z_N"].get<double>(), kKt * kFaceDepth, kKt * kDisplacementTol);
  EXPECT_NEAR(s["final"]["height_m"].get<double>(), kHalf - kFaceDepth, 1e-9);
  EXPECT_NEAR(s["final"]["angle_deg"].get<double>(), 0.0, 1e-9);
  EXPECT_EQ(s["final"]["contacts"].get<int>(), 4);
  // B5 on the same motion (Berkelman & Hollis 2000): the proxy renders k_t δ on the edge (2
  // contacts) and on the face (4 contacts), the penalty sum 2 k δ then 4 k δ: its stiffness
  // doubles.
  const nlohmann::json& n = s["numbers"];
  EXPECT_GT(n["penalty_sum_edge_ticks"].get<int>(), 400);  // of the 500-tick edge hold
  EXPECT_NEAR(n["penalty_sum_edge_force_N"].get<double>(), 2.0 * kKt * kEdgeDepth, 1e-5);
  EXPECT_NEAR(n["penalty_sum_face_force_N"].get<double>(), 4.0 * kKt * kFaceDepth, 1e-5);
  EXPECT_NEAR(n["penalty_sum_stiffness_jump"].get<double>(), 2.0, 1e-6);
  EXPECT_NEAR(s["final"]["f_z_N"].get<double>() / kFaceDepth, kKt, 1e-3 * kKt);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace mrh::experiments
