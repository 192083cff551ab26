// SPDX-License-Identifier: Apache-2.0
// Engine::Start/Tick/Stop: the caller's servo loop as the haptic thread.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "engine_test_util.h"
#include "mrh/core/error.h"
#include "mrh/device/external.h"

namespace mrh::engine::testing {
namespace {

std::unique_ptr<Engine> ExternalT41Engine(const settings::EngineSettings& settings) {
  world::World w = T41World();
  w.ApplyKeyframe("approach");
  device::Specifications specs;
  specs.max_force = 100.0;
  return std::make_unique<Engine>(std::move(w), std::make_unique<device::ExternalDevice>(specs),
                                  device::Calibration{}, settings);
}

class ForceRecorder final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& t) override { forces.push_back(t.displayed_W.f.x()); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<double> forces;
};

TEST(EmbeddedTest, LockstepEmbeddedRunEqualsRunWithFixedDevice) {
  const settings::EngineSettings settings = T41Settings("impulse");
  ForceRecorder reference;
  (void)T41Engine(settings)->Run(&reference);

  auto engine = ExternalT41Engine(settings);
  ForceRecorder embedded;
  engine->Start(&embedded);
  std::vector<double> returned;
  for (std::size_t i = 0; i < reference.forces.size(); ++i) {
    const Wrench w = engine->Tick(static_cast<double>(i) * settings.haptic_dt, {});
    returned.push_back(w.f.x());
  }
  const RunStats stats = engine->Stop();
  EXPECT_EQ(stats.ticks, static_cast<std::int64_t>(reference.forces.size()));
  EXPECT_EQ(embedded.forces, reference.forces);
  EXPECT_EQ(returned, reference.forces);  // identity calibration: device frame = world frame
}

TEST(EmbeddedTest, RealtimeEmbeddedRunRendersContact) {
  settings::EngineSettings settings = T41Settings("single-rate");
  settings.mode = settings::Mode::kRealtime;
  auto engine = ExternalT41Engine(settings);
  engine->Start();
  double max_force = 0.0;
  for (int i = 0; i < 800; ++i) {  // no sleeping: the test is not about timing
    max_force = std::max(max_force, engine->Tick(i * settings.haptic_dt, {}).f.norm());
  }
  const RunStats stats = engine->Stop();
  EXPECT_EQ(stats.ticks, 800);
  EXPECT_TRUE(std::isfinite(max_force));
}

// A render thread reads the body poses while the caller's loop ticks in real time (the physics
// on the engine's thread). Every read must be one whole step: its time matches its step index
// (a torn read would mix two), steps never go back, and the reader sees the world move.
TEST(EmbeddedTest, RenderThreadReadsWholeBodyPoseSnapshotsWhileTheEngineRuns) {
  settings::EngineSettings settings = T41Settings("impulse");
  settings.mode = settings::Mode::kRealtime;
  auto engine = ExternalT41Engine(settings);
  const auto cube = static_cast<std::size_t>(engine->world().FindBody("cube"));
  std::atomic<bool> stop{false};
  std::int64_t reads = 0, fresh = 0, last_step = -1, torn = 0, backwards = 0;
  double last_x = 0.0;
  std::thread reader([&] {
    BodyPoses poses;
    while (!stop.load(std::memory_order_acquire)) {
      if (engine->ReadBodyPoses(&poses)) ++fresh;
      ++reads;
      if (poses.step >= 0 &&
          std::abs(poses.t - static_cast<double>(poses.step + 1) * settings.physics_dt) > 1e-9) {
        ++torn;
      }
      if (poses.step < last_step) ++backwards;
      last_step = poses.step;
      last_x = poses.X_WB[cube].p.x();
      std::this_thread::yield();
    }
  });
  engine->Start();
  for (int i = 0; i < 1000; ++i) {
    (void)engine->Tick(i * settings.haptic_dt, {});
    std::this_thread::sleep_for(std::chrono::microseconds(200));  // let the physics keep up
  }
  const RunStats stats = engine->Stop();
  stop.store(true, std::memory_order_release);
  reader.join();
  EXPECT_GT(stats.steps, 2);
  EXPECT_GT(reads, fresh);
  EXPECT_GE(fresh, 2);
  EXPECT_EQ(torn, 0);
  EXPECT_EQ(backwards, 0);
  EXPECT_GT(last_step, 0);
  EXPECT_GT(last_x, -0.125);  // the cube slid from its start toward the pointer
}

// Another thread sets the gain to zero mid-run; once that store is done (the thread joined),
// every later tick of the haptic loop displays nothing, though the cube still presses on.
TEST(EmbeddedTest, GainSetFromAnotherThreadReachesTheHapticLoop) {
  settings::EngineSettings settings = T41Settings("impulse");
  settings.mode = settings::Mode::kRealtime;
  auto engine = ExternalT41Engine(settings);
  engine->Start();
  double max_before = 0.0, max_after = 0.0;
  const auto tick = [&](int i) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));  // let the physics keep up
    return engine->Tick(i * settings.haptic_dt, {}).f.norm();
  };
  int i = 0;
  for (; i < 600; ++i) max_before = std::max(max_before, tick(i));
  std::thread ui([&] {
    engine->SetDisplayGain(0.0);
  });
  ui.join();
  for (; i < 900; ++i) max_after = std::max(max_after, tick(i));
  const RunStats stats = engine->Stop();
  EXPECT_GT(max_before, 0.5);  // in contact before the switch
  EXPECT_EQ(max_after, 0.0);
  EXPECT_EQ(stats.ticks, 900);
}

TEST(EmbeddedTest, StartNeedsAnExternalDevice) {
  auto engine = T41Engine(T41Settings("impulse"));
  EXPECT_THAT(
      [&] {
        engine->Start();
      },
      ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr("external")));
}

}  // namespace
}  // namespace mrh::engine::testing
