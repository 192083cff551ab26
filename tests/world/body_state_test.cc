// SPDX-License-Identifier: Apache-2.0
// Tests of SetBodyState: round trips through free, slide and hinge joints, and refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mrh/world/world.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using testing::IsNearVec;
using testing::kNoPointer;

// Round trips go through quaternion/matrix conversions in MuJoCo: roundoff only.
constexpr double kTol = 1e-12;

constexpr char kBodies[] = R"(
<mujoco>
  <worldbody>
    <body name="free" pos="0 0 1">
      <freejoint/>
      <geom type="box" size="0.1 0.2 0.3" pos="0.1 -0.05 0.02" euler="10 20 30"/>
    </body>
    <body name="slider" pos="1 0 0.5" euler="0 0 30">
      <joint name="sx" type="slide" axis="1 0 0"/>
      <joint name="sy" type="slide" axis="0 1 0" ref="0.1"/>
      <joint name="sz" type="slide" axis="0 0 1"/>
      <geom type="box" size="0.1 0.1 0.1" pos="0 0.05 0"/>
    </body>
    <body name="planar" pos="2 0 0.5">
      <joint type="slide" axis="1 0 0"/>
      <joint type="slide" axis="0 1 0"/>
      <geom type="sphere" size="0.1"/>
    </body>
    <body name="door" pos="3 0 1" euler="0 0 45">
      <joint name="hinge" type="hinge" axis="0 0 1" pos="-0.4 0 0"/>
      <geom type="box" size="0.4 0.02 0.8" pos="0 0 0"/>
    </body>
    <body name="fixed" pos="4 0 0"><geom type="sphere" size="0.1"/></body>
  </worldbody>
</mujoco>)";

