// SPDX-License-Identifier: Apache-2.0
// The forcedimension device against the in-tree fake libdhd.so: loading, open/close, units and
// frames, torque dropping, vendor errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "device/fake_library.h"
#include "mrh/core/error.h"
#include "mrh/device/hardware.h"

namespace mrh::device {
namespace {

using ::testing::AllOf;
using testing::FakeLibrary;
using ::testing::HasSubstr;

constexpr double kTol = 1e-12;

class ForceDimensionTest : public ::testing::Test {
 protected:
  void SetUp() override { fake_.Get<void()>("fakedhd_Reset")(); }

  std::unique_ptr<Device> Make(bool has_torque = true) {
    Specifications specs;
    specs.has_torque = has_torque;
    return MakeForceDimensionDevice(ForceDimensionSettings{MRH_FAKE_DHD}, specs);
  }

  void SetPose(const double p[3], const double R[9], const double v[3], int buttons) {
    fake_.Get<void(const double*, const double*, const double*, int)>("fakedhd_SetPose")(p, R, v,
                                                                                         buttons);
  }

  int Query(const char* name) { return fake_.Get<int()>(name)(); }

  std::array<double, 6> Force(int i) {
    std::array<double, 6> f{};
    fake_.Get<void(int, double*)>("fakedhd_Force")(i, f.data());
    return f;
  }

  FakeLibrary fake_{MRH_FAKE_DHD};
};

TEST_F(ForceDimensionTest, OpenEnablesForcesAndCloseZeroesDisablesAndCloses) {
  auto device = Make();
  device->Open();
  EXPECT_EQ(Query("fakedhd_IsOpen"), 1);
  EXPECT_EQ(Query("fakedhd_ForceEnabled"), 1);
  device->SetWrench(Wrench{Vec3(1, 2, 3), Vec3::Zero()});
  device->Close();
  EXPECT_EQ(Query("fakedhd_IsOpen"), 0);
  EXPECT_EQ(Query("fakedhd_ForceEnabled"), 0);
  const std::array<double, 6> last = Force(Query("fakedhd_ForceCount") - 1);
  for (double v : last) EXPECT_EQ(v, 0.0);  // the last command before closing is zero
  device->Close();                          // a second Close is harmless
  EXPECT_EQ(Query("fakedhd_CloseCalls"), 1);
}

TEST_F(ForceDimensionTest, ReadsPositionOrientationVelocityAndButtonsInTheDeviceFrame) {
  auto device = Make();
  device->Open();
  // 90 degrees about z: columns are the tool axes in D, so x_T = (0, 1, 0).
  const double p[3] = {0.01, -0.02, 0.03}, v[3] = {0.1, 0.2, -0.3};
  const double R[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
  SetPose(p, R, v, 0b101);
  const DeviceState s = device->Read(0.5);
  EXPECT_DOUBLE_EQ(s.t, 0.5);
  EXPECT_NEAR((s.X_DT.p - Vec3(0.01, -0.02, 0.03)).norm(), 0.0, kTol);
  EXPECT_NEAR((s.X_DT.q * Vec3::UnitX() - Vec3::UnitY()).norm(), 0.0, kTol);
  EXPECT_NEAR((s.V_DT.v - Vec3(0.1, 0.2, -0.3)).norm(), 0.0, kTol);
  EXPECT_NEAR((s.V_DT.w - Vec3(0.1, 0.2, 0.3)).norm(), 0.0, kTol);  // optional symbol used
  EXPECT_EQ(s.buttons, 0b101u);
}

TEST_F(ForceDimensionTest, WritesTheCommandedForceAndTorqueUnchanged) {
  auto device = Make();
  device->Open();
  const int before = Query("fakedhd_ForceCount");
  device->SetWrench(Wrench{Vec3(1.5, -2.0, 0.25), Vec3(0.01, 0.02, -0.03)});
  ASSERT_EQ(Query("fakedhd_ForceCount"), before + 1);
  const std::array<double, 6> f = Force(before);
  const std::array<double, 6> expected{1.5, -2.0, 0.25, 0.01, 0.02, -0.03};
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(f[static_cast<std::size_t>(i)], expected[static_cast<std::size_t>(i)]);
}

TEST_F(ForceDimensionTest, AThreeDofDeviceDropsAndCountsTorque) {
  auto device = Make(/*has_torque=*/false);
  device->Open();
  const int before = Query("fakedhd_ForceCount");
  device->SetWrench(Wrench{Vec3(1, 0, 0), Vec3(0, 0, 0.1)});
  device->SetWrench(Wrench{Vec3(1, 0, 0), Vec3::Zero()});
  const std::array<double, 6> f = Force(before);
  EXPECT_EQ(f[0], 1.0);
  EXPECT_EQ(f[5], 0.0);
  EXPECT_EQ(device->counters().torque_dropped, 1);
}

TEST_F(ForceDimensionTest, AFailedReadKeepsTheLastPoseAndIsCounted) {
  auto device = Make();
  device->Open();
  const double p[3] = {0.01, 0, 0}, v[3] = {0, 0, 0}, R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  SetPose(p, R, v, 0);
  (void)device->Read(0.0);
  const double moved[3] = {0.05, 0, 0};
  SetPose(moved, R, v, 0);
  fake_.Get<void(int)>("fakedhd_FailReads")(1);
  const DeviceState s = device->Read(0.001);
  EXPECT_DOUBLE_EQ(s.X_DT.p.x(), 0.01);
  EXPECT_EQ(device->counters().vendor_errors, 1);
  EXPECT_THAT(device->last_error(), HasSubstr("communication error"));
  EXPECT_DOUBLE_EQ(device->Read(0.002).X_DT.p.x(), 0.05);  // recovers on the next good read
}

TEST_F(ForceDimensionTest, AFailedOpenIsAOneLineErrorWithTheVendorsText) {
  fake_.Get<void(int)>("fakedhd_FailOpen")(1);
  auto device = Make();
  EXPECT_THAT(
      [&] {
        device->Open();
      },
      ::testing::ThrowsMessage<RuntimeError>(AllOf(HasSubstr("dhdOpen failed"),
                                                   HasSubstr("fake: no device found"),
                                                   ::testing::Not(HasSubstr("\n")))));
}

TEST(ForceDimensionLoadTest, AMissingLibraryNamesThePathAndTheLoadersReason) {
  const std::string path = "/nonexistent/libdhd.so";
  EXPECT_THAT(
      [&] {
        (void)MakeForceDimensionDevice(ForceDimensionSettings{path}, {});
      },
      ::testing::ThrowsMessage<InvalidArgument>(
          AllOf(HasSubstr(path), HasSubstr("No such file"), HasSubstr("DHD"))));
}

TEST(ForceDimensionLoadTest, ALibraryWithoutARequiredSymbolNamesTheSymbol) {
  EXPECT_THAT(
      [&] {
        (void)MakeForceDimensionDevice(ForceDimensionSettings{MRH_FAKE_DHD_INCOMPLETE}, {});
      },
      ::testing::ThrowsMessage<InvalidArgument>(
          AllOf(HasSubstr(MRH_FAKE_DHD_INCOMPLETE), HasSubstr("dhdClose"))));
}

}  // namespace
}  // namespace mrh::device
