// SPDX-License-Identifier: Apache-2.0
// Randomized tests of the penetration region against a brute-force halfspace intersection.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "geometry/qhull_halfspaces.h"
#include "mrh/geometry/contact_region.h"
#include "mrh/geometry/distance.h"
#include "mrh/geometry/polyhedron.h"

namespace mrh::geometry {
namespace {

// Bodies are 3–10 cm: vertices from qhull and from 3x3 solves agree to roundoff times the
// conditioning of the vertex's planes; 1e-9 m leaves room for a conditioning of ~1e5.
constexpr double kVertexTol = 1e-9;
// FCL's EPA witness points on such meshes are exact to ~1e-9 m (DEPENDENCIES.md: 1e-8 depth).
constexpr double kWitnessTol = 1e-7;
constexpr int kCases = 1500;

// A random convex body: the hull of 5–9 points in an ellipsoidal shell of 3–10 cm radii.
struct Body {
  Shape shape;
  ConvexPolyhedron polyhedron;
};

Body RandomBody(std::mt19937& rng) {
  std::uniform_real_distribution<double> radius(0.03, 0.1);
  std::uniform_real_distribution<double> shell(0.6, 1.0);
  std::normal_distribution<double> normal;
  std::uniform_int_distribution<int> count(5, 9);
  for (;;) {
    const Vec3 radii(radius(rng), radius(rng), radius(rng));
    std::vector<Vec3> points;
    for (int i = count(rng); i > 0; --i) {
      const Vec3 u = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
      points.push_back(shell(rng) * u.cwiseProduct(radii));
    }
    auto mesh = internal::ConvexHullMesh(points);
    if (!mesh) continue;
    Shape shape;
    shape.type = ShapeType::kMesh;
    shape.mesh = std::make_shared<ConvexMesh>(std::move(*mesh));
    return Body{shape, ConvexPolyhedron::FromShape(shape, 16)};
  }
}

Pose RandomPose(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> offset(-spread, spread);
  std::normal_distribution<double> normal;
  const Quat q = Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
  return Pose{Vec3(offset(rng), offset(rng), offset(rng)), q};
}

std::vector<Halfspace> WorldFaces(const Body& a, const Pose& X_WA, const Body& b,
                                  const Pose& X_WB) {
  std::vector<Halfspace> faces;
  for (const auto& [body, X] : {std::pair{&a, X_WA}, std::pair{&b, X_WB}}) {
    for (const Halfspace& h : body->polyhedron.faces()) {
      const Vec3 a_W = X.q * h.a;
      faces.push_back(Halfspace{a_W, h.b + a_W.dot(X.p)});
    }
  }
  return faces;
}

// Reference: every intersection of three planes that satisfies all halfspaces, deduplicated.
// Plain arrays and Cramer's rule keep it fast in Debug builds, where Eigen is not inlined.
struct Plane {
  double a[3];
  double b;
};

void Cross(const double* u, const double* v, double* out) {
  out[0] = u[1] * v[2] - u[2] * v[1];
  out[1] = u[2] * v[0] - u[0] * v[2];
  out[2] = u[0] * v[1] - u[1] * v[0];
}

double Dot(const double* u, const double* v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

std::vector<Vec3> BruteForceVertices(const std::vector<Halfspace>& hs) {
  std::vector<Plane> planes;
  for (const Halfspace& h : hs) planes.push_back(Plane{{h.a.x(), h.a.y(), h.a.z()}, h.b});
  const std::size_t n = planes.size();
  std::vector<std::array<double, 3>> found;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      double ij[3];
      Cross(planes[i].a, planes[j].a, ij);
      for (std::size_t k = j + 1; k < n; ++k) {
        const double det = Dot(ij, planes[k].a);
        if (std::abs(det) < 1e-9) continue;  // (nearly) parallel planes meet nowhere useful
        double jk[3];
        double ki[3];
        Cross(planes[j].a, planes[k].a, jk);
        Cross(planes[k].a, planes[i].a, ki);
        std::array<double, 3> p{};
        for (int c = 0; c < 3; ++c) {
          p[c] = (planes[i].b * jk[c] + planes[j].b * ki[c] + planes[k].b * ij[c]) / det;
        }
        bool inside = true;
        for (const Plane& q : planes) inside = inside && Dot(q.a, p.data()) <= q.b + kVertexTol;
        if (!inside) continue;
        bool known = false;
        for (const auto& v : found) {
          const double dx = v[0] - p[0], dy = v[1] - p[1], dz = v[2] - p[2];
          known = known || dx * dx + dy * dy + dz * dz <= kVertexTol * kVertexTol;
        }
        if (!known) found.push_back(p);
      }
    }
  }
  std::vector<Vec3> vertices;
  for (const auto& v : found) vertices.emplace_back(v[0], v[1], v[2]);
  return vertices;
}

// Largest distance from a point of `from` to the nearest point of `to`.
double OneSidedDistance(const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
  double worst = 0.0;
  for (const Vec3& p : from) {
    double nearest = 1e300;
    for (const Vec3& q : to) nearest = std::min(nearest, (p - q).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

double MinSlack(const std::vector<Halfspace>& hs, const Vec3& y) {
  double slack = 1e300;
  for (const Halfspace& h : hs) slack = std::min(slack, h.b - h.a.dot(y));
  return slack;
}

Vec3 Mean(const std::vector<Vec3>& points) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

// Tallies of one randomized run, for assertions that the run covered what it claims.
struct Tally {
  int regions = 0;
  int touching = 0;
  int failed = 0;
};

// Checks one penetrating pair: qhull's region equals the brute-force one, and the contact
// points are exactly the brute-force vertices clearly below the plane, none above it.
void CheckPair(const Body& pointer, const Pose& X_WP, const Body& object, const Pose& X_WO,
               const DistanceResult& d, Tally& tally) {
  const std::vector<Halfspace> hs = WorldFaces(pointer, X_WP, object, X_WO);
  const std::vector<Vec3> reference = BruteForceVertices(hs);
  if (reference.size() >= 4 && MinSlack(hs, Mean(reference)) > 1e-7) {
    const auto vertices = IntersectHalfspaces(hs, Mean(reference));
    ASSERT_TRUE(vertices.has_value());
    EXPECT_LE(OneSidedDistance(*vertices, reference), 10 * kVertexTol);
    EXPECT_LE(OneSidedDistance(reference, *vertices), 10 * kVertexTol);
  }
  const RegionOptions options;
  const ContactRegion r =
      ComputeContactRegion(pointer.polyhedron, X_WP, object.polyhedron, X_WO, d, options);
  const Vec3& n = r.n_W;
  double deepest = 0.0;
  for (const Vec3& p : reference) {
    const double depth = n.dot(d.p_WB - p);
    EXPECT_GE(depth, -kWitnessTol) << "region vertex above the plane";
    deepest = std::max(deepest, depth);
  }
  tally.failed += r.status == RegionStatus::kFailed;
  if (r.status == RegionStatus::kTouching) {
    ++tally.touching;
    EXPECT_LE(deepest, options.on_plane_tolerance + kWitnessTol);
    return;
  }
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  ++tally.regions;
  for (std::size_t i = 0; i < r.points_W.size(); ++i) {
    EXPECT_GT(r.depths[i], options.on_plane_tolerance);
    EXPECT_NEAR(r.depths[i], n.dot(r.c_W - r.points_W[i]), 1e-15);
  }
  EXPECT_LE(OneSidedDistance(r.points_W, reference), 10 * kVertexTol);
  std::vector<Vec3> clearly_below;
  for (const Vec3& p : reference) {
    if (n.dot(d.p_WB - p) > options.on_plane_tolerance + kWitnessTol) clearly_below.push_back(p);
  }
  EXPECT_LE(OneSidedDistance(clearly_below, r.points_W), 2 * options.on_plane_tolerance);
}

TEST(RegionPropertyTest, RandomPairsMatchBruteForceSilently) {
  std::mt19937 rng(20240611);
  Tally tally;
  int separated = 0;
  // gtest reports failures on stdout; qhull and the library would write to stderr.
  ::testing::internal::CaptureStderr();
  while (tally.regions + tally.touching + tally.failed < kCases) {
    const Body pointer = RandomBody(rng);
    const Body object = RandomBody(rng);
    const Pose X_WP = RandomPose(rng, 0.05);
    const Pose X_WO = RandomPose(rng, 0.05);
    const DistanceResult d =
        SignedDistance(CollisionShape(pointer.shape), X_WP, CollisionShape(object.shape), X_WO);
    if (d.distance > 0.0) {
      const ContactRegion r =
          ComputeContactRegion(pointer.polyhedron, X_WP, object.polyhedron, X_WO, d);
      separated += r.status == RegionStatus::kSeparated;
      continue;
    }
    CheckPair(pointer, X_WP, object, X_WO, d, tally);
    if (::testing::Test::HasFatalFailure()) break;
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(tally.failed, 0);
  EXPECT_GE(tally.regions, kCases - kCases / 100);
  EXPECT_GT(separated, 0);
}

// Slides a separated pointer along the witness direction n until it penetrates by `depth`,
// and states the signed-distance result that motion implies: B stays below the plane through
// its closest point, A's closest point ends `depth` below it. (Built here rather than asked of
// SignedDistance: FCL's EPA aborts on some exactly touching mesh pairs.)
struct Approached {
  Pose X_WP;
  DistanceResult d;
};

Approached Approach(const Pose& X_WP, const DistanceResult& apart, double depth) {
  const Vec3 n = (apart.p_WA - apart.p_WB).normalized();
  const Vec3 shift = -(apart.distance + depth) * n;
  DistanceResult d;
  d.distance = -depth;
  d.p_WA = apart.p_WA + shift;
  d.p_WB = apart.p_WB;
  return Approached{Pose{X_WP.p + shift, X_WP.q}, d};
}

TEST(RegionPropertyTest, TouchingAndSliverContactsAreHandledSilently) {
  std::mt19937 rng(7);
  Tally tally;
  ::testing::internal::CaptureStderr();
  for (int i = 0; i < 300; ++i) {
    const Body pointer = RandomBody(rng);
    const Body object = RandomBody(rng);
    const Pose X_WO = RandomPose(rng, 0.0);
    const Pose X_WP{Vec3(0, 0, 0.3), RandomPose(rng, 0.0).q};
    const DistanceResult apart =
        SignedDistance(CollisionShape(pointer.shape), X_WP, CollisionShape(object.shape), X_WO);
    for (const double depth : {0.0, 1e-10, 1e-7, 1e-6}) {
      const Approached near = Approach(X_WP, apart, depth);
      CheckPair(pointer, near.X_WP, object, X_WO, near.d, tally);
    }
  }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(tally.failed, 0);
  EXPECT_GT(tally.touching, 0);
  EXPECT_GT(tally.regions, 0);
}

TEST(RegionPropertyTest, CoplanarFacesOfEqualBodiesMatchBruteForce) {
  std::mt19937 rng(11);
  Tally tally;
  std::normal_distribution<double> normal;
  for (int i = 0; i < 300; ++i) {
    const Body body = RandomBody(rng);
    const Pose X_WO = RandomPose(rng, 0.0);
    // Slide a copy within the plane of one of its faces: that face stays coplanar.
    const Halfspace& face =
        body.polyhedron.faces()[static_cast<std::size_t>(i) % body.polyhedron.faces().size()];
    Vec3 slide(normal(rng), normal(rng), normal(rng));
    slide = 0.01 * (slide - slide.dot(face.a) * face.a).normalized();
    const Pose X_WP{X_WO.p + X_WO.q * slide, X_WO.q};
    const DistanceResult d =
        SignedDistance(CollisionShape(body.shape), X_WP, CollisionShape(body.shape), X_WO);
    ASSERT_LT(d.distance, 0.0);
    CheckPair(body, X_WP, body, X_WO, d, tally);
  }
  EXPECT_EQ(tally.failed, 0);
  EXPECT_EQ(tally.regions, 300);
}

}  // namespace
}  // namespace mrh::geometry
