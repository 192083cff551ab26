// SPDX-License-Identifier: Apache-2.0
// Tests of World: model description, stepping against analytic motion, wrenches, mocap,
// keyframes and settings.
#include "mrh/world/world.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "mrh/core/error.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

using testing::IsNearVec;
using testing::kNoPointer;

// Geometry, poses and stored inertias are exact up to MuJoCo's roundoff (its inertia goes
// through an eigen-decomposition).
constexpr double kTol = 1e-12;

// A 60 kg box whose geom is offset and turned 30 degrees about z within its body.
constexpr char kBoxScene[] = R"(
<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="crate" pos="0.5 -0.2 1.0" quat="0.9238795 0 0.3826834 0">
      <freejoint/>
      <geom name="crate" type="box" size="0.1 0.2 0.3" mass="60" pos="0.05 0 0"
            euler="0 0 30"/>
    </body>
    <body name="ghost" pos="0 0 2">
      <freejoint/>
      <geom type="sphere" size="0.05" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>)";

Mat3 RotZ(double degrees) {
  return Eigen::AngleAxisd(degrees * M_PI / 180.0, Vec3::UnitZ()).toRotationMatrix();
}

TEST(BodyInfoTest, BoxMassCentreAndInertiaMatchAnalyticValues) {
  const World world = World::LoadString(kBoxScene, kNoPointer);
  const BodyInfo& crate = world.body(world.FindBody("crate"));
  constexpr double kMass = 60.0;
  const Vec3 h(0.1, 0.2, 0.3);
  // Solid box about its centre, half-extents h: I_xx = m (h_y^2 + h_z^2) / 3, ...
  const Vec3 principal = kMass / 3.0 *
                         Vec3(h.y() * h.y() + h.z() * h.z(), h.x() * h.x() + h.z() * h.z(),
                              h.x() * h.x() + h.y() * h.y());
  const Mat3 expected = RotZ(30) * principal.asDiagonal() * RotZ(30).transpose();
  EXPECT_NEAR(crate.mass, kMass, kTol);
  EXPECT_TRUE(crate.inertia_B.isApprox(expected, 1e-12)) << crate.inertia_B;
  EXPECT_THAT(crate.p_BCm, IsNearVec(Vec3(0.05, 0, 0), kTol));
  EXPECT_FALSE(crate.is_static);
  EXPECT_FALSE(crate.is_mocap);
  ASSERT_EQ(crate.geoms.size(), 1u);
}

TEST(BodyInfoTest, WorldIsStaticAndOwnsThePlane) {
  const World world = World::LoadString(kBoxScene, kNoPointer);
  const BodyInfo& ground = world.body(0);
  EXPECT_TRUE(ground.is_static);
  ASSERT_EQ(ground.geoms.size(), 1u);
  EXPECT_EQ(world.geom(ground.geoms[0]).shape.type, geometry::ShapeType::kPlane);
}

TEST(GeomInfoTest, BoxGeomHasHalfExtentsAndPoseInBody) {
  const World world = World::LoadString(kBoxScene, kNoPointer);
  const GeomInfo& geom = world.geom(world.body(world.FindBody("crate")).geoms[0]);
  EXPECT_EQ(geom.name, "crate");
  EXPECT_EQ(geom.body, world.FindBody("crate"));
  EXPECT_EQ(geom.shape.type, geometry::ShapeType::kBox);
  EXPECT_THAT(geom.shape.size, IsNearVec(Vec3(0.1, 0.2, 0.3), kTol));
  EXPECT_THAT(geom.X_BG.p, IsNearVec(Vec3(0.05, 0, 0), kTol));
  EXPECT_TRUE(geom.X_BG.q.toRotationMatrix().isApprox(RotZ(30), 1e-9));
  EXPECT_TRUE(geom.collides);
}

