// SPDX-License-Identifier: Apache-2.0
// Bad engine settings and scenes are rejected with messages that say what to change.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "engine_test_util.h"
#include "mrh/core/error.h"

namespace mrh::engine::testing {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

TEST(EngineErrorsTest, UnknownMethodListsKnownOnes) {
  EXPECT_THAT(
      [] {
        T41Engine(T41Settings("teleport"));
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("impulse")));
}

TEST(EngineErrorsTest, PhysicsStepNotMultipleOfHapticTickIsRejected) {
  settings::EngineSettings s = T41Settings("impulse");
  s.physics_dt = 0.0505;
  EXPECT_THAT(
      [&] {
        T41Engine(s);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("physics_dt")));
}

TEST(EngineErrorsTest, ContactTorqueModelRefusesTheThesisOnlyKeys) {
  settings::EngineSettings s = T41Settings("impulse");
  s.rendering.torque_model = settings::TorqueModel::kContact;
  s.rendering.rot_damping = 0.1;
  EXPECT_THAT(
      [&] {
        T41Engine(s);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("rendering.rot_damping = 0.1")));
  s.rendering.rot_damping = 0.0;
  s.rendering.rotation_weight = Vec3::Constant(1.0);
  EXPECT_THAT(
      [&] {
        T41Engine(s);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("rendering.rotation_weight")));
}

TEST(EngineErrorsTest, WatchdogShorterThanPhysicsStepIsRejected) {
  settings::EngineSettings s = T41Settings("impulse");
  s.safety.watchdog_timeout = 0.06;
  EXPECT_THAT(
      [&] {
        T41Engine(s);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("safety.watchdog_timeout")));
}

TEST(EngineErrorsTest, PointerWithoutSphereNeedsRadius) {
  settings::EngineSettings s = T41Settings("impulse");
  s.pointer.radius = 0.0;
  world::World w = world::World::LoadString(R"(
    <mujoco><worldbody>
      <body name="pointer" mocap="true"><geom type="box" size="0.01 0.01 0.01"/></body>
    </worldbody></mujoco>)");
  EXPECT_THAT(
      [&] {
        Engine(std::move(w), device::MakeFixedDevice(Pose{}), device::Calibration{}, s);
      },
      ThrowsMessage<SceneError>(HasSubstr("pointer.radius")));
}

TEST(EngineErrorsTest, RadiusComesFromPointerSphereGeom) {
  settings::EngineSettings s = T41Settings("impulse");
  s.pointer.radius = 0.0;
  auto engine = T41Engine(s);
  EXPECT_DOUBLE_EQ(engine->pointer_radius(), 0.02);
}

}  // namespace
}  // namespace mrh::engine::testing
