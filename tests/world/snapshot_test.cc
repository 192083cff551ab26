// SPDX-License-Identifier: Apache-2.0
// Determinism tests of Save/Restore: a restored state steps bit for bit like the original.
#include <gtest/gtest.h>

#include <span>
#include <vector>

#include "mrh/world/world.h"

namespace mrh::world {
namespace {

// Boxes tumbling onto a floor and onto each other: contacts make the solver's warm start matter.
constexpr char kPile[] = R"(
<mujoco>
  <option timestep="0.01"/>
  <worldbody>
    <geom type="plane" size="5 5 0.1"/>
    <body name="a" pos="0 0 0.12" euler="0 0 10"><freejoint/>
      <geom type="box" size="0.1 0.1 0.1"/></body>
    <body name="b" pos="0.05 0 0.4" euler="15 5 0"><freejoint/>
      <geom type="box" size="0.1 0.1 0.1"/></body>
    <body name="c" pos="-0.3 0.1 0.3"><freejoint/><geom type="capsule" size="0.05 0.1"/></body>
    <body name="pointer" mocap="true" pos="1 1 1"><geom type="sphere" size="0.02"/></body>
  </worldbody>
</mujoco>)";

std::vector<double> Copy(std::span<const double> values) {
  return std::vector<double>(values.begin(), values.end());
}

TEST(SnapshotTest, RestoredStateStepsBitIdentically) {
  World world = World::LoadString(kPile);
  for (int i = 0; i < 30; ++i) world.Step();
  ASSERT_GT(world.num_contacts(), 0);  // the warm start is non-trivial
  Snapshot snapshot = world.MakeSnapshot();
  world.Save(&snapshot);
  for (int i = 0; i < 10; ++i) world.Step();
  const std::vector<double> qpos = Copy(world.qpos());
  const std::vector<double> qvel = Copy(world.qvel());
  const double time = world.time();

  world.Restore(snapshot);
  for (int i = 0; i < 10; ++i) world.Step();

  EXPECT_EQ(world.time(), time);
  ASSERT_EQ(world.qpos().size(), qpos.size());
  for (std::size_t i = 0; i < qpos.size(); ++i) EXPECT_EQ(world.qpos()[i], qpos[i]) << i;
  for (std::size_t i = 0; i < qvel.size(); ++i) EXPECT_EQ(world.qvel()[i], qvel[i]) << i;
}

TEST(SnapshotTest, RestoreBringsBackPoseMocapAndPendingWrenches) {
  World world = World::LoadString(kPile);
  const int b = world.FindBody("b");
  world.AddWrenchAtCom(b, Wrench{Vec3(0, 0, 50.0), Vec3::Zero()});
  const Snapshot snapshot = world.MakeSnapshot();  // holds the pending wrench
  const BodyState saved = world.body_state(b);
  world.Step();
  world.Step();
  world.SetMocapPose(world.pointer_body(), Pose{Vec3(0, 0, 3), Quat::Identity()});
  const std::vector<double> qvel_after_push = Copy(world.qvel());

  world.Restore(snapshot);
  EXPECT_EQ(world.body_state(b).X_WB.p, saved.X_WB.p);
  EXPECT_EQ(world.body_state(world.pointer_body()).X_WB.p, Vec3(1, 1, 1));
  world.Step();
  world.Step();
  for (std::size_t i = 0; i < qvel_after_push.size(); ++i) {
    EXPECT_EQ(world.qvel()[i], qvel_after_push[i]) << i;
  }
}

}  // namespace
}  // namespace mrh::world
