// SPDX-License-Identifier: Apache-2.0
// Tests of the allocation guard used by the RT tests: it must see every form of operator new.
#include "support/alloc_guard.h"

#include <gtest/gtest.h>

#include <memory>
#include <new>
#include <thread>
#include <vector>

namespace mrh::testing {
namespace {

// Stores pointers where the optimizer cannot prove them unused, so new/delete pairs are not
// elided.
void* volatile g_sink = nullptr;

struct alignas(64) OverAligned {
  char bytes[64];
};

TEST(AllocGuardTest, CountsNothingWithoutAllocation) {
  AllocGuard guard;
  int x = 3;
  g_sink = &x;
  EXPECT_EQ(guard.count(), 0);
  EXPECT_EQ(guard.deallocations(), 0);
}

TEST(AllocGuardTest, CountsPlainArrayAndNothrowNew) {
  AllocGuard guard;
  int* a = new int(1);
  g_sink = a;
  int* b = new int[4];
  g_sink = b;
  int* c = new (std::nothrow) int(2);
  g_sink = c;
  delete a;
  delete[] b;
  delete c;
  EXPECT_EQ(guard.count(), 3);
  EXPECT_EQ(guard.deallocations(), 3);
}

TEST(AllocGuardTest, CountsAlignedNew) {
  AllocGuard guard;
  auto* p = new OverAligned;
  g_sink = p;
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % alignof(OverAligned), 0u);
  delete p;
  auto* q = new (std::nothrow) OverAligned[3];
  g_sink = q;
  delete[] q;
  EXPECT_EQ(guard.count(), 2);
  EXPECT_EQ(guard.deallocations(), 2);
}

TEST(AllocGuardTest, CountsLibraryAllocations) {
  AllocGuard guard;
  std::vector<double> v(100);
  g_sink = v.data();
  EXPECT_EQ(guard.count(), 1);
}

TEST(AllocGuardTest, DoesNotCountOutsideItsScope) {
  std::int64_t inside = -1;
  {
    AllocGuard guard;
    inside = guard.count();
  }
  auto p = std::make_unique<int>(5);
  g_sink = p.get();
  EXPECT_EQ(inside, 0);
}

TEST(AllocGuardTest, DoesNotCountOtherThreads) {
  AllocGuard guard;
  const std::int64_t before = guard.count();  // std::thread itself allocates its state
  std::thread worker([] {
    for (int i = 0; i < 10; ++i) {
      auto p = std::make_unique<int>(i);
      g_sink = p.get();
    }
  });
  worker.join();
  EXPECT_LE(guard.count() - before, 1);
}

TEST(AllocGuardTest, NestedGuardsCountFromTheirOwnStart) {
  AllocGuard outer;
  auto a = std::make_unique<int>(1);
  g_sink = a.get();
  AllocGuard inner;
  auto b = std::make_unique<int>(2);
  g_sink = b.get();
  EXPECT_EQ(inner.count(), 1);
  EXPECT_EQ(outer.count(), 2);
}

}  // namespace
}  // namespace mrh::testing
