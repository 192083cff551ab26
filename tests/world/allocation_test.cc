// SPDX-License-Identifier: Apache-2.0
// Checks that the per-step queries and Save/Restore do not allocate (they run for many bodies
// every physics step).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "mrh/world/world.h"
#include "world_test_util.h"

namespace {

std::atomic<bool> g_counting{false};
std::atomic<int> g_allocations{0};

}  // namespace

// Counting replacements of the global allocation functions (for this test binary only).
void* operator new(std::size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

void operator delete(void* p) noexcept {
  std::free(p);
}

void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace mrh::world {
namespace {

// Counts operator new calls while alive.
class AllocationCounter {
 public:
  AllocationCounter() {
    g_allocations = 0;
    g_counting = true;
  }

  ~AllocationCounter() { g_counting = false; }

  int count() const { return g_allocations.load(); }
};

constexpr char kScene[] = R"(
<mujoco>
  <worldbody>
    <geom type="plane" size="5 5 0.1"/>
    <body name="box" pos="0 0 0.5"><freejoint/><geom type="box" size="0.1 0.1 0.1"/></body>
    <body name="pointer" mocap="true"><geom type="sphere" size="0.02"/></body>
  </worldbody>
</mujoco>)";

TEST(WorldAllocationTest, CounterSeesAnAllocation) {
  AllocationCounter counter;
  ::operator delete(::operator new(16));
  EXPECT_EQ(counter.count(), 1);
}

TEST(WorldAllocationTest, StateQueriesStepAndSnapshotsDoNotAllocate) {
  World world = World::LoadString(kScene);
  Snapshot snapshot = world.MakeSnapshot();
  const int box = world.FindBody("box");
  AllocationCounter counter;
  for (int i = 0; i < 10; ++i) {
    world.SetMocapPose(world.pointer_body(), Pose{Vec3(0, 0, 0.1 * i), Quat::Identity()});
    world.AddForceAtPoint(box, Vec3(1, 0, 0), Vec3(0, 0, 0.55));
    world.Step();
    const BodyState s = world.body_state(box);
    const Pose X_WG = world.geom_pose(world.body(box).geoms[0]);
    ASSERT_TRUE(IsFinite(s.X_WB) && IsFinite(X_WG));
    world.Save(&snapshot);
    world.Restore(snapshot);
  }
  EXPECT_EQ(counter.count(), 0);
}

}  // namespace
}  // namespace mrh::world
