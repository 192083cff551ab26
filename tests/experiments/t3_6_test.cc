// SPDX-License-Identifier: Apache-2.0
// t3.6's essential result, against mechanics and the consistent reference (the tool as a rigid
// MuJoCo body at 1 ms): the reference itself slides the boxes at Coulomb's μ Σm g; where the
// boxes slide steadily (face, row), local-dynamics-6dof at 20 ms does too, within 5 %, where
// proxy-6dof at 20 ms, which renders the box one step late, does not; no method throws a box
// in any case; off centre, local-dynamics-6dof turns the box the reference's way; and, except
// where the box tips over its edge, nudging the pointer 10 µm sideways moves
// local-dynamics-6dof's mean |f| and box positions by less than one of the acceptance bars (5 % of
// the reference's |f|, 2 cm).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "experiment_test_util.h"
#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

double PoseError(const T36Result& r, const T36Result& ref) {
  double e = 0.0;
  for (std::size_t i = 0; i < r.pose_at.size() && i < ref.pose_at.size(); ++i) {
    e = std::max(e, (r.pose_at[i] - ref.pose_at[i]).norm());
  }
  return e;
}

TEST(T36Test, SlidesAreCoulombsNothingIsThrownAndTheOffCentrePushTurnsTheBox) {
  const std::filesystem::path out = testing::TempDir("mrh_t3_6_test_");
  const auto results = RunT36Cases(out, /*quiet=*/true);
  std::filesystem::remove_all(out);
  ASSERT_EQ(results.size(), 7u);
  constexpr double kPush = 0.08;  // m/s (scenes/t3_6_push.json)
  for (const auto& c : results) {
    ASSERT_EQ(c.size(), 8u);
    ASSERT_EQ(c[0].method, "virtual-coupling@1ms");
    ASSERT_EQ(c[2].method, "proxy-6dof@20ms");
    ASSERT_EQ(c[3].method, "local-dynamics-6dof@20ms");
    const std::string& name = c[0].case_name;
    EXPECT_GT(c[0].peak_speed, 0.05) << name << ": the reference never moved a box";
    if (name == "edge" || name == "centreline") continue;  // open: reported, not checked
    for (std::size_t k = 1; k < 4; ++k) {
      EXPECT_LE(c[k].peak_speed, 2.5 * std::max(kPush, c[0].peak_speed)) << name << " " << k;
    }
    if (name == "face" || name == "row") {
      // Coulomb's μ Σm |g| (μ 0.5, 0.5 kg a box, from the scenes).
      const double coulomb = 0.5 * (name == "row" ? 2.0 : 1.0) * 0.5 * 9.81;
      EXPECT_NEAR(c[3].sliding_f, coulomb, 1e-9) << name;
      EXPECT_NEAR(c[0].mean_f, coulomb, 0.05 * coulomb) << name << ": the reference";
      EXPECT_NEAR(c[3].mean_f, coulomb, 0.05 * coulomb) << name;
      EXPECT_GT(std::abs(c[2].mean_f - coulomb), 0.05 * coulomb) << name;
    }
    if (name == "offcentre") {
      ASSERT_LT(c[0].yaw_at, -0.1) << "the reference did not turn the box";
      EXPECT_LT(c[3].yaw_at, -0.1) << "local-dynamics-6dof did not turn it the same way";
    }
    // c[6], c[7]: local-dynamics-6dof at 20 ms with the pointer 10 µm to -y and +y. The tip
    // case jams the box and tips it over its edge, an unstable equilibrium: reported only.
    if (name == "tip") continue;
    ASSERT_EQ(c[6].method, "local-dynamics-6dof@20ms y-10um");
    ASSERT_EQ(c[7].method, "local-dynamics-6dof@20ms y+10um");
    for (const T36Result* nudged : {&c[6], &c[7]}) {
      EXPECT_LE(std::abs(nudged->mean_f - c[3].mean_f), 0.05 * c[0].mean_f) << name;
      EXPECT_LE(PoseError(*nudged, c[3]), 0.02) << name;
    }
  }
}

}  // namespace
}  // namespace mrh::experiments::internal
