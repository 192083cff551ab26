// SPDX-License-Identifier: Apache-2.0
// Tests of the shape bounding boxes and the incremental sweep and prune against brute force.
#include "mrh/geometry/broadphase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "geometry/support.h"

namespace mrh::geometry {
namespace {

// Shapes here are ~0.1–1 m: bounds are sums of a few products, exact to a few ulps of that.
constexpr double kBoundTol = 1e-14;

Shape MakeShape(ShapeType type, const Vec3& size) {
  Shape s;
  s.type = type;
  s.size = size;
  return s;
}

Shape Tetrahedron() {
  auto mesh = std::make_shared<ConvexMesh>();
  mesh->vertices = {Vec3(0.1, 0, 0), Vec3(0, 0.2, 0), Vec3(0, 0, 0.3), Vec3(-0.1, -0.1, -0.1)};
  mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  Shape s = MakeShape(ShapeType::kMesh, Vec3::Zero());
  s.mesh = mesh;
  return s;
}

Pose RandomPose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Quat q(u(rng), u(rng), u(rng), u(rng));
  q.normalize();
  return Pose{Vec3(u(rng), u(rng), u(rng)), q};
}

// The exact extent of a convex shape along world axis e_i is its support value there.
Aabb BoxFromSupport(const Shape& shape, const Pose& X_WS) {
  Aabb box;
  for (int i = 0; i < 3; ++i) {
    const Vec3 e_S = X_WS.q.conjugate() * Vec3::Unit(i);
    box.max[i] = (X_WS * internal::SupportPoint(shape, e_S))[i];
    box.min[i] = (X_WS * internal::SupportPoint(shape, -e_S))[i];
  }
  return box;
}

TEST(AabbTest, EveryShapeBoxEqualsItsSupportExtents) {
  std::mt19937 rng(7);
  const std::vector<Shape> shapes = {
      MakeShape(ShapeType::kBox, Vec3(0.1, 0.2, 0.3)),
      MakeShape(ShapeType::kSphere, Vec3(0.25, 0, 0)),
      MakeShape(ShapeType::kCapsule, Vec3(0.05, 0.3, 0)),
      MakeShape(ShapeType::kCylinder, Vec3(0.2, 0.1, 0)),
      MakeShape(ShapeType::kEllipsoid, Vec3(0.1, 0.2, 0.4)),
      Tetrahedron(),
  };
  for (const Shape& shape : shapes) {
    for (int trial = 0; trial < 50; ++trial) {
      const Pose X_WS = RandomPose(rng);
      const Aabb box = ComputeAabb(shape, X_WS);
      const Aabb expected = BoxFromSupport(shape, X_WS);
      EXPECT_LT((box.min - expected.min).norm(), kBoundTol) << ShapeTypeName(shape.type);
      EXPECT_LT((box.max - expected.max).norm(), kBoundTol) << ShapeTypeName(shape.type);
    }
  }
}

TEST(AabbTest, PlaneIsUnbounded) {
  const Aabb box = ComputeAabb(MakeShape(ShapeType::kPlane, Vec3::Zero()), Pose{});
  EXPECT_FALSE(box.bounded());
  EXPECT_TRUE(box.Overlaps(Aabb{Vec3::Constant(1e6), Vec3::Constant(1e6 + 1)}));
}

TEST(AabbTest, TouchingBoxesOverlap) {
  const Aabb a{Vec3(0, 0, 0), Vec3(1, 1, 1)};
  EXPECT_TRUE(a.Overlaps(Aabb{Vec3(1, 0, 0), Vec3(2, 1, 1)}));
  EXPECT_FALSE(a.Overlaps(Aabb{Vec3(1.0 + 1e-12, 0, 0), Vec3(2, 1, 1)}));
}

using PairSet = std::set<std::pair<int, int>>;

PairSet BruteForcePairs(const std::vector<Aabb>& boxes, const SweepAndPrune& sap) {
  PairSet pairs;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(boxes.size()); ++j) {
      if (sap.unbounded(i) || sap.unbounded(j)) continue;
      if (boxes[static_cast<std::size_t>(i)].Overlaps(boxes[static_cast<std::size_t>(j)])) {
        pairs.emplace(i, j);
      }
    }
  }
  return pairs;
}

