// SPDX-License-Identifier: Apache-2.0
// The contact export collides only the geoms that may touch the island; its
// bodies and rows must be exactly those of a whole-world collision pass.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "mrh/ir/local_contact.h"
#include "mrh/world/contact_export.h"
#include "mrh/world/world.h"

namespace mrh::world {
namespace {

// A row of six touching cubes (pitch 0.1 m: face to face) on a floor, against a static wall
// box at its +x end, beside three rows of ten cubes with 2 cm gaps. All with friction.
std::string SceneXml() {
  std::string bodies;
  for (int i = 0; i < 6; ++i) {
    bodies += "<body name=\"row" + std::to_string(i) + "\" pos=\"" + std::to_string(0.1 * i) +
              " -0.5 0.05\"><freejoint/><geom type=\"box\" size=\"0.05 0.05 0.05\" "
              "mass=\"0.2\"/></body>";
  }
  for (int i = 0; i < 30; ++i) {
    bodies += "<body pos=\"" + std::to_string(0.12 * (i % 10)) + " " +
              std::to_string(0.25 * (i / 10)) +
              " 0.05\"><freejoint/><geom type=\"box\" size=\"0.05 0.05 0.05\" mass=\"0.2\"/>"
              "</body>";
  }
  return "<mujoco><option timestep=\"0.02\" solver=\"Newton\"/><default><geom condim=\"3\"/>"
         "</default><worldbody><geom type=\"plane\" size=\"20 20 0.1\"/>"
         "<geom type=\"box\" size=\"0.05 0.3 0.2\" pos=\"0.6 -0.5 0.2\"/>" +
         bodies +
         "<body name=\"pointer\" mocap=\"true\" pos=\"-0.1 -0.5 0.05\"><geom type=\"sphere\" "
         "size=\"0.02\" contype=\"0\" conaffinity=\"0\"/></body></worldbody></mujoco>";
}

void ExpectSameModel(const ir::LocalContactModel& a, const ir::LocalContactModel& b) {
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].body, b.bodies[i].body) << "body " << i;
    EXPECT_EQ(a.bodies[i].motion, b.bodies[i].motion) << "body " << i;
  }
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  for (std::size_t i = 0; i < a.contacts.size(); ++i) {
    const ir::LocalContactRow& r = a.contacts[i];
    const ir::LocalContactRow& s = b.contacts[i];
    EXPECT_EQ(r.a, s.a) << "row " << i;
    EXPECT_EQ(r.b, s.b) << "row " << i;
    EXPECT_EQ(r.p_A, s.p_A) << "row " << i;
    EXPECT_EQ(r.p_B, s.p_B) << "row " << i;
    EXPECT_EQ(r.n_B, s.n_B) << "row " << i;
    EXPECT_EQ(r.dist0, s.dist0) << "row " << i;
    EXPECT_EQ(r.mu, s.mu) << "row " << i;
  }
}

TEST(ContactExportIslandTest, IslandPassExportsTheWholeWorldPassRowsForARowOfTouchingCubes) {
  World world = World::LoadString(SceneXml());
  for (int i = 0; i < 10; ++i) world.Step();  // settle: resting contacts, soft penetration
  ContactExporter island(&world);
  ContactExporter whole(&world, 0.005, /*whole_world=*/true);
  const std::vector<int> seeds = {world.FindBody("row0")};
  const std::vector<int> motions = {0};
  auto a = std::make_unique<ir::LocalContactModel>();
  auto b = std::make_unique<ir::LocalContactModel>();
  const std::uint32_t status_whole = whole.Export(seeds, motions, b.get());
  const int contacts_whole = world.num_contacts();
  const std::uint32_t status_island = island.Export(seeds, motions, a.get());
  EXPECT_EQ(status_island, status_whole);
  // The whole row is one island, reached through five cube-cube contacts; its rows include the
  // floor and the wall.
  EXPECT_EQ(b->bodies.size(), 6u);
  ExpectSameModel(*a, *b);
  // The island pass found the island's contacts only (the 30 other cubes rest on the floor).
  EXPECT_LT(world.num_contacts(), contacts_whole);
}

TEST(ContactExportIslandTest, IslandPassExportsTheWholeWorldPassRowsForAPileCube) {
  World world = World::LoadString(SceneXml());
  for (int i = 0; i < 10; ++i) world.Step();
  ContactExporter island(&world);
  ContactExporter whole(&world, 0.005, /*whole_world=*/true);
  // Two seeds: a cube in the middle of the pile (its neighbours 2 cm away, beyond the margin)
  // and the end of the row.
  const std::vector<int> seeds = {world.FindBody("row5"), 6 + 1 + 15};
  const std::vector<int> motions = {0, 1};
  auto a = std::make_unique<ir::LocalContactModel>();
  auto b = std::make_unique<ir::LocalContactModel>();
  EXPECT_EQ(island.Export(seeds, motions, a.get()), whole.Export(seeds, motions, b.get()));
  EXPECT_EQ(b->bodies.size(), 7u);
  ExpectSameModel(*a, *b);
}

}  // namespace
}  // namespace mrh::world
