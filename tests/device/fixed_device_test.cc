// SPDX-License-Identifier: Apache-2.0
// Tests of the fixed device.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "mrh/core/error.h"
#include "mrh/device/simulated.h"

namespace mrh::device {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kTol = 1e-15;  // the pose is copied, only normalization may touch it

Pose SomePose() {
  Pose X;
  X.p = Vec3(0.1, -0.2, 0.3);
  X.q = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitX()));
  return X;
}

TEST(FixedDeviceTest, HoldsItsPoseWithZeroVelocityAtAnyTime) {
  const auto device = MakeFixedDevice(SomePose());
  for (const double t : {0.0, 0.001, 12.5}) {
    const DeviceState s = device->Read(t);
    EXPECT_EQ(s.t, t);
    EXPECT_TRUE(s.X_DT.p.isApprox(SomePose().p, kTol));
    EXPECT_TRUE(s.X_DT.q.isApprox(SomePose().q, kTol));
    EXPECT_EQ(s.V_DT.v, Vec3::Zero());
    EXPECT_EQ(s.V_DT.w, Vec3::Zero());
    EXPECT_EQ(s.buttons, 0u);
  }
}

TEST(FixedDeviceTest, IgnoresTheDisplayedWrench) {
  const auto device = MakeFixedDevice(SomePose());
  device->SetWrench(Wrench{Vec3(100, 0, 0), Vec3(0, 0, 1)});
  const DeviceState s = device->Read(1.0);
  EXPECT_TRUE(s.X_DT.p.isApprox(SomePose().p, kTol));
  EXPECT_EQ(s.V_DT.v, Vec3::Zero());
}

TEST(FixedDeviceTest, ReportsTheGivenSpecifications) {
  Specifications specs;
  specs.model = "bench rig";
  specs.max_force = 7.0;
  const auto device = MakeFixedDevice(SomePose(), specs);
  EXPECT_EQ(device->specifications().model, "bench rig");
  EXPECT_EQ(device->specifications().max_force, 7.0);
}

TEST(FixedDeviceTest, NormalizesItsQuaternion) {
  Pose X;
  X.q = Quat(2.0, 0.0, 0.0, 0.0);
  const auto device = MakeFixedDevice(X);
  EXPECT_NEAR(device->Read(0.0).X_DT.q.w(), 1.0, kTol);
}

TEST(FixedDeviceTest, RejectsNonFinitePose) {
  Pose X;
  X.p.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(
      [&] {
        (void)MakeFixedDevice(X);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("fixed device: pose: position x = nan m")));
}

}  // namespace
}  // namespace mrh::device
