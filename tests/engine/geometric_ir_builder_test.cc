// SPDX-License-Identifier: Apache-2.0
// Tests of the 6-DOF neighbor search and geometric IR: the thesis §3.2.1 cases (face, edge,
// vertex), fallbacks,
// capacities, errors, and the neighbor set against brute force on random scenes.
#include "physics/geometric_ir_builder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/world/world.h"

namespace mrh::physics::internal {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// The pointer is a 0.2 m cube. Signed distances of boxes and planes are exact to ~1e-9 of the
// pair's size and the region vertices are intersections of exact planes, so plane, normal,
// points and depths hold to 1e-9 m.
constexpr double kHalf = 0.1;
constexpr double kExact = 1e-9;
constexpr double kDepth = 0.005;  // penetration of the face, edge and vertex cases (m)

constexpr const char* kCubeOnFloor = R"(
<mujoco>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 0.1"/>
    <body name="pointer" mocap="true" pos="0 0 0.5">
      <geom name="cube" type="box" size="0.1 0.1 0.1" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>)";

struct Result {
  std::unique_ptr<ir::PhysicsSnapshot> snapshot = std::make_unique<ir::PhysicsSnapshot>();
  GeometricIrStats stats;
};

Result BuildAt(world::World& world, const Pose& X_WP,
               const settings::RenderingSettings& rendering = {}) {
  const int pointer = world.pointer_body();
  world.SetMocapPose(pointer, X_WP);
  GeometricIrBuilder builder(world, pointer, rendering);
  Result r;
  builder.Build(world, X_WP, r.snapshot.get());
  r.stats = builder.stats();
  return r;
}

Vec3 PlanePointW(const ir::PhysicsSnapshot& s, const ir::GeometricPair& pair) {
  return s.bodies[static_cast<std::size_t>(pair.motion)].X_WB * pair.p_BC;
}

std::vector<ir::PairPoint> PointsOf(const ir::PhysicsSnapshot& s, const ir::GeometricPair& p) {
  return {s.points.begin() + p.first_point, s.points.begin() + p.first_point + p.num_points};
}

// True when `points` (pointer frame) are exactly the `expected` corners, in any order.
void ExpectCorners(const std::vector<ir::PairPoint>& points, const std::vector<Vec3>& expected) {
  ASSERT_EQ(points.size(), expected.size());
  for (const Vec3& corner : expected) {
    const bool found = std::any_of(points.begin(), points.end(), [&](const ir::PairPoint& p) {
      return (p.p_PV - corner).norm() < kExact;
    });
    EXPECT_TRUE(found) << "corner " << corner.transpose() << " missing";
  }
}

TEST(GeometricIrBuilderTest, FaceOnFloorGivesFourPointerCornersAtDepth) {
  world::World w = world::World::LoadString(kCubeOnFloor);
  const Result r = BuildAt(w, Pose{Vec3(0.03, -0.02, kHalf - kDepth), Quat::Identity()});
  ASSERT_EQ(r.snapshot->pairs.size(), 1u);
  const ir::GeometricPair& pair = r.snapshot->pairs[0];
  EXPECT_TRUE(pair.penetrating);
  EXPECT_NEAR(pair.distance, -kDepth, kExact);
  EXPECT_LT((pair.n_W - Vec3::UnitZ()).norm(), kExact);
  EXPECT_NEAR(PlanePointW(*r.snapshot, pair).z(), 0.0, kExact);
  const std::vector<ir::PairPoint> points = PointsOf(*r.snapshot, pair);
  ExpectCorners(points, {Vec3(kHalf, kHalf, -kHalf), Vec3(-kHalf, kHalf, -kHalf),
                         Vec3(kHalf, -kHalf, -kHalf), Vec3(-kHalf, -kHalf, -kHalf)});
  for (const ir::PairPoint& p : points) EXPECT_NEAR(p.depth, kDepth, kExact);
}

TEST(GeometricIrBuilderTest, EdgeAt45DegreesGivesTheTwoEndsOfTheBuriedEdge) {
  world::World w = world::World::LoadString(kCubeOnFloor);
  // Turned 45° about x, the edge y = z = −0.1 is lowest, 0.1·√2 below the centre.
  const Quat q(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()));
  const Result r = BuildAt(w, Pose{Vec3(0.0, 0.0, kHalf * std::sqrt(2.0) - kDepth), q});
  ASSERT_EQ(r.snapshot->pairs.size(), 1u);
  const ir::GeometricPair& pair = r.snapshot->pairs[0];
  EXPECT_LT((pair.n_W - Vec3::UnitZ()).norm(), kExact);
  EXPECT_NEAR(PlanePointW(*r.snapshot, pair).z(), 0.0, kExact);
  const std::vector<ir::PairPoint> points = PointsOf(*r.snapshot, pair);
  ExpectCorners(points, {Vec3(kHalf, -kHalf, -kHalf), Vec3(-kHalf, -kHalf, -kHalf)});
  for (const ir::PairPoint& p : points) EXPECT_NEAR(p.depth, kDepth, kExact);
}

