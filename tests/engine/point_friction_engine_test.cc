// SPDX-License-Identifier: Apache-2.0
// 3-DOF friction of single-rate, impulse and local-dynamics: a fingertip pressed into
// the floor and dragged along it feels Coulomb's μ f_n once it slides, and nothing tangential with
// μ = 0.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/world/world.h"

namespace mrh::engine::testing {
namespace {

constexpr double kStiffness = 800.0;  // N/m
constexpr double kDepth = 0.004;      // m into the floor (fingertip radius 0.01 m)
constexpr double kMu = 0.5;

class TickLog final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<ir::TickRecord> ticks;
};

// The thumb of scenes/two_finger_grasp.xml, away from the box, 4 mm into the floor, dragged
// 5 cm along +x in 0.5 s.
std::vector<ir::TickRecord> Drag(const std::string& method, double friction) {
  settings::EngineSettings s;
  s.method = method;
  s.haptic_dt = 0.001;
  s.physics_dt = method == "single-rate" ? 0.001 : 0.02;
  s.duration = 0.5;
  s.pointer.body = "thumb";
  s.rendering.stiffness = kStiffness;
  s.rendering.friction = friction;
  s.safety.ramp = false;
  s.realtime_priority = false;
  const double z = 0.01 - kDepth;
  auto device = device::MakeScriptedDevice(
      {device::Keyframe{0.0, Pose{Vec3(0.3, 0.0, z), Quat::Identity()}},
       device::Keyframe{0.5, Pose{Vec3(0.35, 0.0, z), Quat::Identity()}}});
  Engine engine(world::World::LoadFile(
                    MRH_SOURCE_DIR "/scenes/two_finger_grasp.xml",
                    world::LoadOptions{.pointer_body = "thumb", .more_pointer_bodies = {"index"}}),
                std::move(device), device::Calibration{}, s);
  TickLog log;
  engine.Run(&log);
  return log.ticks;
}

TEST(PointFrictionEngineTest, SlidingFingertipFeelsCoulombsForce) {
  for (const char* method : {"single-rate", "impulse", "local-dynamics"}) {
    SCOPED_TRACE(method);
    const std::vector<ir::TickRecord> ticks = Drag(method, kMu);
    ASSERT_EQ(ticks.size(), 500u);
    for (const ir::TickRecord& tick : ticks) {
      const Vec3& f = tick.rendered_W.f;
      EXPECT_NEAR(f.z(), kStiffness * kDepth, 1e-9);
      EXPECT_LE(std::abs(f.x()), kMu * f.z() + 1e-9);  // inside the cone, always
    }
    // Sticking takes μ k δ / k = 2 mm of the 5 cm: from 0.1 s on the tip slides, against the
    // motion, at the cone's edge.
    for (std::size_t i = 100; i < ticks.size(); ++i) {
      EXPECT_NEAR(ticks[i].rendered_W.f.x(), -kMu * kStiffness * kDepth, 1e-9) << "tick " << i;
    }
  }
}

TEST(PointFrictionEngineTest, ZeroFrictionRendersNoTangentialForce) {
  for (const ir::TickRecord& tick : Drag("single-rate", 0.0)) {
    EXPECT_EQ(tick.rendered_W.f.x(), 0.0);
    EXPECT_EQ(tick.rendered_W.f.y(), 0.0);
  }
}

}  // namespace
}  // namespace mrh::engine::testing
