// SPDX-License-Identifier: Apache-2.0
// Tests of the corrected eq. 4.11 penalty renderer.
#include "mrh/render/point_penalty.h"

#include <gtest/gtest.h>

namespace mrh::render {
namespace {

constexpr double kTol = 1e-12;

PlaneContactState FloorContact(double pointer_z) {
  PlaneContactState c;
  c.p_WO = Vec3(0.3, -0.2, 0.0);
  c.n_W = Vec3::UnitZ();
  c.p_WC = Vec3(0.0, 0.0, pointer_z);
  return c;
}

TEST(PointPenaltyTest, PushesPointerOutOfObjectWithSpringForce) {
  const PointPenaltyResult r = RenderPointPenalty(FloorContact(-0.004), 1000.0, 0.0);
  EXPECT_NEAR(r.depth, 0.004, kTol);
  EXPECT_NEAR(r.magnitude, 4.0, kTol);
  // The printed eq. 4.11 would give −4 N here (into the floor); the corrected sign pushes out.
  EXPECT_NEAR(r.f_W.z(), 4.0, kTol);
  EXPECT_NEAR(r.f_W.head<2>().norm(), 0.0, kTol);
}

TEST(PointPenaltyTest, NoForceWhenSeparated) {
  const PointPenaltyResult r = RenderPointPenalty(FloorContact(0.001), 1000.0, 50.0);
  EXPECT_LT(r.depth, 0.0);
  EXPECT_EQ(r.f_W, Vec3::Zero());
}

TEST(PointPenaltyTest, DamperAddsWhilePenetratingDeeper) {
  PlaneContactState c = FloorContact(-0.002);
  c.v_WC = Vec3(0, 0, -0.1);  // moving deeper: δ̇ = +0.1 m/s
  const PointPenaltyResult r = RenderPointPenalty(c, 1000.0, 10.0);
  EXPECT_NEAR(r.magnitude, 1000.0 * 0.002 + 10.0 * 0.1, kTol);
}

TEST(PointPenaltyTest, DamperNeverPullsIntoObject) {
  PlaneContactState c = FloorContact(-0.001);
  c.v_WC = Vec3(0, 0, 1.0);  // leaving fast: kδ + dδ̇ = 1 − 10 < 0
  const PointPenaltyResult r = RenderPointPenalty(c, 1000.0, 10.0);
  EXPECT_EQ(r.magnitude, 0.0);
  EXPECT_EQ(r.f_W, Vec3::Zero());
}

TEST(PointPenaltyTest, MovingObjectRaisesDepthRate) {
  PlaneContactState c = FloorContact(-0.001);
  c.v_WO = Vec3(0, 0, 0.2);  // the object comes toward the pointer
  const PointPenaltyResult r = RenderPointPenalty(c, 0.0, 10.0);
  EXPECT_NEAR(r.magnitude, 2.0, kTol);
}

}  // namespace
}  // namespace mrh::render
