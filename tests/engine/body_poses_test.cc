// SPDX-License-Identifier: Apache-2.0
// Engine::ReadBodyPoses and Engine::SetDisplayGain on one thread (lockstep, exact).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "engine_test_util.h"
#include "mrh/core/error.h"
#include "mrh/device/external.h"

namespace mrh::engine::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

std::unique_ptr<Engine> ExternalT41Engine(const settings::EngineSettings& settings) {
  world::World w = T41World();
  w.ApplyKeyframe("approach");
  device::Specifications specs;
  specs.max_force = 100.0;
  return std::make_unique<Engine>(std::move(w), std::make_unique<device::ExternalDevice>(specs),
                                  device::Calibration{}, settings);
}

// The cube's body origin in t4_1.xml (<body name="cube" pos="-0.125 0 0">).
const Vec3 kCubeStart(-0.125, 0.0, 0.0);

TEST(BodyPosesTest, BeforeAnyStepGivesTheSceneInitialPoses) {
  auto engine = ExternalT41Engine(T41Settings("impulse"));
  const int cube = engine->world().FindBody("cube");
  BodyPoses poses;
  engine->ReadBodyPoses(&poses);
  EXPECT_EQ(poses.step, -1);
  ASSERT_EQ(poses.X_WB.size(), static_cast<std::size_t>(engine->world().num_bodies()));
  EXPECT_EQ(poses.X_WB[static_cast<std::size_t>(cube)].p, kCubeStart);
}

// After each physics period the reader sees that step's poses, equal to the world's, and a
// second read without a new step reports nothing new.
TEST(BodyPosesTest, LockstepReadsFollowEveryStepAndMatchTheWorld) {
  const settings::EngineSettings settings = T41Settings("impulse");
  auto engine = ExternalT41Engine(settings);
  const int cube = engine->world().FindBody("cube");
  const int n = settings.ticks_per_step();
  engine->Start();
  BodyPoses poses;
  for (int period = 0; period < 10; ++period) {
    for (int j = 0; j < n; ++j) (void)engine->Tick((period * n + j) * settings.haptic_dt, {});
    EXPECT_TRUE(engine->ReadBodyPoses(&poses));
    EXPECT_EQ(poses.step, period);
    EXPECT_NEAR(poses.t, (period + 1) * settings.physics_dt, 1e-12);
    EXPECT_EQ(poses.X_WB[static_cast<std::size_t>(cube)].p,
              engine->world().body_state(cube).X_WB.p);
    EXPECT_FALSE(engine->ReadBodyPoses(&poses));
  }
  // The cube slides at 0.017 m/s: after 10 steps of 50 ms it has left its start.
  EXPECT_GT(poses.X_WB[static_cast<std::size_t>(cube)].p.x(), kCubeStart.x() + 0.005);
  (void)engine->Stop();
}

// Two identical lockstep runs; the second halves the gain from tick 300 on. The displayed force
// halves from that tick, while the physics (fed the rendered reaction) stays identical.
TEST(DisplayGainTest, HalvesTheDisplayedForceFromTheNextTickOnly) {
  const settings::EngineSettings settings = T41Settings("impulse");
  constexpr int kTicks = 1500;
  constexpr int kSwitch = 300;
  std::vector<double> reference, scaled;
  for (std::vector<double>* out : {&reference, &scaled}) {
    auto engine = ExternalT41Engine(settings);
    engine->Start();
    for (int i = 0; i < kTicks; ++i) {
      if (out == &scaled && i == kSwitch) engine->SetDisplayGain(0.5);
      out->push_back(engine->Tick(i * settings.haptic_dt, {}).f.x());
    }
    (void)engine->Stop();
  }
  const double peak = *std::max_element(reference.begin(), reference.end(), [](double a, double b) {
    return std::abs(a) < std::abs(b);
  });
  ASSERT_GT(std::abs(peak), 1.0);  // the cube hits the pointer within the run
  for (int i = 0; i < kTicks; ++i) {
    const double expected = i < kSwitch ? reference[i] : 0.5 * reference[i];
    EXPECT_NEAR(scaled[i], expected, 1e-12 * std::abs(peak)) << "tick " << i;
  }
}

TEST(DisplayGainTest, RejectsNegativeAndNonFiniteGainsAndKeepsTheOld) {
  auto engine = ExternalT41Engine(T41Settings("impulse"));
  engine->SetDisplayGain(0.25);
  EXPECT_THAT(
      [&] {
        engine->SetDisplayGain(-1.0);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("gain = -1")));
  EXPECT_THAT(
      [&] {
        engine->SetDisplayGain(std::numeric_limits<double>::quiet_NaN());
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("expected a finite value >= 0")));
  EXPECT_EQ(engine->display_gain(), 0.25);
}

}  // namespace
}  // namespace mrh::engine::testing
