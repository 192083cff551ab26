// SPDX-License-Identifier: Apache-2.0
// local-dynamics with several pointers: a box squeezed between two fingertips is one
// body of one island that takes both fingers' reactions in the same tick.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/engine_impl.h"
#include "haptic_alloc_loop.h"
#include "mrh/core/error.h"
#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/world/world.h"

namespace mrh::engine::testing {
namespace {

constexpr double kDt = 0.001;  // s, haptic

// A free 0.5 kg box in zero gravity between two sphere fingertips (r = 0.01 m) at its mid-height,
// 3 mm and 1 mm into its faces: the squeeze is uneven, so the box moves.
constexpr const char* kSqueezeXml = R"(<mujoco><option gravity="0 0 0"/><worldbody>
  <body name="box" pos="0 0 0"><freejoint/>
    <geom type="box" size="0.05 0.05 0.05" mass="0.5"/></body>
  <body name="f0" mocap="true" pos="-0.057 0 0"><geom type="sphere" size="0.01"/></body>
  <body name="f1" mocap="true" pos="0.059 0 0"><geom type="sphere" size="0.01"/></body>
</worldbody></mujoco>)";

class TickLog final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<ir::TickRecord> ticks;
};

struct Squeeze {
  std::vector<ir::TickRecord> ticks;
  Vec3 momentum = Vec3::Zero();  // the world's box at the end (kg·m/s)
  RunStats stats;
};

Squeeze RunSqueeze(const std::string& method, double physics_dt, double duration) {
  settings::EngineSettings s;
  s.method = method;
  s.haptic_dt = kDt;
  s.physics_dt = physics_dt;
  s.duration = duration;
  s.rendering.stiffness = 1000.0;
  s.safety.ramp = false;
  s.realtime_priority = false;
  s.pointer.body = "f0";
  s.pointers = {settings::PointerLaneSettings{settings::PointerSettings{"f0", 0.0}, s.rendering},
                settings::PointerLaneSettings{settings::PointerSettings{"f1", 0.0}, s.rendering}};
  std::vector<std::unique_ptr<device::Device>> devices;
  devices.push_back(device::MakeFixedDevice(Pose{Vec3(-0.057, 0, 0), Quat::Identity()}));
  devices.push_back(device::MakeFixedDevice(Pose{Vec3(0.059, 0, 0), Quat::Identity()}));
  Engine engine(
      world::World::LoadString(
          kSqueezeXml, world::LoadOptions{.pointer_body = "f0", .more_pointer_bodies = {"f1"}}),
      std::move(devices), std::vector<device::Calibration>(2), s);
  TickLog log;
  Squeeze out;
  out.stats = engine.Run(&log);
  out.ticks = std::move(log.ticks);
  const world::World& w = engine.world();
  const int box = w.FindBody("box");
  out.momentum = w.body(box).mass * w.body_state(box).V_WCm.v;
  return out;
}

// At 20 ms the world's box ends with exactly the momentum both fingers' reactions gave it over
// the periods the physics stepped (all but the last, whose report is never stepped): the
// island took both forces, once each, tick by tick.
TEST(MultiPointerLocalTest, SqueezedBoxTakesBothReactionsOnce) {
  constexpr double kPhysicsDt = 0.02;
  const Squeeze r = RunSqueeze("local-dynamics", kPhysicsDt, 0.12);
  ASSERT_EQ(r.ticks.size(), 2u * 120u);
  const auto stepped_ticks = static_cast<std::int64_t>(120 - kPhysicsDt / kDt);
  Vec3 impulse = Vec3::Zero();
  for (const ir::TickRecord& tick : r.ticks) {
    if (tick.tick < stepped_ticks) impulse += tick.rendered_W.f * kDt;
  }
  EXPECT_GT(r.momentum.norm(), 1e-3);
  EXPECT_NEAR((r.momentum + impulse).norm(), 0.0, 1e-9);
  ASSERT_EQ(r.stats.pointers.size(), 2u);
}

// Both forces act in the same tick: the box's x follows the two-spring law integrated here at
// 1 kHz with semi-implicit Euler, forces from the box's position at the tick's start:
//   f0 = k (3 mm − x) along +x, f1 = k (1 mm + x) along −x, v += (f0 − f1)/m dt, x += v dt;
// each finger feels minus its own force. A reaction applied a tick late would put the fingers
// off this law by ~k·v·dt (about 0.1 N here).
TEST(MultiPointerLocalTest, BothFingersActOnTheIslandInTheSameTick) {
  constexpr double k = 1000.0, m = 0.5;
  const Squeeze r = RunSqueeze("local-dynamics", 0.02, 0.12);
  ASSERT_EQ(r.ticks.size(), 240u);
  double x = 0.0, v = 0.0, worst = 0.0;
  for (std::size_t t = 0; t < 120; ++t) {
    const double f0 = k * (0.003 - x), f1 = k * (0.001 + x);
    worst = std::max(worst, std::abs(r.ticks[2 * t].rendered_W.f.x() + f0));
    worst = std::max(worst, std::abs(r.ticks[2 * t + 1].rendered_W.f.x() - f1));
    v += (f0 - f1) / m * kDt;
    x += v * kDt;
  }
  EXPECT_LT(worst, 1e-6);  // N
}

TEST(MultiPointerLocalTest, HapticTicksOfTheSharedIslandDoNotAllocate) {
  settings::EngineSettings s;
  s.method = "local-dynamics";
  s.physics_dt = 0.02;
  s.duration = 1.0;
  s.safety.ramp = false;
  s.realtime_priority = false;
  s.pointer.body = "f0";
  s.pointers = {settings::PointerLaneSettings{settings::PointerSettings{"f0", 0.0}, s.rendering},
                settings::PointerLaneSettings{settings::PointerSettings{"f1", 0.0}, s.rendering}};
  std::vector<std::unique_ptr<device::Device>> devices;
  devices.push_back(device::MakeFixedDevice(Pose{Vec3(-0.057, 0, 0), Quat::Identity()}));
  devices.push_back(device::MakeFixedDevice(Pose{Vec3(0.059, 0, 0), Quat::Identity()}));
  world::LoadOptions options{.pointer_body = "f0", .more_pointer_bodies = {"f1"}};
  internal::EngineState state(world::World::LoadString(kSqueezeXml, options), std::move(devices),
                              std::vector<device::Calibration>(2), s);
  EXPECT_EQ(HapticAllocations(state, 5), 0);
}

TEST(MultiPointerLocalTest, ThePerturbationModelRefusesSeveralPointers) {
  const auto build = [] {
    settings::EngineSettings s;
    s.method = "local-dynamics";
    s.rendering.local_model = settings::LocalModel::kPerturbation;
    s.pointer.body = "f0";
    s.pointers = {settings::PointerLaneSettings{settings::PointerSettings{"f0", 0.0}, s.rendering},
                  settings::PointerLaneSettings{settings::PointerSettings{"f1", 0.0}, s.rendering}};
    std::vector<std::unique_ptr<device::Device>> devices;
    devices.push_back(device::MakeFixedDevice(Pose{}));
    devices.push_back(device::MakeFixedDevice(Pose{}));
    world::LoadOptions options{.pointer_body = "f0", .more_pointer_bodies = {"f1"}};
    Engine(world::World::LoadString(kSqueezeXml, options), std::move(devices),
           std::vector<device::Calibration>(2), s);
  };
  EXPECT_THAT(build, ::testing::ThrowsMessage<InvalidArgument>(
                         ::testing::HasSubstr("method = \"local-dynamics\" renders one")));
}

}  // namespace
}  // namespace mrh::engine::testing
