// SPDX-License-Identifier: Apache-2.0
// The contact export completes a polyhedral body's contact with a face by rows at its vertices
// near that face: a cube mesh tilted on a box table (MuJoCo: three contacts along its lowest
// edge) gets rows at its four lower corners too, each with its exact gap to the table top; a box
// flat on a plane (MuJoCo: its four corners) gets no duplicates.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "mrh/ir/local_contact.h"
#include "mrh/world/contact_export.h"
#include "mrh/world/world.h"

namespace mrh::world {
namespace {

constexpr double kHalf = 0.02;  // m, the cube's half size
constexpr double kTop = 0.75;   // m, the table top
constexpr double kTilt = 0.02;  // rad, about y

// A cube mesh resting on one lower edge (tilted by kTilt about y, its +x lower edge 0.1 mm into
// the table), so its -x lower corners are 2 h sin(kTilt) = 0.8 mm above the table.
std::string TiltedCubeXml() {
  const double z = kTop - 1e-4 + kHalf * (std::cos(kTilt) + std::sin(kTilt));
  const double half = kTilt / 2.0;
  return "<mujoco><option timestep=\"0.01\"/><asset><mesh name=\"cube\" vertex=\"-.02 -.02 "
         "-.02  .02 -.02 -.02  -.02 .02 -.02  .02 .02 -.02  -.02 -.02 .02  .02 -.02 .02  -.02 "
         ".02 .02  .02 .02 .02\"/></asset><worldbody>"
         "<geom name=\"table\" type=\"box\" size=\"0.3 0.3 0.02\" pos=\"0 0 " +
         std::to_string(kTop - 0.02) + "\"/><body name=\"box\" pos=\"0 0 " + std::to_string(z) +
         "\" quat=\"" + std::to_string(std::cos(half)) + " 0 " + std::to_string(std::sin(half)) +
         " 0\"><freejoint/><geom type=\"mesh\" mesh=\"cube\" mass=\"0.1\"/></body>"
         "<body name=\"pointer\" mocap=\"true\" pos=\"-0.3 0 0.9\"><geom type=\"sphere\" "
         "size=\"0.01\" contype=\"0\" conaffinity=\"0\"/></body></worldbody></mujoco>";
}

TEST(ContactManifoldTest, TiltedCubeMeshOnATableHasRowsAtItsFourLowerCorners) {
  World world = World::LoadString(TiltedCubeXml());
  ContactExporter exporter(&world, 0.005);
  auto model = std::make_unique<ir::LocalContactModel>();
  exporter.Export(std::vector<int>{world.FindBody("box")}, std::vector<int>{0}, model.get());
  ASSERT_EQ(model->bodies.size(), 1u);
  const Pose& X_WB = model->bodies[0].X_WB;
  // Each lower corner has a row (MuJoCo's, within 1 mm, or one at the vertex); its gap is the
  // corner's height above the table top, to MuJoCo's depth convention (0.1 mm).
  for (const double x : {-kHalf, kHalf}) {
    for (const double y : {-kHalf, kHalf}) {
      const Vec3 corner(x, y, -kHalf);
      const double height = (X_WB * corner).z() - kTop;
      int rows = 0;
      for (const ir::LocalContactRow& row : model->contacts) {
        if ((row.p_A - corner).norm() > 1e-3) continue;
        ++rows;
        EXPECT_EQ(row.b, -1);
        EXPECT_NEAR(row.n_B.z(), 1.0, 1e-6);
        EXPECT_NEAR(row.dist0, height, 1e-4) << "corner " << x << ", " << y;
      }
      EXPECT_EQ(rows, 1) << "corner " << x << ", " << y << " at " << height << " m";
    }
  }
}

TEST(ContactManifoldTest, FlatBoxOnAPlaneKeepsMuJoCosFourCorners) {
  World world = World::LoadString(
      "<mujoco><worldbody><geom type=\"plane\" size=\"1 1 0.1\"/><body name=\"box\" "
      "pos=\"0 0 0.0199\"><freejoint/><geom type=\"box\" size=\"0.02 0.02 0.02\" "
      "mass=\"0.1\"/></body><body name=\"pointer\" mocap=\"true\" pos=\"-0.3 0 0.9\"><geom "
      "type=\"sphere\" size=\"0.01\" contype=\"0\" conaffinity=\"0\"/></body></worldbody>"
      "</mujoco>");
  ContactExporter exporter(&world, 0.005);
  auto model = std::make_unique<ir::LocalContactModel>();
  exporter.Export(std::vector<int>{world.FindBody("box")}, std::vector<int>{0}, model.get());
  EXPECT_EQ(model->contacts.size(), 4u);
}

}  // namespace
}  // namespace mrh::world