TEST(GeomInfoTest, GeomWithoutContactBitsDoesNotCollide) {
  const World world = World::LoadString(kBoxScene, kNoPointer);
  const GeomInfo& geom = world.geom(world.body(world.FindBody("ghost")).geoms[0]);
  EXPECT_EQ(geom.shape.type, geometry::ShapeType::kSphere);
  EXPECT_FALSE(geom.collides);
}

TEST(GeomInfoTest, PrimitiveSizesFollowMjcf) {
  const World world = World::LoadString(R"(
    <mujoco><worldbody><body>
      <geom type="capsule" size="0.1 0.4"/>
      <geom type="cylinder" size="0.2 0.5"/>
      <geom type="ellipsoid" size="0.1 0.2 0.3"/>
    </body></worldbody></mujoco>)",
                                        kNoPointer);
  EXPECT_EQ(world.geom(0).shape.type, geometry::ShapeType::kCapsule);
  EXPECT_THAT(world.geom(0).shape.size.head<2>(), IsNearVec(Eigen::Vector2d(0.1, 0.4), kTol));
  EXPECT_EQ(world.geom(1).shape.type, geometry::ShapeType::kCylinder);
  EXPECT_THAT(world.geom(1).shape.size.head<2>(), IsNearVec(Eigen::Vector2d(0.2, 0.5), kTol));
  EXPECT_EQ(world.geom(2).shape.type, geometry::ShapeType::kEllipsoid);
  EXPECT_THAT(world.geom(2).shape.size, IsNearVec(Vec3(0.1, 0.2, 0.3), kTol));
}

TEST(GeomPoseTest, IsBodyPoseComposedWithGeomOffset) {
  const World world = World::LoadString(kBoxScene, kNoPointer);
  const int crate = world.FindBody("crate");
  const GeomInfo& geom = world.geom(world.body(crate).geoms[0]);
  const Pose X_WB = world.body_state(crate).X_WB;
  const Pose X_WG = world.geom_pose(geom.id);
  EXPECT_THAT(X_WG.p, IsNearVec(Vec3((X_WB * geom.X_BG).p), kTol));
  EXPECT_LT(X_WG.q.angularDistance(X_WB.q * geom.X_BG.q), 1e-9);
}

TEST(WorldStepTest, FreeFallMatchesSemiImplicitEulerAndAnalyticMotion) {
  World world = World::LoadString(R"(
    <mujoco><option timestep="0.001" gravity="0 0 -9.81"/>
      <worldbody><body name="ball" pos="0 0 10"><freejoint/><geom size="0.1"/></body>
      </worldbody></mujoco>)",
                                  kNoPointer);
  constexpr int kSteps = 1000;
  constexpr double kDt = 0.001;
  constexpr double kG = 9.81;
  for (int i = 0; i < kSteps; ++i) world.Step();
  const double t = kSteps * kDt;
  const BodyState s = world.body_state(world.FindBody("ball"));
  // Semi-implicit Euler: v_n = -g n dt exactly, z_n = z0 - g dt^2 n (n + 1) / 2, which is the
  // analytic z0 - g t^2 / 2 shifted by its first-order error g t dt / 2.
  constexpr double kRoundoff = 1e-9;
  EXPECT_NEAR(world.time(), t, kRoundoff);
  EXPECT_NEAR(s.V_WCm.v.z(), -kG * t, kRoundoff);
  EXPECT_NEAR(s.p_WCm.z(), 10.0 - 0.5 * kG * kDt * kDt * kSteps * (kSteps + 1), kRoundoff);
  EXPECT_NEAR(s.p_WCm.z(), 10.0 - 0.5 * kG * t * t, 0.5 * kG * t * kDt + kRoundoff);
}

TEST(WorldStepTest, BodyStateFollowsTheStepImmediately) {
  World world = World::LoadString(kBoxScene, kNoPointer);
  const int ghost = world.FindBody("ghost");
  world.Step();
  // The ghost's free joint is the first 7 qpos after the crate's.
  EXPECT_NEAR(world.body_state(ghost).X_WB.p.z(), world.qpos()[7 + 2], kTol);
  EXPECT_LT(world.body_state(ghost).X_WB.p.z(), 2.0);
}

