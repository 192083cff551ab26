// SPDX-License-Identifier: Apache-2.0
// t3.6 (issue 14): the essential result — on the face push, local-dynamics-6dof at 20 ms meets
// the force, spread, position and spin bars against proxy-6dof at 1 ms (the 6-DOF
// reference), where proxy-6dof at 20 ms, which renders the box one step late, misses the force
// bar; and proxy-6dof at 20 ms flings no box in any case (peak speed below 2x the reference's).
// The reference check: nudging the pointer 10 µm sideways moves local-dynamics-6dof's mean |f|,
// mean |τ| and box positions by less than one of the bars in every case, and in the
// mirror-symmetric cases (all but offcentre) most of its mean torque is mirror-even (τ_y). The
// open "edge" case gets the proxy-6dof check only. Where the boxes slide steadily (face, row),
// local-dynamics-6dof's mean |f| is Coulomb's μ Σm g within 5 %.
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

TEST(T36Test, FacePushLocalDynamics6dofAt20MsMeetsTheBarsProxy6dofAt20MsFlingsNothing) {
  const std::filesystem::path out = testing::TempDir("mrh_t3_6_test_");
  const auto results = RunT36Cases(out, /*quiet=*/true);
  std::filesystem::remove_all(out);
  ASSERT_FALSE(results.empty());
  const auto& face = results[0];
  ASSERT_EQ(face.size(), 7u);
  ASSERT_EQ(face[0].case_name, "face");
  ASSERT_EQ(face[0].method, "proxy-6dof@1ms");
  ASSERT_EQ(face[2].method, "local-dynamics-6dof@20ms");
  const T36Result& ref = face[0];
  const T36Result& ld = face[2];
  const T36Result& proxy20 = face[1];
  ASSERT_GT(ref.mean_f, 1.0) << "the reference never pushed";
  EXPECT_NEAR(ld.mean_f, ref.mean_f, 0.05 * ref.mean_f);
  EXPECT_LE(ld.sd_f, 2.0 * ref.sd_f);
  EXPECT_LE(PoseError(ld, ref), 0.02);
  EXPECT_LE(ld.peak_spin, ref.peak_spin + 1.0);
  EXPECT_GT(std::abs(proxy20.mean_f - ref.mean_f), 0.05 * ref.mean_f);
  for (const auto& c : results) {
    ASSERT_EQ(c.size(), 7u);
    EXPECT_GT(c[0].peak_speed, 0.05) << c[0].case_name << ": the reference never moved a box";
    EXPECT_LT(c[1].peak_speed, 2.0 * c[0].peak_speed) << c[0].case_name;
    // "edge" is open (docs/architecture.md): local-dynamics-6dof flings the box there.
    if (c[0].case_name == "face" || c[0].case_name == "row") {
      // The boxes slide steadily: Coulomb's μ Σm |g| (μ 0.5, 0.5 kg a box, from the scenes).
      const double boxes = c[0].case_name == "row" ? 2.0 : 1.0;
      const double coulomb = 0.5 * boxes * 0.5 * 9.81;
      EXPECT_NEAR(c[2].sliding_f, coulomb, 1e-9) << c[0].case_name;
      EXPECT_NEAR(c[2].mean_f, coulomb, 0.05 * coulomb) << c[0].case_name;
    }
    if (c[0].case_name == "edge") continue;
    // c[5], c[6]: local-dynamics-6dof at 20 ms with the pointer 10 µm to -y and +y.
    ASSERT_EQ(c[5].method, "local-dynamics-6dof@20ms y-10um");
    ASSERT_EQ(c[6].method, "local-dynamics-6dof@20ms y+10um");
    for (const T36Result* nudged : {&c[5], &c[6]}) {
      EXPECT_LE(std::abs(nudged->mean_f - c[2].mean_f), 0.05 * c[0].mean_f) << c[0].case_name;
      EXPECT_LE(std::abs(nudged->mean_tau - c[2].mean_tau), 0.10 * c[0].mean_tau) << c[0].case_name;
      EXPECT_LE(PoseError(*nudged, c[2]), 0.02) << c[0].case_name;
    }
    if (c[0].case_name != "offcentre") {
      const Vec3& tau = c[2].mean_tau_W;
      EXPECT_LT(std::hypot(tau.x(), tau.z()), 0.5 * c[2].mean_tau) << c[0].case_name;
    }
  }
}

}  // namespace
}  // namespace mrh::experiments::internal
