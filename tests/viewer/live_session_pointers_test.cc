// SPDX-License-Identifier: Apache-2.0
// The viewer's live session with several pointers: the input drives the chosen pointer, the
// others keep their own session devices, and the feed carries every pointer's ticks.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "viewer/live_session.h"

namespace mrh::viewer::internal {
namespace {

// A bound on a stalled machine, not a timing assumption: the test ends as soon as it sees ticks.
constexpr auto kPatience = std::chrono::seconds(30);

TEST(LiveSessionPointersTest, TheMouseDrivesTheChosenPointerAndTheOthersTheirOwnDevices) {
  // Far from both fingertips of two_finger_grasp.json (z = 0.03 m), in free space.
  device::MouseDevice mouse{Pose{Vec3(0.0, 0.2, 0.3), Quat::Identity()}};
  LiveFeed feed{1u << 15};
  LiveSession live(session::LoadSession(MRH_SOURCE_DIR "/scenes/two_finger_grasp.json"), &mouse,
                   &feed);
  live.set_driven_pointer(1);  // the index finger
  EXPECT_EQ(live.driven_pointer(), 1);
  live.Start(InputSource::kMouse);
  TickSample latest[2];
  bool seen[2] = {false, false};
  const auto give_up = std::chrono::steady_clock::now() + kPatience;
  while (!(seen[0] && seen[1]) && std::chrono::steady_clock::now() < give_up) {
    TickSample sample;
    while (feed.PopTick(&sample)) {
      ASSERT_GE(sample.pointer, 0);
      ASSERT_LT(sample.pointer, 2);
      latest[sample.pointer] = sample;
      seen[sample.pointer] = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(seen[0] && seen[1]);
  // The index finger is where the mouse holds it (identity calibration).
  EXPECT_NEAR(latest[1].X_WP.p.y(), 0.2, 1e-9);
  EXPECT_NEAR(latest[1].X_WP.p.z(), 0.3, 1e-9);
  // The thumb follows its own hand from y = -0.07 m toward the box, at its height.
  EXPECT_LT(latest[0].X_WP.p.y(), -0.04);
  EXPECT_NEAR(latest[0].X_WP.p.z(), 0.03, 5e-3);
}

TEST(LiveSessionPointersTest, AChoiceBeyondThePointersDrivesTheFirst) {
  device::MouseDevice mouse{Pose{Vec3(0.0, 0.0, 0.3), Quat::Identity()}};
  LiveFeed feed{1u << 10};
  LiveSession live(session::LoadSession(MRH_SOURCE_DIR "/scenes/two_finger_grasp.json"), &mouse,
                   &feed);
  live.set_driven_pointer(2);
  EXPECT_EQ(live.driven_pointer(), 0);
}

}  // namespace
}  // namespace mrh::viewer::internal
