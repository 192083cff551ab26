// SPDX-License-Identifier: Apache-2.0
// Tests of PinchKeyframes: the two fingertips' targets close, lift, hold, lower and open.
#include "mrh/device/pinch.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mrh/core/error.h"

namespace mrh::device {
namespace {

TEST(PinchTest, FingersCloseLiftHoldLowerAndOpenSymmetrically) {
  PinchSettings pinch;
  pinch.center = Vec3(0.1, 0.0, 0.03);
  pinch.open_width = 0.14;
  pinch.grip_width = 0.08;
  pinch.lift = 0.05;
  const std::vector<Keyframe> f0 = PinchKeyframes(pinch, 0);
  const std::vector<Keyframe> f1 = PinchKeyframes(pinch, 1);
  ASSERT_EQ(f0.size(), 6u);
  ASSERT_EQ(f1.size(), 6u);
  const double times[] = {0.0, 0.5, 1.0, 2.0, 2.5, 3.0};
  const double widths[] = {0.14, 0.08, 0.08, 0.08, 0.08, 0.14};
  const double heights[] = {0.03, 0.03, 0.08, 0.08, 0.03, 0.03};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(f0[i].t, times[i]);
    EXPECT_DOUBLE_EQ(f1[i].t, times[i]);
    EXPECT_NEAR(f1[i].X_DT.p.y() - f0[i].X_DT.p.y(), widths[i], 1e-15) << i;
    EXPECT_NEAR(f0[i].X_DT.p.z(), heights[i], 1e-15) << i;
    EXPECT_NEAR(f1[i].X_DT.p.z(), heights[i], 1e-15) << i;
    EXPECT_DOUBLE_EQ(f0[i].X_DT.p.x(), 0.1);
  }
  EXPECT_DOUBLE_EQ(pinch.duration(), 3.0);
}

TEST(PinchTest, AGripNotNarrowerThanOpenIsRejected) {
  PinchSettings pinch;
  pinch.grip_width = 0.2;
  EXPECT_THAT(
      [&] {
        PinchKeyframes(pinch, 0);
      },
      ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr("pinch.grip_width")));
  EXPECT_THAT(
      [] {
        PinchKeyframes(PinchSettings{}, 2);
      },
      ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr("finger = 2")));
}

}  // namespace
}  // namespace mrh::device
