// SPDX-License-Identifier: Apache-2.0
// t4.push: local-dynamics with the contact local model against single-rate (1 ms, the
// reference) when pushing resting boxes across a floor with friction; the thesis' perturbation
// model, which chatters there, is run on the one-box case to show the bars can fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "experiment_test_util.h"
#include "experiments/experiments_impl.h"

namespace mrh::experiments::internal {
namespace {

// The acceptance bars.
constexpr double kMeanTolerance = 0.05;      // relative to single-rate's mean |f|
constexpr double kSdRatio = 2.0;             // × single-rate's standard deviation ...
constexpr double kSdFloor = 0.02;            // ... or this share of its mean, whichever is larger
constexpr double kPositionTolerance = 0.02;  // m, box COM 4 s after the touch

struct Bars {
  bool mean, sd, lost, position;
};

Bars Check(const PushResult& r, const PushResult& ref) {
  return {std::abs(r.mean_force - ref.mean_force) <= kMeanTolerance * ref.mean_force,
          r.sd_force <= std::max(kSdRatio * ref.sd_force, kSdFloor * ref.mean_force),
          r.contact_lost <= ref.contact_lost,
          (r.position - ref.position).norm() <= kPositionTolerance};
}

PushCase Case(const std::string& name) {
  for (const PushCase& c : DefaultPushOptions().cases) {
    if (c.name == name) return c;
  }
  ADD_FAILURE() << "no case " << name;
  return {};
}

void ExpectBars(const std::string& name) {
  PushOptions o;
  o.cases = {Case(name)};
  o.methods = {"single-rate", "local-dynamics"};
  const std::filesystem::path out = testing::TempDir("mrh_t4_push_test_" + name + "_");
  const auto results = RunPushCases(out, o, /*quiet=*/true);
  std::filesystem::remove_all(out);
  const PushResult& ref = results[0][0];
  const PushResult& r = results[0][1];
  ASSERT_GT(ref.mean_force, 0.0);
  const Bars b = Check(r, ref);
  EXPECT_TRUE(b.mean) << name << ": mean " << r.mean_force << " N vs " << ref.mean_force;
  EXPECT_TRUE(b.sd) << name << ": sd " << r.sd_force << " N vs " << ref.sd_force;
  EXPECT_TRUE(b.lost) << name << ": contact lost " << r.contact_lost << " vs " << ref.contact_lost;
  EXPECT_TRUE(b.position) << name << ": box " << (r.position - ref.position).norm() << " m off";
}

TEST(T4PushTest, OneBoxLocalDynamicsFeelsLikeSingleRate) {
  ExpectBars("box");
}

TEST(T4PushTest, HeavyBoxLocalDynamicsFeelsLikeSingleRate) {
  ExpectBars("heavy");
}

TEST(T4PushTest, WallLocalDynamicsFeelsLikeSingleRate) {
  ExpectBars("wall");
}

TEST(T4PushTest, RowOfThreeLocalDynamicsFeelsLikeSingleRate) {
  ExpectBars("row");
}

// The row with the pointer 10 µm to the side: neither reference nor local model is sensitive.
TEST(T4PushTest, OffsetRowLocalDynamicsFeelsLikeSingleRate) {
  ExpectBars("row_y+10um");
}

// The row of three between rails.
TEST(T4PushTest, GuidedRowLocalDynamicsFeelsLikeSingleRate) {
  ExpectBars("row_guided");
}

// A push near the top edge that tips the box over.
TEST(T4PushTest, TippingBoxLocalDynamicsFeelsLikeSingleRate) {
  ExpectBars("tip");
}

// Why the scenes use the elliptic cone: on MuJoCo's default pyramidal cone a straight push is
// unstable. Single-rate itself, with the pointer moved 10 µm sideways, turns the box away and
// ends more than the 2 cm position bar from its unmoved run.
TEST(T4PushTest, StraightPushOnThePyramidalConeIsUnstableInSingleRate) {
  PushOptions o;
  o.cases = {Case("box_pyramidal"), Case("box_pyramidal_y+10um")};
  o.methods = {"single-rate"};
  const std::filesystem::path out = testing::TempDir("mrh_t4_push_test_pyramid_");
  const auto results = RunPushCases(out, o, /*quiet=*/true);
  std::filesystem::remove_all(out);
  EXPECT_GT((results[0][0].position - results[1][0].position).norm(), kPositionTolerance);
}

// The thesis' linearised model on the same push: the force chatters and contact is lost.
TEST(T4PushTest, PerturbationModelFailsTheBarsOnTheOneBoxCase) {
  PushOptions o;
  o.cases = {Case("box")};
  o.methods = {"single-rate", "local-dynamics/perturbation"};
  const std::filesystem::path out = testing::TempDir("mrh_t4_push_test_pert_");
  const auto results = RunPushCases(out, o, /*quiet=*/true);
  std::filesystem::remove_all(out);
  const Bars b = Check(results[0][1], results[0][0]);
  EXPECT_FALSE(b.sd && b.lost);
}

}  // namespace
}  // namespace mrh::experiments::internal
