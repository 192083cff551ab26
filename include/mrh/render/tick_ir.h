// SPDX-License-Identifier: Apache-2.0
// The geometric IR as one haptic tick sees it: interpolated planes and re-posed contact points.
#pragma once

#include <cstdint>

#include "mrh/core/fixed_vector.h"
#include "mrh/core/spatial.h"
#include "mrh/ir/snapshot.h"

namespace mrh::render {

/// One pair at this tick (thesis §3.2.2): the object pose blended over the physics step and the
/// plane it carries.
struct TickPair {
  std::uint64_t key = 0;         ///< stable identity of the pair across snapshots (geom ids)
  int body = -1;                 ///< world body id of the object
  int motion = -1;               ///< index into the current snapshot's bodies
  bool is_static = false;        ///< a static object takes no reaction
  Pose X_WB;                     ///< object body pose at this tick (blended)
  Vec3 p_WCm = Vec3::Zero();     ///< object COM at this tick (m, world), for reaction moments
  Vec3 n_W = Vec3::UnitZ();      ///< unit plane normal at this tick, object → pointer
  Vec3 c_W = Vec3::Zero();       ///< plane point at this tick (m, world)
  Vec3 p_BC = Vec3::Zero();      ///< plane point in the object body frame (m)
  int first = 0;                 ///< first index into TickIr::points
  int count = 0;                 ///< points of this pair
  bool new_pair = false;         ///< the pair was not in the previous snapshot
  Twist V_WCm;                   ///< object COM velocity at the end of the step (world)
  int object_geom = -1;          ///< world geom id of the object side
  ir::ContactMaterial material;  ///< the object geom's haptic material (none: rendering.*)
};

/// A pointer contact point at this tick.
struct TickPoint {
  Vec3 p_PV = Vec3::Zero();  ///< pointer body frame (m)
  Vec3 v_W = Vec3::Zero();   ///< world position at the current pointer pose (m)
  double depth = 0.0;        ///< n·(c − v) (m); > 0 penetrating
  int pair = -1;             ///< index into TickIr::pairs
};

/// Everything the proxy solver needs from the IR at one tick. Fixed capacity; RT-safe to fill.
struct TickIr {
  FixedVector<TickPair, ir::kMaxGeometricPairs> pairs;
  FixedVector<TickPoint, ir::kMaxPairPoints> points;
};

}  // namespace mrh::render
