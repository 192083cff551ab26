// SPDX-License-Identifier: Apache-2.0
// Several pointers in one world: independent forces, action = reaction on a shared
// object, refusals, and an allocation-free tick of all pointers.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

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

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kStiffness = 1000.0;  // N/m
constexpr double kDt = 0.001;          // s

// scenes/two_pointers.xml: f0 2 mm into box_a, f1 5 mm into box_b at their scene poses.
const Vec3 kF0OnA(-0.242, 0.0, 0.0), kF1OnB(0.245, 0.0, 0.0);
// The same fingertips on either side of `squeezed`: 3 mm and 1 mm deep.
const Vec3 kF0Squeeze(-0.057, 0.3, 0.0), kF1Squeeze(0.059, 0.3, 0.0);

world::World TwoPointerWorld(std::vector<std::string> more = {"f1"}) {
  return world::World::LoadFile(
      std::string(MRH_SOURCE_DIR) + "/scenes/two_pointers.xml",
      world::LoadOptions{.pointer_body = "f0", .more_pointer_bodies = std::move(more)});
}

settings::EngineSettings TwoPointerSettings(const std::string& method, double duration) {
  settings::EngineSettings s;
  s.method = method;
  s.physics_dt = kDt;
  s.haptic_dt = kDt;
  s.duration = duration;
  s.rendering.stiffness = kStiffness;
  s.safety.ramp = false;
  s.realtime_priority = false;
  s.pointer.body = "f0";
  s.pointers = {settings::PointerLaneSettings{settings::PointerSettings{"f0", 0.0}, s.rendering},
                settings::PointerLaneSettings{settings::PointerSettings{"f1", 0.0}, s.rendering}};
  return s;
}

std::unique_ptr<Engine> TwoPointerEngine(const settings::EngineSettings& s, const Vec3& p0,
                                         const Vec3& p1, world::World world = TwoPointerWorld()) {
  device::Specifications specs;
  specs.max_force = 100.0;
  std::vector<std::unique_ptr<device::Device>> devices;
  devices.push_back(device::MakeFixedDevice(Pose{p0, Quat::Identity()}, specs));
  devices.push_back(device::MakeFixedDevice(Pose{p1, Quat::Identity()}, specs));
  return std::make_unique<Engine>(std::move(world), std::move(devices),
                                  std::vector<device::Calibration>(2), s);
}

class TickLog final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<ir::TickRecord> ticks;
};

TEST(MultiPointerTest, EachTickRecordsEveryPointerInOrder) {
  auto engine = TwoPointerEngine(TwoPointerSettings("single-rate", 0.01), kF0OnA, kF1OnB);
  TickLog log;
  const RunStats stats = engine->Run(&log);
  ASSERT_EQ(stats.ticks, 10);
  ASSERT_EQ(log.ticks.size(), 20u);
  for (std::size_t i = 0; i < log.ticks.size(); ++i) {
    EXPECT_EQ(log.ticks[i].pointer, static_cast<int>(i % 2));
    EXPECT_EQ(log.ticks[i].tick, static_cast<std::int64_t>(i / 2));
  }
  EXPECT_EQ(engine->num_pointers(), 2);
  EXPECT_EQ(engine->pointer_names(), (std::vector<std::string>{"f0", "f1"}));
  ASSERT_EQ(stats.pointers.size(), 2u);
  EXPECT_EQ(stats.pointers[1].body, "f1");
}

// Each fingertip pushes its own box: at the first tick (the initial snapshot) each feels k·depth
// along its box's face normal, 2 mm and 5 mm.
TEST(MultiPointerTest, TwoPointersOnTwoBoxesFeelTheirOwnPenalty) {
  for (const char* method : {"single-rate", "impulse"}) {
    SCOPED_TRACE(method);
    settings::EngineSettings s = TwoPointerSettings(method, 0.05);
    if (std::string(method) == "impulse") s.physics_dt = 0.01;
    auto engine = TwoPointerEngine(s, kF0OnA, kF1OnB);
    TickLog log;
    engine->Run(&log);
    ASSERT_GE(log.ticks.size(), 2u);
    EXPECT_NEAR(log.ticks[0].rendered_W.f.x(), kStiffness * 0.002, 1e-9);
    EXPECT_NEAR(log.ticks[1].rendered_W.f.x(), -kStiffness * 0.005, 1e-9);
    EXPECT_NEAR(log.ticks[0].rendered_W.f.tail<2>().norm(), 0.0, 1e-12);
    EXPECT_NEAR(log.ticks[1].rendered_W.f.tail<2>().norm(), 0.0, 1e-12);
  }
}

