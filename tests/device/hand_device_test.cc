// SPDX-License-Identifier: Apache-2.0
// Tests of the hand device (closed-loop simulated user) against the analytic mass-spring-damper.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mrh/core/error.h"
#include "mrh/device/simulated.h"

namespace mrh::device {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kDt = 1e-3;  // s, the haptic tick
// Round-off floor for quantities that are exactly zero or exactly reached in exact arithmetic:
// positions are O(0.1) m and the loops run a few thousand steps.
constexpr double kExactTol = 1e-9;

Keyframe Key(double t, const Vec3& p, const Quat& q = Quat::Identity()) {
  return Keyframe{t, Pose{p, q}};
}

Vec3 RotationVector(const Quat& q) {
  const Eigen::AngleAxisd aa(q);
  return aa.angle() * aa.axis();
}

// Reads the device at every tick from t_begin to t_end (inclusive); returns the last state.
DeviceState RunTicks(Device& device, double t_begin, double t_end) {
  DeviceState s;
  const auto n = static_cast<int>(std::lround((t_end - t_begin) / kDt));
  for (int i = 0; i <= n; ++i) s = device.Read(t_begin + i * kDt);
  return s;
}

TEST(HandDeviceTest, StartsOnTheTargetPoseAtRest) {
  const auto device = MakeHandDevice(
      {Key(0.0, Vec3(0, 0, 0)), Key(1.0, Vec3(1, 0, 0), Quat(Eigen::AngleAxisd(1, Vec3::UnitY())))},
      HandSettings{});
  const DeviceState s = device->Read(0.25);
  EXPECT_TRUE(s.X_DT.p.isApprox(Vec3(0.25, 0, 0), kExactTol));
  EXPECT_NEAR(s.X_DT.q.angularDistance(Quat(Eigen::AngleAxisd(0.25, Vec3::UnitY()))), 0.0,
              kExactTol);
  EXPECT_EQ(s.V_DT.v, Vec3::Zero());
  EXPECT_EQ(s.V_DT.w, Vec3::Zero());
}

// The target starts moving at speed u at t = 1 while the hand rests on it. The error
// e = x_target - x obeys m e'' + b e' + k e = 0 with e(0) = 0, e'(0) = u, so
// e(tau) = u / wd exp(-zeta wn tau) sin(wd tau).
TEST(HandDeviceTest, TransientWhenTargetStartsMovingMatchesSecondOrderResponse) {
  const HandSettings hand;
  constexpr double kSpeed = 0.1;  // m/s
  const auto device = MakeHandDevice(
      {Key(0.0, Vec3::Zero()), Key(1.0, Vec3::Zero()), Key(3.0, Vec3(2 * kSpeed, 0, 0))}, hand);
  const double wn = std::sqrt(hand.stiffness / hand.mass);
  const double zeta = hand.damping / (2 * std::sqrt(hand.stiffness * hand.mass));
  const double wd = wn * std::sqrt(1 - zeta * zeta);
  // Semi-implicit Euler with a zero-order-held target is first-order accurate: its error is of
  // order (wn h) times the response amplitude u / wd (measured: 0.4 of that).
  const double tol = wn * kDt * kSpeed / wd;
  (void)RunTicks(*device, 0.0, 1.0);
  double max_error = 0.0;
  for (int i = 1; i <= 1000; ++i) {
    const double tau = i * kDt;
    const DeviceState s = device->Read(1.0 + tau);
    const double e = kSpeed * tau - s.X_DT.p.x();
    const double expected = kSpeed / wd * std::exp(-zeta * wn * tau) * std::sin(wd * tau);
    ASSERT_NEAR(e, expected, tol) << "tau = " << tau;
    max_error = std::max(max_error, e);
  }
  EXPECT_GT(max_error, 5 * tol);  // the response is really there, not lost in the tolerance
}

// The damper acts on the velocity error (v_target - v), so for a constant-velocity target the
// steady-state lag is zero (a ground-referenced damper would lag by b u / k = 6.7 mm here).
TEST(HandDeviceTest, TracksConstantVelocityTargetWithoutSteadyStateLag) {
  constexpr double kSpeed = 0.1;  // m/s
  const Vec3 u(kSpeed, -kSpeed, 0.0);
  const auto device = MakeHandDevice({Key(0.0, Vec3::Zero()), Key(4.0, 4.0 * u)}, HandSettings{});
  // Settling: the transient decays as exp(-zeta wn t) = exp(-20 t); after 3 s it is 1e-26.
  const DeviceState s = RunTicks(*device, 0.0, 3.0);
  EXPECT_LT((3.0 * u - s.X_DT.p).norm(), kExactTol);
  EXPECT_LT((u - s.V_DT.v).norm(), kExactTol);
}

TEST(HandDeviceTest, TracksConstantAngularVelocityTarget) {
  const Vec3 w(0.0, 0.0, 0.5);  // rad/s
  const Quat q_end(Eigen::AngleAxisd(2.0, Vec3::UnitZ()));
  const auto device =
      MakeHandDevice({Key(0.0, Vec3::Zero()), Key(4.0, Vec3::Zero(), q_end)}, HandSettings{});
  const DeviceState s = RunTicks(*device, 0.0, 3.0);
  EXPECT_NEAR(s.X_DT.q.angularDistance(Quat(Eigen::AngleAxisd(1.5, Vec3::UnitZ()))), 0.0,
              kExactTol);
  EXPECT_LT((w - s.V_DT.w).norm(), kExactTol);
}

TEST(HandDeviceTest, ConstantDisplayedForceGivesStaticOffsetForceOverStiffness) {
  const HandSettings hand;
  const auto device = MakeHandDevice({Key(0.0, Vec3(0.1, 0.2, 0.3))}, hand);
  const Vec3 force(3.0, 0.0, -1.5);  // N
  (void)device->Read(0.0);
  device->SetWrench(Wrench{force, Vec3::Zero()});
  const DeviceState s = RunTicks(*device, kDt, 3.0);
  const Vec3 offset = s.X_DT.p - Vec3(0.1, 0.2, 0.3);
  EXPECT_LT((offset - force / hand.stiffness).norm(), kExactTol) << offset.transpose();
  EXPECT_LT(s.V_DT.v.norm(), kExactTol);
}

TEST(HandDeviceTest, ConstantDisplayedTorqueGivesStaticTurnTorqueOverStiffness) {
  const HandSettings hand;
  const auto device = MakeHandDevice({Key(0.0, Vec3::Zero())}, hand);
  const Vec3 torque(0.0, 0.01, 0.02);  // N·m
  (void)device->Read(0.0);
  device->SetWrench(Wrench{Vec3::Zero(), torque});
  const DeviceState s = RunTicks(*device, kDt, 3.0);
  const Vec3 turn = RotationVector(s.X_DT.q);
  EXPECT_LT((turn - torque / hand.rot_stiffness).norm(), kExactTol) << turn.transpose();
  EXPECT_TRUE(s.X_DT.p.isZero(kExactTol));
}

// The closed loop a rendering method creates: the hand pushes into a penalty wall (x < 0 is
// solid, k_wall = 2000 N/m) sampled at 1 kHz. It must settle where the hand spring balances the
// wall, x* = k x_target / (k + k_wall), without a growing oscillation.
TEST(HandDeviceTest, PressingAgainstStiffWallSettlesWithBoundedEnergy) {
  const HandSettings hand;
  constexpr double kWall = 2000.0;   // N/m
  constexpr double kTarget = -0.02;  // m, 2 cm inside the wall
  const auto device = MakeHandDevice(
      {Key(0.0, Vec3(0.05, 0, 0)), Key(0.5, Vec3(0.05, 0, 0)), Key(1.0, Vec3(kTarget, 0, 0))},
      hand);
  auto energy = [&](const DeviceState& s) {
    const double depth = std::max(0.0, -s.X_DT.p.x());
    return 0.5 * hand.mass * s.V_DT.v.squaredNorm() +
           0.5 * hand.stiffness * (Vec3(kTarget, 0, 0) - s.X_DT.p).squaredNorm() +
           0.5 * kWall * depth * depth;
  };
  double energy_at_rest_target = 0.0;
  double max_energy = 0.0;
  DeviceState s;
  for (int i = 0; i <= 5000; ++i) {
    s = device->Read(i * kDt);
    device->SetWrench(Wrench{Vec3(kWall * std::max(0.0, -s.X_DT.p.x()), 0, 0), Vec3::Zero()});
    if (i == 1000) energy_at_rest_target = energy(s);
    if (i >= 1000) max_energy = std::max(max_energy, energy(s));
  }
  // From t = 1 s on the target is still, so only the zero-order hold of the wall force can add
  // energy; allow 1 % for it.
  EXPECT_LE(max_energy, 1.01 * energy_at_rest_target);
  const double x_star = hand.stiffness * kTarget / (hand.stiffness + kWall);
  EXPECT_NEAR(s.X_DT.p.x(), x_star, kExactTol);
  EXPECT_LT(s.V_DT.v.norm(), kExactTol);
}

TEST(HandDeviceTest, OneLongReadEqualsManyOneMillisecondReads) {
  const std::vector<Keyframe> target = {Key(0.0, Vec3::Zero()), Key(1.0, Vec3(0.3, 0.1, 0))};
  const auto fine = MakeHandDevice(target, HandSettings{});
  const auto coarse = MakeHandDevice(target, HandSettings{});
  (void)coarse->Read(0.0);
  const DeviceState a = RunTicks(*fine, 0.0, 0.02);
  const DeviceState b = coarse->Read(0.02);
  EXPECT_LT((a.X_DT.p - b.X_DT.p).norm(), 1e-15);
  EXPECT_LT((a.V_DT.v - b.V_DT.v).norm(), 1e-13);
  EXPECT_GT(a.V_DT.v.norm(), 0.01);  // the hand did move
}

TEST(HandDeviceTest, LongGapIsIntegratedWithBoundedWork) {
  const auto device = MakeHandDevice({Key(0.0, Vec3(0.1, 0, 0))}, HandSettings{});
  (void)device->Read(0.0);
  device->SetWrench(Wrench{Vec3(3.0, 0, 0), Vec3::Zero()});
  // 1e9 s would be 1e12 steps; the device integrates the last second only, which settles.
  const DeviceState s = device->Read(1e9);
  EXPECT_TRUE(IsFinite(s.X_DT) && IsFinite(s.V_DT));
  EXPECT_NEAR(s.X_DT.p.x(), 0.1 + 3.0 / HandSettings{}.stiffness, 1e-6);
}

TEST(HandDeviceTest, NonFiniteWrenchIsDisplayedAsZero) {
  const auto device = MakeHandDevice({Key(0.0, Vec3::Zero())}, HandSettings{});
  (void)device->Read(0.0);
  device->SetWrench(Wrench{Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0), Vec3::Zero()});
  const DeviceState s = RunTicks(*device, kDt, 0.1);
  EXPECT_TRUE(IsFinite(s.X_DT));
  EXPECT_TRUE(s.X_DT.p.isZero(kExactTol));
}

