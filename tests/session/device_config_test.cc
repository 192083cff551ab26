// SPDX-License-Identifier: Apache-2.0
// Tests of the `device` block: each type's keys and requirements, poses, keyframes, limits.
#include "session/device_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "session/session_test_util.h"

namespace mrh::session {
namespace {

namespace fs = std::filesystem;
using testing::FixturesDir;
using testing::Parse;
using testing::ThrowsInvalid;
using testing::ThrowsInvalidExactly;
using testing::WithDevice;

// Normalizing a quaternion of O(1) components is exact to a few ulps.
constexpr double kQuatTol = 8 * std::numeric_limits<double>::epsilon();

void ExpectQuatNear(const Quat& actual, const Quat& expected) {
  EXPECT_NEAR(actual.w(), expected.w(), kQuatTol);
  EXPECT_NEAR(actual.x(), expected.x(), kQuatTol);
  EXPECT_NEAR(actual.y(), expected.y(), kQuatTol);
  EXPECT_NEAR(actual.z(), expected.z(), kQuatTol);
}

TEST(DeviceConfigTest, FixedPoseIsReadAndItsQuaternionNormalized) {
  const Session s = LoadSession(FixturesDir() / "fixed.json");
  EXPECT_EQ(s.device.type, "fixed");
  EXPECT_EQ(s.device.pose.p, Vec3(0.1, 0.2, 0.3));
  ExpectQuatNear(s.device.pose.q, Quat::Identity());  // given as [2, 0, 0, 0]
}

TEST(DeviceConfigTest, QuaternionIsReadInWxyzOrder) {
  const double h = std::sqrt(0.5);
  const Session s = Parse(WithDevice(R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 1]})"));
  ExpectQuatNear(s.device.pose.q, Quat(h, 0, 0, h));  // 90° about z
}

TEST(DeviceConfigTest, LimitsOverrideOnlyTheGivenSpecifications) {
  const Session s = Parse(WithDevice(
      R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0], "limits": {"max_force": 100}})"));
  EXPECT_DOUBLE_EQ(s.device.specs.max_force, 100.0);
  EXPECT_DOUBLE_EQ(s.device.specs.max_torque, device::Specifications{}.max_torque);
}

TEST(DeviceConfigTest, AllLimitsAreRead) {
  const Session s = LoadSession(FixturesDir() / "fixed.json");
  EXPECT_DOUBLE_EQ(s.device.specs.max_force, 100.0);
  EXPECT_DOUBLE_EQ(s.device.specs.max_torque, 2.0);
  EXPECT_DOUBLE_EQ(s.device.specs.max_stiffness, 8000.0);
}

TEST(DeviceConfigTest, NonPositiveLimitIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(
            R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0], "limits": {"max_torque": 0}})"));
      },
      ThrowsInvalidExactly("session.json: device.limits.max_torque: 0 N*m; expected a number > 0 "
                           "and <= 1000 N*m"));
}

TEST(DeviceConfigTest, CalibrationIsReadAndItsOrientationNormalized) {
  const Session s = LoadSession(FixturesDir() / "fixed.json");
  EXPECT_EQ(s.device.calibration.X_WD.p, Vec3(1, 2, 3));
  ExpectQuatNear(s.device.calibration.X_WD.q, Quat(0, 0, 0, 1));  // given as [0, 0, 0, 3]
  EXPECT_DOUBLE_EQ(s.device.calibration.scale, 2.0);
}

TEST(DeviceConfigTest, OmittedCalibrationIsTheIdentity) {
  const Session s = Parse(WithDevice(R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0]})"));
  EXPECT_EQ(s.device.calibration.X_WD.p, Vec3::Zero());
  EXPECT_EQ(s.device.calibration.X_WD.q.coeffs(), Quat::Identity().coeffs());
  EXPECT_EQ(s.device.calibration.scale, 1.0);
}

TEST(DeviceConfigTest, NonPositiveCalibrationScaleIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(
            R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0], "calibration": {"scale": 0}})"));
      },
      ThrowsInvalidExactly("session.json: device.calibration.scale: 0; expected a number in "
                           "[0.001, 1000] (world m per device m)"));
}

TEST(DeviceConfigTest, ZeroCalibrationOrientationIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0],
                             "calibration": {"orientation": [0, 0, 0, 0]}})"));
      },
      ThrowsInvalid("session.json: device.calibration.orientation: quaternion (qw, qx, qy, qz) = "
                    "(0, 0, 0, 0) has (almost) zero norm"));
}

TEST(DeviceConfigTest, CalibrationPositionNeedsThreeNumbers) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0],
                             "calibration": {"position": [0, 0]}})"));
      },
      ThrowsInvalidExactly("session.json: device.calibration.position: found an array of 2 "
                           "elements; expected an array of 3 numbers [x, y, z] (m)"));
}

