// SPDX-License-Identifier: Apache-2.0
// Round and mesh objects left on a box table come to rest, as a new user's scene expects. That
// needs several contact points for cylinder-on-box and mesh-on-box (MuJoCo 3's convex collision
// gives them): on one point a cylinder spins at 10 rad/s and drifts 15 cm in 4 s even at 1 ms.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mrh/world/world.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using testing::kNoPointer;

// A static 60 × 60 × 4 cm box table top at z 0.40–0.44 on a floor, and `object` (one body named
// "obj" whose lowest point is 1 mm above the table top), μ 0.5, at time step `dt`.
std::string OnBoxTable(const std::string& object, double dt) {
  return "<mujoco><option timestep=\"" + std::to_string(dt) +
         "\"/><asset><mesh name=\"hexprism\" vertex=\""
         "0.04 0 0  0.02 0.0346 0  -0.02 0.0346 0  -0.04 0 0  -0.02 -0.0346 0  0.02 -0.0346 0 "
         "0.04 0 0.06  0.02 0.0346 0.06  -0.02 0.0346 0.06  -0.04 0 0.06  -0.02 -0.0346 0.06  "
         "0.02 -0.0346 0.06\"/></asset>"
         "<default><geom friction=\"0.5\"/></default><worldbody>"
         "<geom type=\"plane\" size=\"5 5 0.1\"/>"
         "<geom type=\"box\" pos=\"0 0 0.42\" size=\"0.3 0.3 0.02\"/>" +
         object + "</worldbody></mujoco>";
}

struct Rest {
  double speed = 0.0;     // m/s, COM
  double spin = 0.0;      // rad/s
  double drift = 0.0;     // m, horizontal COM displacement since the start
  double max_spin = 0.0;  // rad/s, over the whole run
  double q_w = 1.0;       // w of the final orientation quaternion (1: as it started upright)
};

// Steps `w` for `seconds` and reports the motion of `body` at the end.
Rest Settle(World& w, const std::string& body, double seconds) {
  const int obj = w.FindBody(body);
  const Vec3 start = w.body_state(obj).p_WCm;
  Rest rest;
  const int steps = static_cast<int>(std::lround(seconds / w.timestep()));
  for (int i = 0; i < steps; ++i) {
    w.Step();
    rest.max_spin = std::max(rest.max_spin, w.body_state(obj).V_WCm.w.norm());
  }
  const BodyState s = w.body_state(obj);
  rest.speed = s.V_WCm.v.norm();
  rest.spin = s.V_WCm.w.norm();
  rest.drift = (s.p_WCm - start).head<2>().norm();
  rest.q_w = s.X_WB.q.w();
  EXPECT_TRUE(w.SimulatorWarnings().empty());
  return rest;
}

// The same for body "obj" of scene text `xml`.
Rest Settle(const std::string& xml, double seconds) {
  World w = World::LoadString(xml, kNoPointer, "table.xml");
  return Settle(w, "obj", seconds);
}

const std::string kCylinder =
    "<body name=\"obj\" pos=\"0 0 0.491\"><freejoint/>"
    "<geom type=\"cylinder\" size=\"0.04 0.05\" mass=\"0.3\"/></body>";
const std::string kMesh =
    "<body name=\"obj\" pos=\"0 0 0.441\"><freejoint/>"
    "<geom type=\"mesh\" mesh=\"hexprism\" mass=\"0.3\"/></body>";

// "At rest": speeds far below any a push would give, and no drift beyond a millimetre.
constexpr double kRestSpeed = 1e-3;  // m/s
constexpr double kRestSpin = 1e-2;   // rad/s
constexpr double kRestDrift = 1e-3;  // m

class SettleTest : public ::testing::TestWithParam<double> {};

TEST_P(SettleTest, UprightCylinderOnABoxTableIsAtRestWithinOneSecond) {
  const Rest r = Settle(OnBoxTable(kCylinder, GetParam()), 1.0);
  EXPECT_LT(r.speed, kRestSpeed);
  EXPECT_LT(r.spin, kRestSpin);
  EXPECT_LT(r.drift, kRestDrift);
  EXPECT_LT(r.max_spin, 10 * kRestSpin);
}

TEST_P(SettleTest, ConvexMeshOnABoxTableIsAtRestWithinOneSecond) {
  const Rest r = Settle(OnBoxTable(kMesh, GetParam()), 1.0);
  EXPECT_LT(r.speed, kRestSpeed);
  EXPECT_LT(r.spin, kRestSpin);
  EXPECT_LT(r.drift, kRestDrift);
  EXPECT_LT(r.max_spin, 10 * kRestSpin);
}

// scenes/compound_mug.xml: a non-convex object as one body of convex geoms (cylinder base, a
// ring of wall boxes, a box handle) loads without the concave-mesh warning and stands at rest.
TEST_P(SettleTest, CompoundMugStandsAtRest) {
  World w = World::LoadFile(std::string(MRH_SOURCE_DIR) + "/scenes/compound_mug.xml", kNoPointer);
  EXPECT_TRUE(w.LoadWarnings().empty());
  w.set_timestep(GetParam());
  const Rest r = Settle(w, "mug", 1.0);
  EXPECT_LT(r.speed, kRestSpeed);
  EXPECT_LT(r.spin, kRestSpin);
  EXPECT_LT(r.drift, kRestDrift);
  EXPECT_GT(r.q_w, 0.9999);  // upright
}

// The haptic rate and the physics thread's usual step.
INSTANTIATE_TEST_SUITE_P(Steps, SettleTest, ::testing::Values(0.001, 0.02),
                         [](const ::testing::TestParamInfo<double>& p) {
                           return p.param < 0.01 ? std::string("Dt1ms") : std::string("Dt20ms");
                         });

}  // namespace
}  // namespace mrh::world
