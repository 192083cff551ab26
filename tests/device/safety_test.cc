// SPDX-License-Identifier: Apache-2.0
// Tests of the safety layer: NaN guards, clamp, engage ramp, watchdog and stop.
#include "mrh/device/safety.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "mrh/core/error.h"

namespace mrh::device {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDt = 1e-3;  // s, one haptic tick
// Forces here are O(10) N; a scale and a square root lose a few ulps.
constexpr double kForceTol = 1e-12;

// Only the feature under test is active: no ramp, a fresh physics side.
SafetySettings PlainSettings() {
  SafetySettings s;
  s.ramp = false;
  return s;
}

Wrench Force(double x, double y, double z) {
  return Wrench{Vec3(x, y, z), Vec3::Zero()};
}

TEST(SafetyFilterTest, PassesWrenchWithinLimitsUnchanged) {
  SafetyFilter filter(Specifications{}, PlainSettings());
  std::uint32_t bits = 99;
  const Wrench out =
      filter.Apply(Wrench{Vec3(1, -2, 3), Vec3(0.1, 0.2, -0.3)}, 1.0, 0.0, true, &bits);
  EXPECT_EQ(bits, kSafetyOk);
  EXPECT_TRUE(out.f.isApprox(Vec3(1, -2, 3), kForceTol));
  EXPECT_TRUE(out.tau.isApprox(Vec3(0.1, 0.2, -0.3), kForceTol));
}

TEST(SafetyFilterTest, ClampKeepsForceDirectionAndLimitsMagnitude) {
  Specifications specs;
  specs.max_force = 20.0;
  SafetyFilter filter(specs, PlainSettings());
  std::uint32_t bits = 0;
  // |(30, 40, 0)| = 50 N, scaled by 20 / 50.
  const Wrench out = filter.Apply(Force(30, 40, 0), 1.0, 0.0, true, &bits);
  EXPECT_EQ(bits, kSafetyForceClamped);
  EXPECT_NEAR(out.f.x(), 12.0, kForceTol);
  EXPECT_NEAR(out.f.y(), 16.0, kForceTol);
  EXPECT_NEAR(out.f.z(), 0.0, kForceTol);
}

// Scaling by limit / |f| can round to 20.000000000000007 N; the clamp re-checks.
TEST(SafetyFilterTest, ClampNeverExceedsTheLimitByRounding) {
  Specifications specs;
  specs.max_force = 20.0;
  specs.max_torque = 0.3;
  SafetyFilter filter(specs, PlainSettings());
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> component(-1.0, 1.0);
  std::uniform_real_distribution<double> exponent(1.31, 12.0);  // |f| from ~20.4 N to 1e12 N
  int over = 0;
  for (int i = 0; i < 100000; ++i) {
    Vec3 f(component(rng), component(rng), component(rng));
    if (!(f.norm() > 1e-3)) continue;
    f *= std::pow(10.0, exponent(rng)) / f.norm();
    std::uint32_t bits = 0;
    const Wrench out = filter.Apply(Wrench{f, 0.01 * f}, 1.0, 0.0, true, &bits);
    if (out.f.norm() > specs.max_force || out.tau.norm() > specs.max_torque) ++over;
    ASSERT_TRUE(bits & kSafetyForceClamped);
  }
  EXPECT_EQ(over, 0);
}

TEST(SafetyFilterTest, ClampKeepsTorqueDirectionAndLimitsMagnitude) {
  Specifications specs;
  specs.max_torque = 1.0;
  SafetyFilter filter(specs, PlainSettings());
  std::uint32_t bits = 0;
  const Wrench out =
      filter.Apply(Wrench{Vec3::Zero(), Vec3(0.0, -3.0, 4.0)}, 1.0, 0.0, true, &bits);
  EXPECT_EQ(bits, kSafetyTorqueClamped);
  EXPECT_TRUE(out.tau.isApprox(Vec3(0.0, -0.6, 0.8), kForceTol)) << out.tau.transpose();
}

TEST(SafetyFilterTest, ClampKeepsDirectionOfHugeFiniteForce) {
  Specifications specs;
  specs.max_force = 20.0;
  SafetyFilter filter(specs, PlainSettings());
  std::uint32_t bits = 0;
  // A plain norm overflows to inf here; the direction must still survive.
  const Wrench out = filter.Apply(Force(1e308, 1e308, 0.0), 1.0, 0.0, true, &bits);
  EXPECT_EQ(bits, kSafetyForceClamped);
  const double component = 20.0 / std::sqrt(2.0);
  EXPECT_TRUE(out.f.isApprox(Vec3(component, component, 0.0), kForceTol)) << out.f.transpose();
}

TEST(SafetyFilterTest, NonFiniteWrenchGivesZeroAndItsBit) {
  SafetyFilter filter(Specifications{}, PlainSettings());
  for (const double bad : {kNaN, kInf, -kInf}) {
    std::uint32_t bits = 0;
    const Wrench out = filter.Apply(Wrench{Vec3(1, 1, 1), Vec3(0, bad, 0)}, 1.0, 0.0, true, &bits);
    EXPECT_EQ(bits, kSafetyNonFiniteWrench) << bad;
    EXPECT_EQ(out.f, Vec3::Zero()) << bad;
    EXPECT_EQ(out.tau, Vec3::Zero()) << bad;
  }
}

TEST(SafetyFilterTest, NonFiniteDeviceGivesZeroAndItsBit) {
  SafetyFilter filter(Specifications{}, PlainSettings());
  std::uint32_t bits = 0;
  const Wrench out = filter.Apply(Force(1, 2, 3), 1.0, 0.0, false, &bits);
  EXPECT_EQ(bits, kSafetyNonFiniteDevice);
  EXPECT_EQ(out.f, Vec3::Zero());
  EXPECT_EQ(out.tau, Vec3::Zero());
}

TEST(SafetyFilterTest, DeviceFaultTakesPrecedenceOverWrenchFault) {
  SafetyFilter filter(Specifications{}, PlainSettings());
  std::uint32_t bits = 0;
  (void)filter.Apply(Force(kNaN, 0, 0), 1.0, 0.0, false, &bits);
  EXPECT_EQ(bits, kSafetyNonFiniteDevice);
}

TEST(SafetyFilterTest, RampScalesOutputLinearlyOverRampTime) {
  SafetySettings settings;
  settings.ramp = true;
  settings.ramp_time = 0.5;
  SafetyFilter filter(Specifications{}, settings);
  for (const double t : {0.0, 0.1, 0.25, 0.4}) {
    std::uint32_t bits = 0;
    const Wrench out = filter.Apply(Force(10, 0, 0), t, 0.0, true, &bits);
    EXPECT_NEAR(out.f.x(), 10.0 * t / 0.5, kForceTol) << "t = " << t;
    EXPECT_EQ(bits, kSafetyRamping) << "t = " << t;
  }
  for (const double t : {0.5, 0.75, 100.0}) {
    std::uint32_t bits = 0;
    const Wrench out = filter.Apply(Force(10, 0, 0), t, 0.0, true, &bits);
    EXPECT_NEAR(out.f.x(), 10.0, kForceTol) << "t = " << t;
    EXPECT_EQ(bits, kSafetyOk) << "t = " << t;
  }
}

TEST(SafetyFilterTest, RampDisabledGivesFullOutputAtStart) {
  SafetySettings off;
  off.ramp = false;
  SafetySettings zero_time;
  zero_time.ramp_time = 0.0;
  for (const SafetySettings& settings : {off, zero_time}) {
    SafetyFilter filter(Specifications{}, settings);
    std::uint32_t bits = 0;
    const Wrench out = filter.Apply(Force(10, 0, 0), 0.0, 0.0, true, &bits);
    EXPECT_NEAR(out.f.x(), 10.0, kForceTol);
    EXPECT_EQ(bits, kSafetyOk);
  }
}

TEST(SafetyFilterTest, ClampAppliesAfterRampScaling) {
  SafetySettings settings;
  settings.ramp_time = 1.0;
  Specifications specs;
  specs.max_force = 20.0;
  SafetyFilter filter(specs, settings);
  std::uint32_t bits = 0;
  // 30 N at half ramp is 15 N: below the limit, so no clamp.
  const Wrench out = filter.Apply(Force(30, 0, 0), 0.5, 0.0, true, &bits);
  EXPECT_NEAR(out.f.x(), 15.0, kForceTol);
  EXPECT_EQ(bits, kSafetyRamping);
}

// Runs a 1 kHz tick loop and records the gain (output / input force) and the bits.
struct WatchdogRun {
  SafetySettings settings = [] {
    SafetySettings s;
    s.ramp = false;
    s.watchdog_timeout = 0.25;
    s.watchdog_fade = 0.1;
    return s;
  }();
  SafetyFilter filter{Specifications{}, settings};
  double t = 0.0;

