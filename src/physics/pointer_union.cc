// SPDX-License-Identifier: Apache-2.0
// Several pointers over one contact island: merging their reports, uniting their bodies.
#include "pointer_union.h"

namespace mrh::physics::internal {

void MergePointerReports(std::span<const ir::HapticReport* const> reports,
                         ir::HapticReport* merged) {
  *merged = *reports.back();
  for (std::size_t i = 0; i + 1 < reports.size(); ++i) {
    for (const ir::BodyImpulse& impulse : reports[i]->impulses) {
      merged->AddImpulse(impulse.body, impulse.linear, impulse.angular, impulse.last_force);
    }
  }
}

void UniteBodies(const ir::PhysicsSnapshot& own, ir::PhysicsSnapshot* all, std::span<int> remap) {
  for (std::size_t m = 0; m < own.bodies.size(); ++m) {
    int found = -1;
    for (std::size_t u = 0; u < all->bodies.size() && found < 0; ++u) {
      if (all->bodies[u].body == own.bodies[m].body) found = static_cast<int>(u);
    }
    if (found < 0 && all->bodies.PushBack(own.bodies[m])) {
      found = static_cast<int>(all->bodies.size()) - 1;
    }
    if (found < 0) all->status |= ir::kStatusBodiesFull;
    remap[m] = found;
  }
}

void ShareUnion(std::span<ir::PhysicsSnapshot* const> out) {
  const ir::PhysicsSnapshot& all = *out[0];
  for (std::size_t i = 1; i < out.size(); ++i) {
    out[i]->bodies = all.bodies;
    out[i]->local_model = all.local_model;
    out[i]->status |= all.status;
  }
}

}  // namespace mrh::physics::internal
