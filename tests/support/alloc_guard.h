// SPDX-License-Identifier: Apache-2.0
// Counts heap allocations on the current thread while armed, to prove RT paths do not allocate.
#pragma once

#include <cstdint>

namespace mrh::testing {

/// Arms allocation counting on the current thread for its lifetime. Linking
/// tests/support/alloc_guard.cc into a test executable replaces every global operator new and
/// delete (plain, array, nothrow, aligned, sized) with counting versions backed by malloc/free;
/// they count only while a guard is armed on the calling thread, so other threads and unguarded
/// code are unaffected. Guards nest: each counts from its own construction.
///
///   mrh::testing::AllocGuard guard;
///   for (int i = 0; i < 1000; ++i) device->Read(t);
///   EXPECT_EQ(guard.count(), 0);
class AllocGuard {
 public:
  AllocGuard() noexcept;
  ~AllocGuard();
  AllocGuard(const AllocGuard&) = delete;
  AllocGuard& operator=(const AllocGuard&) = delete;

  /// Calls of any operator new on this thread since construction.
  std::int64_t count() const noexcept;
  /// Calls of any operator delete (with a non-null pointer) on this thread since construction.
  std::int64_t deallocations() const noexcept;

 private:
  std::int64_t start_allocations_;
  std::int64_t start_deallocations_;
};

}  // namespace mrh::testing
