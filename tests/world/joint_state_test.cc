// SPDX-License-Identifier: Apache-2.0
// World::SetBodyStateInParent: joint coordinates from a body's and its parent's states.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mrh/world/world.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using testing::kNoPointer;

// A hinge, a slide on it, a ball on that, then a welded tip, every joint off its reference
// and moving (the keyframe), in a tilted chain.
const char* kChain = R"(<mujoco><worldbody>
  <body name="a" pos="0.1 0.2 1" euler="0.3 0 0.2"><joint name="hinge" axis="0 1 0" pos="0 0 0.05"/>
    <geom type="box" size="0.05 0.02 0.1"/>
    <body name="b" pos="0 0 -0.2" euler="0 0.4 0"><joint name="slide" type="slide" axis="1 0 0"/>
      <geom type="box" size="0.05 0.02 0.02"/>
      <body name="c" pos="0.1 0 0"><joint name="ball" type="ball" pos="0.01 0 0"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.2" size="0.01"/>
        <body name="d" pos="0 0 -0.2"><geom type="sphere" size="0.02"/></body>
      </body>
    </body>
  </body></worldbody>
  <keyframe><key name="moving" qpos="0.7 0.03 0.9 0.1 -0.3 0.2"
                 qvel="1.5 -0.2 0.4 -0.7 0.3"/></keyframe></mujoco>)";

TEST(JointStateTest, CoordinatesComeBackFromTheBodiesStates) {
  World world = World::LoadString(kChain, kNoPointer);
  world.ApplyKeyframe("moving");
  const std::vector<double> qpos(world.qpos().begin(), world.qpos().end());
  const std::vector<double> qvel(world.qvel().begin(), world.qvel().end());
  std::vector<BodyState> states;
  for (int b = 0; b < world.num_bodies(); ++b) states.push_back(world.body_state(b));
  World other = World::LoadString(kChain, kNoPointer);  // at qpos0, at rest
  for (const char* name : {"a", "b", "c", "d"}) {
    const int b = other.FindBody(name);
    const BodyState& s = states[static_cast<std::size_t>(b)];
    const BodyState& p = states[static_cast<std::size_t>(other.body(b).parent)];
    ASSERT_TRUE(other.SetBodyStateInParent(b, s.X_WB, s.V_WCm, p.X_WB, p.V_WCm)) << name;
  }
  // The ball's quaternion may come back as its negative (the same orientation).
  const double sign = other.qpos()[2] * qpos[2] < 0.0 ? -1.0 : 1.0;
  for (std::size_t i = 0; i < qpos.size(); ++i) {
    const double expected = i >= 2 ? sign * qpos[i] : qpos[i];
    EXPECT_NEAR(other.qpos()[i], expected, 1e-9) << "qpos " << i;
  }
  for (std::size_t i = 0; i < qvel.size(); ++i) {
    EXPECT_NEAR(other.qvel()[i], qvel[i], 1e-9) << "qvel " << i;
  }
}

// A body translating on three slides (tilted axes, moving) on a hinged parent.
TEST(JointStateTest, ThreeSlidesComeBackFromTheBodiesStates) {
  const char* xml = R"(<mujoco><worldbody>
    <body name="p" pos="0 0 1"><joint axis="0 1 0"/><geom type="sphere" size="0.05"/>
      <body name="c" pos="0.2 0 0" euler="0.3 0.2 0.1"><joint type="slide" axis="1 0 0"/>
        <joint type="slide" axis="0 1 0"/><joint type="slide" axis="0 0 1"/>
        <geom type="box" size="0.02 0.02 0.02"/></body></body></worldbody>
    <keyframe><key name="k" qpos="0.4 0.01 -0.02 0.03" qvel="0.9 0.1 0.2 -0.3"/></keyframe>
    </mujoco>)";
  World world = World::LoadString(xml, kNoPointer);
  world.ApplyKeyframe("k");
  const BodyState c = world.body_state(world.FindBody("c"));
  const BodyState p = world.body_state(world.FindBody("p"));
  World other = World::LoadString(xml, kNoPointer);
  ASSERT_TRUE(other.SetBodyStateInParent(other.FindBody("c"), c.X_WB, c.V_WCm, p.X_WB, p.V_WCm));
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_NEAR(other.qpos()[i], world.qpos()[i], 1e-9) << "qpos " << i;
    EXPECT_NEAR(other.qvel()[i], world.qvel()[i], 1e-9) << "qvel " << i;
  }
}

TEST(JointStateTest, TwoJointsAndNonFiniteStatesAreRefused) {
  World world = World::LoadString(
      "<mujoco><worldbody><body name=\"x\"><joint axis=\"0 1 0\"/><joint axis=\"1 0 0\"/>"
      "<geom type=\"sphere\" size=\"0.1\"/></body></worldbody></mujoco>",
      kNoPointer);
  const int x = world.FindBody("x");
  EXPECT_FALSE(world.SetBodyStateInParent(x, Pose{}, Twist{}, Pose{}, Twist{}));
  World chain = World::LoadString(kChain, kNoPointer);
  Pose bad;
  bad.p.x() = std::nan("");
  EXPECT_FALSE(chain.SetBodyStateInParent(chain.FindBody("a"), bad, Twist{}, Pose{}, Twist{}));
}

TEST(JointStateTest, FindsJointsByNameAndReadsTheirCoordinate) {
  World world = World::LoadString(kChain, kNoPointer);
  world.ApplyKeyframe("moving");
  EXPECT_EQ(world.num_joints(), 3);
  EXPECT_DOUBLE_EQ(world.joint_position(world.FindJoint("slide")), 0.03);
  EXPECT_EQ(world.FindJoint("none"), -1);
}

}  // namespace
}  // namespace mrh::world
