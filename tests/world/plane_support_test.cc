// SPDX-License-Identifier: Apache-2.0
// MuJoCo's plane–convex collision reports at most 4 contact points, so a hexagonal prism standing
// on a plane rests on 4 of its 6 bottom vertices (the floor's support, and with it the
// friction's moment, is not the hexagon's). scenes/t3_7_mesh.xml gives its prism a point foot
// under each bottom vertex so that MuJoCo, the reference of experiment t3.7, sees all 6. Should
// a MuJoCo release report the whole face, the first test fails and the feet can go.
#include <gtest/gtest.h>

#include <string>

#include "mrh/world/world.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using testing::kNoPointer;

// scenes/t3_7_mesh.xml's prism without its feet: circumradius 0.04 m, 6 cm tall, on a plane.
constexpr char kBarePrism[] =
    "<mujoco><option timestep=\"0.001\"/><asset><mesh name=\"hex\" vertex=\""
    "0.034641 0.02 -0.03  0 0.04 -0.03  -0.034641 0.02 -0.03  -0.034641 -0.02 -0.03  "
    "0 -0.04 -0.03  0.034641 -0.02 -0.03  0.034641 0.02 0.03  0 0.04 0.03  "
    "-0.034641 0.02 0.03  -0.034641 -0.02 0.03  0 -0.04 0.03  0.034641 -0.02 0.03\"/>"
    "</asset><worldbody><geom type=\"plane\" size=\"3 3 0.1\"/>"
    "<body name=\"object\" pos=\"0 0 0.03\"><freejoint/>"
    "<geom type=\"mesh\" mesh=\"hex\" mass=\"0.3\"/></body></worldbody></mujoco>";

// Contacts after 0.2 s at rest.
int RestingContacts(World& w) {
  for (int i = 0; i < 200; ++i) w.Step();
  return w.num_contacts();
}

TEST(PlaneSupportTest, MuJoCoStandsAHexagonalPrismOnFourOfItsSixVertices) {
  World w = World::LoadString(kBarePrism, kNoPointer);
  EXPECT_EQ(RestingContacts(w), 4);
}

TEST(PlaneSupportTest, TheT37PrismsFeetGiveTheFloorAllSixVertices) {
  World w = World::LoadFile(std::string(MRH_SOURCE_DIR) + "/scenes/t3_7_mesh.xml", kNoPointer);
  w.set_timestep(0.001);
  // The mesh's own 4 and one per foot.
  EXPECT_EQ(RestingContacts(w), 4 + 6);
}

}  // namespace
}  // namespace mrh::world
