// SPDX-License-Identifier: Apache-2.0
// Several pointers on real devices: each names its own Force Dimension device (device.id),
// OpenHaptics device (device.name) or UDP port (device.bind); two claiming one are refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "mrh/core/error.h"
#include "mrh/session/session.h"
#include "session/session_test_util.h"

namespace mrh::session {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using testing::Parse;
using testing::ThrowsInvalid;

// Matches a callable that throws mrh::InvalidArgument whose message matches `matcher`.
template <typename M>
auto ThrowsWith(M matcher) {
  return ::testing::ThrowsMessage<InvalidArgument>(matcher);
}

// Two pointers f0 and f1 with the given device blocks.
std::string TwoPointers(const std::string& device0, const std::string& device1) {
  return R"({"scene": "scene.xml", "method": "single-rate", "pointers": [)"
         R"({"body": "f0", "device": )" +
         device0 + R"(}, {"body": "f1", "device": )" + device1 + "}]}";
}

TEST(DeviceClaimsTest, TwoForceDimensionDevicesByIndex) {
  const Session s = Parse(TwoPointers(R"({"type": "forcedimension", "id": 0})",
                                      R"({"type": "forcedimension", "id": 1})"));
  ASSERT_EQ(s.pointer_devices.size(), 2u);
  EXPECT_EQ(s.pointer_devices[0].forcedimension.id, 0);
  EXPECT_EQ(s.pointer_devices[1].forcedimension.id, 1);
  EXPECT_EQ(s.engine.mode, settings::Mode::kRealtime);  // real devices answer in wall-clock time
}

TEST(DeviceClaimsTest, OneForceDimensionDeviceKeepsTheDefault) {
  const Session s = Parse(R"({"scene": "scene.xml", "method": "single-rate",
                              "device": {"type": "forcedimension"}})");
  EXPECT_EQ(s.device.forcedimension.id, -1);
}

TEST(DeviceClaimsTest, TheSameForceDimensionIndexTwiceNamesTheLaterPointer) {
  EXPECT_THAT(
      [] {
        Parse(TwoPointers(R"({"type": "forcedimension", "id": 1})",
                          R"({"type": "forcedimension", "id": 1})"));
      },
      ThrowsWith(AllOf(HasSubstr("pointers[1].device.id"), HasSubstr("pointers[0]"))));
}

TEST(DeviceClaimsTest, SeveralForceDimensionPointersEachNeedAnIndex) {
  EXPECT_THAT(
      [] {
        Parse(
            TwoPointers(R"({"type": "forcedimension", "id": 0})", R"({"type": "forcedimension"})"));
      },
      ThrowsInvalid("pointers[1].device.id"));
}

TEST(DeviceClaimsTest, AForceDimensionIndexOutOfRangeIsRefused) {
  EXPECT_THAT(
      [] {
        Parse(TwoPointers(R"({"type": "forcedimension", "id": 0})",
                          R"({"type": "forcedimension", "id": 128})"));
      },
      ThrowsInvalid("pointers[1].device.id"));
}

TEST(DeviceClaimsTest, TwoOpenHapticsDevicesByName) {
  const Session s = Parse(TwoPointers(R"({"type": "openhaptics", "name": "Left Touch"})",
                                      R"({"type": "openhaptics", "name": "Right Touch"})"));
  EXPECT_EQ(s.pointer_devices[0].openhaptics.name, "Left Touch");
  EXPECT_EQ(s.pointer_devices[1].openhaptics.name, "Right Touch");
}

TEST(DeviceClaimsTest, TheSameOpenHapticsNameTwiceNamesTheLaterPointer) {
  EXPECT_THAT(
      [] {
        Parse(TwoPointers(R"({"type": "openhaptics", "name": "Touch"})",
                          R"({"type": "openhaptics", "name": "Touch"})"));
      },
      ThrowsWith(AllOf(HasSubstr("pointers[1].device.name"), HasSubstr("\"Touch\""))));
}

TEST(DeviceClaimsTest, SeveralOpenHapticsPointersEachNeedAName) {
  EXPECT_THAT(
      [] {
        Parse(TwoPointers(R"({"type": "openhaptics", "name": ""})",
                          R"({"type": "openhaptics", "name": "Touch"})"));
      },
      ThrowsInvalid("pointers[0].device.name"));
  EXPECT_THAT(
      [] {
        Parse(TwoPointers(R"({"type": "openhaptics", "name": "Touch"})",
                          R"({"type": "openhaptics"})"));
      },
      ThrowsInvalid("pointers[1].device.name"));
}

TEST(DeviceClaimsTest, TwoUdpPointersOnTwoPorts) {
  const Session s = Parse(TwoPointers(R"({"type": "udp", "bind": "127.0.0.1:47801"})",
                                      R"({"type": "udp", "bind": "127.0.0.1:47802"})"));
  EXPECT_EQ(s.pointer_devices[0].udp.bind, "127.0.0.1:47801");
  EXPECT_EQ(s.pointer_devices[1].udp.bind, "127.0.0.1:47802");
}

TEST(DeviceClaimsTest, TheSameUdpPortTwiceNamesTheLaterPointersBind) {
  EXPECT_THAT(
      [] {
        Parse(TwoPointers(R"({"type": "udp", "bind": "127.0.0.1:47801"})",
                          R"({"type": "udp", "bind": "0.0.0.0:47801"})"));
      },
      ThrowsWith(AllOf(HasSubstr("pointers[1].device.bind"), HasSubstr("47801"))));
  // Both on the default bind: the error names the device block that left it implicit.
  EXPECT_THAT(
      [] {
        Parse(TwoPointers(R"({"type": "udp"})", R"({"type": "udp"})"));
      },
      ThrowsWith(AllOf(HasSubstr("pointers[1].device"), HasSubstr("47800"))));
}

TEST(DeviceClaimsTest, PortZeroIsPickedByTheSystemAndNeverClashes) {
  const Session s = Parse(TwoPointers(R"({"type": "udp", "bind": "127.0.0.1:0"})",
                                      R"({"type": "udp", "bind": "127.0.0.1:0"})"));
  EXPECT_EQ(s.pointer_devices.size(), 2u);
}

TEST(DeviceClaimsTest, DifferentDeviceTypesNeverClash) {
  const Session s =
      Parse(TwoPointers(R"({"type": "forcedimension"})", R"({"type": "openhaptics"})"));
  EXPECT_EQ(s.pointer_devices[1].type, "openhaptics");
}

}  // namespace
}  // namespace mrh::session