// A free 2 kg box whose COM is offset from its body origin, in zero gravity.
constexpr char kFloatingBox[] = R"(
<mujoco>
  <option timestep="0.001" gravity="0 0 0"/>
  <worldbody>
    <body name="box" pos="0.3 0.1 0.5" euler="20 -35 50">
      <freejoint/>
      <geom type="box" size="0.1 0.15 0.05" mass="2" pos="0.1 0 0" euler="0 10 0"/>
    </body>
  </worldbody>
</mujoco>)";

TEST(WorldForceTest, ForceAtPointGivesAnalyticLinearAndAngularVelocityChange) {
  World world = World::LoadString(kFloatingBox, kNoPointer);
  const int box = world.FindBody("box");
  const BodyInfo& info = world.body(box);
  const BodyState before = world.body_state(box);
  const Mat3 R_WB = before.X_WB.q.toRotationMatrix();
  const Mat3 I_W = R_WB * info.inertia_B * R_WB.transpose();
  const Vec3 f(1.0, 2.0, -0.5);
  const Vec3 r(0.05, -0.1, 0.2);  // from the COM to the point of application
  world.AddForceAtPoint(box, f, before.p_WCm + r);
  world.Step();
  const BodyState after = world.body_state(box);
  const double dt = world.timestep();
  const Vec3 alpha = I_W.inverse() * r.cross(f);
  // One semi-implicit Euler step from rest is exact, except that the COM velocity is read at
  // the rotated COM offset: an error below |alpha|^2 dt^3 |p_BCm|.
  const double tol = alpha.squaredNorm() * dt * dt * dt * info.p_BCm.norm() + 1e-12;
  EXPECT_THAT(after.V_WCm.v, IsNearVec(Vec3(f * dt / info.mass), tol));
  EXPECT_THAT(after.V_WCm.w, IsNearVec(Vec3(alpha * dt), 1e-12));
}

TEST(WorldForceTest, WrenchAtComTorqueOnlySpinsWithoutTranslating) {
  World world = World::LoadString(kFloatingBox, kNoPointer);
  const int box = world.FindBody("box");
  const Mat3 R_WB = world.body_state(box).X_WB.q.toRotationMatrix();
  const Mat3 I_W = R_WB * world.body(box).inertia_B * R_WB.transpose();
  const Vec3 tau(0.0, 0.3, 0.1);
  world.AddWrenchAtCom(box, Wrench{Vec3::Zero(), tau});
  world.Step();
  const BodyState after = world.body_state(box);
  const double dt = world.timestep();
  const Vec3 alpha = I_W.inverse() * tau;
  EXPECT_THAT(after.V_WCm.w, IsNearVec(Vec3(alpha * dt), 1e-12));
  // As above: the COM offset turns during the step, which shows as |alpha|^2 dt^3 |p_BCm|.
  const double tol = alpha.squaredNorm() * dt * dt * dt * world.body(box).p_BCm.norm();
  EXPECT_THAT(after.V_WCm.v, IsNearVec(Vec3::Zero(), tol));
}

TEST(WorldForceTest, WrenchesApplyForOneStepOnly) {
  World world = World::LoadString(kFloatingBox, kNoPointer);
  const int box = world.FindBody("box");
  world.AddWrenchAtCom(box, Wrench{Vec3(4.0, 0, 0), Vec3::Zero()});
  world.Step();
  const double v1 = world.body_state(box).V_WCm.v.x();
  world.Step();
  EXPECT_NEAR(world.body_state(box).V_WCm.v.x(), v1, 1e-12);
  EXPECT_NEAR(v1, 4.0 / 2.0 * world.timestep(), 1e-12);
}

