// SPDX-License-Identifier: Apache-2.0
// The Perturber's contact queries: the velocity change that contacts outside a known set gave a
// body in the step just taken.
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "mrh/world/perturbation.h"
#include "perturbation_test_util.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using testing::Bodies;
using testing::kBusy;
using testing::kNoPointer;
using testing::kSkipTol;

TEST(PerturberTest, NewContactVelocityChangeIsTheLandingImpulseOnly) {
  // A box dropped flat onto a floor: in its landing step the floor contacts are new, and the
  // velocity change they cause is all of the step's change except gravity's.
  World world = World::LoadString(R"(
<mujoco><option timestep="0.02"/><worldbody>
  <geom type="plane" size="5 5 0.1"/>
  <body name="box" pos="0 0 0.11" euler="0 0 30"><freejoint/>
    <geom type="box" size="0.1 0.1 0.1" mass="2"/></body>
</worldbody></mujoco>)",
                                  kNoPointer);
  const int box = world.FindBody("box");
  Perturber perturber(&world);
  const int bodies[] = {box};
  perturber.Begin(bodies);
  perturber.ZeroForceRun();
  const std::span<const std::uint64_t> before = perturber.base_contacts();
  EXPECT_TRUE(before.empty());  // 1 cm above the floor
  const std::vector<std::uint64_t> known(before.begin(), before.end());
  perturber.End();
  Twist landed;
  Twist u_before;
  for (int step = 0; step < 20 && landed.v.isZero(0.0); ++step) {
    u_before = world.body_state(box).V_WCm;
    world.Step();
    landed = perturber.NewContactVelocityChange(box, known);
  }
  ASSERT_GT(landed.v.z(), 0.0);  // the floor pushes up
  const Twist u_after = world.body_state(box).V_WCm;
  const Vec3 expected = u_after.v - u_before.v - Vec3(0, 0, -9.81 * 0.02);
  EXPECT_LE((landed.v - expected).norm(), kSkipTol);
  EXPECT_LE((landed.w - (u_after.w - u_before.w)).norm(), kSkipTol);
}

TEST(PerturberTest, KnownContactsGiveNoVelocityChange) {
  World world = World::LoadString(kBusy, kNoPointer);
  for (int i = 0; i < 5; ++i) world.Step();
  const std::vector<int> bodies = Bodies(world, {"resting"});
  Perturber perturber(&world);
  perturber.Begin(bodies);
  perturber.ZeroForceRun();
  const std::span<const std::uint64_t> base = perturber.base_contacts();
  ASSERT_FALSE(base.empty());
  const std::vector<std::uint64_t> known(base.begin(), base.end());
  perturber.End();
  world.Step();
  const Twist dV = perturber.NewContactVelocityChange(bodies[0], known);
  EXPECT_EQ(dV.v, Vec3::Zero());
  EXPECT_EQ(dV.w, Vec3::Zero());
}

}  // namespace
}  // namespace mrh::world
