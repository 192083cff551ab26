// SPDX-License-Identifier: Apache-2.0
// Tests of the viewer's recorder: ticks on the viewer clock, IR in the world frame, drops counted.
#include "viewer/live_feed.h"

#include <gtest/gtest.h>

#include <numbers>

#include "mrh/ir/snapshot.h"

namespace mrh::viewer::internal {
namespace {

constexpr double kTol = 1e-12;  // m; one pose composition

TEST(LiveFeedTest, TicksArriveOnTheViewerClock) {
  LiveFeed feed(8);
  feed.set_time_offset(10.0);
  ir::TickRecord tick;
  tick.t = 0.25;
  tick.displayed_W.f = Vec3(0.0, 0.0, 2.0);
  feed.OnTick(tick);
  TickSample sample;
  ASSERT_TRUE(feed.PopTick(&sample));
  EXPECT_DOUBLE_EQ(sample.t, 10.25);
  EXPECT_EQ(sample.displayed_W.f.z(), 2.0);
  EXPECT_FALSE(feed.PopTick(&sample));
}

TEST(LiveFeedTest, TicksCarryTheMethodsProxyPose) {
  LiveFeed feed(8);
  ir::TickRecord tick;
  tick.X_WP.p = Vec3(0.0, 0.0, 0.099);
  tick.X_WQ.p = Vec3(0.0, 0.0, 0.1);
  feed.OnTick(tick);
  TickSample sample;
  ASSERT_TRUE(feed.PopTick(&sample));
  EXPECT_EQ(sample.X_WQ.p, tick.X_WQ.p);
  EXPECT_EQ(sample.X_WP.p, tick.X_WP.p);
}

TEST(LiveFeedTest, CountsTicksDroppedWhenTheUiFallsBehind) {
  LiveFeed feed(2);
  for (int i = 0; i < 5; ++i) feed.OnTick(ir::TickRecord{});
  EXPECT_EQ(feed.dropped_ticks(), 3);
}

TEST(LiveFeedTest, PlacesPlaneIrPointsInTheWorldFrame) {
  ir::PhysicsSnapshot snapshot;
  snapshot.step = 7;
  ir::BodyMotion body;
  body.X_WB =
      Pose{Vec3(1.0, 0.0, 0.0), Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitZ()))};
  ASSERT_TRUE(snapshot.bodies.PushBack(body));
  ir::PointContact contact;
  contact.motion = 0;
  contact.p_BC = Vec3(0.1, 0.0, 0.0);
  contact.n_W = Vec3::UnitZ();
  ASSERT_TRUE(snapshot.contacts.PushBack(contact));
  LiveFeed feed(1);
  feed.OnSnapshot(snapshot);
  ASSERT_TRUE(feed.UpdateIr());
  const IrView& ir = feed.ir();
  EXPECT_EQ(ir.step, 7);
  ASSERT_EQ(ir.planes.size(), 1u);
  // A quarter turn about z takes the body's x axis to the world's y axis.
  EXPECT_TRUE(ir.planes[0].p_W.isApprox(Vec3(1.0, 0.1, 0.0), kTol));
  EXPECT_TRUE(ir.planes[0].n_W.isApprox(Vec3::UnitZ(), kTol));
  ASSERT_EQ(ir.object_points_W.size(), 1u);
}

TEST(LiveFeedTest, KeepsGeometricIrPointsInThePointerFrame) {
  ir::PhysicsSnapshot snapshot;
  ASSERT_TRUE(snapshot.bodies.PushBack(ir::BodyMotion{}));
  ir::GeometricPair pair;
  pair.motion = 0;
  pair.first_point = 0;
  pair.num_points = 2;
  ASSERT_TRUE(snapshot.pairs.PushBack(pair));
  ASSERT_TRUE(snapshot.points.PushBack(ir::PairPoint{Vec3(0.01, 0.0, 0.0), 0.001}));
  ASSERT_TRUE(snapshot.points.PushBack(ir::PairPoint{Vec3(0.0, 0.02, 0.0), 0.002}));
  LiveFeed feed(1);
  feed.OnSnapshot(snapshot);
  ASSERT_TRUE(feed.UpdateIr());
  ASSERT_EQ(feed.ir().pointer_points_P.size(), 2u);
  EXPECT_TRUE(feed.ir().pointer_points_P[1].isApprox(Vec3(0.0, 0.02, 0.0), kTol));
  EXPECT_EQ(feed.ir().planes.size(), 1u);
}

TEST(LiveFeedTest, SkipsIrEntriesThatNameNoNeighbor) {
  ir::PhysicsSnapshot snapshot;
  ir::PointContact contact;
  contact.motion = 3;  // no such neighbor
  ASSERT_TRUE(snapshot.contacts.PushBack(contact));
  LiveFeed feed(1);
  feed.OnSnapshot(snapshot);
  ASSERT_TRUE(feed.UpdateIr());
  EXPECT_TRUE(feed.ir().planes.empty());
}

}  // namespace
}  // namespace mrh::viewer::internal
