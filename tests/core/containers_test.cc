// SPDX-License-Identifier: Apache-2.0
// Tests of the fixed-capacity containers and the lock-free exchanges.
#include <gtest/gtest.h>

#include <thread>

#include "mrh/core/fixed_vector.h"
#include "mrh/core/spsc_ring.h"
#include "mrh/core/triple_buffer.h"

namespace mrh {
namespace {

TEST(FixedVectorTest, DropsItemsBeyondCapacity) {
  FixedVector<int, 2> v;
  EXPECT_TRUE(v.PushBack(1));
  EXPECT_TRUE(v.PushBack(2));
  EXPECT_FALSE(v.PushBack(3));
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[1], 2);
}

TEST(FixedVectorTest, CopiesCarryTheElementsInUseAndTheSize) {
  FixedVector<int, 4> a;
  ASSERT_TRUE(a.PushBack(7));
  ASSERT_TRUE(a.PushBack(8));
  const FixedVector<int, 4> copy(a);
  ASSERT_EQ(copy.size(), 2u);
  EXPECT_EQ(copy[0], 7);
  EXPECT_EQ(copy[1], 8);

  FixedVector<int, 4> b;
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(b.PushBack(-i));
  b = a;  // a larger vector assigned a smaller one shrinks to it
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0], 7);
  EXPECT_EQ(b[1], 8);
  EXPECT_TRUE(b.PushBack(9));
  EXPECT_EQ(b[2], 9);

  a.Clear();
  b = a;
  EXPECT_TRUE(b.empty());
  const FixedVector<int, 4>& self = b;
  b = self;
  EXPECT_TRUE(b.empty());
}

TEST(TripleBufferTest, ReaderSeesNewestPublishedValue) {
  TripleBuffer<int> buffer(-1);
  EXPECT_FALSE(buffer.Update());
  EXPECT_EQ(buffer.read_slot(), -1);
  buffer.write_slot() = 1;
  buffer.Publish();
  buffer.write_slot() = 2;
  buffer.Publish();
  EXPECT_TRUE(buffer.Update());
  EXPECT_EQ(buffer.read_slot(), 2);
  EXPECT_FALSE(buffer.Update());
  EXPECT_EQ(buffer.read_slot(), 2);
}

TEST(TripleBufferTest, ConcurrentReaderNeverSeesTornOrOlderValues) {
  struct Pair {
    long a = 0;
    long b = 0;
  };

  TripleBuffer<Pair> buffer;
  constexpr long kCount = 20000;
  std::thread writer([&] {
    for (long i = 1; i <= kCount; ++i) {
      buffer.write_slot() = Pair{i, -i};
      buffer.Publish();
    }
  });
  long last = 0;
  while (last < kCount) {
    if (buffer.Update()) {
      const Pair& p = buffer.read_slot();
      ASSERT_EQ(p.a, -p.b);
      ASSERT_GT(p.a, last);
      last = p.a;
    }
  }
  writer.join();
}

TEST(SpscRingTest, KeepsOrderAndRejectsWhenFull) {
  SpscRing<int> ring(2);
  EXPECT_TRUE(ring.TryPush(1));
  EXPECT_TRUE(ring.TryPush(2));
  EXPECT_FALSE(ring.TryPush(3));
  int x = 0;
  ASSERT_TRUE(ring.TryPop(&x));
  EXPECT_EQ(x, 1);
  ASSERT_TRUE(ring.TryPop(&x));
  EXPECT_EQ(x, 2);
  EXPECT_FALSE(ring.TryPop(&x));
}

TEST(SpscRingTest, TransfersEverythingAcrossThreads) {
  SpscRing<long> ring(16);
  constexpr long kCount = 50000;
  std::thread producer([&] {
    for (long i = 0; i < kCount;) {
      if (ring.TryPush(i)) ++i;
    }
  });
  long expected = 0;
  long value = 0;
  while (expected < kCount) {
    if (ring.TryPop(&value)) {
      ASSERT_EQ(value, expected);
      ++expected;
    }
  }
  producer.join();
}

}  // namespace
}  // namespace mrh