TEST(DeviceConfigTest, DeviceMustBeAnObject) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"("fixed")"));
      },
      ThrowsInvalidExactly("session.json: device: found a string (\"fixed\"); expected an "
                           "object with keys: type, model, limits, calibration, pose, keyframes, "
                           "trajectory, hand, replay, library, id, name, bind, timeout, fade"));
}

TEST(DeviceConfigTest, MissingTypeIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"pose": [0, 0, 0, 1, 0, 0, 0]})"));
      },
      ThrowsInvalidExactly("session.json: device.type: missing; expected one of "
                           "\"fixed\", \"scripted\", \"hand\", \"replay\", \"external\", "
                           "\"forcedimension\", \"openhaptics\", \"udp\""));
}

TEST(DeviceConfigTest, UnknownTypeIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "mouse"})"));
      },
      ThrowsInvalidExactly("session.json: device.type: unknown device type \"mouse\"; "
                           "expected one of \"fixed\", \"scripted\", \"hand\", \"replay\", "
                           "\"external\", "
                           "\"forcedimension\", \"openhaptics\", \"udp\""));
}

TEST(DeviceConfigTest, KeyOfAnotherTypeIsAnErrorNamingTheType) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0, 0],
                             "keyframes": [[0, 0, 0, 0, 1, 0, 0, 0]]})"));
      },
      ThrowsInvalidExactly("session.json: device.keyframes: not used by device type \"fixed\"; "
                           "expected only the keys of a fixed device: type, model, limits, "
                           "calibration, pose"));
}

TEST(DeviceConfigTest, HandParametersOnAScriptedDeviceAreAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "scripted", "keyframes": [[0, 0, 0, 0, 1, 0, 0, 0]],
                             "hand": {"mass": 1}})"));
      },
      ThrowsInvalid("session.json: device.hand: not used by device type \"scripted\"; expected "
                    "only the keys of a scripted device: type, model, limits, calibration, "
                    "keyframes, trajectory"));
}

TEST(DeviceConfigTest, FixedDeviceWithoutPoseIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "fixed"})"));
      },
      ThrowsInvalidExactly("session.json: device.pose: missing; expected [x, y, z, qw, "
                           "qx, qy, qz] (m, quaternion) for a fixed device"));
}

TEST(DeviceConfigTest, PoseOfWrongLengthIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "fixed", "pose": [0, 0, 0, 1, 0, 0]})"));
      },
      ThrowsInvalidExactly("session.json: device.pose: found an array of 6 elements; "
                           "expected an array of 7 numbers [x, y, z, qw, qx, qy, qz] (m, "
                           "quaternion)"));
}

TEST(DeviceConfigTest, ZeroPoseQuaternionIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "fixed", "pose": [0, 0, 0, 0, 0, 0, 0]})"));
      },
      ThrowsInvalidExactly("session.json: device.pose: quaternion (qw, qx, qy, qz) = (0, "
                           "0, 0, 0) has (almost) zero norm; expected a rotation, e.g. "
                           "1, 0, 0, 0 for none"));
}

TEST(DeviceConfigTest, ScriptedKeyframesAreReadWithNormalizedQuaternions) {
  const Session s = LoadSession(FixturesDir() / "scripted.json");
  ASSERT_EQ(s.device.keyframes.size(), 2u);
  EXPECT_DOUBLE_EQ(s.device.keyframes[1].t, 1.5);
  EXPECT_EQ(s.device.keyframes[1].X_DT.p, Vec3(0.1, 0, 0));
  ExpectQuatNear(s.device.keyframes[1].X_DT.q, Quat(0, 1, 0, 0));
  EXPECT_TRUE(s.device.trajectory.empty());
}

TEST(DeviceConfigTest, TrajectoryPathIsResolvedAgainstTheSessionFolder) {
  const Session s = LoadSession(FixturesDir() / "hand.json");
  EXPECT_EQ(s.device.trajectory, (FixturesDir() / "approach.csv").lexically_normal());
  EXPECT_TRUE(s.device.keyframes.empty());
}

TEST(DeviceConfigTest, HandParametersAreRead) {
  const device::HandSettings hand = LoadSession(FixturesDir() / "hand.json").device.hand;
  EXPECT_DOUBLE_EQ(hand.mass, 0.8);
  EXPECT_DOUBLE_EQ(hand.stiffness, 400.0);
  EXPECT_DOUBLE_EQ(hand.damping, 30.0);
  EXPECT_DOUBLE_EQ(hand.inertia, 0.001);
  EXPECT_DOUBLE_EQ(hand.rot_stiffness, 3.0);
  EXPECT_DOUBLE_EQ(hand.rot_damping, 0.1);
}

