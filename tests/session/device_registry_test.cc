// SPDX-License-Identifier: Apache-2.0
// The device registry: every built-in type the parser knows has a descriptor, and back.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "mrh/session/devices.h"
#include "session/schema.h"

namespace mrh::session {
namespace {

TEST(DeviceRegistryTest, BuiltInTypesAreTheParsersTypes) {
  std::set<std::string> parsed;
  for (const internal::DeviceType& type : internal::kDeviceTypes) parsed.emplace(type.name);
  std::set<std::string> registered;
  for (const DeviceDescriptor& d : DeviceDescriptors()) {
    SCOPED_TRACE(d.name);
    EXPECT_FALSE(d.summary.empty());
    EXPECT_TRUE(static_cast<bool>(d.factory));
    registered.insert(d.name);
  }
  EXPECT_EQ(registered, parsed);
}

TEST(DeviceRegistryTest, UnknownNameIsNotFound) {
  EXPECT_FALSE(FindDevice("joystick").has_value());
  EXPECT_TRUE(FindDevice("scripted").has_value());
}

}  // namespace
}  // namespace mrh::session
