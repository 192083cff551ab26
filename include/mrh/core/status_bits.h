// SPDX-License-Identifier: Apache-2.0
// Names of a status word's bits, kept in a table beside the enum that defines the bits.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace mrh {

/// One named bit of a status word. `mask` has exactly one bit set (an enumerator of the status
/// enum, never its position written out); `name` is snake_case ("rows_full"). Pairing the name
/// with the enumerator itself is what keeps the two from drifting apart.
struct StatusBitName {
  std::uint32_t mask = 0;
  std::string_view name;
};

/// True if every mask has exactly one bit set, every name is non-empty, and no mask or name
/// appears twice. Each table is checked with static_assert where it is defined.
constexpr bool ValidStatusBitNames(std::span<const StatusBitName> names) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::uint32_t m = names[i].mask;
    if (m == 0 || (m & (m - 1)) != 0 || names[i].name.empty()) return false;
    for (std::size_t j = 0; j < i; ++j) {
      if (names[j].mask == m || names[j].name == names[i].name) return false;
    }
  }
  return true;
}

}  // namespace mrh
