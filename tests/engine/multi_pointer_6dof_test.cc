// SPDX-License-Identifier: Apache-2.0
// The 6-DOF methods with several pointers: a box squeezed between two box fingertips takes both
// proxies' reactions; under local-dynamics-6dof it is one body of one island that takes them in
// the same tick, under proxy-6dof the physics step runs both proxies against it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "engine/engine_impl.h"
#include "haptic_alloc_loop.h"
#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/world/world.h"

namespace mrh::engine::testing {
namespace {

constexpr double kDt = 0.001;  // s, haptic
constexpr double kK = 1000.0;  // N/m, rendering.stiffness
constexpr double kMass = 0.5;  // kg

// A free 0.5 kg box in zero gravity between two cube fingertips (half side 0.01 m, colliding
// with nothing in MuJoCo, as IR-based pointers do) whose faces are 3 mm and 1 mm into the box's
// faces: the squeeze is uneven, so the box moves along x.
constexpr const char* kSqueezeXml = R"(<mujoco><option gravity="0 0 0"/><worldbody>
  <body name="box" pos="0 0 0"><freejoint/>
    <geom type="box" size="0.05 0.05 0.05" mass="0.5"/></body>
  <body name="f0" mocap="true" pos="-0.057 0 0">
    <geom type="box" size="0.01 0.01 0.01" contype="0" conaffinity="0"/></body>
  <body name="f1" mocap="true" pos="0.059 0 0">
    <geom type="box" size="0.01 0.01 0.01" contype="0" conaffinity="0"/></body>
</worldbody></mujoco>)";

class TickLog final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord& step, const world::World& w) override {
    steps.emplace_back(step.t, w.body_state(w.FindBody("box")).p_WCm.x());
  }

  std::vector<ir::TickRecord> ticks;
  std::vector<std::pair<double, double>> steps;  // (t, the world's box x)
};

settings::EngineSettings SqueezeSettings(double duration,
                                         const char* method = "local-dynamics-6dof") {
  settings::EngineSettings s;
  s.method = method;
  s.haptic_dt = kDt;
  s.physics_dt = 0.02;
  s.duration = duration;
  s.rendering.stiffness = kK;
  s.rendering.damping = 0.0;
  s.rendering.rot_stiffness = 20.0;
  s.rendering.friction = 0.0;
  s.safety.ramp = false;
  s.realtime_priority = false;
  s.pointer.body = "f0";
  s.pointers = {settings::PointerLaneSettings{settings::PointerSettings{"f0", 0.0}, s.rendering},
                settings::PointerLaneSettings{settings::PointerSettings{"f1", 0.0}, s.rendering}};
  return s;
}

std::vector<std::unique_ptr<device::Device>> Fingers() {
  std::vector<std::unique_ptr<device::Device>> devices;
  devices.push_back(device::MakeFixedDevice(Pose{Vec3(-0.057, 0, 0), Quat::Identity()}));
  devices.push_back(device::MakeFixedDevice(Pose{Vec3(0.059, 0, 0), Quat::Identity()}));
  return devices;
}

world::LoadOptions TwoPointers() {
  return world::LoadOptions{.pointer_body = "f0", .more_pointer_bodies = {"f1"}};
}

struct Squeeze {
  std::vector<ir::TickRecord> ticks;
  Vec3 momentum = Vec3::Zero();  // the world's box at the end (kg·m/s)
  RunStats stats;
};

Squeeze RunSqueeze(double duration) {
  Engine engine(world::World::LoadString(kSqueezeXml, TwoPointers()), Fingers(),
                std::vector<device::Calibration>(2), SqueezeSettings(duration));
  TickLog log;
  Squeeze out;
  out.stats = engine.Run(&log);
  out.ticks = std::move(log.ticks);
  const world::World& w = engine.world();
  const int box = w.FindBody("box");
  out.momentum = w.body(box).mass * w.body_state(box).V_WCm.v;
  return out;
}

