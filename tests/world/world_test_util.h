// SPDX-License-Identifier: Apache-2.0
// Matchers and options shared by the world tests.
#pragma once

#include <gmock/gmock.h>

#include "mrh/world/world.h"

namespace mrh::world::testing {

/// Load options for scenes without a haptic pointer.
inline const LoadOptions kNoPointer{.pointer_body = ""};

MATCHER_P2(IsNearVec, expected, tolerance, "") {
  const double error = (arg - expected).norm();
  *result_listener << "is " << arg.transpose() << ", error " << error;
  return error <= tolerance;
}

}  // namespace mrh::world::testing
