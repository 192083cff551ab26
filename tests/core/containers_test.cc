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
