// SPDX-License-Identifier: Apache-2.0
// Several Force Dimension devices in one process: device.id selects the device through
// dhdOpenID, and every later call names the ID that open returned (the fake's IDs are the
// index + 10, so passing the index instead would show).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>

#include "device/fake_library.h"
#include "mrh/core/error.h"
#include "mrh/device/hardware.h"

namespace mrh::device {
namespace {

using ::testing::AllOf;
using testing::FakeLibrary;
using ::testing::HasSubstr;

class ForceDimensionIdTest : public ::testing::Test {
 protected:
  void SetUp() override { fake_.Get<void()>("fakedhd_Reset")(); }

  static std::unique_ptr<Device> Make(int id) {
    ForceDimensionSettings settings{MRH_FAKE_DHD};
    settings.id = id;
    return MakeForceDimensionDevice(settings, Specifications{});
  }

  int Query(const char* name) { return fake_.Get<int()>(name)(); }

  int ForceId(int i) { return fake_.Get<int(int)>("fakedhd_ForceId")(i); }

  double ForceX(int i) {
    std::array<double, 6> f{};
    fake_.Get<void(int, double*)>("fakedhd_Force")(i, f.data());
    return f[0];
  }

  FakeLibrary fake_{MRH_FAKE_DHD};
};

TEST_F(ForceDimensionIdTest, TwoDevicesByIndexEachReceiveTheirOwnForce) {
  auto first = Make(0);
  auto second = Make(1);
  first->Open();
  EXPECT_EQ(Query("fakedhd_LastOpenIndex"), 0);
  second->Open();
  EXPECT_EQ(Query("fakedhd_LastOpenIndex"), 1);
  EXPECT_EQ(Query("fakedhd_EnabledIds"), (1 << 10) | (1 << 11));
  const int before = Query("fakedhd_ForceCount");
  first->SetWrench(Wrench{Vec3(1, 0, 0), Vec3::Zero()});
  second->SetWrench(Wrench{Vec3(2, 0, 0), Vec3::Zero()});
  ASSERT_EQ(Query("fakedhd_ForceCount"), before + 2);
  EXPECT_EQ(ForceId(before), 10);
  EXPECT_EQ(ForceX(before), 1.0);
  EXPECT_EQ(ForceId(before + 1), 11);
  EXPECT_EQ(ForceX(before + 1), 2.0);
  second->Close();
  EXPECT_EQ(Query("fakedhd_EnabledIds"), 1 << 10);  // closing one leaves the other running
}

TEST_F(ForceDimensionIdTest, TheDefaultDeviceStillOpensThroughDhdOpen) {
  auto device = Make(-1);
  device->Open();
  EXPECT_EQ(Query("fakedhd_LastOpenIndex"), -1);  // dhdOpenID was not called
  EXPECT_EQ(Query("fakedhd_IsOpen"), 1);
}

TEST_F(ForceDimensionIdTest, AMissingDeviceNamesItsIndex) {
  auto device = Make(3 + 1);  // the fake enumerates four devices, 0..3
  EXPECT_THAT(
      [&] {
        device->Open();
      },
      ::testing::ThrowsMessage<RuntimeError>(
          AllOf(HasSubstr("dhdOpenID(4) failed"), HasSubstr("fake: no such device"))));
}

TEST_F(ForceDimensionIdTest, AnIdOutsideTheDhdRangeIsRefused) {
  EXPECT_THROW((void)Make(128), InvalidArgument);
  EXPECT_THROW((void)Make(-2), InvalidArgument);
}

}  // namespace
}  // namespace mrh::device
