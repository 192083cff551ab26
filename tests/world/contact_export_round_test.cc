// SPDX-License-Identifier: Apache-2.0
// The contact export makes the round body of a round/flat pair of island bodies its A, so the
// row's normal stays on the flat body: a normal fixed on a rolling ball would turn with it.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "mrh/ir/local_contact.h"
#include "mrh/world/contact_export.h"
#include "mrh/world/world.h"

namespace mrh::world {
namespace {

// A ball touching a box's +x face, both resting on a floor. The ball's geom comes first, so
// MuJoCo's contact has the ball as geom1 when `ball_first`.
std::string SceneXml(bool ball_first) {
  const std::string ball =
      "<body name=\"ball\" pos=\"0.0649 0 0.025\"><freejoint/><geom type=\"sphere\" "
      "size=\"0.025\" mass=\"0.1\"/></body>";
  const std::string box =
      "<body name=\"box\" pos=\"0 0 0.04\"><freejoint/><geom type=\"box\" "
      "size=\"0.04 0.04 0.04\" mass=\"0.2\"/></body>";
  return "<mujoco><option timestep=\"0.02\"/><worldbody><geom type=\"plane\" size=\"5 5 0.1\"/>" +
         (ball_first ? ball + box : box + ball) +
         "<body name=\"pointer\" mocap=\"true\" pos=\"-0.2 0 0.04\"><geom type=\"sphere\" "
         "size=\"0.02\" contype=\"0\" conaffinity=\"0\"/></body></worldbody></mujoco>";
}

void ExpectBallIsA(bool ball_first) {
  World world = World::LoadString(SceneXml(ball_first));
  ContactExporter exporter(&world);
  const int box = world.FindBody("box");
  const int ball = world.FindBody("ball");
  auto model = std::make_unique<ir::LocalContactModel>();
  exporter.Export(std::vector<int>{box}, std::vector<int>{0}, model.get());
  ASSERT_EQ(model->bodies.size(), 2u) << "the ball is in the box's island";
  int pairs = 0;
  for (const ir::LocalContactRow& row : model->contacts) {
    if (row.b < 0) continue;  // a floor row
    ++pairs;
    EXPECT_EQ(model->bodies[static_cast<std::size_t>(row.a)].body, ball);
    EXPECT_EQ(model->bodies[static_cast<std::size_t>(row.b)].body, box);
    EXPECT_GT(row.r_A, 0.0) << "A is the ball";
    EXPECT_EQ(row.r_B, 0.0);
    // The normal, in the box's frame, points from the box's +x face toward the ball.
    EXPECT_NEAR(row.n_B.x(), 1.0, 1e-6);
  }
  EXPECT_EQ(pairs, 1);
}

TEST(ContactExportRoundTest, BallIsAWhenItIsGeom1) {
  ExpectBallIsA(true);
}

TEST(ContactExportRoundTest, BallIsAWhenItIsGeom2) {
  ExpectBallIsA(false);
}

}  // namespace
}  // namespace mrh::world
