// SPDX-License-Identifier: Apache-2.0
// The openhaptics device against the in-tree fake libHD.so, whose servo "scheduler" the test
// runs by hand: column-major transforms in mm, forces written, the servo client, HD errors.
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

class OpenHapticsTest : public ::testing::Test {
 protected:
  void SetUp() override { fake_.Get<void()>("fakehd_Reset")(); }

  std::unique_ptr<Device> Make(bool has_torque = false) {
    Specifications specs;
    specs.has_torque = has_torque;
    return MakeOpenHapticsDevice(OpenHapticsSettings{MRH_FAKE_HD, "PHANToM 1"}, specs);
  }

  int Ticks(int n) { return fake_.Get<int(int)>("fakehd_RunServoTicks")(n); }

  int Query(const char* name) { return fake_.Get<int()>(name)(); }

  std::array<double, 3> Force(int i) {
    std::array<double, 3> f{};
    fake_.Get<void(int, double*)>("fakehd_Force")(i, f.data());
    return f;
  }

  FakeLibrary fake_{MRH_FAKE_HD};
};

TEST_F(OpenHapticsTest, OpenStartsTheSchedulerWithForceOutputAndCloseStopsIt) {
  auto device = Make();
  device->Open();
  EXPECT_STREQ(fake_.Get<const char*()>("fakehd_DeviceName")(), "PHANToM 1");
  EXPECT_EQ(Query("fakehd_ForceOutputEnabled"), 1);
  EXPECT_EQ(Query("fakehd_SchedulerRunning"), 1);
  EXPECT_EQ(Ticks(3), 3);
  EXPECT_EQ(Query("fakehd_Unbalanced"), 0);  // every hdBeginFrame has its hdEndFrame
  device->Close();
  EXPECT_EQ(Query("fakehd_SchedulerRunning"), 0);
  EXPECT_EQ(Query("fakehd_Disabled"), 1);
  EXPECT_EQ(Ticks(1), 0);  // unscheduled
}

TEST_F(OpenHapticsTest, ReadsTheColumnMajorTransformInMillimetresAsMetres) {
  // Rotation of 90 degrees about y (x_T = -z_D), translation (10, 20, -30) mm, column-major:
  // m[0..2] is the tool x axis, m[12..14] the position.
  const double m[16] = {0, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 10, 20, -30, 1};
  fake_.Get<void(const double*)>("fakehd_SetTransform")(m);
  const double v[3] = {100, 0, -50};  // mm/s
  fake_.Get<void(const double*)>("fakehd_SetVelocity")(v);
  fake_.Get<void(int)>("fakehd_SetButtons")(2);
  auto device = Make();
  device->Open();  // reads once synchronously: the pose is there before any servo tick
  const DeviceState s = device->Read(1.0);
  EXPECT_NEAR((s.X_DT.p - Vec3(0.010, 0.020, -0.030)).norm(), 0.0, kTol);
  EXPECT_NEAR((s.X_DT.q * Vec3::UnitX() - Vec3(0, 0, -1)).norm(), 0.0, kTol);
  EXPECT_NEAR((s.X_DT.q * Vec3::UnitZ() - Vec3(1, 0, 0)).norm(), 0.0, kTol);
  EXPECT_NEAR((s.V_DT.v - Vec3(0.1, 0, -0.05)).norm(), 0.0, kTol);
  EXPECT_EQ(s.buttons, 2u);
  EXPECT_DOUBLE_EQ(s.t, 1.0);
}

TEST_F(OpenHapticsTest, TheNextServoTickWritesTheCommandedForceInNewtons) {
  auto device = Make();
  device->Open();
  device->SetWrench(Wrench{Vec3(0.5, -1.0, 2.0), Vec3::Zero()});
  ASSERT_EQ(Ticks(1), 1);
  const std::array<double, 3> f = Force(Query("fakehd_ForceCount") - 1);
  EXPECT_EQ(f[0], 0.5);
  EXPECT_EQ(f[1], -1.0);
  EXPECT_EQ(f[2], 2.0);
  device->Close();
}

TEST_F(OpenHapticsTest, AThreeDofDeviceNeverWritesTorqueAndCountsTheDrop) {
  auto device = Make(/*has_torque=*/false);
  device->Open();
  device->SetWrench(Wrench{Vec3(1, 0, 0), Vec3(0.1, 0, 0)});
  ASSERT_EQ(Ticks(2), 2);
  EXPECT_EQ(Query("fakehd_TorqueWrites"), 0);
  EXPECT_EQ(device->counters().torque_dropped, 2);  // one per servo tick that had torque
}

class EchoClient final : public ServoClient {
 public:
  Wrench OnServoTick(double t, const DeviceState& reading) noexcept override {
    ++calls;
    last_t = t;
    return Wrench{-100.0 * reading.X_DT.p, Vec3::Zero()};  // a spring to the origin
  }

  int calls = 0;
  double last_t = -1.0;
};

TEST_F(OpenHapticsTest, AServoClientRunsInsideTheVendorsCallback) {
  const double m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1};  // z = 5 mm
  fake_.Get<void(const double*)>("fakehd_SetTransform")(m);
  auto device = Make();
  EchoClient client;
  dynamic_cast<ServoDevice&>(*device).SetServoClient(&client);
  device->Open();
  ASSERT_EQ(Ticks(4), 4);
  EXPECT_EQ(client.calls, 4);
  EXPECT_GE(client.last_t, 0.0);
  const std::array<double, 3> f = Force(Query("fakehd_ForceCount") - 1);
  EXPECT_NEAR(f[2], -100.0 * 0.005, kTol);
  device->Close();
}

TEST_F(OpenHapticsTest, HdErrorsInTheServoLoopAreCountedAndTheLoopGoesOn) {
  auto device = Make();
  device->Open();
  fake_.Get<void(int)>("fakehd_FailFrames")(2);
  EXPECT_EQ(Ticks(5), 5);
  EXPECT_EQ(device->counters().vendor_errors, 2);
  EXPECT_THAT(device->last_error(), HasSubstr("fake HD error"));
}

TEST_F(OpenHapticsTest, AFailedInitIsAOneLineErrorNamingTheCall) {
  fake_.Get<void(int)>("fakehd_FailInit")(1);
  auto device = Make();
  EXPECT_THAT(
      [&] {
        device->Open();
      },
      ::testing::ThrowsMessage<RuntimeError>(
          AllOf(HasSubstr("hdInitDevice failed"), HasSubstr("fake HD error"),
                HasSubstr("PHANToM 1"), ::testing::Not(HasSubstr("\n")))));
}

TEST(OpenHapticsLoadTest, AMissingLibraryNamesThePathAndTheLoadersReason) {
  EXPECT_THAT(
      [] {
        (void)MakeOpenHapticsDevice(OpenHapticsSettings{"libHD-missing.so", ""}, {});
      },
      ::testing::ThrowsMessage<InvalidArgument>(AllOf(HasSubstr("libHD-missing.so"),
                                                      HasSubstr("cannot open shared object"),
                                                      HasSubstr("OpenHaptics"))));
}

}  // namespace
}  // namespace mrh::device
