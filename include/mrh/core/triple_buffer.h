// SPDX-License-Identifier: Apache-2.0
// Lock-free single-producer / single-consumer triple buffer of preallocated values.
#pragma once

#include <atomic>
#include <cstdint>
#include <utility>

namespace mrh {

/// Hands the newest complete value from one writer thread to one reader thread. Neither side
/// ever waits or allocates: the writer fills its private slot and publishes it; the reader picks
/// up the newest published slot. Values are constructed once (copies of `initial`) so that every
/// slot already owns whatever capacity it needs. RT-safe (both ends).
template <typename T>
class TripleBuffer {
 public:
  explicit TripleBuffer(const T& initial = T{}) : slots_{initial, initial, initial} {}

  TripleBuffer(const TripleBuffer&) = delete;
  TripleBuffer& operator=(const TripleBuffer&) = delete;

  /// Writer: the private slot to fill. Its contents are stale (an older value); overwrite all of
  /// it.
  T& write_slot() noexcept { return slots_[write_]; }

  /// Writer: makes the write slot the newest value and takes a fresh private slot.
  void Publish() noexcept {
    const std::uint8_t prev =
        middle_.exchange(static_cast<std::uint8_t>(write_ | kFresh), std::memory_order_acq_rel);
    write_ = prev & kIndexMask;
  }

  /// Reader: takes the newest published value if there is one; returns true if it is new.
  bool Update() noexcept {
    if ((middle_.load(std::memory_order_acquire) & kFresh) == 0) return false;
    const std::uint8_t prev = middle_.exchange(read_, std::memory_order_acq_rel);
    read_ = prev & kIndexMask;
    return true;
  }

  /// Reader: the value taken by the last successful Update() (initially a copy of `initial`).
  const T& read_slot() const noexcept { return slots_[read_]; }

 private:
  static constexpr std::uint8_t kFresh = 0x4;
  static constexpr std::uint8_t kIndexMask = 0x3;
  T slots_[3];
  std::uint8_t write_ = 0;
  std::uint8_t read_ = 1;
  std::atomic<std::uint8_t> middle_{2};
};

}  // namespace mrh