constexpr char kKeyframeScene[] = R"(
<mujoco>
  <option gravity="0 0 0"/>
  <worldbody>
    <body name="cube" pos="-0.125 0 0">
      <joint name="x" type="slide" axis="1 0 0"/>
      <geom type="box" size="0.1 0.1 0.1" mass="60"/>
    </body>
    <body name="pointer" mocap="true" pos="0 0 0"><geom type="sphere" size="0.02"/></body>
  </worldbody>
  <keyframe>
    <key name="approach" time="0.5" qpos="0.01" qvel="0.017" mpos="0.3 0 0.1"
         mquat="1 0 0 0"/>
    <key name="rest" qpos="0"/>
  </keyframe>
</mujoco>)";

TEST(KeyframeTest, ApplySetsPositionsVelocitiesMocapAndTime) {
  World world = World::LoadString(kKeyframeScene);
  world.ApplyKeyframe("approach");
  EXPECT_DOUBLE_EQ(world.time(), 0.5);
  EXPECT_DOUBLE_EQ(world.qpos()[0], 0.01);
  EXPECT_DOUBLE_EQ(world.qvel()[0], 0.017);
  const BodyState cube = world.body_state(world.FindBody("cube"));
  EXPECT_THAT(cube.X_WB.p, IsNearVec(Vec3(-0.115, 0, 0), kTol));
  EXPECT_THAT(cube.V_WCm.v, IsNearVec(Vec3(0.017, 0, 0), kTol));
  EXPECT_THAT(world.body_state(world.pointer_body()).X_WB.p, IsNearVec(Vec3(0.3, 0, 0.1), kTol));
}

TEST(KeyframeTest, UnknownNameListsTheKeyframes) {
  World world = World::LoadString(kKeyframeScene, {}, "t.xml");
  EXPECT_THAT(
      [&] {
        world.ApplyKeyframe("nope");
      },
      ThrowsMessage<SceneError>(
          HasSubstr("t.xml: no keyframe named 'nope'; the scene has 'approach', 'rest'")));
}

TEST(KeyframeTest, SceneWithoutKeyframesSaysHowToAddOne) {
  World world = World::LoadString(kFloatingBox, kNoPointer, "k.xml");
  EXPECT_THAT(
      [&] {
        world.ApplyKeyframe("start");
      },
      ThrowsMessage<SceneError>(HasSubstr("the scene has no keyframes: add <keyframe>")));
}

TEST(MocapTest, SetMocapPoseMovesPointerBodyAndGeoms) {
  World world = World::LoadString(kKeyframeScene);
  const int pointer = world.pointer_body();
  const Pose X_WP{Vec3(0.1, -0.2, 0.3), Quat(Eigen::AngleAxisd(0.4, Vec3::UnitY()))};
  world.SetMocapPose(pointer, X_WP);
  EXPECT_THAT(world.body_state(pointer).X_WB.p, IsNearVec(X_WP.p, kTol));
  EXPECT_LT(world.body_state(pointer).X_WB.q.angularDistance(X_WP.q), 1e-12);
  EXPECT_THAT(world.geom_pose(world.body(pointer).geoms[0]).p, IsNearVec(X_WP.p, kTol));
}

TEST(WorldSettingsTest, TimestepMustBePositiveAndFinite) {
  World world = World::LoadString(kFloatingBox, kNoPointer);
  world.set_timestep(0.02);
  EXPECT_DOUBLE_EQ(world.timestep(), 0.02);
  EXPECT_THAT(
      [&] {
        world.set_timestep(0.0);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("World::set_timestep: dt = 0")));
  EXPECT_THAT(
      [&] {
        world.set_timestep(std::nan(""));
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("expected a finite value > 0")));
}

TEST(WorldSettingsTest, GravityIsReadAndWritten) {
  World world = World::LoadString(kFloatingBox, kNoPointer);
  EXPECT_THAT(world.gravity(), IsNearVec(Vec3::Zero(), 0.0));
  world.set_gravity(Vec3(0, 0, -2.0));
  world.Step();
  EXPECT_NEAR(world.body_state(world.FindBody("box")).V_WCm.v.z(), -2.0 * world.timestep(), 1e-12);
}

}  // namespace
}  // namespace mrh::world

