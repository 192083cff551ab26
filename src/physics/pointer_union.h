// SPDX-License-Identifier: Apache-2.0
// Several pointers over one contact island: merging their reports, uniting their bodies.
#pragma once

#include <span>

#include "mrh/ir/snapshot.h"

namespace mrh::physics::internal {

/// The report a step with several pointers synchronizes from: the last pointer's (its haptic
/// half steps the shared island, so its report holds the island's end states) with every other
/// pointer's reaction impulses added. `reports` in pointer order, at least one. Physics thread.
void MergePointerReports(std::span<const ir::HapticReport* const> reports,
                         ir::HapticReport* merged);

/// Unites `own`'s bodies into `all`'s, appending those `all` lacks: remap[m] is the index in
/// all.bodies of own.bodies[m], or −1 when `all` is full (kStatusBodiesFull is then set on it).
/// @pre remap.size() >= own.bodies.size(). Physics thread.
void UniteBodies(const ir::PhysicsSnapshot& own, ir::PhysicsSnapshot* all, std::span<int> remap);

/// Gives every other pointer's snapshot pointer 0's (out[0]'s) united bodies, its island and
/// its status bits. Physics thread.
void ShareUnion(std::span<ir::PhysicsSnapshot* const> out);

}  // namespace mrh::physics::internal
