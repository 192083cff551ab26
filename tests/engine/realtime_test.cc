// SPDX-License-Identifier: Apache-2.0
// The real-time scheduler runs the same data flow on two threads (checked for races under TSan).
// No assertion here depends on wall-clock timing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "engine_test_util.h"
#include "mrh/device/simulated.h"

namespace mrh::engine::testing {
namespace {

class OrderRecorder final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& t) override { ticks.push_back(t.tick); }

  void OnStep(const physics::StepRecord& s, const world::World&) override {
    steps.push_back(s.step);
  }

  std::vector<std::int64_t> ticks;
  std::vector<std::int64_t> steps;
};

TEST(RealtimeTest, RunsBothThreadsAndRecordsInOrder) {
  settings::EngineSettings s = T41Settings("impulse");
  s.mode = settings::Mode::kRealtime;
  s.duration = 0.6;
  auto engine = T41Engine(s);
  OrderRecorder recorder;
  const RunStats stats = engine->Run(&recorder);
  EXPECT_EQ(stats.mode, settings::Mode::kRealtime);
  EXPECT_GT(stats.ticks, 0);
  EXPECT_GT(stats.steps, 0);
  EXPECT_EQ(static_cast<std::int64_t>(recorder.ticks.size()), stats.ticks);
  for (std::size_t i = 0; i < recorder.ticks.size(); ++i) {
    ASSERT_EQ(recorder.ticks[i], static_cast<std::int64_t>(i));
  }
  for (std::size_t i = 0; i < recorder.steps.size(); ++i) {
    ASSERT_EQ(recorder.steps[i], static_cast<std::int64_t>(i));
  }
  EXPECT_EQ(stats.fault_nonfinite_wrench, 0);
  EXPECT_GE(stats.jitter_max_us, stats.jitter_p50_us);
}

class PointerRecorder final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& t) override { ticks.push_back({t.tick, t.pointer}); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<std::pair<std::int64_t, int>> ticks;
};

// Several pointers in real time: the haptic thread ticks both pointers each tick, the
// physics thread steps one world with both pointers' reports; both pointers' box gets pushed.
TEST(RealtimeTest, TwoPointersRunOnOneHapticThread) {
  settings::EngineSettings s;
  s.method = "impulse";
  s.mode = settings::Mode::kRealtime;
  s.physics_dt = 0.02;
  s.duration = 0.4;
  s.safety.ramp = false;
  s.realtime_priority = false;
  s.pointer.body = "f0";
  s.pointers = {settings::PointerLaneSettings{settings::PointerSettings{"f0", 0.0}, s.rendering},
                settings::PointerLaneSettings{settings::PointerSettings{"f1", 0.0}, s.rendering}};
  std::vector<std::unique_ptr<device::Device>> devices;
  // scenes/two_pointers.xml: f0 2 mm into box_a, f1 5 mm into box_b.
  devices.push_back(device::MakeFixedDevice(Pose{Vec3(-0.242, 0, 0), Quat::Identity()}));
  devices.push_back(device::MakeFixedDevice(Pose{Vec3(0.245, 0, 0), Quat::Identity()}));
  Engine engine(world::World::LoadFile(
                    std::string(MRH_SOURCE_DIR) + "/scenes/two_pointers.xml",
                    world::LoadOptions{.pointer_body = "f0", .more_pointer_bodies = {"f1"}}),
                std::move(devices), std::vector<device::Calibration>(2), s);
  PointerRecorder recorder;
  const RunStats stats = engine.Run(&recorder);
  ASSERT_GT(stats.ticks, 0);
  ASSERT_EQ(static_cast<std::int64_t>(recorder.ticks.size()), 2 * stats.ticks);
  for (std::size_t i = 0; i < recorder.ticks.size(); ++i) {
    ASSERT_EQ(recorder.ticks[i].first, static_cast<std::int64_t>(i / 2));
    ASSERT_EQ(recorder.ticks[i].second, static_cast<int>(i % 2));
  }
  EXPECT_EQ(stats.dropped_reports, 0);
  ASSERT_EQ(stats.pointers.size(), 2u);
  EXPECT_GT(stats.pointers[0].max_force, 0.0);
  EXPECT_GT(stats.pointers[1].max_force, 0.0);
  int pushed = 0;
  for (const physics::BodyImpulseTotal& impulse : stats.impulses) {
    if (impulse.name == "box_a" && impulse.linear.x() < 0.0) ++pushed;
    if (impulse.name == "box_b" && impulse.linear.x() > 0.0) ++pushed;
  }
  EXPECT_EQ(pushed, 2);
}

TEST(RealtimeTest, ContactDeliversImpulseToCube) {
  // The impulse method's 50 ms physics steps keep up with wall time even in sanitizer builds on
  // a loaded machine (single-rate's 1 ms steps do not), so contact is reached in every build.
  settings::EngineSettings s = T41Settings("impulse");
  s.mode = settings::Mode::kRealtime;
  s.duration = 1.0;  // contact starts at ~0.29 s
  auto engine = T41Engine(s);
  const RunStats stats = engine->Run(nullptr);
  ASSERT_FALSE(stats.impulses.empty());
  EXPECT_LT(stats.impulses.front().linear.x(), 0.0);
}

TEST(RealtimeTest, RequestStopFromTheCallingThreadEndsTheRun) {
  settings::EngineSettings s = T41Settings("impulse");
  s.mode = settings::Mode::kRealtime;
  s.duration = 60.0;
  auto engine = T41Engine(s);
  // The first progress call comes after ~100 ms of wall time; the haptic thread sees the request
  // at its next tick, so the run ends far short of 60 s whatever the machine's load.
  const RunStats stats = engine->Run(nullptr, [&](double) {
    engine->RequestStop();
  });
  EXPECT_GT(stats.ticks, 0);
  EXPECT_LT(stats.ticks, 30'000);
  EXPECT_LT(stats.wall_time, 30.0);
}

}  // namespace
}  // namespace mrh::engine::testing
