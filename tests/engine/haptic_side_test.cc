// SPDX-License-Identifier: Apache-2.0
// The tick records the haptic side fills: the proxy pose is the method's own, or the pointer's.
#include "mrh/haptic/haptic_side.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/engine/method.h"
#include "mrh/world/world.h"

namespace mrh::engine::testing {
namespace {

// A 0.2 m cube pointer (the T3.1 pointer) over a floor plane at z = 0.
constexpr double kHalf = 0.1;    // m, pointer half side
constexpr double kDepth = 1e-3;  // m, how far the pointer is pressed into the floor
constexpr char kFloorScene[] = R"(
<mujoco>
  <option timestep="0.02" gravity="0 0 -9.81"/>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="pointer" mocap="true" pos="0 0 0.5">
      <geom name="pointer" type="box" size="0.1 0.1 0.1" contype="0" conaffinity="0"
            density="1000"/></body>
  </worldbody>
</mujoco>)";

// The T3.1 gains (k_t = k_r = 9000, R_w = 3.33·1, μ = 0), with enough PGS sweeps to converge
// on a cube face from a cold start (see proxy_method_test.cc).
settings::EngineSettings FloorSettings(const std::string& method) {
  settings::EngineSettings s;
  s.method = method;
  s.physics_dt = 0.02;
  s.haptic_dt = 0.001;
  s.duration = 0.1;
  s.pointer.radius = kHalf;  // the 3-DOF methods see the cube as a sphere of this radius
  s.rendering.stiffness = 9000.0;
  s.rendering.rot_stiffness = 9000.0;
  s.rendering.rotation_weight = Vec3::Constant(3.33);
  s.rendering.torque_model = settings::TorqueModel::kThesis;
  s.rendering.friction = 0.0;
  s.rendering.max_iterations = 2000;
  s.safety.ramp = false;
  s.realtime_priority = false;
  if (method == "single-rate") s.physics_dt = s.haptic_dt;  // it steps the world every tick
  return s;
}

class Ticks final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<ir::TickRecord> ticks;
};

std::vector<ir::TickRecord> RunPressedIntoFloor(const std::string& method) {
  const Pose X_WP{Vec3(0.02, -0.03, kHalf - kDepth), Quat::Identity()};
  // contact-volume replaces MuJoCo's contacts by its own penalty (session::LoadWorld).
  const world::LoadOptions options{.penalty_contacts = method == "contact-volume"};
  Engine engine(world::World::LoadString(kFloorScene, options), device::MakeFixedDevice(X_WP), {},
                FloorSettings(method));
  Ticks recorder;
  (void)engine.Run(&recorder);
  return recorder.ticks;
}

void CheckProxyOnTheFloor(const std::vector<ir::TickRecord>& ticks) {
  ASSERT_FALSE(ticks.empty());
  // The PGS error bound of proxy_method_test.cc (FacePressedIntoFloor...): the solver stops
  // within ~m·κ·tol of the exact Δr, κ = 4 / (4h²/R_w), m = 4 points.
  const double kappa = 4.0 / (4.0 * kHalf * kHalf / 3.33);
  const double tol = 4.0 * kappa * FloorSettings("proxy-6dof").rendering.solver_tolerance;
  for (const ir::TickRecord& t : ticks) {
    // The pointer sinks kDepth into the floor; its proxy stays on it (bottom face at z = 0).
    EXPECT_GT((t.X_WQ.p - t.X_WP.p).norm(), kDepth / 2);
    EXPECT_NEAR(t.X_WQ.p.z() - kHalf, 0.0, tol);
    EXPECT_NEAR(t.X_WQ.p.x(), t.X_WP.p.x(), tol);
    EXPECT_NEAR(t.X_WQ.p.y(), t.X_WP.p.y(), tol);
  }
}

// local-dynamics-6dof treats the static floor as proxy-6dof does.
TEST(HapticSideTest, ProxyPoseOfProxy6dofLiesOnTheSurfaceWhenPressedIntoTheFloor) {
  for (const char* method : {"proxy-6dof", "local-dynamics-6dof"}) {
    SCOPED_TRACE(method);
    CheckProxyOnTheFloor(RunPressedIntoFloor(method));
  }
}

TEST(HapticSideTest, ProxyPoseIsThePointerPoseForMethodsWithoutAProxy) {
  for (const auto& [method, summary] : ListMethods()) {
    // proxy-6dof and local-dynamics-6dof have a proxy; virtual-coupling reports its tool pose
    // (and needs a free tool).
    if (method == "proxy-6dof" || method == "local-dynamics-6dof" || method == "virtual-coupling") {
      continue;
    }
    SCOPED_TRACE(method);
    const std::vector<ir::TickRecord> ticks = RunPressedIntoFloor(method);
    ASSERT_FALSE(ticks.empty());
    for (const ir::TickRecord& t : ticks) {
      EXPECT_EQ(t.X_WQ.p, t.X_WP.p);
      EXPECT_EQ(t.X_WQ.q.coeffs(), t.X_WP.q.coeffs());
    }
  }
}

}  // namespace
}  // namespace mrh::engine::testing
