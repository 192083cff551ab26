// SPDX-License-Identifier: Apache-2.0
// Tests of the replay device (recorded ticks.csv interpolated by time).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <numbers>

#include "device/test_files.h"
#include "mrh/core/error.h"
#include "mrh/device/simulated.h"

namespace mrh::device {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;
using testing::WriteTestFile;

// Poses are O(1); interpolation loses a few ulps.
constexpr double kTol = 1e-12;

// A ticks.csv as `mrh run` writes it: more columns than the pose, in its own order.
constexpr const char* kTicks =
    "t,fx,fy,fz,px,py,pz,qw,qx,qy,qz,bits\n"
    "0.000,0,0,0,0.0,0.0,0.0,1,0,0,0,0\n"
    "0.001,1,0,0,0.001,0.002,0.0,1,0,0,0,0\n"
    "0.003,1,0,0,0.001,0.002,0.004,0.7071067811865476,0,0,0.7071067811865476,16\n";

TEST(ReplayDeviceTest, InterpolatesRecordedPosesByTime) {
  const auto device = MakeReplayDevice(WriteTestFile("ticks.csv", kTicks));
  const DeviceState s = device->Read(0.0005);
  EXPECT_TRUE(s.X_DT.p.isApprox(Vec3(0.0005, 0.001, 0.0), kTol)) << s.X_DT.p.transpose();
  const DeviceState turn = device->Read(0.002);
  EXPECT_TRUE(turn.X_DT.p.isApprox(Vec3(0.001, 0.002, 0.002), kTol));
  EXPECT_NEAR(
      turn.X_DT.q.angularDistance(Quat(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()))),
      0.0, kTol);
}

TEST(ReplayDeviceTest, VelocityIsTheRecordedSegmentSlope) {
  const auto device = MakeReplayDevice(WriteTestFile("ticks.csv", kTicks));
  const DeviceState s = device->Read(0.002);
  // Segment 0.001 → 0.003 s: dp = (0, 0, 0.004) m, a quarter turn about z in 2 ms.
  EXPECT_TRUE(s.V_DT.v.isApprox(Vec3(0, 0, 2.0), kTol)) << s.V_DT.v.transpose();
  EXPECT_TRUE(s.V_DT.w.isApprox(Vec3(0, 0, std::numbers::pi / 2 / 0.002), kTol))
      << s.V_DT.w.transpose();
}

TEST(ReplayDeviceTest, HoldsTheLastPoseAfterTheRecordingEnds) {
  const auto device = MakeReplayDevice(WriteTestFile("ticks.csv", kTicks));
  const DeviceState s = device->Read(10.0);
  EXPECT_TRUE(s.X_DT.p.isApprox(Vec3(0.001, 0.002, 0.004), kTol));
  EXPECT_EQ(s.V_DT.v, Vec3::Zero());
}

TEST(ReplayDeviceTest, MissingPoseColumnNamesFileLineAndColumn) {
  const auto path = WriteTestFile("ticks.csv", "t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n");
  EXPECT_THAT(
      [&] {
        (void)MakeReplayDevice(path);
      },
      ThrowsMessage<InvalidArgument>(
          HasSubstr(path.string() + ":1: header lacks column 'px'; expected a ticks.csv header")));
}

TEST(ReplayDeviceTest, MalformedRowNamesFileAndLine) {
  const auto path =
      WriteTestFile("ticks.csv", "t,px,py,pz,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n0.001,0,0,1e,1,0,0,0\n");
  EXPECT_THAT(
      [&] {
        (void)MakeReplayDevice(path);
      },
      ThrowsMessage<InvalidArgument>(
          HasSubstr(path.string() + ":3: column 'pz' = '1e' is not a number")));
}

TEST(ReplayDeviceTest, RepeatedTimeNamesFileAndLine) {
  const auto path =
      WriteTestFile("ticks.csv", "t,px,py,pz,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n0,0,0,0,1,0,0,0\n");
  EXPECT_THAT(
      [&] {
        (void)MakeReplayDevice(path);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr(path.string() + ":3: column 't': t = 0 s")));
}

}  // namespace
}  // namespace mrh::device
