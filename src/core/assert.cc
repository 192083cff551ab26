// SPDX-License-Identifier: Apache-2.0
// The abort path of MRH_DEMAND / MRH_ASSERT.
#include "mrh/core/assert.h"

#include <cstdio>
#include <cstdlib>

namespace mrh::internal {

void AssertionFailed(const char* condition, std::source_location where) {
  std::fprintf(stderr, "mrhaptics: internal check failed: %s at %s:%u (%s)\n", condition,
               where.file_name(), static_cast<unsigned>(where.line()), where.function_name());
  std::abort();
}

}  // namespace mrh::internal