TEST(GeometricIrBuilderTest, ObjectVertexIntoPointerFaceGivesThreePointsOnTheFace) {
  world::World w = world::World::LoadString(R"(
<mujoco>
  <worldbody>
    <body name="tip" mocap="true"><geom type="box" size="0.05 0.05 0.05"/></body>
    <body name="pointer" mocap="true" pos="0 0 0.5">
      <geom type="box" size="0.1 0.1 0.1" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>)");
  // A 0.1 m cube standing on a corner: its diagonal (1, 1, 1) turned onto +z puts a vertex at
  // the top. The pointer's bottom face sits kDepth below that vertex.
  const Quat up = Quat::FromTwoVectors(Vec3(1, 1, 1).normalized(), Vec3::UnitZ());
  w.SetMocapPose(w.FindBody("tip"), Pose{Vec3::Zero(), up});
  const Vec3 apex(0, 0, 0.05 * std::sqrt(3.0));
  const Result r = BuildAt(w, Pose{Vec3(0.03, 0.02, apex.z() - kDepth + kHalf), Quat::Identity()});
  ASSERT_EQ(r.snapshot->pairs.size(), 1u);
  const ir::GeometricPair& pair = r.snapshot->pairs[0];
  EXPECT_LT((pair.n_W - Vec3::UnitZ()).norm(), kExact);
  EXPECT_NEAR(PlanePointW(*r.snapshot, pair).z(), apex.z(), kExact);
  const std::vector<ir::PairPoint> points = PointsOf(*r.snapshot, pair);
  ASSERT_EQ(points.size(), 3u);
  for (const ir::PairPoint& p : points) {
    EXPECT_NEAR(p.depth, kDepth, kExact);
    EXPECT_NEAR(p.p_PV.z(), -kHalf, kExact);
    // Each of the apex's three edges leaves the axis at 54.7°: it crosses the face δ·√2 out.
    const Vec3 p_W = p.p_PV + Vec3(0.03, 0.02, apex.z() - kDepth + kHalf);
    EXPECT_NEAR(p_W.head<2>().norm(), kDepth * std::sqrt(2.0), kExact);
  }
}

TEST(GeometricIrBuilderTest, SeparatedNeighborSendsThePointersClosestPoint) {
  world::World w = world::World::LoadString(kCubeOnFloor);
  const double gap = 0.02;
  const Result r = BuildAt(w, Pose{Vec3(0, 0, kHalf + gap), Quat::Identity()});
  ASSERT_EQ(r.snapshot->pairs.size(), 1u);
  const ir::GeometricPair& pair = r.snapshot->pairs[0];
  EXPECT_FALSE(pair.penetrating);
  EXPECT_NEAR(pair.distance, gap, kExact);
  ASSERT_EQ(pair.num_points, 1);
  const ir::PairPoint& p = r.snapshot->points[static_cast<std::size_t>(pair.first_point)];
  EXPECT_NEAR(p.p_PV.z(), -kHalf, kExact);
  EXPECT_NEAR(p.depth, -gap, kExact);
}

TEST(GeometricIrBuilderTest, ObjectBeyondNeighborDistanceIsNoPair) {
  world::World w = world::World::LoadString(kCubeOnFloor);
  settings::RenderingSettings rendering;
  rendering.neighbor_distance = 0.05;
  const Result r = BuildAt(w, Pose{Vec3(0, 0, kHalf + 0.06), Quat::Identity()}, rendering);
  EXPECT_TRUE(r.snapshot->pairs.empty());
  EXPECT_TRUE(r.snapshot->bodies.empty());
  EXPECT_EQ(r.stats.candidates, 1);  // the floor plane is always a candidate
}

TEST(GeometricIrBuilderTest, ConcaveToolGivesOnePairPerPieceWithPointsInBodyFrame) {
  world::World w = world::World::LoadString(R"(
<mujoco>
  <worldbody>
    <geom type="plane" size="2 2 0.1"/>
    <body name="pointer" mocap="true" pos="0 0 0.5">
      <geom name="left" type="box" size="0.05 0.05 0.05" pos="-0.1 0 0" contype="0" conaffinity="0"/>
      <geom name="right" type="box" size="0.05 0.05 0.05" pos="0.1 0 0" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>)");
  const Result r = BuildAt(w, Pose{Vec3(0, 0, 0.05 - kDepth), Quat::Identity()});
  ASSERT_EQ(r.snapshot->pairs.size(), 2u);
  EXPECT_NE(r.snapshot->pairs[0].pointer_geom, r.snapshot->pairs[1].pointer_geom);
  for (const ir::GeometricPair& pair : r.snapshot->pairs) {
    const double x = w.geom(pair.pointer_geom).name == "left" ? -0.1 : 0.1;
    ExpectCorners(PointsOf(*r.snapshot, pair),
                  {Vec3(x - 0.05, 0.05, -0.05), Vec3(x + 0.05, 0.05, -0.05),
                   Vec3(x - 0.05, -0.05, -0.05), Vec3(x + 0.05, -0.05, -0.05)});
  }
  EXPECT_EQ(r.snapshot->bodies.size(), 1u);  // both pairs share the world body
}

