// SPDX-License-Identifier: Apache-2.0
// Tests of the viewer's live session: starts, restarts from the current state, rejects bad gains.
#include "viewer/live_session.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "mrh/core/error.h"

namespace mrh::viewer::internal {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// How long a test waits for the real-time engine to make progress before it gives up. A bound
// on a stalled machine, not a timing assumption: the tests pass as soon as progress is seen.
constexpr auto kPatience = std::chrono::seconds(30);

session::Session TinySession() {
  return session::LoadSession(MRH_SOURCE_DIR "/tests/apps/fixtures/tiny.json");
}

// Pops ticks until one has t >= t_min; false if none arrives within kPatience.
bool WaitForTick(LiveFeed& feed, double t_min, TickSample* sample) {
  const auto give_up = std::chrono::steady_clock::now() + kPatience;
  while (std::chrono::steady_clock::now() < give_up) {
    while (feed.PopTick(sample)) {
      if (sample->t >= t_min) return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

class LiveSessionTest : public ::testing::Test {
 protected:
  device::MouseDevice mouse_{Pose{Vec3(0.0, 0.0, 0.3), Quat::Identity()}};
  LiveFeed feed_{1u << 15};
};

TEST_F(LiveSessionTest, RunsTheSessionInRealTimeWithItsOwnDevice) {
  LiveSession live(TinySession(), &mouse_, &feed_);
  live.Start(InputSource::kSession);
  TickSample sample;
  ASSERT_TRUE(WaitForTick(feed_, 0.01, &sample));
  // tiny.json holds the fixed device at z = 0.12 m.
  EXPECT_NEAR(sample.X_WP.p.z(), 0.12, 1e-12);
  EXPECT_EQ(live.settings().mode, settings::Mode::kRealtime);
  EXPECT_EQ(live.source(), InputSource::kSession);
}

TEST_F(LiveSessionTest, TheIrOfEachPhysicsStepReachesTheFeed) {
  LiveSession live(TinySession(), &mouse_, &feed_);
  live.Start(InputSource::kSession);
  // The pointer (r = 2 cm at z = 0.12 m) rests on the cube's top face (z = 0.1 m): the plane IR
  // has the cube's top plane, normal +z. The penalty force presses the cube into MuJoCo's soft
  // floor, so the face sits a few millimetres low (2.8 mm measured).
  constexpr double kSinkTol = 5e-3;  // m
  const auto give_up = std::chrono::steady_clock::now() + kPatience;
  while (std::chrono::steady_clock::now() < give_up) {
    if (feed_.UpdateIr() && feed_.ir().step >= 1) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_GE(feed_.ir().step, 1);
  bool has_top_plane = false;
  for (const IrPlane& plane : feed_.ir().planes) {
    has_top_plane |=
        plane.n_W.isApprox(Vec3::UnitZ(), 1e-6) && std::abs(plane.p_W.z() - 0.1) < kSinkTol;
  }
  EXPECT_TRUE(has_top_plane);
}

TEST_F(LiveSessionTest, RestartContinuesTheViewerClockWithNewGains) {
  LiveSession live(TinySession(), &mouse_, &feed_);
  live.Start(InputSource::kSession);
  TickSample sample;
  ASSERT_TRUE(WaitForTick(feed_, 0.01, &sample));
  settings::EngineSettings stiffer = live.settings();
  stiffer.rendering.stiffness = 2500.0;
  live.Restart(stiffer, InputSource::kMouse, /*keep_world=*/true);
  EXPECT_EQ(live.settings().rendering.stiffness, 2500.0);
  EXPECT_EQ(live.source(), InputSource::kMouse);
  EXPECT_EQ(live.starts(), 2);
  // The new engine's ticks continue after the old engine's last one.
  EXPECT_GT(live.time_offset(), sample.t);
  ASSERT_TRUE(WaitForTick(feed_, live.time_offset(), &sample));
  EXPECT_NEAR(sample.X_WP.p.z(), 0.3, 1e-9);  // the mouse's pose
}

TEST_F(LiveSessionTest, RejectedGainsKeepThePreviousSessionRunning) {
  LiveSession live(TinySession(), &mouse_, &feed_);
  live.Start(InputSource::kSession);
  settings::EngineSettings bad = live.settings();
  bad.rendering.stiffness = -1.0;
  EXPECT_THAT(
      [&] {
        live.Restart(bad, InputSource::kSession, true);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("stiffness")));
  EXPECT_EQ(live.settings().rendering.stiffness, 1000.0);
  EXPECT_EQ(live.starts(), 2);
  TickSample sample;
  EXPECT_TRUE(WaitForTick(feed_, live.time_offset(), &sample));
}

TEST_F(LiveSessionTest, AMissingReplayFileIsAnErrorAndTheSessionGoesOn) {
  LiveSession live(TinySession(), &mouse_, &feed_);
  live.Start(InputSource::kSession);
  live.set_replay_file("/no/such/ticks.csv");
  EXPECT_THAT(
      [&] {
        live.Restart(live.settings(), InputSource::kReplay, false);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("/no/such/ticks.csv")));
  EXPECT_EQ(live.source(), InputSource::kSession);
}

}  // namespace
}  // namespace mrh::viewer::internal
