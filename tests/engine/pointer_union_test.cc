// SPDX-License-Identifier: Apache-2.0
// Several pointers over one island: the merged report and the united body list.
#include "physics/pointer_union.h"

#include <gtest/gtest.h>

#include <array>
#include <memory>

namespace mrh::physics::internal {
namespace {

ir::BodyMotion Body(int id) {
  ir::BodyMotion m;
  m.body = id;
  return m;
}

TEST(PointerUnionTest, MergedReportSumsEveryPointersImpulsesAndKeepsTheLastIslandStates) {
  auto a = std::make_unique<ir::HapticReport>();
  auto b = std::make_unique<ir::HapticReport>();
  a->AddImpulse(3, Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(10, 0, 0));
  a->AddImpulse(4, Vec3(0, 2, 0), Vec3::Zero(), Vec3::Zero());
  b->AddImpulse(3, Vec3(-0.5, 0, 0), Vec3(0, 0, 2), Vec3(-5, 0, 0));
  (void)b->local_states.PushBack(ir::LocalBodyState{3, Pose{}, Twist{}});
  const std::array<const ir::HapticReport*, 2> reports = {a.get(), b.get()};
  auto merged = std::make_unique<ir::HapticReport>();
  MergePointerReports(reports, merged.get());
  ASSERT_EQ(merged->local_states.size(), 1u);  // the stepping (last) pointer's
  ASSERT_EQ(merged->impulses.size(), 2u);
  for (const ir::BodyImpulse& j : merged->impulses) {
    if (j.body == 3) {
      EXPECT_EQ(j.linear, Vec3(0.5, 0, 0));
      EXPECT_EQ(j.angular, Vec3(0, 0, 3));
    } else {
      EXPECT_EQ(j.body, 4);
      EXPECT_EQ(j.linear, Vec3(0, 2, 0));
    }
  }
}

TEST(PointerUnionTest, UnitedBodiesRenumberIntoTheFirstSnapshotAndFlagOverflow) {
  auto all = std::make_unique<ir::PhysicsSnapshot>();
  auto own = std::make_unique<ir::PhysicsSnapshot>();
  (void)all->bodies.PushBack(Body(7));
  (void)all->bodies.PushBack(Body(9));
  (void)own->bodies.PushBack(Body(9));
  (void)own->bodies.PushBack(Body(11));
  std::array<int, 2> remap{};
  UniteBodies(*own, all.get(), remap);
  EXPECT_EQ(remap[0], 1);  // body 9, already there
  EXPECT_EQ(remap[1], 2);  // body 11, appended
  ASSERT_EQ(all->bodies.size(), 3u);
  EXPECT_EQ(all->bodies[2].body, 11);
  EXPECT_EQ(all->status & ir::kStatusBodiesFull, 0u);
  // A full union takes no more bodies: the extra one maps to -1 and is flagged.
  while (all->bodies.size() < ir::kMaxNeighborBodies) (void)all->bodies.PushBack(Body(100));
  auto more = std::make_unique<ir::PhysicsSnapshot>();
  (void)more->bodies.PushBack(Body(12));
  std::array<int, 1> one{};
  UniteBodies(*more, all.get(), one);
  EXPECT_EQ(one[0], -1);
  EXPECT_NE(all->status & ir::kStatusBodiesFull, 0u);
}

}  // namespace
}  // namespace mrh::physics::internal
