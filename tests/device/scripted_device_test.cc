// SPDX-License-Identifier: Apache-2.0
// Tests of the scripted device and the keyframe CSV loader.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>
#include <numbers>

#include "device/test_files.h"
#include "mrh/core/error.h"
#include "mrh/device/simulated.h"

namespace mrh::device {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;
using testing::WriteTestFile;

constexpr double kPi = std::numbers::pi;
// Poses are O(1) m / rad; slerp and a rotation-vector log lose a few ulps.
constexpr double kTol = 1e-12;

Quat Rz(double angle) {
  return Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
}

Quat Rx(double angle) {
  return Quat(Eigen::AngleAxisd(angle, Vec3::UnitX()));
}

Keyframe Key(double t, const Vec3& p, const Quat& q = Quat::Identity()) {
  return Keyframe{t, Pose{p, q}};
}

// Rotation vector of the short-arc rotation from a to b, applied on the left (b = R a).
Vec3 RotationFromTo(const Quat& a, const Quat& b) {
  const Eigen::AngleAxisd aa(b * a.conjugate());  // Eigen picks the angle in [0, pi]
  return aa.angle() * aa.axis();
}

TEST(ScriptedDeviceTest, InterpolatesPositionLinearlyAndOrientationBySlerp) {
  const auto device =
      MakeScriptedDevice({Key(1.0, Vec3(0, 0, 0), Rz(0.0)), Key(3.0, Vec3(2, -4, 6), Rz(kPi / 2))});
  const DeviceState s = device->Read(1.5);  // a quarter of the way
  EXPECT_TRUE(s.X_DT.p.isApprox(Vec3(0.5, -1.0, 1.5), kTol)) << s.X_DT.p.transpose();
  EXPECT_NEAR(s.X_DT.q.angularDistance(Rz(kPi / 8)), 0.0, kTol);
  EXPECT_EQ(s.t, 1.5);
}

TEST(ScriptedDeviceTest, VelocityIsTheSegmentSlope) {
  const auto device =
      MakeScriptedDevice({Key(0.0, Vec3(0, 0, 0), Rz(0.0)), Key(2.0, Vec3(2, -4, 6), Rz(kPi / 2)),
                          Key(3.0, Vec3(2, -4, 6), Rz(kPi / 2))});
  const DeviceState first = device->Read(0.7);
  EXPECT_TRUE(first.V_DT.v.isApprox(Vec3(1, -2, 3), kTol)) << first.V_DT.v.transpose();
  EXPECT_TRUE(first.V_DT.w.isApprox(Vec3(0, 0, kPi / 4), kTol)) << first.V_DT.w.transpose();
  const DeviceState second = device->Read(2.5);
  EXPECT_LT(second.V_DT.v.norm(), kTol);
  EXPECT_LT(second.V_DT.w.norm(), kTol);
}

TEST(ScriptedDeviceTest, AngularVelocityIsExpressedInTheDeviceFrame) {
  // Start tilted about x, then turn about the device's z axis: w must be along D's z, not the
  // tool's (which would be -y after the tilt).
  const Quat q0 = Rx(kPi / 2);
  const Quat q1 = Rz(0.6) * q0;
  const auto device = MakeScriptedDevice({Key(0.0, Vec3::Zero(), q0), Key(2.0, Vec3::Zero(), q1)});
  const DeviceState s = device->Read(1.0);
  EXPECT_TRUE(s.V_DT.w.isApprox(Vec3(0, 0, 0.3), kTol)) << s.V_DT.w.transpose();
  // And it agrees with a finite difference of the interpolated orientation.
  constexpr double kH = 1e-6;  // s; central-difference error O(kH^2) is negligible here
  const Vec3 w_fd =
      RotationFromTo(device->Read(1.0 - kH).X_DT.q, device->Read(1.0 + kH).X_DT.q) / (2 * kH);
  EXPECT_LT((w_fd - s.V_DT.w).norm(), 1e-6);
}

TEST(ScriptedDeviceTest, TakesTheShortArcForNegatedQuaternions) {
  const Quat q1 = Rz(0.4);
  const Quat minus_q1(-q1.w(), -q1.x(), -q1.y(), -q1.z());
  const auto device =
      MakeScriptedDevice({Key(0.0, Vec3::Zero()), Key(1.0, Vec3::Zero(), minus_q1)});
  const DeviceState s = device->Read(0.5);
  EXPECT_TRUE(s.V_DT.w.isApprox(Vec3(0, 0, 0.4), kTol)) << s.V_DT.w.transpose();
  EXPECT_NEAR(s.X_DT.q.angularDistance(Rz(0.2)), 0.0, kTol);
}

TEST(ScriptedDeviceTest, HoldsEndPosesWithZeroVelocity) {
  const auto device =
      MakeScriptedDevice({Key(1.0, Vec3(1, 0, 0), Rz(0.1)), Key(2.0, Vec3(3, 0, 0), Rz(0.5))});
  const DeviceState before = device->Read(0.0);
  EXPECT_TRUE(before.X_DT.p.isApprox(Vec3(1, 0, 0), kTol));
  EXPECT_NEAR(before.X_DT.q.angularDistance(Rz(0.1)), 0.0, kTol);
  EXPECT_EQ(before.V_DT.v, Vec3::Zero());
  const DeviceState after = device->Read(5.0);
  EXPECT_TRUE(after.X_DT.p.isApprox(Vec3(3, 0, 0), kTol));
  EXPECT_NEAR(after.X_DT.q.angularDistance(Rz(0.5)), 0.0, kTol);
  EXPECT_EQ(after.V_DT.v, Vec3::Zero());
  EXPECT_EQ(after.V_DT.w, Vec3::Zero());
}

TEST(ScriptedDeviceTest, PassesThroughEveryKeyframe) {
  const std::vector<Keyframe> keys = {Key(0.0, Vec3(0, 0, 0)), Key(0.5, Vec3(1, 2, 0)),
                                      Key(0.75, Vec3(-1, 0, 3)), Key(2.0, Vec3(0, 0, 1))};
  const auto device = MakeScriptedDevice(keys);
  for (const Keyframe& k : keys) {
    EXPECT_TRUE(device->Read(k.t).X_DT.p.isApprox(k.X_DT.p, kTol)) << "t = " << k.t;
  }
}

TEST(ScriptedDeviceTest, IgnoresTheDisplayedWrench) {
  const auto device = MakeScriptedDevice({Key(0.0, Vec3(0, 0, 0)), Key(1.0, Vec3(1, 0, 0))});
  device->SetWrench(Wrench{Vec3(50, 50, 50), Vec3::Zero()});
  EXPECT_TRUE(device->Read(0.5).X_DT.p.isApprox(Vec3(0.5, 0, 0), kTol));
}

TEST(ScriptedDeviceTest, NormalizesKeyframeQuaternions) {
  const auto device = MakeScriptedDevice({Key(0.0, Vec3::Zero(), Quat(0.0, 0.0, 0.0, 3.0))});
  EXPECT_NEAR(device->Read(0.0).X_DT.q.norm(), 1.0, kTol);
}

TEST(ScriptedDeviceTest, RejectsNoKeyframes) {
  EXPECT_THAT(
      [] {
        (void)MakeScriptedDevice({});
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("expected at least one keyframe")));
}

TEST(ScriptedDeviceTest, RejectsNonIncreasingTimesNamingTheKeyframe) {
  EXPECT_THAT(
      [] {
        (void)MakeScriptedDevice(
            {Key(0.0, Vec3::Zero()), Key(1.0, Vec3::Zero()), Key(1.0, Vec3::Zero())});
      },
      ThrowsMessage<InvalidArgument>(
          HasSubstr("keyframe 2: t = 1 s is not 1e-06 s or more after the previous t = 1 s")));
}

TEST(ScriptedDeviceTest, RejectsNonFiniteValuesNamingTheKeyframe) {
  EXPECT_THAT(
      [] {
        (void)MakeScriptedDevice({Key(0.0, Vec3::Zero()),
                                  Key(1.0, Vec3(0, std::numeric_limits<double>::infinity(), 0))});
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("keyframe 1: position y = inf m")));
}

TEST(ScriptedDeviceTest, RejectsZeroQuaternionNamingTheKeyframe) {
  EXPECT_THAT(
      [] {
        (void)MakeScriptedDevice({Key(0.0, Vec3::Zero(), Quat(0, 0, 0, 0))});
      },
      ThrowsMessage<InvalidArgument>(HasSubstr(
          "keyframe 0: quaternion (qw, qx, qy, qz) = (0, 0, 0, 0) has (almost) zero norm")));
}

TEST(LoadKeyframesCsvTest, ReadsColumnsInAnyOrderIgnoringExtras) {
  const auto path = WriteTestFile("keys.csv",
                                  "qw,qx,qy,qz,note,t,z,y,x\n"
                                  "2,0,0,0,start,0.0,3,2,1\n"
                                  "\n"
                                  "1, 0, 0, 1, turn, 0.5, 6, 5, 4\r\n");
  const std::vector<Keyframe> keys = LoadKeyframesCsv(path);
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0].t, 0.0);
  EXPECT_TRUE(keys[0].X_DT.p.isApprox(Vec3(1, 2, 3), kTol));
  EXPECT_NEAR(keys[0].X_DT.q.angularDistance(Quat::Identity()), 0.0, kTol);
  EXPECT_EQ(keys[1].t, 0.5);
  EXPECT_TRUE(keys[1].X_DT.p.isApprox(Vec3(4, 5, 6), kTol));
  EXPECT_NEAR(keys[1].X_DT.q.angularDistance(Rz(kPi / 2)), 0.0, kTol);
  EXPECT_NEAR(keys[1].X_DT.q.norm(), 1.0, kTol);
}