// The other pointer does not disturb a pointer: f0's force trace on box_a is the same whether
// f1 pushes box_b or f0 runs alone.
TEST(MultiPointerTest, APointerIsUndisturbedByTheOther) {
  settings::EngineSettings two = TwoPointerSettings("single-rate", 0.3);
  auto engine = TwoPointerEngine(two, kF0OnA, kF1OnB);
  TickLog both;
  engine->Run(&both);

  settings::EngineSettings one = two;
  one.pointers.clear();
  device::Specifications specs;
  specs.max_force = 100.0;
  Engine alone(TwoPointerWorld(), device::MakeFixedDevice(Pose{kF0OnA, Quat::Identity()}, specs),
               device::Calibration{}, one);
  TickLog single;
  alone.Run(&single);
  ASSERT_EQ(both.ticks.size(), 2 * single.ticks.size());
  double max_f1 = 0.0;
  for (std::size_t i = 0; i < single.ticks.size(); ++i) {
    EXPECT_NEAR((both.ticks[2 * i].rendered_W.f - single.ticks[i].rendered_W.f).norm(), 0.0, 1e-12)
        << "tick " << i;
    max_f1 = std::max(max_f1, both.ticks[2 * i + 1].rendered_W.f.norm());
  }
  EXPECT_GT(max_f1, 1.0);  // f1 did push box_b meanwhile
}

// A box squeezed by two fingertips (3 mm and 1 mm deep) in one world step per tick: the box's
// momentum, and RunStats's impulse total for it, are exactly minus the sum of both pointers'
// rendered forces × dt over the ticks whose reaction was stepped (all but the last: its report
// is never stepped). The box oscillates between the fingers (ω = √(2k/m) ≈ 63 rad/s); 0.125 s is
// 1.25 periods, near its fastest.
TEST(MultiPointerTest, SqueezedBoxConservesMomentum) {
  auto engine = TwoPointerEngine(TwoPointerSettings("single-rate", 0.125), kF0Squeeze, kF1Squeeze);
  TickLog log;
  const RunStats stats = engine->Run(&log);
  Vec3 all = Vec3::Zero(), last = Vec3::Zero();
  for (const ir::TickRecord& tick : log.ticks) {
    all += tick.rendered_W.f * kDt;
    if (tick.tick == stats.ticks - 1) last += tick.rendered_W.f * kDt;
  }
  const world::World& w = engine->world();
  const int box = w.FindBody("squeezed");
  const Vec3 momentum = w.body(box).mass * w.body_state(box).V_WCm.v;
  EXPECT_GT(momentum.norm(), 1e-3);  // the squeeze is uneven: the box moved
  EXPECT_NEAR((momentum + (all - last)).norm(), 0.0, 1e-9);
  bool found = false;
  for (const physics::BodyImpulseTotal& impulse : stats.impulses) {
    if (impulse.body != box) continue;
    found = true;
    EXPECT_NEAR((impulse.linear + (all - last)).norm(), 0.0, 1e-9);
  }
  EXPECT_TRUE(found);
}

TEST(MultiPointerTest, MethodsOfOnePointerRefuseSeveral) {
  EXPECT_THAT(
      [] {
        TwoPointerEngine(TwoPointerSettings("penalty-sum", 0.1), kF0OnA, kF1OnB);
      },
      ThrowsMessage<InvalidArgument>(
          AllOf(HasSubstr("pointers lists 2 pointers"), HasSubstr("\"penalty-sum\""))));
}

TEST(MultiPointerTest, ASecondPointerThatStillCollidesIsRejected) {
  EXPECT_THAT(
      [] {
        TwoPointerEngine(TwoPointerSettings("single-rate", 0.1), kF0OnA, kF1OnB,
                         TwoPointerWorld({}));
      },
      ThrowsMessage<SceneError>(HasSubstr("pointers[1].body = 'f1'")));
}

TEST(MultiPointerTest, ASecondPointerMustBeAMocapBody) {
  settings::EngineSettings s = TwoPointerSettings("single-rate", 0.1);
  s.pointers[1].pointer.body = "box_b";
  EXPECT_THAT(
      [&] {
        TwoPointerEngine(s, kF0OnA, kF1OnB);
      },
      ThrowsMessage<SceneError>(HasSubstr("pointers[1].body = 'box_b'")));
}

TEST(MultiPointerTest, DeviceCountMustMatch) {
  std::vector<std::unique_ptr<device::Device>> devices;
  devices.push_back(device::MakeFixedDevice(Pose{}));
  EXPECT_THAT(
      [&] {
        Engine(TwoPointerWorld(), std::move(devices), std::vector<device::Calibration>(1),
               TwoPointerSettings("single-rate", 0.1));
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("2 pointer(s) but 1 device(s)")));
}

TEST(MultiPointerTest, HapticTicksOfAllPointersDoNotAllocate) {
  std::vector<std::unique_ptr<device::Device>> devices;
  devices.push_back(device::MakeFixedDevice(Pose{kF0Squeeze, Quat::Identity()}));
  devices.push_back(device::MakeFixedDevice(Pose{kF1Squeeze, Quat::Identity()}));
  settings::EngineSettings s = TwoPointerSettings("impulse", 1.0);
  s.physics_dt = 0.01;
  internal::EngineState state(TwoPointerWorld(), std::move(devices),
                              std::vector<device::Calibration>(2), s);
  EXPECT_EQ(HapticAllocations(state, 20), 0);
}

}  // namespace
}  // namespace mrh::engine::testing
