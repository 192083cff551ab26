// SPDX-License-Identifier: Apache-2.0
// RT contract of the haptic tick: no allocation, NaN device input → zero output + fault bit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/engine_impl.h"
#include "engine_test_util.h"
#include "haptic_alloc_loop.h"
#include "mrh/device/simulated.h"

namespace mrh::engine::testing {
namespace {

using internal::EngineState;
using internal::PhysicsSide;

EngineState MakeState(const settings::EngineSettings& settings,
                      std::unique_ptr<device::Device> device) {
  world::World w = T41World();
  w.ApplyKeyframe("approach");
  return EngineState(std::move(w), std::move(device), device::Calibration{}, settings);
}

TEST(RtTickTest, HapticTicksNeverAllocateInContact) {
  for (const char* method : {"impulse", "single-rate"}) {
    settings::EngineSettings settings = T41Settings(method);
    EngineState state = MakeState(settings, device::MakeFixedDevice(Pose{}));
    const int periods = static_cast<int>(1.5 / state.settings.physics_dt);
    EXPECT_EQ(HapticAllocations(state, periods), 0) << method;
    EXPECT_GT(state.haptic->counters().max_force, 1.0) << method << ": contact never happened";
  }
}

// A mechanism in the island (scenes/chain6_boxes.xml: a 6-link hinged chain with springs,
// damping, armature, dry friction and limits among 8 free boxes), its tip pushed into the
// boxes: the joint rows allocate nothing either.
TEST(RtTickTest, HapticTicksWithAMechanismInTheIslandNeverAllocate) {
  for (const char* method : {"local-dynamics", "local-dynamics-6dof"}) {
    settings::EngineSettings s;
    s.method = method;
    s.physics_dt = 0.02;
    s.duration = 1.0;
    s.pointer.radius = 0.015;
    s.rendering.stiffness = 1200.0;
    s.rendering.damping = 3.0;
    s.safety.ramp = false;
    s.realtime_priority = false;
    auto device = device::MakeScriptedDevice(
        {device::Keyframe{0.0, Pose{Vec3(0.62, 0.04, 0.02), Quat::Identity()}},
         device::Keyframe{1.0, Pose{Vec3(0.62, -0.01, 0.02), Quat::Identity()}}});
    EngineState state(world::World::LoadFile(MRH_SOURCE_DIR "/scenes/chain6_boxes.xml"),
                      std::move(device), device::Calibration{}, s);
    EXPECT_EQ(HapticAllocations(state, 50), 0) << method;
    EXPECT_GT(state.haptic->counters().max_force, 0.1) << method << ": contact never happened";
  }
}

// A device whose readings turn to NaN after `bad_after` seconds.
class FaultyDevice final : public device::Device {
 public:
  explicit FaultyDevice(double bad_after) : bad_after_(bad_after) {}

  const device::Specifications& specifications() const override { return specs_; }

  device::DeviceState Read(double t) noexcept override {
    device::DeviceState s;
    s.t = t;
    if (t >= bad_after_) s.X_DT.p.x() = std::numeric_limits<double>::quiet_NaN();
    return s;
  }

  void SetWrench(const Wrench& w) noexcept override { last_ = w; }

  Wrench last_;

 private:
  device::Specifications specs_;
  double bad_after_;
};

TEST(RtTickTest, NonFiniteDeviceReadingGivesZeroOutputAndFaultCount) {
  auto device = std::make_unique<FaultyDevice>(0.8);  // in contact by then
  FaultyDevice* raw = device.get();
  EngineState state = MakeState(T41Settings("impulse"), std::move(device));
  (void)HapticAllocations(state, 20);  // 1 s
  EXPECT_GT(state.haptic->counters().nonfinite_device, 0);
  EXPECT_EQ(raw->last_.f, Vec3::Zero());
  EXPECT_TRUE(IsFinite(raw->last_));
}

}  // namespace
}  // namespace mrh::engine::testing
