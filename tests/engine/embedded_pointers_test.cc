// SPDX-License-Identifier: Apache-2.0
// Engine::Start/Tick/Stop with several pointers: the caller's loop drives the one pointer with
// an external device, the others read their own devices in the same tick.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/device/external.h"
#include "mrh/device/simulated.h"
#include "mrh/engine/engine.h"
#include "mrh/world/world.h"

namespace mrh::engine::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kStiffness = 1000.0;  // N/m
constexpr double kDt = 0.001;          // s
// scenes/two_pointers.xml: f0 2 mm into box_a's +x face, f1 5 mm into box_b's −x face.
const Vec3 kF0OnA(-0.242, 0.0, 0.0), kF1OnB(0.245, 0.0, 0.0);

class TickLog final : public physics::Recorder {
 public:
  void OnTick(const ir::TickRecord& tick) override { ticks.push_back(tick); }

  void OnStep(const physics::StepRecord&, const world::World&) override {}

  std::vector<ir::TickRecord> ticks;
};

// f0 on a fixed device, f1 on `f1_device`.
std::unique_ptr<Engine> Engine2(std::unique_ptr<device::Device> f1_device,
                                std::unique_ptr<device::Device> f0_device = nullptr) {
  settings::EngineSettings s;
  s.method = "single-rate";
  s.physics_dt = kDt;
  s.haptic_dt = kDt;
  s.duration = 1.0;
  s.rendering.stiffness = kStiffness;
  s.safety.ramp = false;
  s.realtime_priority = false;
  s.pointer.body = "f0";
  s.pointers = {settings::PointerLaneSettings{settings::PointerSettings{"f0", 0.0}, s.rendering},
                settings::PointerLaneSettings{settings::PointerSettings{"f1", 0.0}, s.rendering}};
  device::Specifications specs;
  specs.max_force = 100.0;
  std::vector<std::unique_ptr<device::Device>> devices;
  devices.push_back(f0_device ? std::move(f0_device)
                              : device::MakeFixedDevice(Pose{kF0OnA, Quat::Identity()}, specs));
  devices.push_back(std::move(f1_device));
  return std::make_unique<Engine>(
      world::World::LoadFile(
          std::string(MRH_SOURCE_DIR) + "/scenes/two_pointers.xml",
          world::LoadOptions{.pointer_body = "f0", .more_pointer_bodies = {"f1"}}),
      std::move(devices), std::vector<device::Calibration>(2), s);
}

TEST(EmbeddedPointersTest, TheLoopDrivesOnePointerAndTheOthersReadTheirOwnDevices) {
  device::Specifications specs;
  specs.max_force = 100.0;
  device::DeviceState reading;
  reading.X_DT = Pose{kF1OnB, Quat::Identity()};
  auto external = std::make_unique<device::ExternalDevice>(specs);
  // Start builds the first snapshot around every pointer's reading: the caller's comes first.
  external->Feed(reading);
  auto engine = Engine2(std::move(external));
  TickLog log;
  engine->Start(&log);
  const Wrench w = engine->Tick(0.0, reading);
  // The returned wrench is f1's (identity calibration): k times 5 mm, out of box_b's −x face.
  EXPECT_NEAR(w.f.x(), -kStiffness * 0.005, 1e-9);
  (void)engine->Tick(kDt, reading);
  const RunStats stats = engine->Stop();
  EXPECT_EQ(stats.ticks, 2);
  // Every tick rendered both pointers: f0 on its fixed device, 2 mm into box_a.
  ASSERT_EQ(log.ticks.size(), 4u);
  EXPECT_EQ(log.ticks[0].pointer, 0);
  EXPECT_NEAR(log.ticks[0].rendered_W.f.x(), kStiffness * 0.002, 1e-9);
  EXPECT_EQ(log.ticks[1].pointer, 1);
  EXPECT_NEAR(log.ticks[1].rendered_W.f.x(), -kStiffness * 0.005, 1e-9);
}

TEST(EmbeddedPointersTest, TwoExternalDevicesAreRefused) {
  auto engine = Engine2(std::make_unique<device::ExternalDevice>(device::Specifications{}),
                        std::make_unique<device::ExternalDevice>(device::Specifications{}));
  EXPECT_THAT(
      [&] {
        engine->Start();
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("exactly one pointer an external device")));
}

TEST(EmbeddedPointersTest, NoExternalDeviceIsRefused) {
  auto engine = Engine2(device::MakeFixedDevice(Pose{kF1OnB, Quat::Identity()}));
  EXPECT_THAT(
      [&] {
        engine->Start();
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("needs an external device")));
}

}  // namespace
}  // namespace mrh::engine::testing