PairSet SapPairs(const SweepAndPrune& sap) {
  PairSet pairs;
  for (int i = 0; i < sap.size(); ++i) {
    for (const int j : sap.overlaps(i)) pairs.emplace(std::min(i, j), std::max(i, j));
  }
  return pairs;
}

std::vector<int> BruteForceQuery(const std::vector<Aabb>& boxes, const SweepAndPrune& sap,
                                 const std::vector<int>& group) {
  std::vector<int> out;
  for (int h = 0; h < static_cast<int>(boxes.size()); ++h) {
    if (std::find(group.begin(), group.end(), h) != group.end()) continue;
    const bool hit = std::any_of(group.begin(), group.end(), [&](int g) {
      return sap.unbounded(h) ||
             boxes[static_cast<std::size_t>(g)].Overlaps(boxes[static_cast<std::size_t>(h)]);
    });
    if (hit) out.push_back(h);
  }
  return out;
}

// Hundreds of boxes of mixed sizes in a 2 m cube, moving coherently, some teleporting.
struct RandomScene {
  explicit RandomScene(int n, unsigned seed) : rng(seed) {
    std::uniform_real_distribution<double> pos(-1.0, 1.0), half(0.01, 0.15), speed(-0.03, 0.03);
    for (int i = 0; i < n; ++i) {
      centres.emplace_back(pos(rng), pos(rng), pos(rng));
      halves.emplace_back(half(rng), half(rng), half(rng));
      velocities.emplace_back(speed(rng), speed(rng), speed(rng));
    }
  }

  std::vector<Aabb> Boxes() const {
    std::vector<Aabb> boxes;
    for (std::size_t i = 0; i < centres.size(); ++i) {
      boxes.push_back(Aabb{centres[i] - halves[i], centres[i] + halves[i]});
    }
    return boxes;
  }

  void Move() {
    std::uniform_real_distribution<double> pos(-1.0, 1.0), u(0.0, 1.0);
    for (std::size_t i = 0; i < centres.size(); ++i) {
      centres[i] += velocities[i];
      if (u(rng) < 0.02) centres[i] = Vec3(pos(rng), pos(rng), pos(rng));
    }
  }

  std::mt19937 rng;
  std::vector<Vec3> centres, halves, velocities;
};

TEST(SweepAndPruneTest, PairsEqualBruteForceOverManyIncrementalSteps) {
  RandomScene scene(400, 11);
  SweepAndPrune sap;
  std::vector<Aabb> boxes = scene.Boxes();
  for (const Aabb& b : boxes) sap.Add(b);
  sap.Add(Aabb::Unbounded());  // a floor plane
  boxes.push_back(Aabb::Unbounded());
  (void)sap.Update();
  ASSERT_EQ(SapPairs(sap), BruteForcePairs(boxes, sap));
  std::int64_t total_swaps = 0;
  for (int step = 0; step < 60; ++step) {
    scene.Move();
    const std::vector<Aabb> moved = scene.Boxes();
    for (std::size_t i = 0; i < moved.size(); ++i) {
      boxes[i] = moved[i];
      sap.SetBox(static_cast<int>(i), moved[i]);
    }
    total_swaps += sap.Update();
    const PairSet expected = BruteForcePairs(boxes, sap);
    ASSERT_EQ(SapPairs(sap), expected) << "step " << step;
    ASSERT_EQ(sap.num_pairs(), static_cast<std::int64_t>(expected.size()));
  }
  EXPECT_GT(total_swaps, 0);
}

