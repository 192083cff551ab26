// SPDX-License-Identifier: Apache-2.0
// Haptic materials through the engine: every IR-based method renders a contact with its geom's
// material, a geom without one with rendering.*, and a vibration starts at contact onset.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/world/world.h"

namespace mrh::engine::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kDepth = 1e-3;        // m, how far the pointer is held inside a block
constexpr double kSoft = 400.0;        // N/m
constexpr double kHard = 3000.0;       // N/m
constexpr double kRendering = 1000.0;  // N/m, rendering.stiffness (the plain block)
constexpr double kTop = 0.05;          // m, top face of every block
constexpr double kHalf = 0.01;         // m, pointer sphere radius / box half side

// Three static blocks along x: "soft" at −0.2, "hard" at 0, and one without a material at 0.2.
// The pointer is a sphere (3-DOF methods) or a box (6-DOF: its face gives four points at equal
// depth, so the proxy offset is exactly the depth).
world::World Blocks(bool box_pointer) {
  std::string xml = R"(<mujoco><option gravity="0 0 0"/>
    <asset><material name="soft"/><material name="hard"/><material name="unused_by_session"/>
    </asset><worldbody>
    <geom name="soft" type="box" pos="-0.2 0 0" size="0.05 0.05 0.05" material="soft"/>
    <geom name="hard" type="box" pos="0 0 0" size="0.05 0.05 0.05" material="hard"/>
    <geom name="plain" type="box" pos="0.2 0 0" size="0.05 0.05 0.05"
          material="unused_by_session"/>
    <body name="pointer" mocap="true" pos="0 0 0.5">)";
  xml += box_pointer ? R"(<geom type="box" size="0.01 0.01 0.01" contype="0" conaffinity="0"/>)"
                     : R"(<geom type="sphere" size="0.01" contype="0" conaffinity="0"/>)";
  xml += "</body></worldbody></mujoco>";
  return world::World::LoadString(xml);
}

settings::MaterialSettings Stiffness(double k) {
  settings::MaterialSettings m;
  m.stiffness = k;
  return m;
}

settings::EngineSettings Settings(const std::string& method) {
  settings::EngineSettings s;
  s.method = method;
  s.physics_dt = 0.01;
  s.haptic_dt = 0.001;
  s.duration = 0.05;
  s.pointer.radius = kHalf;
  s.rendering.stiffness = kRendering;
  s.rendering.rot_stiffness = 1.0;
  s.rendering.materials["soft"] = Stiffness(kSoft);
  s.rendering.materials["hard"] = Stiffness(kHard);
  s.safety.ramp = false;
  s.realtime_priority = false;
  return s;
}

class LastTick final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord& /*step*/, const world::World& /*world*/) override {}

  std::vector<ir::TickRecord> ticks;
};

// The force felt with the pointer held kDepth inside the block centred at x.
double RestingForce(const std::string& method, double x) {
  const bool box = method == "proxy-6dof" || method == "local-dynamics-6dof";
  const Pose X_WP{Vec3(x, 0.0, kTop + kHalf - kDepth), Quat::Identity()};
  Engine engine(Blocks(box), device::MakeFixedDevice(X_WP), {}, Settings(method));
  LastTick tap;
  (void)engine.Run(&tap);
  return tap.ticks.back().rendered_W.f.z();
}

class MaterialStiffnessTest : public ::testing::TestWithParam<const char*> {};

TEST_P(MaterialStiffnessTest, EachBlockFeelsItsMaterialsStiffnessTimesDepth) {
  // Static blocks: the force at rest is the spring alone, k·depth (1e-9 N: rounding).
  constexpr double kTol = 1e-9;
  EXPECT_NEAR(RestingForce(GetParam(), -0.2), kSoft * kDepth, kTol);
  EXPECT_NEAR(RestingForce(GetParam(), 0.0), kHard * kDepth, kTol);
  // A geom whose MJCF material the session does not name uses rendering.stiffness.
  EXPECT_NEAR(RestingForce(GetParam(), 0.2), kRendering * kDepth, kTol);
}

