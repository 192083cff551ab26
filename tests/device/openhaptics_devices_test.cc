// SPDX-License-Identifier: Apache-2.0
// Two OpenHaptics devices in one process, each by name, on HD's one scheduler: each servo
// callback writes to its own device, and closing one keeps the other's servo loop running.
#include <gtest/gtest.h>

#include <array>

#include "device/fake_library.h"
#include "mrh/device/hardware.h"

namespace mrh::device {
namespace {

using testing::FakeLibrary;

class OpenHapticsDevicesTest : public ::testing::Test {
 protected:
  void SetUp() override { fake_.Get<void()>("fakehd_Reset")(); }

  static std::unique_ptr<Device> Make(const char* name) {
    return MakeOpenHapticsDevice(OpenHapticsSettings{MRH_FAKE_HD, name}, Specifications{});
  }

  int Ticks(int n) { return fake_.Get<int(int)>("fakehd_RunServoTicks")(n); }

  int Query(const char* name) { return fake_.Get<int()>(name)(); }

  unsigned int ForceDevice(int i) { return fake_.Get<unsigned int(int)>("fakehd_ForceDevice")(i); }

  double ForceX(int i) {
    std::array<double, 3> f{};
    fake_.Get<void(int, double*)>("fakehd_Force")(i, f.data());
    return f[0];
  }

  FakeLibrary fake_{MRH_FAKE_HD};
};

TEST_F(OpenHapticsDevicesTest, EachServoCallbackWritesItsOwnDevice) {
  auto left = Make("Left");
  auto right = Make("Right");
  left->Open();   // the fake's device handle 1
  right->Open();  // handle 2
  EXPECT_STREQ(fake_.Get<const char*()>("fakehd_DeviceName")(), "Right");
  left->SetWrench(Wrench{Vec3(1, 0, 0), Vec3::Zero()});
  right->SetWrench(Wrench{Vec3(2, 0, 0), Vec3::Zero()});
  const int before = Query("fakehd_ForceCount");
  ASSERT_EQ(Ticks(1), 1);  // one servo tick runs both callbacks, left's first
  ASSERT_EQ(Query("fakehd_ForceCount"), before + 2);
  EXPECT_EQ(ForceDevice(before), 1u);
  EXPECT_EQ(ForceX(before), 1.0);
  EXPECT_EQ(ForceDevice(before + 1), 2u);
  EXPECT_EQ(ForceX(before + 1), 2.0);
  right->Close();
  left->Close();
}

TEST_F(OpenHapticsDevicesTest, ClosingOneDeviceKeepsTheOthersServoLoopRunning) {
  auto left = Make("Left");
  auto right = Make("Right");
  left->Open();
  right->Open();
  left->Close();
  EXPECT_EQ(Query("fakehd_SchedulerRunning"), 1);
  right->SetWrench(Wrench{Vec3(3, 0, 0), Vec3::Zero()});
  ASSERT_EQ(Ticks(1), 1);
  const int last = Query("fakehd_ForceCount") - 1;
  EXPECT_EQ(ForceDevice(last), 2u);
  EXPECT_EQ(ForceX(last), 3.0);
  right->Close();
  EXPECT_EQ(Query("fakehd_SchedulerRunning"), 0);
  // Started once per device joining, stopped once per device joining after the first and per
  // device leaving: the scheduler never ran while a device was initialized or disabled.
  EXPECT_EQ(Query("fakehd_StartCalls"), 3);
  EXPECT_EQ(Query("fakehd_StopCalls"), 3);
}

}  // namespace
}  // namespace mrh::device
