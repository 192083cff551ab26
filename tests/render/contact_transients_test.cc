// SPDX-License-Identifier: Apache-2.0
// Contact transients: onset detection, the decaying sinusoid, superposition and capacity.
#include "mrh/render/contact_transients.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace mrh::render {
namespace {

constexpr double kDt = 0.001;                 // s
constexpr double kTol = 1e-12;                // N, rounding at forces of a few N
const ir::Vibration kAlu{20.0, 60.0, 250.0};  // N·s/m, 1/s, Hz

double Q(const ir::Vibration& v, double speed, double t) {
  return v.amplitude * speed * std::exp(-v.decay * t) *
         std::sin(2.0 * std::numbers::pi * v.frequency * t);
}

TEST(ContactTransientsTest, OnsetStartsADecayingSinusoidAlongTheNormal) {
  ContactTransients transients;
  const Vec3 n = Vec3::UnitZ();
  for (int k = 0; k < 50; ++k) {
    transients.Touch(3, n, 0.2, kAlu);  // held: only the first tick is an onset
    const Vec3 f = transients.EndTick(kDt);
    EXPECT_NEAR(f.z(), Q(kAlu, 0.2, k * kDt), kTol) << "tick " << k;
    EXPECT_NEAR(f.x(), 0.0, kTol);
  }
}

TEST(ContactTransientsTest, TwoOnsetsOverlapAndAreSummed) {
  ContactTransients transients;
  const ir::Vibration wood{10.0, 40.0, 100.0};
  for (int k = 0; k < 30; ++k) {
    transients.Touch(1, Vec3::UnitZ(), 0.1, kAlu);
    if (k >= 5) transients.Touch(2, Vec3::UnitX(), 0.3, wood);
    const Vec3 f = transients.EndTick(kDt);
    const double second = k >= 5 ? Q(wood, 0.3, (k - 5) * kDt) : 0.0;
    EXPECT_NEAR(f.z(), Q(kAlu, 0.1, k * kDt), kTol);
    EXPECT_NEAR(f.x(), second, kTol);
  }
  EXPECT_EQ(transients.active(), 2u);
}

TEST(ContactTransientsTest, LeavingAndTouchingAgainIsANewOnset) {
  ContactTransients transients;
  transients.Touch(1, Vec3::UnitZ(), 0.1, kAlu);
  (void)transients.EndTick(kDt);
  (void)transients.EndTick(kDt);  // not touched: contact ended
  transients.Touch(1, Vec3::UnitZ(), 0.1, kAlu);
  (void)transients.EndTick(kDt);
  EXPECT_EQ(transients.active(), 2u);
}

TEST(ContactTransientsTest, GeomsWithoutVibrationAndRecedingContactsAddNothing) {
  ContactTransients transients;
  transients.Touch(1, Vec3::UnitZ(), 0.5, ir::Vibration{});
  transients.Touch(2, Vec3::UnitZ(), -0.5, kAlu);  // moving away: v = 0
  for (int k = 0; k < 10; ++k) EXPECT_EQ(transients.EndTick(kDt), Vec3::Zero());
}

TEST(ContactTransientsTest, ATransientEndsWhenItsEnvelopeIsNegligible) {
  ContactTransients transients;
  transients.Touch(1, Vec3::UnitZ(), 0.1, kAlu);
  // e^(−60 t) < 1e-4 after t = ln(1e4) / 60 = 0.154 s.
  for (int k = 0; k < 160; ++k) (void)transients.EndTick(kDt);
  EXPECT_EQ(transients.active(), 0u);
}

TEST(ContactTransientsTest, OnsetsBeyondCapacityAreDroppedAndCounted) {
  ContactTransients transients;
  for (int g = 0; g < static_cast<int>(kMaxTransients) + 3; ++g) {
    transients.Touch(g, Vec3::UnitZ(), 0.1, kAlu);
  }
  (void)transients.EndTick(kDt);
  EXPECT_EQ(transients.active(), kMaxTransients);
  EXPECT_EQ(transients.dropped(), 3u);
}

TEST(ContactTransientsTest, AddTransientForceLeavesTheForceUntouchedWithoutTransients) {
  ContactTransients transients;
  Vec3 f(-0.0, 1.0, 2.0);
  AddTransientForce(kDt, &transients, &f);
  EXPECT_TRUE(std::signbit(f.x()));  // not even −0 + 0
}

}  // namespace
}  // namespace mrh::render
