// SPDX-License-Identifier: Apache-2.0
// Tests of MakeDevice: each device type is built from its session block with the session limits.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "session/session_test_util.h"

namespace mrh::session {
namespace {

namespace fs = std::filesystem;
using testing::FixturesDir;
using testing::Parse;
using testing::ThrowsInvalid;
using testing::WithDevice;

// Poses are O(0.1 m); interpolation of such values is exact to a few ulps.
constexpr double kPositionTol = 1e-15;

void ExpectPositionNear(const Vec3& actual, const Vec3& expected) {
  EXPECT_NEAR((actual - expected).norm(), 0.0, kPositionTol) << actual.transpose();
}

TEST(MakeDeviceTest, FixedDeviceHoldsTheSessionPose) {
  const Session s = LoadSession(FixturesDir() / "fixed.json");
  const auto device = MakeDevice(s);
  EXPECT_EQ(device->Read(0.0).X_DT.p, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(device->Read(5.0).X_DT.p, Vec3(0.1, 0.2, 0.3));
}

TEST(MakeDeviceTest, DeviceGetsTheSessionLimits) {
  const auto device = MakeDevice(LoadSession(FixturesDir() / "fixed.json"));
  EXPECT_DOUBLE_EQ(device->specifications().max_force, 100.0);
  EXPECT_DOUBLE_EQ(device->specifications().max_torque, 2.0);
  EXPECT_DOUBLE_EQ(device->specifications().max_stiffness, 8000.0);
}

TEST(MakeDeviceTest, ScriptedDeviceInterpolatesTheInlineKeyframes) {
  const Session s = Parse(WithDevice(R"({"type": "scripted", "keyframes": [
      [0, 0, 0, 0.1, 1, 0, 0, 0], [2, 0.2, 0, 0.1, 1, 0, 0, 0]]})"));
  const auto device = MakeDevice(s);
  ExpectPositionNear(device->Read(0.5).X_DT.p, Vec3(0.05, 0, 0.1));  // a quarter of the way
}

TEST(MakeDeviceTest, ScriptedDeviceFollowsTheTrajectoryFile) {
  // approach.csv: (0, 0, 0.1) at t = 0 → (0.1, 0, 0) at t = 1.
  const auto device = MakeDevice(LoadSession(FixturesDir() / "nested" / "session.json"));
  ExpectPositionNear(device->Read(0.5).X_DT.p, Vec3(0.05, 0, 0.05));
  ExpectPositionNear(device->Read(3.0).X_DT.p, Vec3(0.1, 0, 0));  // holds the last pose
}

TEST(MakeDeviceTest, HandDeviceStartsOnItsTarget) {
  const auto device = MakeDevice(LoadSession(FixturesDir() / "hand.json"));
  ExpectPositionNear(device->Read(0.0).X_DT.p, Vec3(0, 0, 0.1));
}

TEST(MakeDeviceTest, ReplayDeviceReplaysTheRecordedPoses) {
  const auto device = MakeDevice(LoadSession(FixturesDir() / "replay.json"));
  ExpectPositionNear(device->Read(0.001).X_DT.p, Vec3(0, 0, 0.0999));
}

TEST(MakeDeviceTest, MalformedTrajectoryIsAnErrorNamingTheSessionKey) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path csv = fs::path(::testing::TempDir()) /
                       (std::string("mrh_") + info->name() + std::to_string(::getpid()) + ".csv");
  std::ofstream(csv) << "t,x,y,z,qw,qx,qy,qz\n0,0,0,oops,1,0,0,0\n";
  Session s;
  s.file = "session.json";
  s.device.type = "scripted";
  s.device.trajectory = csv;
  EXPECT_THAT(
      [&] {
        MakeDevice(s);
      },
      ThrowsInvalid("session.json: device.trajectory: "));
}

TEST(MakeDeviceTest, DeviceErrorIsPrefixedWithTheSessionAndType) {
  Session s;
  s.file = "session.json";
  s.device.type = "scripted";  // a hand-built session with no keyframes
  EXPECT_THAT(
      [&] {
        MakeDevice(s);
      },
      ThrowsInvalid("session.json: device (scripted): "));
}

TEST(MakeDeviceTest, UnknownTypeOfAHandBuiltSessionIsAnError) {
  Session s;
  s.file = "session.json";
  s.device.type = "joystick";
  EXPECT_THAT(
      [&] {
        MakeDevice(s);
      },
      ThrowsInvalid("session.json: device.type: unknown device type \"joystick\""));
}

}  // namespace
}  // namespace mrh::session