INSTANTIATE_TEST_SUITE_P(IrMethods, MaterialStiffnessTest,
                         ::testing::Values("impulse", "single-rate", "local-dynamics", "proxy-6dof",
                                           "local-dynamics-6dof"));

TEST(MaterialsTest, AMaterialNoGeomUsesIsRejectedByName) {
  settings::EngineSettings s = Settings("impulse");
  s.rendering.materials["glas"] = Stiffness(5.0);
  const auto make = [&] {
    Engine engine(Blocks(false), device::MakeFixedDevice(Pose{}), {}, s);
  };
  EXPECT_THAT(make, ThrowsMessage<InvalidArgument>(
                        HasSubstr("materials.glas: no geom of the scene uses the MJCF material")));
}

TEST(MaterialsTest, NegativeStiffnessIsRejectedWithItsKey) {
  settings::EngineSettings s = Settings("impulse");
  s.rendering.materials["soft"].stiffness = -1.0;
  EXPECT_THAT(
      [&] {
        s.Validate();
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("materials.soft.stiffness = -1 N/m")));
}

TEST(MaterialsTest, NanDampingIsRejectedWithItsKey) {
  settings::EngineSettings s = Settings("impulse");
  s.rendering.materials["hard"].damping = std::nan("");
  EXPECT_THAT(
      [&] {
        s.Validate();
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("materials.hard.damping = nan")));
}

TEST(MaterialsTest, VibrationAboveNyquistIsRejected) {
  settings::EngineSettings s = Settings("impulse");
  s.rendering.materials["hard"].vibration = settings::VibrationSettings{10.0, 50.0, 600.0};
  EXPECT_THAT(
      [&] {
        s.Validate();
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("materials.hard.vibration.frequency = 600 Hz")));
}

// A tap at 0.1 m/s onto the hard block with a vibration: the rendered force carries the
// transient a·v·e^(−B t)·sin(2π f t) on top of the spring; the safety layer clamps what the
// device displays.
TEST(MaterialsTest, VibrationAtOnsetIsRenderedAndTheDisplayIsClamped) {
  settings::EngineSettings s = Settings("single-rate");
  s.physics_dt = 0.001;
  s.duration = 0.1;
  constexpr double kA = 500.0, kB = 30.0, kF = 100.0, kV = 0.1;  // N·s/m, 1/s, Hz, m/s
  s.rendering.materials["hard"].vibration = settings::VibrationSettings{kA, kB, kF};
  device::Specifications limits;
  limits.max_force = 10.0;                 // below a·v = 50 N
  const double z0 = kTop + kHalf + 0.002;  // starts 2 mm above; contact at t = 0.02 s
  auto device = device::MakeScriptedDevice(
      {device::Keyframe{0.0, Pose{Vec3(0, 0, z0), Quat::Identity()}},
       device::Keyframe{0.03, Pose{Vec3(0, 0, z0 - 0.03 * kV), Quat::Identity()}}},
      limits);
  Engine engine(Blocks(false), std::move(device), {}, s);
  LastTick tap;
  (void)engine.Run(&tap);
  double peak_rendered = 0.0, peak_displayed = 0.0;
  for (const ir::TickRecord& t : tap.ticks) {
    peak_rendered = std::max(peak_rendered, std::abs(t.rendered_W.f.z()));
    peak_displayed = std::max(peak_displayed, t.displayed_W.f.norm());
  }
  // The first quarter period's peak is a·v·e^(−B/(4f)) ≈ 46 N; the spring adds < 3 N.
  EXPECT_GT(peak_rendered, 0.8 * kA * kV);
  EXPECT_LE(peak_displayed, limits.max_force + 1e-9);
}

}  // namespace
}  // namespace mrh::engine::testing
