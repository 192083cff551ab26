// SPDX-License-Identifier: Apache-2.0
// Tests of when the viewer draws the proxy ghost: only where the method's proxy leaves the pointer.
#include "viewer/overlay.h"

#include <gtest/gtest.h>

namespace mrh::viewer::internal {
namespace {

const Pose kPointer{Vec3(0.1, -0.2, 0.3), Quat(Eigen::AngleAxisd(0.4, Vec3::UnitX()))};

TickSample Tick(const Pose& X_WQ) {
  TickSample tick;
  tick.X_WP = kPointer;
  tick.X_WQ = X_WQ;
  return tick;
}

TEST(ShowsGhostTest, NoGhostWhenTheProxyIsThePointer) {
  // Methods without a proxy report the pointer pose, whatever wrench they render.
  TickSample tick = Tick(kPointer);
  tick.rendered_W = Wrench{Vec3(0.0, 0.0, 20.0), Vec3(0.1, 0.0, 0.0)};
  EXPECT_FALSE(ShowsGhost(tick));
}

TEST(ShowsGhostTest, GhostWhenTheProxyIsAMillimetreAway) {
  EXPECT_TRUE(ShowsGhost(Tick(Pose{kPointer.p + Vec3(0.0, 0.0, 1e-3), kPointer.q})));
}

TEST(ShowsGhostTest, GhostWhenTheProxyIsTurned) {
  const Quat turned = Quat(Eigen::AngleAxisd(0.05, Vec3::UnitZ())) * kPointer.q;
  EXPECT_TRUE(ShowsGhost(Tick(Pose{kPointer.p, turned})));
}

TEST(ShowsGhostTest, NoGhostForAnOffsetTooSmallToSee) {
  // 0.05 mm and 0.5 mrad: the ghost would only flicker inside the pointer.
  const Quat turned = Quat(Eigen::AngleAxisd(5e-4, Vec3::UnitZ())) * kPointer.q;
  EXPECT_FALSE(ShowsGhost(Tick(Pose{kPointer.p + Vec3(5e-5, 0.0, 0.0), turned})));
}

}  // namespace
}  // namespace mrh::viewer::internal
