// SPDX-License-Identifier: Apache-2.0
// Tests of RenderPointFriction: the stick spring inside Coulomb's cone, the slide at its edge.
#include "mrh/render/point_friction.h"

#include <gtest/gtest.h>

namespace mrh::render {
namespace {

const Vec3 kUp = Vec3::UnitZ();

// Inside the cone the anchor stays and the force is the tangential spring k·e only: the normal
// part of the offset does not count.
TEST(PointFrictionTest, SticksInsideTheCone) {
  const Vec3 anchor(0.001, 0.0, -0.004);
  const PointFrictionResult r =
      RenderPointFriction(anchor, Vec3::Zero(), kUp, /*k=*/1000.0, /*mu=*/0.5, /*f_n=*/4.0);
  EXPECT_FALSE(r.slipping);
  EXPECT_NEAR((r.f_W - Vec3(1.0, 0.0, 0.0)).norm(), 0.0, 1e-12);  // 1000 N/m × 1 mm
  EXPECT_EQ(r.p_WA, anchor);
}

// Beyond the cone the force is μ f_n toward the anchor, and the anchor is dragged so that the
// spring gives exactly that on the next tick.
TEST(PointFrictionTest, SlidesAtTheConesEdge) {
  const Vec3 pointer(0.0, 0.0, 0.0);
  const PointFrictionResult r =
      RenderPointFriction(Vec3(0.0, 0.01, 0.0), pointer, kUp, 1000.0, 0.5, 4.0);
  EXPECT_TRUE(r.slipping);
  EXPECT_NEAR((r.f_W - Vec3(0.0, 2.0, 0.0)).norm(), 0.0, 1e-12);  // μ f_n = 2 N, not 10 N
  EXPECT_NEAR((r.p_WA - Vec3(0.0, 0.002, 0.0)).norm(), 0.0, 1e-15);
  const PointFrictionResult next = RenderPointFriction(r.p_WA, pointer, kUp, 1000.0, 0.5, 4.0);
  EXPECT_FALSE(next.slipping);
  EXPECT_NEAR((next.f_W - r.f_W).norm(), 0.0, 1e-12);
}

TEST(PointFrictionTest, NoNormalForceNoFriction) {
  const PointFrictionResult r =
      RenderPointFriction(Vec3(0.003, 0.0, 0.0), Vec3::Zero(), kUp, 1000.0, 0.8, 0.0);
  EXPECT_TRUE(r.slipping);
  EXPECT_EQ(r.f_W.norm(), 0.0);
}

}  // namespace
}  // namespace mrh::render