TEST(SweepAndPruneTest, GroupQueryEqualsBruteForceAndListsPlanes) {
  RandomScene scene(300, 5);
  SweepAndPrune sap;
  std::vector<Aabb> boxes = scene.Boxes();
  for (const Aabb& b : boxes) sap.Add(b);
  const int plane = sap.Add(Aabb::Unbounded());
  boxes.push_back(Aabb::Unbounded());
  const std::vector<int> group = {3, 17, 42};
  std::vector<int> out;
  for (int step = 0; step < 30; ++step) {
    (void)sap.Update();
    sap.QueryOverlapping(group, &out);
    ASSERT_EQ(out, BruteForceQuery(boxes, sap, group)) << "step " << step;
    ASSERT_TRUE(std::binary_search(out.begin(), out.end(), plane));
    scene.Move();
    const std::vector<Aabb> moved = scene.Boxes();
    for (std::size_t i = 0; i < moved.size(); ++i) {
      boxes[i] = moved[i];
      sap.SetBox(static_cast<int>(i), moved[i]);
    }
  }
}

TEST(SweepAndPruneTest, UpdateWithoutMotionMakesNoSwaps) {
  RandomScene scene(200, 3);
  SweepAndPrune sap;
  for (const Aabb& b : scene.Boxes()) sap.Add(b);
  (void)sap.Update();
  const PairSet before = SapPairs(sap);
  const std::vector<Aabb> same = scene.Boxes();
  for (std::size_t i = 0; i < same.size(); ++i) sap.SetBox(static_cast<int>(i), same[i]);
  EXPECT_EQ(sap.Update(), 0);
  EXPECT_EQ(SapPairs(sap), before);
}

TEST(SweepAndPruneTest, SmallMotionCostsFewSwaps) {
  // One box sliding 0.5 box widths along x on a row of unit-spaced boxes passes at most two
  // endpoints per axis; a rebuild would sort all 2n endpoints.
  SweepAndPrune sap;
  for (int i = 0; i < 100; ++i) {
    sap.Add(Aabb{Vec3(i, 0, 0), Vec3(i + 0.4, 0.4, 0.4)});
  }
  (void)sap.Update();
  sap.SetBox(50, Aabb{Vec3(50.5, 0, 0), Vec3(50.9, 0.4, 0.4)});
  EXPECT_LE(sap.Update(), 2);
  EXPECT_EQ(sap.num_pairs(), 0);
  sap.SetBox(50, Aabb{Vec3(50.8, 0, 0), Vec3(51.2, 0.4, 0.4)});
  EXPECT_LE(sap.Update(), 2);
  EXPECT_EQ(sap.num_pairs(), 1);
  EXPECT_EQ(std::vector<int>(sap.overlaps(50).begin(), sap.overlaps(50).end()),
            std::vector<int>{51});
}

TEST(SweepAndPruneTest, TouchingBoxesOnAGridArePairs) {
  // Unit cubes sharing faces, edges and corners on a 3x3x3 grid: every pair of grid
  // neighbours (Chebyshev distance 1) touches.
  SweepAndPrune sap;
  std::vector<Vec3> corners;
  for (int x = 0; x < 3; ++x) {
    for (int y = 0; y < 3; ++y) {
      for (int z = 0; z < 3; ++z) corners.emplace_back(x, y, z);
    }
  }
  for (const Vec3& c : corners) sap.Add(Aabb{c, c + Vec3::Ones()});
  (void)sap.Update();
  std::int64_t expected = 0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    for (std::size_t j = i + 1; j < corners.size(); ++j) {
      if ((corners[i] - corners[j]).cwiseAbs().maxCoeff() <= 1.0) ++expected;
    }
  }
  EXPECT_EQ(sap.num_pairs(), expected);
}

TEST(SweepAndPruneTest, NonFiniteBoxOverlapsNothing) {
  SweepAndPrune sap;
  const int a = sap.Add(Aabb{Vec3::Zero(), Vec3::Ones()});
  const int b = sap.Add(Aabb{Vec3::Constant(0.5), Vec3::Constant(1.5)});
  (void)sap.Update();
  ASSERT_EQ(sap.num_pairs(), 1);
  const double nan = std::nan("");
  sap.SetBox(b, Aabb{Vec3::Constant(nan), Vec3::Constant(nan)});
  (void)sap.Update();
  EXPECT_EQ(sap.num_pairs(), 0);
  EXPECT_TRUE(sap.overlaps(a).empty());
}

}  // namespace
}  // namespace mrh::geometry
