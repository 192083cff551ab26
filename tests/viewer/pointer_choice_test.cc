// SPDX-License-Identifier: Apache-2.0
// Which pointer the viewer's input drives, and the device block it takes the calibration from.
#include "viewer/pointer_choice.h"

#include <gtest/gtest.h>

namespace mrh::viewer::internal {
namespace {

session::Session TwoFingers() {
  return session::LoadSession(MRH_SOURCE_DIR "/scenes/two_finger_grasp.json");
}

TEST(PointerChoiceTest, NamesEveryPointerInSessionOrder) {
  const std::vector<std::string> names = PointerNames(TwoFingers());
  ASSERT_EQ(names.size(), 2u);
  EXPECT_EQ(names[0], "thumb");
  EXPECT_EQ(names[1], "index");
}

TEST(PointerChoiceTest, AOnePointerSessionHasItsPointerBody) {
  const std::vector<std::string> names =
      PointerNames(session::LoadSession(MRH_SOURCE_DIR "/scenes/demo.json"));
  ASSERT_EQ(names.size(), 1u);
  EXPECT_EQ(names[0], "pointer");
}

TEST(PointerChoiceTest, AChoiceOutOfRangeFallsBackToTheFirst) {
  EXPECT_EQ(ChoosePointer(1, 2), 1);
  EXPECT_EQ(ChoosePointer(0, 2), 0);
  EXPECT_EQ(ChoosePointer(2, 2), 0);
  EXPECT_EQ(ChoosePointer(-1, 2), 0);
  EXPECT_EQ(ChoosePointer(3, 1), 0);
}

TEST(PointerChoiceTest, EachPointerHasItsOwnDeviceBlock) {
  const session::Session s = TwoFingers();
  // two_finger_grasp.json: the thumb's hand starts at y = -0.07, the index's at +0.07.
  EXPECT_EQ(PointerDevice(s, 0).keyframes.front().X_DT.p.y(), -0.07);
  EXPECT_EQ(PointerDevice(s, 1).keyframes.front().X_DT.p.y(), 0.07);
}

}  // namespace
}  // namespace mrh::viewer::internal
