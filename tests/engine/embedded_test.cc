// SPDX-License-Identifier: Apache-2.0
// Engine::Start/Tick/Stop: the caller's servo loop as the haptic thread.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine_test_util.h"
#include "mrh/core/error.h"
#include "mrh/device/external.h"

namespace mrh::engine::testing {
namespace {

std::unique_ptr<Engine> ExternalT41Engine(const EngineSettings& settings) {
  world::World w = T41World();
  w.ApplyKeyframe("approach");
  device::Specifications specs;
  specs.max_force = 100.0;
  return std::make_unique<Engine>(std::move(w), std::make_unique<device::ExternalDevice>(specs),
                                  device::Calibration{}, settings);
}

class ForceRecorder final : public Recorder {
 public:
  void OnTick(const TickRecord& t) override { forces.push_back(t.displayed_W.f.x()); }
  void OnStep(const StepRecord&, const world::World&) override {}
  std::vector<double> forces;
};

TEST(EmbeddedTest, LockstepEmbeddedRunEqualsRunWithFixedDevice) {
  const EngineSettings settings = T41Settings("impulse");
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
  EngineSettings settings = T41Settings("single-rate");
  settings.mode = Mode::kRealtime;
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

TEST(EmbeddedTest, StartNeedsAnExternalDevice) {
  auto engine = T41Engine(T41Settings("impulse"));
  EXPECT_THAT([&] { engine->Start(); }, ::testing::ThrowsMessage<InvalidArgument>(
                                            ::testing::HasSubstr("external")));
}

}  // namespace
}  // namespace mrh::engine::testing
