// SPDX-License-Identifier: Apache-2.0
// Tests of the haptic-side IR interpolation (thesis §3.2.2): blends, new pairs, re-posed points.
#include "mrh/render/ir_interpolator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "support/alloc_guard.h"

namespace mrh::render {
namespace {

// Poses and points are ~0.1–1 m; a blend is a few flops: exact to ~1e-15 m.
constexpr double kTol = 1e-12;

constexpr int kPointerGeom = 7;
constexpr int kFloorGeom = 0;
constexpr int kBoxGeom = 3;

Quat AboutZ(double angle) {
  return Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
}

// Body 2 moves by (0.1, 0, 0) and turns 90° about z over the step; one pair (pointer geom 7 vs
// box geom 3) with plane point (0.05, 0, 0) on the body and two pointer points.
std::unique_ptr<ir::PhysicsSnapshot> MovingBoxSnapshot(const Vec3& n_W) {
  auto s = std::make_unique<ir::PhysicsSnapshot>();
  ir::BodyMotion body;
  body.body = 2;
  body.X_WB_prev = Pose{Vec3(0, 0, 0), Quat::Identity()};
  body.X_WB = Pose{Vec3(0.1, 0, 0), AboutZ(std::numbers::pi / 2)};
  body.p_BCm = Vec3(0.01, 0, 0);
  (void)s->bodies.PushBack(body);
  ir::GeometricPair pair;
  pair.motion = 0;
  pair.object_geom = kBoxGeom;
  pair.pointer_geom = kPointerGeom;
  pair.n_W = n_W;
  pair.p_BC = Vec3(0.05, 0, 0);
  pair.first_point = 0;
  pair.num_points = 2;
  (void)s->pairs.PushBack(pair);
  (void)s->points.PushBack(ir::PairPoint{Vec3(0.1, 0.1, -0.1), 0.002});
  (void)s->points.PushBack(ir::PairPoint{Vec3(-0.1, 0.1, -0.1), 0.002});
  return s;
}

// Adds a static floor pair (pointer geom 7 vs floor geom 0) with one point.
void AddFloorPair(ir::PhysicsSnapshot* s, const Vec3& n_W) {
  ir::BodyMotion world;
  world.body = 0;
  world.is_static = true;
  (void)s->bodies.PushBack(world);
  ir::GeometricPair pair;
  pair.motion = static_cast<int>(s->bodies.size()) - 1;
  pair.object_geom = kFloorGeom;
  pair.pointer_geom = kPointerGeom;
  pair.n_W = n_W;
  pair.first_point = static_cast<int>(s->points.size());
  pair.num_points = 1;
  (void)s->pairs.PushBack(pair);
  (void)s->points.PushBack(ir::PairPoint{Vec3(0, 0, -0.1), 0.0});
}

struct Fixture {
  std::unique_ptr<IrInterpolator> interpolator = std::make_unique<IrInterpolator>();
  std::unique_ptr<TickIr> tick = std::make_unique<TickIr>();
};

TEST(IrInterpolatorTest, AlphaZeroGivesPreviousObjectPoseAndNewPairNormal) {
  Fixture f;
  f.interpolator->Adopt(*MovingBoxSnapshot(Vec3::UnitZ()));
  f.interpolator->Evaluate(0.0, Pose{}, f.tick.get());
  ASSERT_EQ(f.tick->pairs.size(), 1u);
  const TickPair& p = f.tick->pairs[0];
  EXPECT_LT((p.X_WB.p - Vec3::Zero()).norm(), kTol);
  EXPECT_LT(p.X_WB.q.angularDistance(Quat::Identity()), kTol);
  EXPECT_LT((p.c_W - Vec3(0.05, 0, 0)).norm(), kTol);
  EXPECT_LT((p.n_W - Vec3::UnitZ()).norm(), kTol);
  EXPECT_TRUE(p.new_pair);
  EXPECT_EQ(p.key, PairKey(kPointerGeom, kBoxGeom));
  EXPECT_EQ(p.body, 2);
}

TEST(IrInterpolatorTest, AlphaOneGivesNewObjectPose) {
  Fixture f;
  f.interpolator->Adopt(*MovingBoxSnapshot(Vec3::UnitZ()));
  f.interpolator->Evaluate(1.0, Pose{}, f.tick.get());
  const TickPair& p = f.tick->pairs[0];
  EXPECT_LT((p.X_WB.p - Vec3(0.1, 0, 0)).norm(), kTol);
  // The plane point (0.05, 0, 0) on the body turned 90° about z: (0.1, 0.05, 0).
  EXPECT_LT((p.c_W - Vec3(0.1, 0.05, 0)).norm(), kTol);
  EXPECT_LT((p.p_WCm - Vec3(0.1, 0.01, 0)).norm(), kTol);
}

TEST(IrInterpolatorTest, AlphaHalfGivesHalfwayPositionAndHalfAngle) {
  Fixture f;
  f.interpolator->Adopt(*MovingBoxSnapshot(Vec3::UnitZ()));
  f.interpolator->Evaluate(0.5, Pose{}, f.tick.get());
  const TickPair& p = f.tick->pairs[0];
  EXPECT_LT((p.X_WB.p - Vec3(0.05, 0, 0)).norm(), kTol);
  EXPECT_LT(p.X_WB.q.angularDistance(AboutZ(std::numbers::pi / 4)), kTol);
  const double c = 0.05 * std::cos(std::numbers::pi / 4);
  EXPECT_LT((p.c_W - Vec3(0.05 + c, c, 0)).norm(), kTol);
}

TEST(IrInterpolatorTest, PersistingPairBlendsFromLastRenderedNormal) {
  Fixture f;
  f.interpolator->Adopt(*MovingBoxSnapshot(Vec3::UnitZ()));
  f.interpolator->Evaluate(1.0, Pose{}, f.tick.get());
  f.interpolator->Adopt(*MovingBoxSnapshot(Vec3::UnitX()));
  f.interpolator->Evaluate(0.0, Pose{}, f.tick.get());
  EXPECT_LT((f.tick->pairs[0].n_W - Vec3::UnitZ()).norm(), kTol);
  EXPECT_FALSE(f.tick->pairs[0].new_pair);
  f.interpolator->Evaluate(0.5, Pose{}, f.tick.get());
  EXPECT_LT((f.tick->pairs[0].n_W - Vec3(1, 0, 1).normalized()).norm(), kTol);
  f.interpolator->Evaluate(1.0, Pose{}, f.tick.get());
  EXPECT_LT((f.tick->pairs[0].n_W - Vec3::UnitX()).norm(), kTol);
}

TEST(IrInterpolatorTest, NewPairUsesNewNormalWhileOldPairBlends) {
  Fixture f;
  f.interpolator->Adopt(*MovingBoxSnapshot(Vec3::UnitZ()));
  f.interpolator->Evaluate(1.0, Pose{}, f.tick.get());
  // The next snapshot lists the new floor pair first: matching is by geom ids, not position.
  auto next = std::make_unique<ir::PhysicsSnapshot>();
  AddFloorPair(next.get(), Vec3::UnitY());
  const auto box = MovingBoxSnapshot(Vec3::UnitX());
  ir::BodyMotion moved = box->bodies[0];
  (void)next->bodies.PushBack(moved);
  ir::GeometricPair pair = box->pairs[0];
  pair.motion = 1;
  pair.first_point = static_cast<int>(next->points.size());
  (void)next->pairs.PushBack(pair);
  for (const ir::PairPoint& p : box->points) (void)next->points.PushBack(p);
  f.interpolator->Adopt(*next);
  f.interpolator->Evaluate(0.0, Pose{}, f.tick.get());
  ASSERT_EQ(f.tick->pairs.size(), 2u);
  EXPECT_TRUE(f.tick->pairs[0].new_pair);
  EXPECT_LT((f.tick->pairs[0].n_W - Vec3::UnitY()).norm(), kTol);
  EXPECT_FALSE(f.tick->pairs[1].new_pair);
  EXPECT_LT((f.tick->pairs[1].n_W - Vec3::UnitZ()).norm(), kTol);
}

TEST(IrInterpolatorTest, PointsFollowCurrentPointerPose) {
  Fixture f;
  f.interpolator->Adopt(*MovingBoxSnapshot(Vec3::UnitZ()));
  const Pose X_WP{Vec3(0.2, -0.1, 0.05), AboutZ(std::numbers::pi / 2)};
  f.interpolator->Evaluate(1.0, X_WP, f.tick.get());
  ASSERT_EQ(f.tick->points.size(), 2u);
  // (0.1, 0.1, −0.1) turned 90° about z is (−0.1, 0.1, −0.1); plus the pointer position.
  const TickPoint& v = f.tick->points[0];
  EXPECT_LT((v.v_W - Vec3(0.1, 0.0, -0.05)).norm(), kTol);
  EXPECT_LT((v.p_PV - Vec3(0.1, 0.1, -0.1)).norm(), kTol);
  // Plane z = 0 (normal +z through (0.1, 0.05, 0)): the point is 0.05 m below it.
  EXPECT_NEAR(v.depth, 0.05, kTol);
  EXPECT_EQ(v.pair, 0);
  EXPECT_EQ(f.tick->pairs[0].first, 0);
  EXPECT_EQ(f.tick->pairs[0].count, 2);
}

TEST(IrInterpolatorTest, NonFinitePointerPoseGivesNoContacts) {
  Fixture f;
  f.interpolator->Adopt(*MovingBoxSnapshot(Vec3::UnitZ()));
  f.interpolator->Evaluate(0.5, Pose{Vec3(std::nan(""), 0, 0), Quat::Identity()}, f.tick.get());
  EXPECT_TRUE(f.tick->pairs.empty());
  EXPECT_TRUE(f.tick->points.empty());
}

TEST(IrInterpolatorTest, AdoptAndEvaluateNeverAllocate) {
  Fixture f;
  const auto a = MovingBoxSnapshot(Vec3::UnitZ());
  auto b = MovingBoxSnapshot(Vec3::UnitX());
  AddFloorPair(b.get(), Vec3::UnitZ());
  mrh::testing::AllocGuard guard;
  for (int step = 0; step < 10; ++step) {
    f.interpolator->Adopt(step % 2 == 0 ? *a : *b);
    for (int j = 0; j < 20; ++j) {
      f.interpolator->Evaluate((j + 1) / 20.0, Pose{Vec3(0, 0, 0.01 * j), Quat::Identity()},
                               f.tick.get());
    }
  }
  EXPECT_EQ(guard.count(), 0);
}

}  // namespace
}  // namespace mrh::render