namespace mrh::world {
namespace {

// A stiff spring at a 20 ms step: the explicit spring force diverges on the first step, and
// MuJoCo resets the state (mjWARN_BADQACC).
constexpr char kDivergingScene[] = R"(
<mujoco>
  <option timestep="0.02"/>
  <worldbody>
    <body pos="0 0 1">
      <joint type="hinge" axis="0 1 0" stiffness="1e12" springref="1"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.01" mass="0.001"/>
    </body>
  </worldbody>
</mujoco>)";

TEST(WorldWarningsTest, NoneForAHealthyScene) {
  World world = World::LoadString(kBoxScene, testing::kNoPointer);
  for (int i = 0; i < 10; ++i) world.Step();
  EXPECT_TRUE(world.SimulatorWarnings().empty());
}

TEST(WorldWarningsTest, DivergenceIsReportedWithItsFixAndNotLoggedToAFile) {
  std::filesystem::remove("MUJOCO_LOG.TXT");
  World world = World::LoadString(kDivergingScene, testing::kNoPointer, "spring.xml");
  for (int i = 0; i < 3; ++i) world.Step();
  const std::vector<std::string> warnings = world.SimulatorWarnings();
  ASSERT_GE(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("spring.xml"));
  EXPECT_THAT(warnings[0], HasSubstr("bad number in qacc"));
  EXPECT_THAT(warnings[0], HasSubstr("lower the timestep"));
  EXPECT_FALSE(std::filesystem::exists("MUJOCO_LOG.TXT"));
}

TEST(WorldDivergenceTest, NoneForAHealthyScene) {
  World world = World::LoadString(kBoxScene, testing::kNoPointer);
  for (int i = 0; i < 10; ++i) {
    world.Step();
    EXPECT_EQ(world.FindDivergence(20.0), "");
  }
}

TEST(WorldDivergenceTest, MujocoResettingTheStateIsReportedOnceNamingTheBody) {
  World world = World::LoadString(kDivergingScene, testing::kNoPointer, "spring.xml");
  world.Step();
  const std::string why = world.FindDivergence(20.0);
  EXPECT_THAT(why, HasSubstr("spring.xml: the simulation diverged at t = "));
  EXPECT_THAT(why, HasSubstr("bad number in qacc"));
  EXPECT_THAT(why, HasSubstr("body #1"));
  EXPECT_THAT(why, HasSubstr("likely causes"));
  EXPECT_EQ(why.find('\n'), std::string::npos);
  EXPECT_EQ(world.FindDivergence(20.0), "");  // nothing new since the last call
}

// A free body's centre-of-mass speed includes its spin about an off-centre origin: a body
// spinning at 100 rad/s whose COM is 0.3 m from its frame origin moves at 30 m/s.
TEST(WorldDivergenceTest, FreeBodyFasterThanTheLimitIsNamedWithItsSpeed) {
  World world = World::LoadString(R"(<mujoco><option gravity="0 0 0"/><worldbody>
      <body name="spinner" pos="0 0 1"><freejoint/>
        <geom type="sphere" pos="0.3 0 0" size="0.01" mass="1"/></body>
      </worldbody>
      <keyframe><key name="spin" qpos="0 0 1 1 0 0 0" qvel="0 0 0 0 0 100"/></keyframe>
      </mujoco>)",
                                  testing::kNoPointer, "spin.xml");
  world.ApplyKeyframe("spin");
  EXPECT_EQ(world.FindDivergence(31.0), "");
  const std::string why = world.FindDivergence(29.0);
  EXPECT_THAT(why, HasSubstr("spin.xml: the simulation diverged at t = 0 s: body 'spinner' "
                             "moves at 30 m/s, over safety.max_body_speed = 29 m/s"));
  EXPECT_EQ(world.FindDivergence(0.0), "");  // 0 disables the speed test
}

}  // namespace
}  // namespace mrh::world
