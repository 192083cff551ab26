// SPDX-License-Identifier: Apache-2.0
// Checks SignedDistance on random poses of every pair of solid shapes against optimality
// conditions written with independent support functions.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "distance_test_util.h"
#include "geometry/support.h"
#include "mrh/geometry/distance.h"

namespace mrh::geometry {
namespace {

using testing::BoxMeshShape;
using testing::BoxShape;
using testing::CapsuleShape;
using testing::CylinderShape;
using testing::EllipsoidShape;
using testing::SphereShape;

// Support value h(u) = max over the posed shape of u·x.
double SupportValue(const Shape& shape, const Pose& X_WS, const Vec3& u_W) {
  return u_W.dot(X_WS * internal::SupportPoint(shape, X_WS.q.conjugate() * u_W));
}

bool IsCurved(const Shape& s) {
  return s.type == ShapeType::kCylinder || s.type == ShapeType::kEllipsoid;
}

Quat RandomRotation(std::mt19937* rng) {
  std::normal_distribution<double> g;
  return Quat(Eigen::Vector4d(g(*rng), g(*rng), g(*rng), g(*rng)).normalized());
}

Vec3 RandomUnit(std::mt19937* rng) {
  std::normal_distribution<double> g;
  return Vec3(g(*rng), g(*rng), g(*rng)).normalized();
}

std::vector<Shape> Solids() {
  return {SphereShape(0.3),          CapsuleShape(0.2, 0.3),
          CylinderShape(0.3, 0.25),  EllipsoidShape(0.4, 0.2, 0.3),
          BoxShape(0.25, 0.2, 0.15), BoxMeshShape(0.3, 0.2, 0.25)};
}

// For witness points p_A, p_B and n the unit direction from A toward B (separated: p_B - p_A;
// penetrating: p_A - p_B), p_A must maximize n·x over A and p_B minimize it over B: then the
// planes through them certify the distance (separated) or the overlap along n (penetrating).
// For penetration, no direction may separate the shapes with less motion than the reported depth.
TEST(SignedDistanceCertificateTest, WitnessPointsAreSupportPointsOnRandomPoses) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> offset(-0.6, 0.6);
  const std::vector<Shape> solids = Solids();
  int penetrating = 0;
  int separated = 0;
  for (const Shape& shape_a : solids) {
    for (const Shape& shape_b : solids) {
      const CollisionShape a(shape_a);
      const CollisionShape b(shape_b);
      // Sizes ~0.4 m: FCL stops at 1e-9 (polytopes) or 1e-6 (curved) of that; allow headroom.
      const double tol = IsCurved(shape_a) || IsCurved(shape_b) ? 2e-6 : 1e-9;
      for (int trial = 0; trial < 40; ++trial) {
        const Pose X_WA{Vec3(0.1, 0.2, 0.3), RandomRotation(&rng)};
        const Pose X_WB{Vec3(offset(rng), offset(rng), offset(rng)), RandomRotation(&rng)};
        const DistanceResult r = SignedDistance(a, X_WA, b, X_WB);
        const Vec3 gap = r.distance > 0 ? Vec3(r.p_WB - r.p_WA) : Vec3(r.p_WA - r.p_WB);
        ASSERT_NEAR(gap.norm(), std::abs(r.distance), tol);
        if (gap.norm() < 1e-6) continue;  // touching: no direction to check
        const Vec3 n = gap.normalized();
        EXPECT_NEAR(SupportValue(shape_a, X_WA, n), n.dot(r.p_WA), tol)
            << ShapeTypeName(shape_a.type) << "-" << ShapeTypeName(shape_b.type);
        EXPECT_NEAR(SupportValue(shape_b, X_WB, -n), -n.dot(r.p_WB), tol)
            << ShapeTypeName(shape_a.type) << "-" << ShapeTypeName(shape_b.type);
        if (r.distance < 0) {
          ++penetrating;
          for (int k = 0; k < 50; ++k) {
            const Vec3 u = RandomUnit(&rng);
            EXPECT_GE(SupportValue(shape_a, X_WA, u) + SupportValue(shape_b, X_WB, -u),
                      -r.distance - tol);
          }
        } else {
          ++separated;
        }
      }
    }
  }
  // The poses must exercise both regimes for the test to mean something.
  EXPECT_GT(penetrating, 200);
  EXPECT_GT(separated, 200);
}

// Shapes touching or centred exactly on each other's corners, edges and faces: the exact
// alignments on which FCL's GJK/EPA throw, abort or return NaN if called naively.
TEST(SignedDistanceCertificateTest, ExactlyAlignedContactsGiveFiniteConsistentResults) {
  std::mt19937 rng(7);
  const std::vector<Shape> solids = Solids();
  int checked = 0;
  for (const Shape& shape_a : solids) {
    for (const Shape& shape_b : solids) {
      const CollisionShape a(shape_a);
      const CollisionShape b(shape_b);
      const double tol = IsCurved(shape_a) || IsCurved(shape_b) ? 2e-6 : 1e-9;
      for (int trial = 0; trial < 27; ++trial) {
        // B's centre on A's support point along a lattice direction, axis-aligned or turned.
        const Vec3 u(trial % 3 - 1.0, (trial / 3) % 3 - 1.0, trial / 9 - 1.0);
        if (u.isZero()) continue;
        const Pose X_WA = Pose::Identity();
        const Quat q = trial % 2 ? Quat::Identity() : RandomRotation(&rng);
        const Pose X_WB{internal::SupportPoint(shape_a, u), q};
        const DistanceResult r = SignedDistance(a, X_WA, b, X_WB);
        ASSERT_TRUE(std::isfinite(r.distance) && r.p_WA.allFinite() && r.p_WB.allFinite());
        EXPECT_NEAR((r.p_WA - r.p_WB).norm(), std::abs(r.distance), tol)
            << ShapeTypeName(shape_a.type) << "-" << ShapeTypeName(shape_b.type) << " " << trial;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 36 * 26);
}

}  // namespace
}  // namespace mrh::geometry
