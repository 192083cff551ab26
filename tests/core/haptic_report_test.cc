// SPDX-License-Identifier: Apache-2.0
// Tests of merging haptic reports when the physics side receives several periods at once.
#include <gtest/gtest.h>

#include "mrh/ir/snapshot.h"

namespace mrh::ir {
namespace {

TEST(HapticReportTest, MergeSumsImpulsesPerBodyAndTakesLaterPointer) {
  HapticReport a;
  a.period = 3;
  a.ticks = 50;
  a.AddImpulse(2, Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(5, 0, 0));
  HapticReport b;
  b.period = 4;
  b.ticks = 50;
  b.X_WP.p = Vec3(0, 0, 1);
  b.AddImpulse(2, Vec3(0.5, 0, 0), Vec3::Zero(), Vec3(4, 0, 0));
  b.AddImpulse(7, Vec3(0, 1, 0), Vec3::Zero(), Vec3(0, 2, 0));
  a.MergeLater(b);
  EXPECT_EQ(a.period, 4);
  EXPECT_EQ(a.ticks, 100);
  EXPECT_EQ(a.X_WP.p, Vec3(0, 0, 1));
  ASSERT_EQ(a.impulses.size(), 2u);
  EXPECT_EQ(a.impulses[0].linear, Vec3(1.5, 0, 0));
  EXPECT_EQ(a.impulses[0].last_force, Vec3(4, 0, 0));
  EXPECT_EQ(a.impulses[1].body, 7);
}

TEST(HapticReportTest, BodyUntouchedInLaterPeriodHasZeroLastForce) {
  HapticReport a;
  a.AddImpulse(2, Vec3(1, 0, 0), Vec3::Zero(), Vec3(5, 0, 0));
  HapticReport b;
  a.MergeLater(b);
  EXPECT_EQ(a.impulses[0].last_force, Vec3::Zero());
}

TEST(HapticReportTest, OverflowSetsStatusBit) {
  HapticReport a;
  for (int i = 0; i < static_cast<int>(kMaxNeighborBodies) + 1; ++i) {
    a.AddImpulse(i, Vec3::Zero(), Vec3::Zero(), Vec3::Zero());
  }
  EXPECT_EQ(a.impulses.size(), kMaxNeighborBodies);
  EXPECT_NE(a.status & kStatusBodiesFull, 0u);
}

TEST(HapticReportTest, MergeKeepsTheNewestLocalStatePerBody) {
  HapticReport earlier;
  ASSERT_TRUE(earlier.local_states.PushBack({3, Pose{Vec3(1, 0, 0), Quat::Identity()}, {}}));
  ASSERT_TRUE(earlier.local_states.PushBack({4, Pose{Vec3(2, 0, 0), Quat::Identity()}, {}}));
  HapticReport later;
  ASSERT_TRUE(later.local_states.PushBack({4, Pose{Vec3(5, 0, 0), Quat::Identity()}, {}}));
  ASSERT_TRUE(later.local_states.PushBack({7, Pose{Vec3(6, 0, 0), Quat::Identity()}, {}}));
  earlier.MergeLater(later);
  ASSERT_EQ(earlier.local_states.size(), 3u);
  EXPECT_EQ(earlier.local_states[0].X_WB.p.x(), 1.0);
  EXPECT_EQ(earlier.local_states[1].X_WB.p.x(), 5.0);
  EXPECT_EQ(earlier.local_states[2].body, 7);
}

}  // namespace
}  // namespace mrh::ir