TEST(HandDeviceTest, OpenPutsTheHandBackOnItsTarget) {
  const auto device = MakeHandDevice({Key(0.0, Vec3::Zero())}, HandSettings{});
  (void)device->Read(0.0);
  device->SetWrench(Wrench{Vec3(3.0, 0, 0), Vec3::Zero()});
  ASSERT_GT(RunTicks(*device, kDt, 0.5).X_DT.p.x(), 0.005);
  device->Open();
  const DeviceState s = device->Read(0.6);
  EXPECT_EQ(s.X_DT.p, Vec3::Zero());
  EXPECT_EQ(s.V_DT.v, Vec3::Zero());
}

TEST(HandSettingsTest, DefaultsAreValid) {
  EXPECT_NO_THROW(HandSettings{}.Validate());
}

TEST(HandSettingsTest, EveryNonPositiveOrNonFiniteValueNamesItsKey) {
  struct Case {
    double HandSettings::*member;
    const char* key;
  };

  const Case cases[] = {{&HandSettings::mass, "device.hand.mass"},
                        {&HandSettings::stiffness, "device.hand.stiffness"},
                        {&HandSettings::damping, "device.hand.damping"},
                        {&HandSettings::inertia, "device.hand.inertia"},
                        {&HandSettings::rot_stiffness, "device.hand.rot_stiffness"},
                        {&HandSettings::rot_damping, "device.hand.rot_damping"}};
  for (const Case& c : cases) {
    for (const double bad : {0.0, -1.0, std::numeric_limits<double>::infinity()}) {
      HandSettings hand;
      hand.*c.member = bad;
      EXPECT_THAT(
          [&] {
            hand.Validate();
          },
          ThrowsMessage<InvalidArgument>(HasSubstr(std::string(c.key) + " = ")))
          << c.key << " = " << bad;
    }
  }
}

TEST(HandSettingsTest, MessageGivesValueUnitAndExpectation) {
  HandSettings hand;
  hand.mass = -0.5;
  EXPECT_THAT(
      [&] {
        hand.Validate();
      },
      ThrowsMessage<InvalidArgument>(
          HasSubstr("device.hand.mass = -0.5 kg; expected a finite value in [0.001, 1000] kg")));
}

TEST(HandDeviceTest, RejectsInvalidSettings) {
  HandSettings hand;
  hand.damping = 0.0;
  EXPECT_THAT(
      [&] {
        (void)MakeHandDevice({Key(0.0, Vec3::Zero())}, hand);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("device.hand.damping")));
}

TEST(HandDeviceTest, RejectsBadTargetNamingTheKeyframe) {
  EXPECT_THAT(
      [] {
        (void)MakeHandDevice({Key(1.0, Vec3::Zero()), Key(0.5, Vec3::Zero())}, HandSettings{});
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("hand device: target keyframe 1: t = 0.5 s")));
}

}  // namespace
}  // namespace mrh::device
