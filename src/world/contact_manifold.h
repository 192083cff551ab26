// SPDX-License-Identifier: Apache-2.0
// Vertex rows of the contact local model: a polyhedral body's support points near a contact's
// plane, so that the island simulated at the haptic rate keeps a body resting on a face.
#pragma once

#include <mujoco/mujoco.h>

#include <cstdint>

#include "mrh/core/spatial.h"
#include "mrh/ir/local_contact.h"
#include "mrh/ir/snapshot.h"

namespace mrh::world::internal {

/// MuJoCo's convex–convex collision gives one contact point for a tilted box, convex mesh or
/// cylinder on a face (a flat one gets several, multiccd). A body held by one row pivots about
/// it for a whole haptic period and sinks through the face; so every row of such a geom (A)
/// against a flat-faced surface (B: a plane, box, mesh or cylinder) is completed with rows at
/// A's vertices (box corners, mesh vertices, 8 points on each cylinder rim) within `margin` of
/// the row's plane (through the row's point on B, its normal): same B, normal, friction and
/// solver parameters; the point on B is the vertex's projection onto that plane; a vertex
/// within 1 mm of one of the pair's rows (in A's frame) is left out. `row` is in
/// LocalContactRow terms (a, b set; p_B, n_B, t_B in B's frame or world); X_WA, X_WB the
/// exported poses (X_WB unused when row.b < 0). Returns ir::kStatusContactsFull if `out` filled.
std::uint32_t AddVertexRows(const mjModel& m, const mjData& d, int geom_A, int geom_B,
                            const ir::LocalContactRow& row, const Pose& X_WA, const Pose& X_WB,
                            double margin, ir::LocalContactModel* out);

}  // namespace mrh::world::internal