TEST(GeometricIrBuilderTest, BodyMotionHoldsPosesBeforeAndAfterTheStep) {
  world::World w = world::World::LoadString(R"(
<mujoco>
  <option timestep="0.02"/>
  <worldbody>
    <body name="box" pos="0 0 0"><freejoint/><geom type="box" size="0.05 0.05 0.05"/></body>
    <body name="pointer" mocap="true" pos="0 0 0.5">
      <geom type="box" size="0.1 0.1 0.1" contype="0" conaffinity="0"/>
    </body>
  </worldbody>
</mujoco>)");
  const int box = w.FindBody("box");
  const Pose X_WP{Vec3(0, 0, 0.05 + kHalf - kDepth), Quat::Identity()};
  w.SetMocapPose(w.pointer_body(), X_WP);
  GeometricIrBuilder builder(w, w.pointer_body(), settings::RenderingSettings{});
  const Pose before = w.body_state(box).X_WB;
  builder.CapturePreviousPoses(w);
  w.Step();
  auto s = std::make_unique<ir::PhysicsSnapshot>();
  builder.Build(w, X_WP, s.get());
  ASSERT_EQ(s->bodies.size(), 1u);
  const ir::BodyMotion& m = s->bodies[0];
  EXPECT_EQ(m.body, box);
  EXPECT_FALSE(m.is_static);
  EXPECT_LT((m.X_WB_prev.p - before.p).norm(), kExact);
  EXPECT_LT((m.X_WB.p - w.body_state(box).X_WB.p).norm(), kExact);
  EXPECT_GT((m.X_WB.p - before.p).norm(), 1e-4);  // it fell 2 mm under gravity
}

TEST(GeometricIrBuilderTest, FullSnapshotKeepsTheDeepestPairsAndSetsStatus) {
  // 8 x 9 = 72 small boxes under the pointer face: 66 buried 3 mm, the 6 of the first row 1 mm.
  std::ostringstream xml;
  xml << "<mujoco><worldbody>";
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 9; ++j) {
      const double top = i == 0 && j < 6 ? 0.001 : 0.003;
      xml << "<geom type='box' size='0.005 0.005 0.005' pos='" << -0.08 + 0.02 * i << " "
          << -0.08 + 0.02 * j << " " << top - 0.005 << "'/>";
    }
  }
  xml << "<body name='pointer' mocap='true'><geom type='box' size='0.1 0.1 0.1' contype='0' "
         "conaffinity='0'/></body></worldbody></mujoco>";
  world::World w = world::World::LoadString(xml.str());
  const Result r = BuildAt(w, Pose{Vec3(0, 0, kHalf), Quat::Identity()});
  ASSERT_EQ(r.snapshot->pairs.size(), ir::kMaxGeometricPairs);
  EXPECT_NE(r.snapshot->status & ir::kStatusPairsFull, 0u);
  EXPECT_EQ(r.stats.dropped_pairs, 72 - static_cast<int>(ir::kMaxGeometricPairs));
  for (const ir::GeometricPair& pair : r.snapshot->pairs) EXPECT_LT(pair.distance, -0.002);
}

TEST(GeometricIrBuilderTest, PointerWithoutGeomThrowsNamingTheBody) {
  world::World w = world::World::LoadString(R"(
<mujoco><worldbody>
  <geom type="plane" size="1 1 0.1"/>
  <body name="pointer" mocap="true"/>
</worldbody></mujoco>)");
  EXPECT_THAT(
      [&] {
        GeometricIrBuilder builder(w, w.pointer_body(), settings::RenderingSettings{});
      },
      ThrowsMessage<SceneError>(HasSubstr("pointer body 'pointer' has no geom")));
}

