// SPDX-License-Identifier: Apache-2.0
// Mechanisms in the contact local model: the island's joints (world/contact_export.h) simulated
// by the local solver (render/local_contact_solver.h) against MuJoCo at the same 1 ms step, and
// the joint coordinates written back into the world.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "mrh/ir/local_contact.h"
#include "mrh/render/local_contact_solver.h"
#include "mrh/world/contact_export.h"
#include "mrh/world/world.h"

namespace mrh {
namespace {

const world::LoadOptions kNoPointer{.pointer_body = ""};

world::World Load(const std::string& name) {
  return world::World::LoadFile(std::string(MRH_SOURCE_DIR) + "/scenes/" + name, kNoPointer);
}

struct Island {
  std::unique_ptr<ir::LocalContactModel> model = std::make_unique<ir::LocalContactModel>();
  render::LocalContactSolver solver;
};

// Exports the island of `seed` from `world` and adopts it. The world steps 1 ms here, so the
// exporter's own horizon (two steps) is short of the 20 ms period: a 3 cm margin stands in.
void ExportIsland(world::World& world, int seed, Island* island) {
  world::ContactExporter exporter(&world, 0.03, false, /*articulated=*/true);
  const std::vector<int> seeds{seed}, motions{0};
  (void)exporter.Export(seeds, motions, island->model.get());
  island->solver.Adopt(*island->model);
}

// A constant force on `body` at its point p_B (body frame), for `seconds` at 1 ms, in MuJoCo and
// in the local solver; returns the largest difference seen in a hinge or slide coordinate (rad
// or m) or in a body's orientation (rad).
double LargestJointDifference(world::World world, const std::string& body_name, const Vec3& p_B,
                              const Vec3& f_W, double seconds) {
  world.set_timestep(0.001);
  const int body = world.FindBody(body_name);
  Island island;
  ExportIsland(world, body, &island);
  const int local = [&] {
    for (std::size_t i = 0; i < island.solver.size(); ++i) {
      if (island.solver.world_body(i) == body) return static_cast<int>(i);
    }
    return -1;
  }();
  EXPECT_GE(local, 0);
  double worst = 0.0;
  const int steps = static_cast<int>(std::lround(seconds / 0.001));
  for (int k = 0; k < steps; ++k) {
    if (k % 20 == 0) ExportIsland(world, body, &island);  // a 20 ms physics period's rows
    const Pose X_W = world.body_state(body).X_WB;
    world.AddForceAtPoint(body, f_W, X_W * p_B);
    world.Step();
    const Pose X_L = island.solver.X_WB(static_cast<std::size_t>(local));
    island.solver.AddForce(static_cast<std::size_t>(local), f_W, X_L * p_B);
    EXPECT_TRUE(island.solver.Step(0.001));
    for (std::size_t j = 0; j < island.solver.joint_count(); ++j) {
      const int joint = island.model->joints[j].joint;
      if (joint < 0 || island.model->joints[j].type == ir::LocalJointType::kBall) continue;
      const double d = island.solver.JointPosition(j) - world.joint_position(joint);
      worst = std::max(worst, std::abs(d));
    }
    for (std::size_t i = 0; i < island.solver.size(); ++i) {  // every body's orientation (rad)
      const Quat q_mj = world.body_state(island.solver.world_body(i)).X_WB.q;
      worst = std::max(worst, island.solver.X_WB(i).q.angularDistance(q_mj));
    }
  }
  return worst;
}

// The d2 lamp (three sprung, damped hinges with armature and limits) pressed down near its
// head, the shade kept off the floor: the local joints follow MuJoCo's generalized coordinates
// to within 1 mrad (0.06°) over 2 s. (Pressed at 3 N the shade lands on the floor, and the
// contact's timing, found anew every 20 ms here, moves the joints by up to 1°.)
TEST(ArticulatedIslandTest, LampBentByAForceFollowsMuJoCo) {
  const double worst = LargestJointDifference(Load("d2_lamp.xml"), "upper_arm", Vec3(0, 0, 0.24),
                                              Vec3(0, 0, -1.5), 2.0);
  EXPECT_LT(worst, 1e-3);
}

// The drawer (slide with damping, dry friction and limits) pulled out by a constant force, for
// 0.5 s: it stays short of its limit (pulled at 2 N into the limit, the local soft limit's
// impact differs from MuJoCo's by up to 5 mm).
TEST(ArticulatedIslandTest, DrawerPulledByAForceFollowsMuJoCo) {
  const double worst =
      LargestJointDifference(Load("d2_drawer.xml"), "drawer", Vec3::Zero(), Vec3(1.0, 0, 0), 0.5);
  EXPECT_LT(worst, 1e-3);  // m
}

// A pendulum on a ball joint (damping, armature, a spring toward its rest orientation) pushed
// sideways off its swing plane, with a lamp head welded to it (a child body with no joint):
// the orientations follow MuJoCo's within 1 mrad over 1 s.
TEST(ArticulatedIslandTest, BallPendulumWithAWeldedHeadFollowsMuJoCo) {
  const std::string xml =
      "<mujoco><option timestep=\"0.02\"/><worldbody>"
      "<body name=\"rod\" pos=\"0 0 1\"><joint name=\"ball\" type=\"ball\" damping=\"0.02\" "
      "armature=\"0.001\" stiffness=\"0.5\"/>"
      "<geom type=\"capsule\" fromto=\"0 0 0 0.1 0 -0.3\" size=\"0.01\" mass=\"0.2\"/>"
      "<body name=\"head\" pos=\"0.1 0 -0.3\" euler=\"0 0.5 0\"><geom type=\"box\" "
      "size=\"0.03 0.02 0.01\" mass=\"0.1\"/></body></body></worldbody></mujoco>";
  const double worst = LargestJointDifference(world::World::LoadString(xml, kNoPointer), "rod",
                                              Vec3(0.05, 0, -0.15), Vec3(0, 0.5, 0), 1.0);
  EXPECT_LT(worst, 1e-3);
}

// T4.1's cube translates on three orthogonal slides (it cannot turn), pushed off-centre and
// obliquely: its three coordinates follow MuJoCo's within 1 µm over 0.5 s, and it stays level.
TEST(ArticulatedIslandTest, CubeOnThreeSlidesFollowsMuJoCo) {
  const double worst = LargestJointDifference(Load("t4_1.xml"), "cube", Vec3(0.02, 0.03, 0.01),
                                              Vec3(1.0, 0.5, -0.3), 0.5);
  EXPECT_LT(worst, 1e-6);
}

// A 3D chain falling and swinging under gravity in joint space: hinges about alternating axes
// (springs, damping, armature), a telescoping slide on a turning parent and a welded tip, pushed
// sideways at the tip. Joint space integrates MuJoCo's own equations (its coordinates, mass
// matrix and velocity-product terms, damping implicit), so the coordinates agree with MuJoCo's
// to rounding over 1 s of fast motion.
TEST(ArticulatedIslandTest, ChainInJointSpaceFollowsMuJoCoToRounding) {
  std::string xml = "<mujoco><option timestep=\"0.02\"/><worldbody>";
  const char* axes[] = {"0 1 0", "1 0 0", "0 1 0", "0 0 1", "1 0 0"};
  for (int i = 0; i < 5; ++i) {
    const std::string type =
        i == 3 ? "slide\" axis=\"1 0 0" : std::string("hinge\" axis=\"") + axes[i];
    xml += "<body name=\"l" + std::to_string(i) + "\" pos=\"" + (i == 0 ? "0 0 1" : "0.1 0 0") +
           "\"><joint type=\"" + type +
           "\" damping=\"0.02\" stiffness=\"0.3\" armature=\"0.0002\"/><geom type=\"capsule\" "
           "fromto=\"0 0 0 0.1 0 0\" size=\"0.01\" mass=\"0.1\"/>";
  }
  xml +=
      "<body name=\"tip\" pos=\"0.1 0 0\" euler=\"0.3 0 0\"><geom type=\"box\" "
      "size=\"0.02 0.01 0.01\" mass=\"0.05\"/></body>";
  xml += "</body></body></body></body></body></worldbody></mujoco>";
  const double worst = LargestJointDifference(world::World::LoadString(xml, kNoPointer), "l4",
                                              Vec3(0.1, 0, 0), Vec3(0, 0.5, 0), 1.0);
  EXPECT_LT(worst, 1e-9);
}

// A body on two hinges is not simulated locally: the exporter says so, naming body and joint,
// and leaves the body out of the island.
TEST(ArticulatedIslandTest, TwoJointBodyIsNamedAndLeftToTheWorld) {
  world::World world = world::World::LoadString(
      "<mujoco><worldbody><body name=\"arm\" pos=\"0 0 1\"><joint name=\"j1\" axis=\"0 1 0\"/>"
      "<joint name=\"j2\" axis=\"1 0 0\"/><geom type=\"box\" size=\"0.1 0.1 0.1\"/></body>"
      "</worldbody></mujoco>",
      kNoPointer);
  world::ContactExporter exporter(&world, 0.005, false, true);
  ASSERT_EQ(exporter.warnings().size(), 1u);
  EXPECT_NE(exporter.warnings()[0].find("'arm'"), std::string::npos) << exporter.warnings()[0];
  EXPECT_NE(exporter.warnings()[0].find("'j1'"), std::string::npos) << exporter.warnings()[0];
  EXPECT_FALSE(exporter.IsIslandBody(world.FindBody("arm")));
}

}  // namespace
}  // namespace mrh
