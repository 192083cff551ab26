// SPDX-License-Identifier: Apache-2.0
// Start of the normal blend of the point IR (thesis §3.2.2, §4.3.1: the IR is interpolated over
// the physics period) when a new snapshot is adopted.
#pragma once

#include <array>

#include "mrh/core/spatial.h"
#include "mrh/ir/snapshot.h"

namespace mrh::haptic::internal {

using ContactNormals = std::array<Vec3, ir::kMaxPointContacts>;

/// For each contact of `next`: the normal last rendered for the same geom in `current` (so the
/// blend continues from what the user felt), or next's own normal for a new contact.
/// RT-safe.
inline void CarryRenderedNormals(const ir::PhysicsSnapshot& next,
                                 const ir::PhysicsSnapshot& current,
                                 const ContactNormals& rendered_n,
                                 ContactNormals* previous_n) noexcept {
  for (std::size_t i = 0; i < next.contacts.size(); ++i) {
    const ir::PointContact& c = next.contacts[i];
    (*previous_n)[i] = c.n_W;
    for (std::size_t o = 0; o < current.contacts.size(); ++o) {
      if (current.contacts[o].geom == c.geom) {
        (*previous_n)[i] = rendered_n[o];
        break;
      }
    }
  }
}

}  // namespace mrh::haptic::internal