// A random scene: `n` mocap objects of every shape type in a 1 m cube above a floor, and a
// two-piece pointer (a box and a capsule).
std::string RandomScene(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> pos(-0.5, 0.5), size(0.01, 0.05);
  const char* types[] = {"box", "sphere", "capsule", "cylinder", "ellipsoid", "mesh"};
  std::ostringstream xml;
  xml << "<mujoco><asset><mesh name='tet' vertex='0.04 0 0  0 0.04 0  0 0 0.04  -0.03 -0.03 "
         "-0.03'/></asset><worldbody><geom type='plane' size='2 2 0.1' pos='0 0 -0.55'/>";
  for (int i = 0; i < n; ++i) {
    const std::string type = types[i % 6];
    xml << "<body name='o" << i << "' mocap='true' pos='" << pos(rng) << " " << pos(rng) << " "
        << pos(rng) << "'><geom type='" << type << "'";
    if (type == "mesh") {
      xml << " mesh='tet'";
    } else {
      xml << " size='" << size(rng) << " " << size(rng) << " " << size(rng) << "'";
    }
    xml << "/></body>";
  }
  xml << "<body name='pointer' mocap='true'>"
         "<geom type='box' size='0.06 0.04 0.03' contype='0' conaffinity='0'/>"
         "<geom type='capsule' size='0.02 0.06' pos='0.1 0 0' euler='0 90 0' contype='0' "
         "conaffinity='0'/></body></worldbody></mujoco>";
  return xml.str();
}

Pose RandomPose(std::mt19937& rng, const Vec3& centre, double reach) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return Pose{centre + reach * Vec3(u(rng), u(rng), u(rng)),
              Quat(u(rng), u(rng), u(rng), u(rng)).normalized()};
}

using PairSet = std::set<std::pair<int, int>>;  // (pointer geom, object geom)

// Every pointer geom against every other geom, with shapes prepared once.
class BruteForce {
 public:
  explicit BruteForce(const world::World& w) {
    for (int g = 0; g < w.num_geoms(); ++g) shapes_.emplace_back(w.geom(g).shape);
  }

  PairSet Neighbors(const world::World& w, const Pose& X_WP, double threshold) const {
    PairSet pairs;
    for (const int pg : w.body(w.pointer_body()).geoms) {
      const Pose X_WG = X_WP * w.geom(pg).X_BG;
      for (int g = 0; g < w.num_geoms(); ++g) {
        if (w.geom(g).body == w.pointer_body()) continue;
        const geometry::DistanceResult d =
            geometry::SignedDistance(shapes_[static_cast<std::size_t>(pg)], X_WG,
                                     shapes_[static_cast<std::size_t>(g)], w.geom_pose(g));
        if (d.distance <= threshold) pairs.emplace(pg, g);
      }
    }
    return pairs;
  }

 private:
  std::vector<geometry::CollisionShape> shapes_;
};

TEST(GeometricIrBuilderTest, NeighborsEqualBruteForceOnRandomMovingScenes) {
  constexpr int kObjects = 300;
  std::mt19937 rng(2024);
  world::World w = world::World::LoadString(RandomScene(kObjects, rng));
  settings::RenderingSettings rendering;
  rendering.neighbor_distance = 0.03;
  rendering.neighbor_margin = 0.01;  // below neighbor_distance: the builder must still be exact
  GeometricIrBuilder builder(w, w.pointer_body(), rendering);
  const BruteForce brute_force(w);
  auto s = std::make_unique<ir::PhysicsSnapshot>();
  std::vector<int> bodies;
  std::vector<Pose> poses;
  for (int i = 0; i < kObjects; ++i) {
    bodies.push_back(w.FindBody("o" + std::to_string(i)));
    poses.push_back(w.body_state(bodies.back()).X_WB);
  }
  int total = 0;
  for (int step = 0; step < 25; ++step) {
    // Every object drifts and turns a little; the pointer jumps anywhere in the cube.
    for (int i = 0; i < kObjects; ++i) {
      Pose& X = poses[static_cast<std::size_t>(i)];
      X = Pose{X.p, X.q} * RandomPose(rng, Vec3::Zero(), 0.01);
      X.p = X.p.cwiseMax(Vec3::Constant(-0.5)).cwiseMin(Vec3::Constant(0.5));
      w.SetMocapPose(bodies[static_cast<std::size_t>(i)], X);
    }
    const Pose X_WP = RandomPose(rng, Vec3::Zero(), 0.45);
    builder.Build(w, X_WP, s.get());
    const PairSet expected = brute_force.Neighbors(w, X_WP, rendering.neighbor_distance);
    ASSERT_LT(expected.size(), ir::kMaxGeometricPairs);
    PairSet actual;
    for (const ir::GeometricPair& p : s->pairs) actual.emplace(p.pointer_geom, p.object_geom);
    ASSERT_EQ(actual, expected) << "step " << step;
    EXPECT_EQ(builder.stats().neighbors, static_cast<int>(expected.size()));
    EXPECT_LT(builder.stats().candidates, 2 * kObjects / 4);  // the broad phase prunes
    total += static_cast<int>(expected.size());
  }
  EXPECT_GT(total, 25) << "the scenes are too sparse to test anything";
}

}  // namespace
}  // namespace mrh::physics::internal
