// SPDX-License-Identifier: Apache-2.0
// The engine on the T4.1 world: action = reaction, momentum bookkeeping, baseline behaviour.
#include <gtest/gtest.h>

#include "engine_test_util.h"

namespace mrh::engine::testing {
namespace {

// Relative tolerance for momentum identities that hold up to floating-point summation.
constexpr double kMomentumTol = 1e-9;

int CubeBody(const Engine& engine) {
  return engine.world().FindBody("cube");
}

double CubeVelocityX(const Engine& engine) {
  return engine.world().body_state(CubeBody(engine)).V_WCm.v.x();
}

Vec3 CubeImpulse(const RunStats& stats, int cube) {
  for (const physics::BodyImpulseTotal& total : stats.impulses) {
    if (total.body == cube) return total.linear;
  }
  return Vec3::Zero();
}

class T41Test : public ::testing::TestWithParam<const char*> {};

TEST_P(T41Test, CubeMomentumChangeEqualsImpulseFromPointer) {
  auto engine = T41Engine(T41Settings(GetParam()));
  const RunStats stats = engine->Run(nullptr);
  const Vec3 impulse = CubeImpulse(stats, CubeBody(*engine));
  const double dp = kCubeMass * (CubeVelocityX(*engine) - kCubeSpeed);
  // Contact is over before the run ends, so every reported impulse was applied to the cube.
  EXPECT_NEAR(dp, impulse.x(), kMomentumTol * kCubeMass * kCubeSpeed);
  EXPECT_LT(impulse.x(), 0.0);
  EXPECT_EQ(stats.fault_nonfinite_wrench, 0);
  EXPECT_EQ(stats.dropped_reports, 0);
}

TEST_P(T41Test, CubeBouncesBack) {
  auto engine = T41Engine(T41Settings(GetParam()));
  (void)engine->Run(nullptr);
  EXPECT_LT(CubeVelocityX(*engine), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Methods, T41Test, ::testing::Values("single-rate", "impulse"));

TEST(T41BaselineTest, SingleRateBounceIsNearlyElastic) {
  // Undamped spring at 1 kHz: the bounce returns ~2mv (T4.1's elastic limit), up to the
  // discretisation's small energy error.
  auto engine = T41Engine(T41Settings("single-rate"));
  const RunStats stats = engine->Run(nullptr);
  const double impulse = -CubeImpulse(stats, CubeBody(*engine)).x();
  EXPECT_NEAR(impulse, 2.0 * kCubeMass * kCubeSpeed, 0.02 * 2.0 * kCubeMass * kCubeSpeed);
}

TEST(T41BaselineTest, ImpulseMethodDeliversClearlyMoreThanSingleRate) {
  auto single = T41Engine(T41Settings("single-rate"));
  const double j_single = -CubeImpulse(single->Run(nullptr), CubeBody(*single)).x();
  settings::EngineSettings s = T41Settings("impulse");
  s.duration = 2.5;
  auto impulse = T41Engine(s);
  const double j_impulse = -CubeImpulse(impulse->Run(nullptr), CubeBody(*impulse)).x();
  // The thesis measured +60 % (3.2 vs 2.0 N·s); the delay must inject clearly more (over 20 %).
  EXPECT_GT(j_impulse, 1.2 * j_single);
}

TEST(T41BaselineTest, SingleRateStepsAtHapticRate) {
  auto engine = T41Engine(T41Settings("single-rate"));
  EXPECT_DOUBLE_EQ(engine->settings().physics_dt, 0.001);
  const RunStats stats = engine->Run(nullptr);
  EXPECT_EQ(stats.steps, stats.ticks);
}

}  // namespace
}  // namespace mrh::engine::testing
