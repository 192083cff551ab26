// SPDX-License-Identifier: Apache-2.0
// A vector with inline storage and a compile-time capacity: never allocates, never grows.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>

namespace mrh {

/// Fixed-capacity vector of trivially usable T. PushBack on a full vector drops the item and
/// returns false (the caller sets an overflow status bit). RT-safe. Copies copy the size()
/// elements in use, not the whole capacity (a snapshot's 2048-point buffer holding 10 points
/// copies 10); the slots beyond size() of the target keep whatever they held.
template <typename T, std::size_t N>
class FixedVector {
 public:
  static constexpr std::size_t kCapacity = N;

  FixedVector() = default;

  FixedVector(const FixedVector& other) noexcept { CopyFrom(other); }

  FixedVector& operator=(const FixedVector& other) noexcept {
    if (this != &other) CopyFrom(other);
    return *this;
  }

  [[nodiscard]] bool PushBack(const T& value) noexcept {
    if (size_ == N) return false;
    data_[size_++] = value;
    return true;
  }

  void Clear() noexcept { size_ = 0; }

  std::size_t size() const noexcept { return size_; }

  bool empty() const noexcept { return size_ == 0; }

  bool full() const noexcept { return size_ == N; }

  T& operator[](std::size_t i) noexcept { return data_[i]; }

  const T& operator[](std::size_t i) const noexcept { return data_[i]; }

  T* begin() noexcept { return data_.data(); }

  T* end() noexcept { return data_.data() + size_; }

  const T* begin() const noexcept { return data_.data(); }

  const T* end() const noexcept { return data_.data() + size_; }

  std::span<const T> span() const noexcept { return {data_.data(), size_}; }

 private:
  void CopyFrom(const FixedVector& other) noexcept {
    std::copy(other.data_.begin(), other.data_.begin() + other.size_, data_.begin());
    size_ = other.size_;
  }

  std::array<T, N> data_{};
  std::size_t size_ = 0;
};

}  // namespace mrh
