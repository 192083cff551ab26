// SPDX-License-Identifier: Apache-2.0
// MuJoCo's buffers sized from the scene: piles of boxes with friction run without dropping
// contacts, scenes MuJoCo 2.2.2 cannot hold are refused in one line, a scene's own <size> wins.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "mrh/core/error.h"
#include "mrh/world/world.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::kNoPointer;

// `count` 10 cm boxes (friction, condim 3 unless `condim` says otherwise) in layers of 50
// (5 × 10, 2 cm gaps) stacked on a floor, 1 mm apart vertically; `extra` goes into <mujoco>.
std::string BoxPile(int count, const std::string& extra = "", int condim = 3) {
  std::string bodies;
  for (int i = 0; i < count; ++i) {
    const int layer = i / 50;
    const int in_layer = i % 50;
    bodies += "<body pos=\"" + std::to_string(0.12 * (in_layer % 10)) + " " +
              std::to_string(0.12 * (in_layer / 10)) + " " + std::to_string(0.05 + 0.101 * layer) +
              "\"><freejoint/><geom type=\"box\" size=\"0.05 0.05 0.05\" mass=\"0.2\"/></body>";
  }
  return "<mujoco>" + extra + "<option timestep=\"0.005\"/><default><geom condim=\"" +
         std::to_string(condim) + "\" friction=\"0.5\"/></default><worldbody>" +
         "<geom type=\"plane\" size=\"5 5 0.1\"/>" + bodies + "</worldbody></mujoco>";
}

// MuJoCo 2.2.2's defaults (nconmax 100, njmax 500) hold 25 resting boxes: 150 dropped contacts
// on every step (issue 18). Sized from the scene, three layers of 50 settle with none dropped.
TEST(ModelSizeTest, PileOf150BoxesWithFrictionDropsNoContacts) {
  World w = World::LoadString(BoxPile(150), kNoPointer);
  for (int i = 0; i < 40; ++i) w.Step();
  EXPECT_GE(w.num_contacts(), 4 * 150);  // each box on the floor or on the box below
  EXPECT_THAT(w.SimulatorWarnings(), ::testing::IsEmpty());
}

TEST(ModelSizeTest, SceneSizeWinsOverThePlan) {
  World w = World::LoadString(BoxPile(30, "<size nconmax=\"20\"/>"), kNoPointer);
  w.Step();
  EXPECT_EQ(w.num_contacts(), 20);
  ASSERT_EQ(w.SimulatorWarnings().size(), 1u);
  EXPECT_THAT(w.SimulatorWarnings()[0], HasSubstr("contact buffer full"));
}

TEST(ModelSizeTest, SizeInACommentIsNotTheScenes) {
  World w = World::LoadString(BoxPile(30, "<!-- <size nconmax=\"20\"/> -->"), kNoPointer);
  w.Step();
  EXPECT_EQ(w.num_contacts(), 4 * 30);
  EXPECT_THAT(w.SimulatorWarnings(), ::testing::IsEmpty());
}

// 700 boxes resting with pyramidal friction need 700 × 16 rows; with 4200 dofs that is 2.5 GB of
// MuJoCo 2.2.2's dense constraint arrays, over its int-sized buffer.
TEST(ModelSizeTest, TooManyFrictionRowsIsAOneLineSceneError) {
  EXPECT_THAT([] { (void)World::LoadString(BoxPile(700), kNoPointer, "pile.xml"); },
              ::testing::ThrowsMessage<SceneError>(AllOf(
                  HasSubstr("pile.xml"), HasSubstr("constraint rows"),
                  HasSubstr("cone=\"elliptic\""), ::testing::Not(HasSubstr("\n")))));
}

TEST(ModelSizeTest, ExplicitNjmaxTooLargeNamesTheKey) {
  EXPECT_THAT([] {
    (void)World::LoadString(BoxPile(10, "<size njmax=\"400000\"/>"), kNoPointer, "big.xml");
  },
              ::testing::ThrowsMessage<SceneError>(
                  AllOf(HasSubstr("big.xml"), HasSubstr("<size njmax>"),
                        HasSubstr("lower njmax or remove it"))));
}

}  // namespace
}  // namespace mrh::world