TEST(LoadKeyframesCsvTest, MissingColumnNamesFileLineAndColumn) {
  const auto path = WriteTestFile("keys.csv", "t,x,y,z,qx,qy,qz\n0,0,0,0,0,0,0\n");
  EXPECT_THAT(
      [&] {
        (void)LoadKeyframesCsv(path);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr(path.string() + ":1: header lacks column 'qw'")));
}

TEST(LoadKeyframesCsvTest, NonNumericValueNamesFileLineAndColumn) {
  const auto path =
      WriteTestFile("keys.csv", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n1,0,abc,0,1,0,0,0\n");
  EXPECT_THAT(
      [&] {
        (void)LoadKeyframesCsv(path);
      },
      ThrowsMessage<InvalidArgument>(
          HasSubstr(path.string() + ":3: column 'y' = 'abc' is not a number")));
}

TEST(LoadKeyframesCsvTest, NonFiniteValueNamesFileLine) {
  const auto path = WriteTestFile("keys.csv", "t,x,y,z,qw,qx,qy,qz\n0,nan,0,0,1,0,0,0\n");
  EXPECT_THAT(
      [&] {
        (void)LoadKeyframesCsv(path);
      },
      ThrowsMessage<InvalidArgument>(
          HasSubstr(path.string() + ":2: column 'x' = nan; expected a finite number")));
}

TEST(LoadKeyframesCsvTest, ShortRowNamesFileLine) {
  const auto path = WriteTestFile("keys.csv", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0\n");
  EXPECT_THAT(
      [&] {
        (void)LoadKeyframesCsv(path);
      },
      ThrowsMessage<InvalidArgument>(
          HasSubstr(path.string() + ":2: 7 fields; expected at least 8")));
}

TEST(LoadKeyframesCsvTest, ZeroQuaternionNamesFileLine) {
  const auto path = WriteTestFile("keys.csv", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,0,0,0,0\n");
  EXPECT_THAT(
      [&] {
        (void)LoadKeyframesCsv(path);
      },
      ThrowsMessage<InvalidArgument>(
          HasSubstr(path.string() +
                    ":2: columns x,y,z,qw,qx,qy,qz: quaternion (qw, qx, qy, qz) = (0, 0, 0, 0)")));
}

TEST(LoadKeyframesCsvTest, NonIncreasingTimeNamesFileLine) {
  const auto path = WriteTestFile(
      "keys.csv", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n1,0,0,0,1,0,0,0\n0.5,0,0,0,1,0,0,0\n");
  EXPECT_THAT(
      [&] {
        (void)LoadKeyframesCsv(path);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr(
          path.string() + ":4: column 't': t = 0.5 s is not 1e-06 s or more after the previous")));
}

TEST(LoadKeyframesCsvTest, HeaderOnlyFileNamesFile) {
  const auto path = WriteTestFile("keys.csv", "t,x,y,z,qw,qx,qy,qz\n");
  EXPECT_THAT(
      [&] {
        (void)LoadKeyframesCsv(path);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr(path.string() + ":1: no data rows")));
}

TEST(LoadKeyframesCsvTest, EmptyFileAsksForTheHeader) {
  const auto path = WriteTestFile("keys.csv", "");
  EXPECT_THAT(
      [&] {
        (void)LoadKeyframesCsv(path);
      },
      ThrowsMessage<InvalidArgument>(
          HasSubstr(path.string() + ":1: no header; expected a keyframe CSV header with columns "
                                    "t,x,y,z,qw,qx,qy,qz")));
}

TEST(LoadKeyframesCsvTest, MissingFileNamesThePath) {
  const std::filesystem::path path = "/nonexistent/mrh/keys.csv";
  EXPECT_THAT(
      [&] {
        (void)LoadKeyframesCsv(path);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("/nonexistent/mrh/keys.csv: cannot open the file")));
}

TEST(LoadKeyframesCsvTest, LoadedKeyframesDriveAScriptedDevice) {
  const auto path =
      WriteTestFile("keys.csv", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n2,0.2,0,0,1,0,0,0\n");
  const auto device = MakeScriptedDevice(LoadKeyframesCsv(path));
  EXPECT_TRUE(device->Read(1.0).X_DT.p.isApprox(Vec3(0.1, 0, 0), kTol));
}

}  // namespace
}  // namespace mrh::device
