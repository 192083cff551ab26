// SPDX-License-Identifier: Apache-2.0
// Tests of the SO(3) exp and log maps between rotation vectors and unit quaternions.
#include "mrh/core/spatial.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace mrh {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Quaternion components are O(1): a few roundings of sin, cos and a division.
constexpr double kQuatTol = 10 * kEps;
// Rotation vectors up to π rad: exp then log round to a few ulps of the angle.
constexpr double kAngleTol = 10 * kEps * std::numbers::pi;

Vec3 RandomRotationVector(std::mt19937* rng, double max_angle) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> angle(0.0, max_angle);
  const Vec3 axis = Vec3(normal(*rng), normal(*rng), normal(*rng)).normalized();
  return angle(*rng) * axis;
}

Quat RandomUnitQuat(std::mt19937* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  return Quat(normal(*rng), normal(*rng), normal(*rng), normal(*rng)).normalized();
}

// The same rotation: q and −q both count.
double RotationDistance(const Quat& a, const Quat& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

TEST(QuatFromRotationVectorTest, ZeroVectorGivesTheIdentityExactly) {
  const Quat q = QuatFromRotationVector(Vec3::Zero());
  // Exact by contract (no rounding enters (1, 0, 0, 0)), so callers may compare to identity.
  EXPECT_EQ(q.w(), 1.0);
  EXPECT_EQ(q.vec(), Vec3::Zero());
}

TEST(QuatFromRotationVectorTest, MatchesAngleAxisOnRandomVectors) {
  std::mt19937 rng(20240611);
  for (int trial = 0; trial < 1000; ++trial) {
    // Up to 2π, so angles past π (which wrap around) are covered too.
    const Vec3 theta = RandomRotationVector(&rng, 2.0 * std::numbers::pi);
    const Quat expected(Eigen::AngleAxisd(theta.norm(), theta.normalized()));
    const Quat q = QuatFromRotationVector(theta);
    EXPECT_LT((q.coeffs() - expected.coeffs()).norm(), kQuatTol) << "trial " << trial;
    EXPECT_NEAR(q.norm(), 1.0, kQuatTol) << "trial " << trial;
  }
}

TEST(QuatFromRotationVectorTest, RotatesVectorsByRodriguesFormula) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 theta = RandomRotationVector(&rng, std::numbers::pi);
    const Vec3 x(normal(rng), normal(rng), normal(rng));
    const double angle = theta.norm();
    const Vec3 k = theta / angle;
    const Vec3 expected =
        std::cos(angle) * x + std::sin(angle) * k.cross(x) + (1.0 - std::cos(angle)) * k.dot(x) * k;
    EXPECT_LT((QuatFromRotationVector(theta) * x - expected).norm(), kQuatTol * (1.0 + x.norm()))
        << "trial " << trial;
  }
}

TEST(QuatFromRotationVectorTest, SmallAnglesMatchTheExactMapToDoublePrecision) {
  // Both sides of the series threshold (internal::kSmallRotationAngle = 1e-8) and far below it.
  const Vec3 axis = Vec3(1.0, -2.0, 0.5).normalized();
  for (const double angle : {1e-6, 2e-8, 1.0001e-8, 1e-8, 0.9999e-8, 1e-9, 1e-12, 1e-15}) {
    const Quat q = QuatFromRotationVector(angle * axis);
    EXPECT_NEAR(q.w(), std::cos(0.5 * angle), kQuatTol) << angle;
    // Relative to the angle: the vector part is ~angle/2 and must keep its digits.
    EXPECT_LT((q.vec() - std::sin(0.5 * angle) * axis).norm(), 4 * kEps * angle) << angle;
    EXPECT_NEAR(q.norm(), 1.0, kQuatTol) << angle;
  }
}

TEST(QuatFromRotationVectorTest, IsContinuousAcrossTheSeriesThreshold) {
  const Vec3 axis = Vec3(0.3, 0.4, -1.0).normalized();
  const double below = std::nextafter(internal::kSmallRotationAngle, 0.0);
  const Quat a = QuatFromRotationVector(below * axis);
  const Quat b = QuatFromRotationVector(internal::kSmallRotationAngle * axis);
  EXPECT_LT((a.coeffs() - b.coeffs()).norm(), 4 * kEps * internal::kSmallRotationAngle);
}

TEST(RotationVectorFromQuatTest, IdentityGivesTheZeroVector) {
  EXPECT_EQ(RotationVectorFromQuat(Quat::Identity()), Vec3::Zero());
}

TEST(RotationVectorFromQuatTest, MatchesAngleAxisOnRandomQuaternions) {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 1000; ++trial) {
    const Quat q = RandomUnitQuat(&rng);  // w < 0 for about half of them
    const Eigen::AngleAxisd expected(q);  // Eigen picks the angle in [0, π]
    const Vec3 theta = RotationVectorFromQuat(q);
    EXPECT_LE(theta.norm(), std::numbers::pi + kAngleTol) << "trial " << trial;
    EXPECT_LT((theta - expected.angle() * expected.axis()).norm(), kAngleTol) << "trial " << trial;
  }
}

TEST(RotationVectorFromQuatTest, TakesTheShortArcForEitherSign) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const Quat q = RandomUnitQuat(&rng);
    const Quat minus_q(-q.w(), -q.x(), -q.y(), -q.z());
    EXPECT_LT((RotationVectorFromQuat(q) - RotationVectorFromQuat(minus_q)).norm(), kAngleTol)
        << "trial " << trial;
  }
}

TEST(RotationVectorFromQuatTest, InvertsQuatFromRotationVectorBelowPi) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 1000; ++trial) {
    // Short of π, where θ and the opposite vector of length 2π − |θ| are the same rotation.
    const Vec3 theta = RandomRotationVector(&rng, std::numbers::pi - 1e-6);
    EXPECT_LT((RotationVectorFromQuat(QuatFromRotationVector(theta)) - theta).norm(), kAngleTol)
        << "trial " << trial;
  }
}

TEST(RotationVectorFromQuatTest, InvertsQuatFromRotationVectorAtSmallAngles) {
  const Vec3 axis = Vec3(-0.7, 0.1, 0.2).normalized();
  for (const double angle : {1e-6, 3e-8, 2e-8, 1e-8, 1e-9, 1e-12, 1e-15}) {
    const Vec3 theta = angle * axis;
    EXPECT_LT((RotationVectorFromQuat(QuatFromRotationVector(theta)) - theta).norm(),
              4 * kEps * angle)
        << angle;
  }
}

TEST(RotationVectorFromQuatTest, ExpOfTheLogIsTheSameRotation) {
  std::mt19937 rng(12);
  for (int trial = 0; trial < 1000; ++trial) {
    const Quat q = RandomUnitQuat(&rng);
    EXPECT_LT(RotationDistance(QuatFromRotationVector(RotationVectorFromQuat(q)), q), kQuatTol)
        << "trial " << trial;
  }
}

}  // namespace
}  // namespace mrh