// Both proxies' reactions act on the island in the same tick: the box's x follows the
// two-spring law integrated here at 1 kHz with semi-implicit Euler, forces from the box's
// position at the tick's start: f0 = k (3 mm − x) along +x, f1 = k (1 mm + x) along −x,
// v += (f0 − f1)/m dt, x += v dt; each finger feels minus its own force. A reaction applied a
// tick late, or one pointer's planes not riding on the island, puts a finger off this law by
// about k·v·dt or more.
TEST(MultiPointer6dofTest, BothProxiesActOnTheIslandInTheSameTick) {
  const Squeeze r = RunSqueeze(0.12);
  ASSERT_EQ(r.ticks.size(), 240u);
  double x = 0.0, v = 0.0, worst = 0.0;
  for (std::size_t t = 0; t < 120; ++t) {
    const double f0 = kK * (0.003 - x), f1 = kK * (0.001 + x);
    ASSERT_EQ(r.ticks[2 * t].pointer, 0);
    ASSERT_EQ(r.ticks[2 * t + 1].pointer, 1);
    worst = std::max(worst, std::abs(r.ticks[2 * t].rendered_W.f.x() + f0));
    worst = std::max(worst, std::abs(r.ticks[2 * t + 1].rendered_W.f.x() - f1));
    v += (f0 - f1) / kMass * kDt;
    x += v * kDt;
  }
  EXPECT_GT(std::abs(x), 1e-4);  // the box did move (m)
  EXPECT_LT(worst, 1e-6);        // N
}

// The world's box ends with exactly the momentum both fingers' reactions gave it over the
// periods the physics stepped (all but the last, whose report is never stepped).
TEST(MultiPointer6dofTest, SqueezedBoxTakesBothReactionsOnce) {
  const Squeeze r = RunSqueeze(0.12);
  ASSERT_EQ(r.ticks.size(), 240u);
  const auto stepped_ticks = static_cast<std::int64_t>(120 - 0.02 / kDt);
  Vec3 impulse = Vec3::Zero();
  for (const ir::TickRecord& tick : r.ticks) {
    if (tick.tick < stepped_ticks) impulse += tick.rendered_W.f * kDt;
  }
  EXPECT_GT(r.momentum.norm(), 1e-3);
  EXPECT_NEAR((r.momentum + impulse).norm(), 0.0, 1e-9);
  ASSERT_EQ(r.stats.pointers.size(), 2u);
}

// proxy-6dof at 20 ms with the "local" reaction: each physics step runs both pointers' proxies
// at 1 kHz against the box, so the world's box follows the same two-spring law (integrated here
// at 1 kHz as above) at the end of every step, to rounding. With one pointer's reaction missing the
// box would head for x = 3 mm instead of oscillating about 1 mm; applied twice, for 0.
TEST(MultiPointer6dofTest, ProxyStepsMoveTheBoxUnderBothProxies) {
  Engine engine(world::World::LoadString(kSqueezeXml, TwoPointers()), Fingers(),
                std::vector<device::Calibration>(2), SqueezeSettings(0.2, "proxy-6dof"));
  TickLog log;
  const RunStats stats = engine.Run(&log);
  ASSERT_GE(log.steps.size(), 8u);
  // The run's reaction totals are what the world's box received, counted once.
  const world::World& w = engine.world();
  const int box = w.FindBody("box");
  ASSERT_EQ(stats.impulses.size(), 1u);
  const Vec3 momentum = w.body(box).mass * w.body_state(box).V_WCm.v;
  EXPECT_GT(momentum.norm(), 1e-4);
  EXPECT_LT((stats.impulses[0].linear - momentum).norm(), 1e-9);
  double x = 0.0, v = 0.0, t = 0.0, worst = 0.0, peak = 0.0;
  for (const auto& [t_step, x_world] : log.steps) {
    while (t < t_step - 0.5 * kDt) {
      v += (kK * (0.003 - x) - kK * (0.001 + x)) / kMass * kDt;
      x += v * kDt;
      t += kDt;
    }
    worst = std::max(worst, std::abs(x_world - x));
    peak = std::max(peak, x);
  }
  EXPECT_GT(peak, 1.5e-3);  // m: the law's swing reaches 2 mm
  EXPECT_LT(worst, 1e-9);   // m
  // Each finger felt its own side: f0 pushes +x, so it feels −x; f1 the opposite.
  ASSERT_EQ(log.ticks.size(), 400u);
  EXPECT_LT(log.ticks[100].rendered_W.f.x(), 0.0);
  EXPECT_GT(log.ticks[101].rendered_W.f.x(), 0.0);
}

TEST(MultiPointer6dofTest, HapticTicksOfTheSharedIslandDoNotAllocate) {
  internal::EngineState state(world::World::LoadString(kSqueezeXml, TwoPointers()), Fingers(),
                              std::vector<device::Calibration>(2), SqueezeSettings(1.0));
  EXPECT_EQ(HapticAllocations(state, 5), 0);
}

}  // namespace
}  // namespace mrh::engine::testing
