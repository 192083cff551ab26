// SPDX-License-Identifier: Apache-2.0
// Tests of the mouse device: filter response, teleport, workspace clamp, wrench hand-back, RT.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>

#include "mrh/core/error.h"
#include "mrh/device/mouse.h"
#include "support/alloc_guard.h"

namespace mrh::device {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kDt = 1e-3;   // s, one haptic tick
constexpr double kTau = 0.02;  // s, the filter time constant under test
// Positions are O(0.1 m); each tick is a handful of double operations.
constexpr double kPosTol = 1e-12;
constexpr double kAngleTol = 1e-9;  // rad; slerp goes through acos/sin

MouseDevice MakeDevice(const Pose& X0 = Pose{}) {
  return MouseDevice(X0, MouseDeviceSettings{.smoothing = kTau});
}

// Reads at ticks 1..n (t = i·kDt) and returns the last state.
DeviceState ReadTicks(MouseDevice& device, int first, int last) {
  DeviceState state;
  for (int i = first; i <= last; ++i) state = device.Read(i * kDt);
  return state;
}

TEST(MouseDeviceTest, ReadsTheInitialPoseAtRestBeforeAnyTarget) {
  const Pose X0{Vec3(0.1, -0.2, 0.3), Quat::Identity()};
  MouseDevice device = MakeDevice(X0);
  const DeviceState state = ReadTicks(device, 0, 10);
  EXPECT_TRUE(state.X_DT.p.isApprox(X0.p, kPosTol));
  EXPECT_NEAR(state.V_DT.v.norm(), 0.0, kPosTol);
}

TEST(MouseDeviceTest, ApproachesTheTargetExponentiallyWithTheSmoothingTimeConstant) {
  MouseDevice device = MakeDevice();
  device.Read(0.0);
  const Vec3 target(0.1, 0.0, 0.0);
  device.SetTarget(Pose{target, Quat::Identity()});
  const int ticks = 20;  // one time constant
  const DeviceState state = ReadTicks(device, 1, ticks);
  // x(T) = target (1 − exp(−T/τ)), exact for the discretized filter at any step.
  const double expected = target.x() * (1.0 - std::exp(-ticks * kDt / kTau));
  EXPECT_NEAR(state.X_DT.p.x(), expected, kPosTol);
}

TEST(MouseDeviceTest, VelocityIsTheFiniteDifferenceOfConsecutiveReadings) {
  MouseDevice device = MakeDevice();
  device.Read(0.0);
  device.SetTarget(Pose{Vec3(0.0, 0.05, 0.0), Quat::Identity()});
  const DeviceState a = device.Read(kDt);
  const DeviceState b = device.Read(2 * kDt);
  const Vec3 expected = (b.X_DT.p - a.X_DT.p) / kDt;
  EXPECT_TRUE(b.V_DT.v.isApprox(expected, 1e-9));
  EXPECT_GT(b.V_DT.v.y(), 0.0);
}

TEST(MouseDeviceTest, ComesToRestAtTheTarget) {
  MouseDevice device = MakeDevice();
  device.Read(0.0);
  const Vec3 target(0.0, 0.0, -0.1);
  device.SetTarget(Pose{target, Quat::Identity()});
  const DeviceState state = ReadTicks(device, 1, 2000);  // 100 τ
  // Residual error is |target| exp(−100), far below the tolerance.
  EXPECT_TRUE(state.X_DT.p.isApprox(target, kPosTol));
  EXPECT_NEAR(state.V_DT.v.norm(), 0.0, 1e-9);
}

TEST(MouseDeviceTest, TurnsTowardTheTargetOrientationAtTheSameRate) {
  MouseDevice device = MakeDevice();
  device.Read(0.0);
  const double angle = 0.5;  // rad about z
  device.SetTarget(Pose{Vec3::Zero(), Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()))});
  const int ticks = 20;
  const DeviceState state = ReadTicks(device, 1, ticks);
  const Eigen::AngleAxisd reached(state.X_DT.q);
  const double expected = angle * (1.0 - std::exp(-ticks * kDt / kTau));
  EXPECT_NEAR(reached.angle(), expected, kAngleTol);
  EXPECT_NEAR(reached.axis().z(), 1.0, kAngleTol);
  EXPECT_GT(state.V_DT.w.z(), 0.0);
}

TEST(MouseDeviceTest, TeleportJumpsToThePoseAtRest) {
  MouseDevice device = MakeDevice();
  device.Read(0.0);
  const Vec3 there(0.2, 0.2, 0.2);
  device.Teleport(Pose{there, Quat::Identity()});
  const DeviceState jumped = device.Read(kDt);
  const DeviceState next = device.Read(2 * kDt);
  EXPECT_TRUE(jumped.X_DT.p.isApprox(there, kPosTol));
  EXPECT_NEAR(jumped.V_DT.v.norm(), 0.0, kPosTol);
  EXPECT_NEAR(next.V_DT.v.norm(), 0.0, kPosTol);
}

