// SPDX-License-Identifier: Apache-2.0
// The RT contract of the device module: Read, SetWrench and SafetyFilter::Apply never allocate.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "device/test_files.h"
#include "mrh/device/safety.h"
#include "mrh/device/simulated.h"
#include "support/alloc_guard.h"

namespace mrh::device {
namespace {

constexpr int kTicks = 1000;
constexpr double kDt = 1e-3;  // s

// Many keyframes so the binary search does real work.
std::vector<Keyframe> Circle() {
  std::vector<Keyframe> keys;
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.02 * i;
    keys.push_back(Keyframe{t, Pose{Vec3(0.1 * std::cos(t), 0.1 * std::sin(t), 0.0),
                                    Quat(Eigen::AngleAxisd(t, Vec3::UnitZ()))}});
  }
  return keys;
}

// Runs kTicks of Read + SetWrench with a wrench that depends on the reading (closed loop) and
// returns the allocations seen.
std::int64_t CountTickAllocations(Device& device) {
  mrh::testing::AllocGuard guard;
  for (int i = 0; i < kTicks; ++i) {
    const DeviceState s = device.Read(i * kDt);
    device.SetWrench(Wrench{-100.0 * s.X_DT.p, Vec3(0, 0, -0.1 * s.V_DT.w.z())});
  }
  return guard.count() + guard.deallocations();
}

TEST(DeviceRtTest, FixedDeviceTicksWithoutAllocating) {
  const auto device = MakeFixedDevice(Pose{});
  EXPECT_EQ(CountTickAllocations(*device), 0);
}

TEST(DeviceRtTest, ScriptedDeviceTicksWithoutAllocating) {
  const auto device = MakeScriptedDevice(Circle());
  EXPECT_EQ(CountTickAllocations(*device), 0);
}

TEST(DeviceRtTest, HandDeviceTicksWithoutAllocating) {
  const auto device = MakeHandDevice(Circle(), HandSettings{});
  EXPECT_EQ(CountTickAllocations(*device), 0);
}

TEST(DeviceRtTest, ReplayDeviceTicksWithoutAllocating) {
  std::string csv = "t,px,py,pz,qw,qx,qy,qz\n";
  for (int i = 0; i <= 200; ++i) {
    csv += std::to_string(0.005 * i) + "," + std::to_string(0.001 * i) + ",0,0,1,0,0,0\n";
  }
  const auto device = MakeReplayDevice(testing::WriteTestFile("ticks.csv", csv));
  EXPECT_EQ(CountTickAllocations(*device), 0);
}

TEST(DeviceRtTest, SafetyFilterAppliesWithoutAllocating) {
  SafetyFilter filter(Specifications{}, SafetySettings{});
  std::uint32_t bits_seen = 0;
  mrh::testing::AllocGuard guard;
  for (int i = 0; i < kTicks; ++i) {
    const double t = i * kDt;
    std::uint32_t bits = 0;
    // Exercise every branch: ramp, clamp, watchdog, NaN wrench, NaN device.
    const Wrench rendered{Vec3(i % 7 == 0 ? std::nan("") : 50.0, 0, 0), Vec3(0, 0, 3.0)};
    (void)filter.Apply(rendered, t, t > 0.6 ? t - 0.3 : 0.0, i % 11 != 0, &bits);
    bits_seen |= bits;
  }
  filter.Stop();
  std::uint32_t bits = 0;
  (void)filter.Apply(Wrench{}, 1.0, 0.0, true, &bits);
  bits_seen |= bits;
  EXPECT_EQ(guard.count() + guard.deallocations(), 0);
  EXPECT_EQ(bits_seen, kSafetyNonFiniteWrench | kSafetyNonFiniteDevice | kSafetyForceClamped |
                           kSafetyTorqueClamped | kSafetyRamping | kSafetyWatchdog |
                           kSafetyStopped);
}

}  // namespace
}  // namespace mrh::device