TEST(DeviceConfigTest, InvalidHandParameterIsAnErrorNamingTheKey) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "hand", "keyframes": [[0, 0, 0, 0, 1, 0, 0, 0]],
                             "hand": {"mass": 0}})"));
      },
      ThrowsInvalid("session.json: device.hand.mass = 0 kg"));
}

TEST(DeviceConfigTest, BothKeyframesAndTrajectoryIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "scripted", "trajectory": "approach.csv",
                             "keyframes": [[0, 0, 0, 0, 1, 0, 0, 0]]})"));
      },
      ThrowsInvalidExactly("session.json: device: both \"keyframes\" and \"trajectory\" are set; "
                           "expected exactly one of \"keyframes\" and \"trajectory\" for a "
                           "scripted device"));
}

TEST(DeviceConfigTest, HandWithoutATargetIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "hand"})"));
      },
      ThrowsInvalidExactly("session.json: device: neither \"keyframes\" nor "
                           "\"trajectory\" is set; expected exactly one of \"keyframes\" "
                           "and \"trajectory\" for a hand device"));
}

TEST(DeviceConfigTest, EmptyKeyframesAreAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "scripted", "keyframes": []})"));
      },
      ThrowsInvalidExactly("session.json: device.keyframes: found an empty array; "
                           "expected at least one keyframe"));
}

TEST(DeviceConfigTest, KeyframesThatAreNotAnArrayAreAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "scripted", "keyframes": {}})"));
      },
      ThrowsInvalidExactly("session.json: device.keyframes: found an object; expected an "
                           "array of keyframes [t, x, y, z, qw, qx, qy, qz] (s, m, "
                           "quaternion)"));
}

TEST(DeviceConfigTest, KeyframeOfWrongLengthIsNamedByIndex) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "scripted",
            "keyframes": [[0, 0, 0, 0, 1, 0, 0, 0], [1, 0, 0, 0, 1, 0, 0]]})"));
      },
      ThrowsInvalidExactly("session.json: device.keyframes[1]: found an array of 7 elements; "
                           "expected an array of 8 numbers [t, x, y, z, qw, qx, qy, qz] (s, m, "
                           "quaternion)"));
}

TEST(DeviceConfigTest, KeyframeTimesMustIncreaseStrictly) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "scripted",
            "keyframes": [[1, 0, 0, 0, 1, 0, 0, 0], [1, 0, 0, 0, 1, 0, 0, 0]]})"));
      },
      ThrowsInvalidExactly("session.json: device.keyframes[1]: t = 1 s is not 1e-06 s or more "
                           "after the previous t = 1 s; expected strictly increasing times"));
}

TEST(DeviceConfigTest, ZeroKeyframeQuaternionIsNamedByIndex) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "scripted", "keyframes": [[0, 0, 0, 0, 0, 0, 0, 0]]})"));
      },
      ThrowsInvalid("session.json: device.keyframes[0]: quaternion (qw, qx, qy, qz) = (0, 0, 0, "
                    "0) has (almost) zero norm"));
}

TEST(DeviceConfigTest, MissingTrajectoryFileIsAnErrorNamingKeyAndPath) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "scripted", "trajectory": "no_such.csv"})"));
      },
      ThrowsInvalid("session.json: device.trajectory: file " +
                    (FixturesDir() / "no_such.csv").lexically_normal().string() +
                    " does not exist; expected a keyframe CSV file as a path relative to the "
                    "session file's folder"));
}

TEST(DeviceConfigTest, ReplayPathIsResolvedAgainstTheSessionFolder) {
  const Session s = LoadSession(FixturesDir() / "replay.json");
  EXPECT_EQ(s.device.type, "replay");
  EXPECT_EQ(s.device.replay, (FixturesDir() / "ticks.csv").lexically_normal());
}

TEST(DeviceConfigTest, ReplayWithoutAFileIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "replay"})"));
      },
      ThrowsInvalidExactly("session.json: device.replay: missing; expected the path of a "
                           "recorded run's ticks.csv"));
}

TEST(DeviceConfigTest, MissingReplayFileIsAnError) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(R"({"type": "replay", "replay": "runs/ticks.csv"})"));
      },
      ThrowsInvalid("session.json: device.replay: file " +
                    (FixturesDir() / "runs" / "ticks.csv").lexically_normal().string() +
                    " does not exist"));
}

TEST(DeviceConfigTest, PoseOnAReplayDeviceIsAnErrorNamingTheType) {
  EXPECT_THAT(
      [] {
        Parse(WithDevice(
            R"({"type": "replay", "replay": "ticks.csv", "pose": [0, 0, 0, 1, 0, 0, 0]})"));
      },
      ThrowsInvalid("session.json: device.pose: not used by device type \"replay\""));
}

}  // namespace
}  // namespace mrh::session
