// SPDX-License-Identifier: Apache-2.0
// Invariant checks: MRH_ASSERT (debug builds only) and MRH_DEMAND (always on, aborts).
#pragma once

#include <source_location>

namespace mrh::internal {

/// Prints the failed condition with its source location to stderr and aborts. Not RT-safe (it
/// ends the process, which is the point: continuing would make the output unsafe).
[[noreturn]] void AssertionFailed(const char* condition,
                                  std::source_location where = std::source_location::current());

}  // namespace mrh::internal

/// Always-on check for conditions whose failure would make the output unsafe.
#define MRH_DEMAND(condition)                                       \
  do {                                                              \
    if (!(condition)) ::mrh::internal::AssertionFailed(#condition); \
  } while (false)

#ifdef NDEBUG
#define MRH_ASSERT(condition) \
  do {                        \
  } while (false)
#else
#define MRH_ASSERT(condition) MRH_DEMAND(condition)
#endif
