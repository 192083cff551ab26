// SPDX-License-Identifier: Apache-2.0
// Lock-free single-producer / single-consumer ring of fixed capacity.
#pragma once

#include <atomic>
#include <cstddef>
#include <vector>

namespace mrh {

/// Bounded FIFO between one producer and one consumer thread. Storage is allocated once in the
/// constructor; TryPush on a full ring drops the item and returns false. Both ends are RT-safe.
template <typename T>
class SpscRing {
 public:
  /// @pre capacity >= 1. Not RT-safe (allocates).
  explicit SpscRing(std::size_t capacity) : buffer_(capacity + 1) {}

  SpscRing(const SpscRing&) = delete;
  SpscRing& operator=(const SpscRing&) = delete;

  [[nodiscard]] bool TryPush(const T& value) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    const std::size_t next = Next(head);
    if (next == tail_.load(std::memory_order_acquire)) return false;
    buffer_[head] = value;
    head_.store(next, std::memory_order_release);
    return true;
  }

  [[nodiscard]] bool TryPop(T* out) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    *out = buffer_[tail];
    tail_.store(Next(tail), std::memory_order_release);
    return true;
  }

  std::size_t capacity() const noexcept { return buffer_.size() - 1; }

 private:
  std::size_t Next(std::size_t i) const noexcept { return i + 1 == buffer_.size() ? 0 : i + 1; }

  std::vector<T> buffer_;
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
};

}  // namespace mrh