TEST(MouseDeviceTest, ClampsTargetsToTheWorkspace) {
  Specifications specs = MouseSpecifications();
  specs.workspace_min = Vec3::Constant(-0.1);
  specs.workspace_max = Vec3::Constant(0.1);
  MouseDevice device(Pose{}, MouseDeviceSettings{.smoothing = kTau}, specs);
  device.Teleport(Pose{Vec3(5.0, -5.0, 0.05), Quat::Identity()});
  const DeviceState state = device.Read(0.0);
  EXPECT_TRUE(state.X_DT.p.isApprox(Vec3(0.1, -0.1, 0.05), kPosTol));
}

TEST(MouseDeviceTest, IgnoresANonFiniteTarget) {
  const Pose X0{Vec3(0.01, 0.0, 0.0), Quat::Identity()};
  MouseDevice device = MakeDevice(X0);
  device.Read(0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  device.SetTarget(Pose{Vec3(nan, 0.0, 0.0), Quat::Identity()});
  const DeviceState state = ReadTicks(device, 1, 50);
  EXPECT_TRUE(IsFinite(state.X_DT));
  EXPECT_TRUE(state.X_DT.p.isApprox(X0.p, kPosTol));
}

TEST(MouseDeviceTest, AReadingThatDoesNotAdvanceTimeHoldsThePose) {
  MouseDevice device = MakeDevice();
  device.Read(0.0);
  device.SetTarget(Pose{Vec3(0.1, 0.0, 0.0), Quat::Identity()});
  const DeviceState a = device.Read(kDt);
  const DeviceState b = device.Read(kDt);
  EXPECT_TRUE(b.X_DT.p.isApprox(a.X_DT.p, kPosTol));
  EXPECT_NEAR(b.V_DT.v.norm(), 0.0, kPosTol);
}

TEST(MouseDeviceTest, AReadingAtAnEarlierTimeRestartsTheClock) {
  MouseDevice device = MakeDevice();
  device.Read(5.0);
  device.SetTarget(Pose{Vec3(0.1, 0.0, 0.0), Quat::Identity()});
  const DeviceState restarted = device.Read(0.0);
  const DeviceState next = device.Read(kDt);
  EXPECT_NEAR(restarted.X_DT.p.x(), 0.0, kPosTol);
  EXPECT_NEAR(next.X_DT.p.x(), 0.1 * (1.0 - std::exp(-kDt / kTau)), kPosTol);
}

TEST(MouseDeviceTest, CarriesTheButtonsOfTheTarget) {
  MouseDevice device = MakeDevice();
  device.SetTarget(Pose{}, 0b101u);
  EXPECT_EQ(device.Read(0.0).buttons, 0b101u);
}

TEST(MouseDeviceTest, HandsTheCommandedWrenchToTheUiThread) {
  MouseDevice device = MakeDevice();
  const Wrench w{Vec3(1.0, 2.0, 3.0), Vec3(0.1, 0.2, 0.3)};
  std::thread haptic([&] {
    device.SetWrench(w);
  });
  haptic.join();
  const Wrench seen = device.LatestWrench();
  EXPECT_TRUE(seen.f.isApprox(w.f));
  EXPECT_TRUE(seen.tau.isApprox(w.tau));
}

TEST(MouseDeviceTest, ReadAndSetWrenchDoNotAllocate) {
  MouseDevice device = MakeDevice();
  device.SetTarget(Pose{Vec3(0.1, 0.1, 0.1), Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()))});
  mrh::testing::AllocGuard guard;
  for (int i = 0; i < 1000; ++i) {
    const DeviceState s = device.Read(i * kDt);
    device.SetWrench(Wrench{-100.0 * s.X_DT.p, -s.V_DT.w});
    device.SetTarget(Pose{Vec3(0.0, 0.001 * i, 0.0), Quat::Identity()});
  }
  EXPECT_EQ(guard.count() + guard.deallocations(), 0);
}

TEST(MouseDeviceTest, RejectsANonPositiveSmoothingNamingIt) {
  EXPECT_THAT(
      [] {
        MouseDevice(Pose{}, MouseDeviceSettings{.smoothing = 0.0});
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("smoothing = 0 s")));
}

TEST(MouseDeviceTest, RejectsANonFiniteInitialPose) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THAT(
      [&] {
        MouseDevice(Pose{Vec3(inf, 0.0, 0.0), Quat::Identity()});
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("initial pose is not finite")));
}

TEST(MouseDeviceTest, RejectsAnInvertedWorkspace) {
  Specifications specs = MouseSpecifications();
  specs.workspace_min = Vec3::Constant(1.0);
  specs.workspace_max = Vec3::Constant(-1.0);
  EXPECT_THAT(
      [&] {
        MouseDevice(Pose{}, MouseDeviceSettings{}, specs);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("workspace_min exceeds workspace_max")));
}

}  // namespace
}  // namespace mrh::device
