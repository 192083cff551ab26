// SPDX-License-Identifier: Apache-2.0
// Number formatting for setup-path error messages (the device module does not link fmt).
#pragma once

#include <charconv>
#include <string>

namespace mrh::device::internal {

/// The shortest decimal text that reads back as `value` ("nan", "inf" included). Not RT-safe.
inline std::string FormatNumber(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

}  // namespace mrh::device::internal