Quat Rotation(double angle, const Vec3& axis) {
  return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

TEST(SetBodyStateTest, FreeBodyRoundTripsPoseAndComTwist) {
  World world = World::LoadString(kBodies, kNoPointer);
  const int body = world.FindBody("free");
  const Pose X_WB{Vec3(0.3, -0.7, 2.0), Rotation(1.1, Vec3(1, 2, 3))};
  const Twist V_WCm{Vec3(0.5, -1.0, 0.25), Vec3(-2.0, 0.4, 3.0)};
  ASSERT_TRUE(world.SetBodyState(body, X_WB, V_WCm));
  const BodyState s = world.body_state(body);
  EXPECT_THAT(s.X_WB.p, IsNearVec(X_WB.p, kTol));
  EXPECT_LT(s.X_WB.q.angularDistance(X_WB.q), kTol);
  EXPECT_THAT(s.p_WCm, IsNearVec(Vec3(X_WB * world.body(body).p_BCm), kTol));
  EXPECT_THAT(s.V_WCm.v, IsNearVec(V_WCm.v, kTol));
  EXPECT_THAT(s.V_WCm.w, IsNearVec(V_WCm.w, kTol));
}

TEST(SetBodyStateTest, FreeBodyStateSurvivesAStepAsRigidMotion) {
  // In zero gravity, a free body's COM keeps moving at the set velocity.
  World world = World::LoadString(kBodies, kNoPointer);
  world.set_gravity(Vec3::Zero());
  const int body = world.FindBody("free");
  const Twist V_WCm{Vec3(0.5, -1.0, 0.25), Vec3::Zero()};
  ASSERT_TRUE(world.SetBodyState(body, Pose{Vec3(0, 0, 5), Quat::Identity()}, V_WCm));
  const Vec3 p0 = world.body_state(body).p_WCm;
  world.Step();
  EXPECT_THAT(world.body_state(body).p_WCm, IsNearVec(Vec3(p0 + V_WCm.v * world.timestep()), kTol));
}

TEST(SetBodyStateTest, ThreeSlidesRoundTripTranslationAndVelocity) {
  World world = World::LoadString(kBodies, kNoPointer);
  const int body = world.FindBody("slider");
  const BodyState start = world.body_state(body);
  const Pose X_WB{start.X_WB.p + Vec3(0.2, -0.3, 0.4), start.X_WB.q};
  const Twist V_WCm{Vec3(0.1, 0.2, -0.3), Vec3::Zero()};
  ASSERT_TRUE(world.SetBodyState(body, X_WB, V_WCm));
  const BodyState s = world.body_state(body);
  EXPECT_THAT(s.X_WB.p, IsNearVec(X_WB.p, kTol));
  EXPECT_THAT(s.V_WCm.v, IsNearVec(V_WCm.v, kTol));
  EXPECT_THAT(s.V_WCm.w, IsNearVec(Vec3::Zero(), kTol));
}

TEST(SetBodyStateTest, SlidesRefuseARotationAndLeaveTheStateAlone) {
  World world = World::LoadString(kBodies, kNoPointer);
  const int body = world.FindBody("slider");
  const BodyState start = world.body_state(body);
  const std::vector<double> qpos(world.qpos().begin(), world.qpos().end());
  const Pose turned{start.X_WB.p, start.X_WB.q * Rotation(0.01, Vec3::UnitX())};
  EXPECT_FALSE(world.SetBodyState(body, turned, Twist{}));
  EXPECT_FALSE(world.SetBodyState(body, start.X_WB, Twist{Vec3::Zero(), Vec3(0, 0, 0.1)}));
  for (std::size_t i = 0; i < qpos.size(); ++i) EXPECT_EQ(world.qpos()[i], qpos[i]);
}

TEST(SetBodyStateTest, PlanarSlidesRefuseOutOfPlaneMotion) {
  World world = World::LoadString(kBodies, kNoPointer);
  const int body = world.FindBody("planar");
  const BodyState start = world.body_state(body);
  EXPECT_TRUE(world.SetBodyState(body, Pose{start.X_WB.p + Vec3(0.1, 0.2, 0), start.X_WB.q},
                                 Twist{Vec3(1, 0, 0), Vec3::Zero()}));
  EXPECT_FALSE(
      world.SetBodyState(body, Pose{start.X_WB.p + Vec3(0, 0, 0.1), start.X_WB.q}, Twist{}));
  EXPECT_FALSE(world.SetBodyState(body, start.X_WB, Twist{Vec3(0, 0, 1), Vec3::Zero()}));
}

TEST(SetBodyStateTest, HingeRoundTripsRotationAboutItsAnchor) {
  World world = World::LoadString(kBodies, kNoPointer);
  const int body = world.FindBody("door");
  const BodyState start = world.body_state(body);
  // Swing 0.6 rad about the vertical axis through the anchor (hinge pos in the body frame).
  const Vec3 anchor_W = start.X_WB * Vec3(-0.4, 0, 0);
  const Quat swing = Rotation(0.6, Vec3::UnitZ());
  const Pose X_WB{anchor_W + swing * (start.X_WB.p - anchor_W), swing * start.X_WB.q};
  const Vec3 w(0, 0, 1.5);
  const Vec3 p_WCm = X_WB * world.body(body).p_BCm;
  const Twist V_WCm{w.cross(p_WCm - anchor_W), w};
  ASSERT_TRUE(world.SetBodyState(body, X_WB, V_WCm));
  const BodyState s = world.body_state(body);
  EXPECT_THAT(s.X_WB.p, IsNearVec(X_WB.p, kTol));
  EXPECT_LT(s.X_WB.q.angularDistance(X_WB.q), kTol);
  EXPECT_THAT(s.V_WCm.v, IsNearVec(V_WCm.v, kTol));
  EXPECT_THAT(s.V_WCm.w, IsNearVec(V_WCm.w, kTol));
  EXPECT_NEAR(world.qpos()[world.qpos().size() - 1], 0.6, kTol);
}

TEST(SetBodyStateTest, HingeRefusesRotationOffItsAxis) {
  World world = World::LoadString(kBodies, kNoPointer);
  const int body = world.FindBody("door");
  const BodyState start = world.body_state(body);
  EXPECT_FALSE(world.SetBodyState(
      body, Pose{start.X_WB.p, Rotation(0.2, Vec3::UnitX()) * start.X_WB.q}, Twist{}));
}

TEST(SetBodyStateTest, BodyWithoutJointsIsRefused) {
  World world = World::LoadString(kBodies, kNoPointer);
  const int body = world.FindBody("fixed");
  EXPECT_FALSE(world.SetBodyState(body, world.body_state(body).X_WB, Twist{}));
}

TEST(SetBodyStateTest, NonFiniteStateIsRefused) {
  World world = World::LoadString(kBodies, kNoPointer);
  const int body = world.FindBody("free");
  EXPECT_FALSE(world.SetBodyState(body, Pose{Vec3(NAN, 0, 0), Quat::Identity()}, Twist{}));
}

}  // namespace
}  // namespace mrh::world
