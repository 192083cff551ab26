// SPDX-License-Identifier: Apache-2.0
// Method descriptors: every registered method's status-bit names come from the tables beside
// the enums, are unique and non-empty where a bit is defined, and read as RunStats reports them.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mrh/engine/method.h"

namespace mrh::engine::testing {
namespace {

TEST(MethodDescriptorTest, EveryMethodHasANameASummaryAndAFactory) {
  const std::vector<MethodDescriptor> methods = MethodDescriptors();
  ASSERT_GE(methods.size(), 8u);
  for (const MethodDescriptor& d : methods) {
    SCOPED_TRACE(d.name);
    EXPECT_FALSE(d.name.empty());
    EXPECT_FALSE(d.summary.empty());
    EXPECT_EQ(d.summary.find('\n'), std::string::npos) << "one line";
    EXPECT_TRUE(static_cast<bool>(d.factory));
  }
}

TEST(MethodDescriptorTest, StatusBitNamesAreUniqueAndNonEmptyWhereABitIsDefined) {
  for (const MethodDescriptor& d : MethodDescriptors()) {
    SCOPED_TRACE(d.name);
    std::uint32_t defined = 0;
    for (const StatusBitGroup& group : d.status_bits) {
      EXPECT_FALSE(group.prefix.empty());
      EXPECT_TRUE(ValidStatusBitNames(group.names));
      for (const StatusBitName& bit : group.names) {
        EXPECT_EQ(defined & bit.mask, 0u) << bit.name << ": bit named twice";
        defined |= bit.mask;
      }
    }
    const std::vector<std::string> names = StatusBitNames(d.status_bits);
    std::set<std::string> seen;
    for (std::size_t i = 0; i < names.size(); ++i) {
      const bool is_defined = (defined >> i) & 1u;
      EXPECT_EQ(!names[i].empty(), is_defined) << "bit " << i;
      if (is_defined) {
        EXPECT_TRUE(seen.insert(names[i]).second) << names[i] << " twice";
      }
    }
  }
}

// The names summary.json carries (RunStats::method_status), bit i at index i.
TEST(MethodDescriptorTest, BuiltInStatusBitNamesReadAsRunStatsReportsThem) {
  const std::map<std::string, std::vector<std::string>> expected = {
      {"single-rate", {}},
      {"impulse", {}},
      {"proxy-6dof",
       {"proxy.rows_full", "proxy.not_converged", "proxy.bad_input", "",
        "proxy.pair_force_limited"}},
      {"penalty-sum", {"", "", "penalty_sum.bad_input"}},
      {"virtual-coupling", {"virtual_coupling.bad_input"}},
      {"contact-volume", {"contact_volume.bad_input"}},
      {"local-dynamics", {"local_dynamics.local_body_fault"}},
      {"local-dynamics-6dof",
       {"proxy.rows_full", "proxy.not_converged", "proxy.bad_input",
        "local_dynamics.local_body_fault", "proxy.pair_force_limited"}},
  };
  std::map<std::string, std::vector<std::string>> actual;
  for (const MethodDescriptor& d : MethodDescriptors()) {
    if (expected.count(d.name) != 0) actual[d.name] = StatusBitNames(d.status_bits);
  }
  EXPECT_EQ(actual, expected);
}

// session::LoadWorld loads the scene as the method says; only these two need more than the
// default (a mocap pointer, MuJoCo's own contacts).
TEST(MethodDescriptorTest, WorldNeedsOfTheBuiltIns) {
  for (const MethodDescriptor& d : MethodDescriptors()) {
    SCOPED_TRACE(d.name);
    EXPECT_EQ(d.world.dynamic_pointer, d.name == "virtual-coupling");
    EXPECT_EQ(d.world.penalty_contacts, d.name == "contact-volume");
  }
  EXPECT_FALSE(FindMethod("no-such-method").has_value());
}

// Run reports plot a torque, and the viewer shows rot_stiffness, only where the method has one.
TEST(MethodDescriptorTest, OnlyThe3DofMethodsRenderNoTorque) {
  const std::set<std::string> three_dof = {"single-rate", "impulse", "local-dynamics"};
  const std::set<std::string> proxies = {"proxy-6dof", "local-dynamics-6dof"};
  for (const char* name :
       {"single-rate", "impulse", "proxy-6dof", "penalty-sum", "virtual-coupling", "contact-volume",
        "local-dynamics", "local-dynamics-6dof"}) {
    SCOPED_TRACE(name);
    const std::optional<MethodDescriptor> d = FindMethod(name);
    ASSERT_TRUE(d.has_value());
    EXPECT_EQ(d->settings.torque, three_dof.count(name) == 0);
    EXPECT_EQ(d->settings.rot_stiffness, proxies.count(name) == 1);
  }
}

TEST(MethodDescriptorTest, StatusBitNamesLeaveUnnamedBitsEmpty) {
  static constexpr StatusBitName kBits[] = {{1u << 2, "two"}, {1u << 0, "zero"}};
  const StatusBitGroup groups[] = {{"toy", kBits}};
  EXPECT_EQ(StatusBitNames(groups), (std::vector<std::string>{"toy.zero", "", "toy.two"}));
}

TEST(MethodDescriptorTest, ValidStatusBitNamesRejectsDriftAndDuplicates) {
  static constexpr StatusBitName kTwoBits[] = {{3u, "both"}};
  static constexpr StatusBitName kNoName[] = {{1u, ""}};
  static constexpr StatusBitName kSameBit[] = {{1u, "a"}, {1u, "b"}};
  static constexpr StatusBitName kSameName[] = {{1u, "a"}, {2u, "a"}};
  EXPECT_FALSE(ValidStatusBitNames(kTwoBits));
  EXPECT_FALSE(ValidStatusBitNames(kNoName));
  EXPECT_FALSE(ValidStatusBitNames(kSameBit));
  EXPECT_FALSE(ValidStatusBitNames(kSameName));
}

}  // namespace
}  // namespace mrh::engine::testing