  // Advances one tick with the given physics age; returns the gain.
  double Tick(double physics_age, std::uint32_t* bits) {
    t += kDt;
    return filter.Apply(Force(10, 0, 0), t, physics_age, true, bits).f.x() / 10.0;
  }
};

// One tick of fade (dt / watchdog_fade): the stale tick can begin one tick early or late.
constexpr double kGainTol = kDt / 0.1 + 1e-9;

TEST(SafetyFilterTest, WatchdogFadesLinearlyOverFadeTimeAfterTimeout) {
  WatchdogRun run;
  std::uint32_t bits = 0;
  // The physics side stalls at t = 0: age = t.
  while (run.t + kDt < 0.25 - kDt / 2) {
    EXPECT_NEAR(run.Tick(run.t + kDt, &bits), 1.0, kForceTol) << "t = " << run.t;
    EXPECT_EQ(bits, kSafetyOk) << "t = " << run.t;
  }
  while (run.t + kDt < 0.36) {
    const double age = run.t + kDt;
    const double gain = run.Tick(age, &bits);
    const double expected = std::clamp(1.0 - (age - 0.25) / 0.1, 0.0, 1.0);
    EXPECT_NEAR(gain, expected, kGainTol) << "t = " << run.t;
    if (age > 0.25 + kDt) {
      EXPECT_EQ(bits, kSafetyWatchdog) << "t = " << run.t;
    }
  }
  EXPECT_EQ(run.Tick(run.t + kDt, &bits), 0.0);
  EXPECT_EQ(bits, kSafetyWatchdog);
}

TEST(SafetyFilterTest, WatchdogRecoversAtTheFadeRateWithoutStep) {
  WatchdogRun run;
  std::uint32_t bits = 0;
  while (run.t < 1.0) (void)run.Tick(run.t + kDt, &bits);  // stalled long enough to fade out
  ASSERT_EQ(run.Tick(1.0, &bits), 0.0);
  // Snapshots arrive again (age 0): the gain climbs back at 1 / watchdog_fade per second.
  const double t_fresh = run.t;
  double previous = 0.0;
  while (run.t < t_fresh + 0.2) {
    const double gain = run.Tick(0.0, &bits);
    const double expected = std::min(1.0, (run.t - t_fresh) / 0.1);
    EXPECT_NEAR(gain, expected, kGainTol) << "t = " << run.t;
    EXPECT_LE(gain - previous, kGainTol) << "a step at t = " << run.t;
    // Away from the moment the gain reaches 1, where rounding decides the tick.
    if (run.t - t_fresh < 0.1 - kDt) {
      EXPECT_EQ(bits, kSafetyWatchdog) << "t = " << run.t;
    } else if (run.t - t_fresh > 0.1 + 2 * kDt) {
      EXPECT_EQ(bits, kSafetyOk) << "t = " << run.t;
    }
    previous = gain;
  }
  EXPECT_EQ(previous, 1.0);
}

TEST(SafetyFilterTest, WatchdogTreatsNonFinitePhysicsAgeAsStale) {
  WatchdogRun run;
  std::uint32_t bits = 0;
  (void)run.Tick(kNaN, &bits);
  EXPECT_EQ(bits, kSafetyWatchdog);
}

TEST(SafetyFilterTest, StopGivesZeroForever) {
  SafetyFilter filter(Specifications{}, PlainSettings());
  std::uint32_t bits = 0;
  ASSERT_NEAR(filter.Apply(Force(5, 0, 0), 1.0, 0.0, true, &bits).f.x(), 5.0, kForceTol);
  filter.Stop();
  EXPECT_TRUE(filter.stopped());
  for (int i = 1; i <= 1000; ++i) {
    const Wrench out = filter.Apply(Force(5, 0, 0), 1.0 + i * kDt, 0.0, true, &bits);
    ASSERT_EQ(out.f, Vec3::Zero()) << "tick " << i;
    ASSERT_EQ(out.tau, Vec3::Zero()) << "tick " << i;
    ASSERT_EQ(bits, kSafetyStopped) << "tick " << i;
  }
}

TEST(SafetyFilterTest, OutputIsFiniteForNonFiniteTime) {
  SafetyFilter filter(Specifications{}, SafetySettings{});
  for (const double t : {kNaN, kInf, -kInf}) {
    std::uint32_t bits = 0;
    const Wrench out = filter.Apply(Force(5, 0, 0), t, 0.0, true, &bits);
    EXPECT_TRUE(IsFinite(out)) << t;
  }
}

TEST(SafetySettingsTest, DefaultsAreValid) {
  EXPECT_NO_THROW(SafetySettings{}.Validate());
}

TEST(SafetySettingsTest, NegativeRampTimeNamesItsKey) {
  SafetySettings s;
  s.ramp_time = -0.1;
  EXPECT_THAT(
      [&] {
        s.Validate();
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("safety.ramp_time = -0.1 s")));
}

TEST(SafetySettingsTest, NonFiniteWatchdogTimeoutNamesItsKey) {
  SafetySettings s;
  s.watchdog_timeout = kNaN;
  EXPECT_THAT(
      [&] {
        s.Validate();
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("safety.watchdog_timeout")));
}

TEST(SafetySettingsTest, NegativeWatchdogFadeNamesItsKey) {
  SafetySettings s;
  s.watchdog_fade = -1.0;
  EXPECT_THAT(
      [&] {
        s.Validate();
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("safety.watchdog_fade")));
}

TEST(SafetyFilterTest, ConstructorRejectsInvalidSettings) {
  SafetySettings s;
  s.watchdog_fade = kInf;
  EXPECT_THAT(
      [&] {
        SafetyFilter filter(Specifications{}, s);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("safety.watchdog_fade")));
}

TEST(SafetyFilterTest, ConstructorRejectsNegativeForceLimit) {
  Specifications specs;
  specs.max_force = -1.0;
  EXPECT_THAT(
      [&] {
        SafetyFilter filter(specs, SafetySettings{});
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("device.limits.max_force = -1 N")));
}

TEST(SafetyFilterTest, ConstructorRejectsNonFiniteTorqueLimit) {
  Specifications specs;
  specs.max_torque = kNaN;
  EXPECT_THAT(
      [&] {
        SafetyFilter filter(specs, SafetySettings{});
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("device.limits.max_torque")));
}

}  // namespace
}  // namespace mrh::device
