// SPDX-License-Identifier: Apache-2.0
// One-shot geometric IR of a pointer pose: what proxy-6dof's physics half would send.
#pragma once

#include "mrh/core/spatial.h"
#include "mrh/ir/snapshot.h"
#include "mrh/settings/settings.h"

namespace mrh::world {
class World;
}

namespace mrh::physics {

/// Builds the geometric IR (thesis §3.2.1) of `pointer_body` at X_WP (world) against the world
/// in its current state, with the neighbor and tessellation settings of `rendering`, into
/// `out` (pairs, contact points in the pointer frame, bodies; status bits on overflow). The
/// same builder as the proxy-6dof method, set up from scratch: for inspection (`mrh ir`) and
/// tools, not for a loop (set-up prepares every geom's polyhedron).
/// @throws mrh::SceneError if the pointer body has no geom, a pointer geom is a plane, or a geom
/// cannot be represented (the message names the geom). Physics thread; not RT-safe.
void BuildGeometricIr(const world::World& world, int pointer_body,
                      const settings::RenderingSettings& rendering, const Pose& X_WP,
                      ir::PhysicsSnapshot* out);

}  // namespace mrh::physics
