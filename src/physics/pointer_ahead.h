// SPDX-License-Identifier: Apache-2.0
// Where the pointer will be some time after a haptic report (physics-side prediction).
#pragma once

#include "mrh/core/spatial.h"
#include "mrh/ir/snapshot.h"

namespace mrh::physics::internal {

/// The report's pointer pose moved on for t seconds with the report's twist (world frame).
inline Pose PointerAhead(const ir::HapticReport& report, double t) {
  return Pose{
      report.X_WP.p + t * report.V_WP.v,
      (QuatFromRotationVector(t * report.V_WP.w) * report.X_WP.q.normalized()).normalized()};
}

}  // namespace mrh::physics::internal
