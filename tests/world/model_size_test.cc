// SPDX-License-Identifier: Apache-2.0
// MuJoCo's arena sized from the scene: piles of boxes with friction run without dropping
// contacts, a scene's own <size memory> wins, and an arena too small is a one-line error.
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

// `count` 10 cm boxes (friction, condim 3 unless `condim` says otherwise) in layers of
// `per_layer` (rows of 10, 2 cm gaps) stacked on a floor, 1 mm apart vertically; `extra` goes into
// <mujoco>.
std::string BoxPile(int count, const std::string& extra = "", int condim = 3, int per_layer = 50) {
  std::string bodies;
  for (int i = 0; i < count; ++i) {
    const int layer = i / per_layer;
    const int in_layer = i % per_layer;
    bodies += "<body pos=\"" + std::to_string(0.12 * (in_layer % 10)) + " " +
              std::to_string(0.12 * (in_layer / 10)) + " " + std::to_string(0.05 + 0.101 * layer) +
              "\"><freejoint/><geom type=\"box\" size=\"0.05 0.05 0.05\" mass=\"0.2\"/></body>";
  }
  return "<mujoco>" + extra + "<option timestep=\"0.005\"/><default><geom condim=\"" +
         std::to_string(condim) + "\" friction=\"0.5\"/></default><worldbody>" +
         "<geom type=\"plane\" size=\"5 5 0.1\"/>" + bodies + "</worldbody></mujoco>";
}

// MuJoC// Sized from the scene, three layers of 50 boxes settle with no contact dropped.
TEST(ModelSizeTest, PileOf150BoxesWithFrictionDropsNoContacts) {
  World w = World::LoadString(BoxPile(150), kNoPointer);
  for (int i = 0; i < 40; ++i) w.Step();
  EXPECT_GE(w.num_contacts(), 4 * 150);  // each box on the floor or on the box below
  EXPECT_THAT(w.SimulatorWarnings(), ::testing::IsEmpty());
}

// The arena holds 1000 boxes resting on a floor with pyramidal friction (16 rows each),
// dropping nothing.
TEST(ModelSizeTest, ThousandBoxesWithPyramidalFrictionLoadAndStep) {
  World w = World::LoadString(BoxPile(1000, "", 3, 1000), kNoPointer, "pile.xml");
  for (int i = 0; i < 10; ++i) w.Step();  // one layer, 1 mm up: landed within 20 ms
  EXPECT_GE(w.num_contacts(), 4 * 1000);
  EXPECT_THAT(w.SimulatorWarnings(), ::testing::IsEmpty());
}

// The scene's own arena size wins over the plan (which holds this pile easily): 200 KB is too
// small for 30 boxes' contacts, a one-line error that names the scene and the key to change.
TEST(ModelSizeTest, SceneMemoryWinsAndTooSmallIsAOneLineError) {
  World w = World::LoadString(BoxPile(30, "<size memory=\"200K\"/>"), kNoPointer, "small.xml");
  EXPECT_THAT(
      [&] {
        for (int i = 0; i < 10; ++i) w.Step();  // the boxes land within a few steps
      },
      ::testing::ThrowsMessage<RuntimeError>(AllOf(
          HasSubstr("small.xml"), HasSubstr("<size memory"), ::testing::Not(HasSubstr("\n")))));
}

TEST(ModelSizeTest, SizeInACommentIsNotTheScenes) {
  World w = World::LoadString(BoxPile(30, "<!-- <size memory=\"200K\"/> -->"), kNoPointer);
  w.Step();
  EXPECT_EQ(w.num_contacts(), 4 * 30);
  EXPECT_THAT(w.SimulatorWarnings(), ::testing::IsEmpty());
}

}  // namespace
}  // namespace mrh::world
